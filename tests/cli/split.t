#!/usr/bin/env bash
# A run sliced in parts (lamina slice --layers, lamina join): the parts of
# examples/parallel-slice.sh (GNU parallel, 4 parts) and of
# examples/slurm-slice.sbatch (array tasks run here, its sbatch a stub)
# join into byte for byte the whole run's program, for every shipped
# dialect; join refuses what does not make one run, writing nothing.
. "$(dirname "$0")/lib.sh"
EX="$TESTS/../examples"
export LAMINA

# every shipped dialect, on parts that split across contours, holes,
# islands (LADRP's island order follows the stage from the layer before),
# skins (LPBF's look three layers up and down across part boundaries)
jobs=(
    "creol-ladrp|$M/thesis_cube_hole.ug|"
    "creol-ladrp|$M/thesis_cube.ug|--islands --angle-step 30"
    "ded-gcode|$M/frame_island.stl|--islands"
    "sls-contours|$M/frame_island.stl|"
    "cli-ascii|$M/thesis_cube_hole.ug|"
    "cli-binary|$M/frame_island.stl|"
    "lpbf-cli|$M/thesis_cube_hole.ug|"
    "lpbf-cli|$M/frame_island.stl|-w 0.5 -s hatch_strategy=islands -s island_size=3"
)
for j in "${jobs[@]}"; do
    IFS='|' read -r machine model extra <<<"$j"
    # shellcheck disable=SC2086
    "$LAMINA" slice "$model" -m "$machine" $extra -o "$TMP/whole" 2>"$TMP/whole.err"
    ok $? "$machine $(basename "$model") $extra: the whole run"
    rm -f "$TMP/split"
    # shellcheck disable=SC2086
    run "$EX/parallel-slice.sh" -n 4 "$model" "$TMP/split" -m "$machine" $extra
    is "$RC" 0 "$machine $(basename "$model") $extra: parallel-slice.sh -n 4 succeeds"
    cmp -s "$TMP/whole" "$TMP/split"
    ok $? "$machine $(basename "$model") $extra: 4 parts joined = the whole run, byte for byte"
    is "$ERR" "$(cat "$TMP/whole.err")" "$machine $(basename "$model") $extra: the same messages (build-time estimate)"
done
# LADRP islands go nearest first from where the stage was left: two
# blocks side by side are rastered A then B, then B then A on the next
# layer, so a part must plan the layers before it to start as the whole run
python3 - "$TMP/two.stl" <<'PY'
import sys
def box(x0, y0, z0, x1, y1, z1):
    v = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return [(v[a], v[b], v[c]) for q in quads for a, b, c in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
with open(sys.argv[1], "w") as f:
    f.write("solid two\n")
    for t in box(0, 0, 0, 4, 4, 6) + box(10, 0, 0, 14, 4, 6):
        f.write("facet normal 0 0 0\nouter loop\n")
        f.writelines("vertex %g %g %g\n" % p for p in t)
        f.write("endloop\nendfacet\n")
    f.write("endsolid two\n")
PY
"$LAMINA" slice "$TMP/two.stl" -m ded-gcode --islands -o "$TMP/whole" 2>/dev/null
run "$EX/parallel-slice.sh" -n 4 "$TMP/two.stl" "$TMP/split" -m ded-gcode --islands
cmp -s "$TMP/whole" "$TMP/split"
ok $? "ded-gcode islands on two blocks: 4 parts joined = the whole run"
# (the test means something: layers do start on either block)
starts=$(awk '/^; layer/ { want = 1 } want && /^G0 / { want = 0; print (substr($2, 2) + 0 > 7 ? "B" : "A") }' \
    "$TMP/whole" | sort -u | tr -d '\n')
is "$starts" AB "the whole run starts some layers on each block"

ls -A "$TMP" | grep -q lamina-parts
ok $((!$?)) "parallel-slice.sh leaves no parts behind"

# GNU parallel's --sshlogin mode, with ':' (this machine) as the host
run "$EX/parallel-slice.sh" -n 3 -S : "$M/thesis_cube_hole.ug" "$TMP/ssh" -m cli-binary
"$LAMINA" slice "$M/thesis_cube_hole.ug" -m cli-binary -o "$TMP/whole" 2>/dev/null
cmp -s "$TMP/whole" "$TMP/ssh"
ok $? "parallel-slice.sh -S : (the --sshlogin path): 3 parts joined = the whole run"

# A:B ranges, given in any order, one of a single layer; join prints the
# estimate as the whole run does
cube=$M/thesis_cube_hole.ug
n=$("$LAMINA" slice "$cube" -m lpbf-cli -o "$TMP/whole" --json - 2>/dev/null | jq '.layers | length')
ok $(( !(n > 10) )) "the LPBF cube has more than 10 layers ($n)"
"$LAMINA" slice "$cube" -m lpbf-cli -o "$TMP/whole" 2>"$TMP/whole.err"
"$LAMINA" slice "$cube" -m lpbf-cli --layers "1:5" -o "$TMP/a" &&
    "$LAMINA" slice "$cube" -m lpbf-cli --layers "6:6" -o "$TMP/b" &&
    "$LAMINA" slice "$cube" -m lpbf-cli --layers "7:$n" -o "$TMP/c"
ok $? "slice --layers 1:5, 6:6, 7:$n"
run "$LAMINA" join "$TMP/c" "$TMP/a" "$TMP/b" -o "$TMP/joined"
cmp -s "$TMP/whole" "$TMP/joined"
ok $? "join of A:B parts given out of order = the whole run"
grep -q 'estimated build time' "$TMP/whole.err" && is "$ERR" "$(cat "$TMP/whole.err")" "join: the whole run's estimate"
ok $(( $(stat -c %s "$TMP/b") >= $(stat -c %s "$TMP/a") )) "a one-layer part is smaller than a five-layer one"

# usage errors of --layers (exit 2, nothing written)
for bad in "0:3|the first layer is 1" "4:3|A <= B" "1:$((n + 1))|the run has $n layers" \
           "5/4|1 <= K <= N" "1/$((n + 1))|too few for $((n + 1)) parts" "x|takes A:B" "1:|takes A:B" \
           "1:2:3|takes A:B"; do
    IFS='|' read -r arg msg <<<"$bad"
    run "$LAMINA" slice "$cube" -m lpbf-cli --layers "$arg" -o "$TMP/bad"
    is "$RC" 2 "--layers $arg: usage error"
    case $ERR in *"$msg"*) ok 0 "--layers $arg: says '$msg'" ;; *) ok 1 "--layers $arg: says '$msg' (got: $ERR)" ;; esac
    [ ! -e "$TMP/bad" ]
    ok $? "--layers $arg: no file"
done
run "$LAMINA" slice "$cube" --layers 1:2 --svg "$TMP/bad.svg" -o "$TMP/bad"
is "$RC" 2 "--layers with --svg: usage error"
run "$LAMINA" slice "$cube" --layers 1:2
is "$RC" 2 "--layers without -o: usage error"
like "$ERR" "give it a file" "--layers without -o says why"

# join refuses, and writes nothing (an existing program stays as it was)
echo keep >"$TMP/prog"
refuse() { # DESCRIPTION REGEX PARTS...
    local d=$1 re=$2
    shift 2
    run "$LAMINA" join "$@" -o "$TMP/prog"
    is "$RC" 1 "join refuses $d"
    like "$ERR" "$re" "join $d: says why"
    is "$(cat "$TMP/prog")" keep "join $d: the output is untouched"
}
refuse "a missing range" "layers 6\.\.6 are missing" "$TMP/a" "$TMP/c"
refuse "missing last layers" "layers 7\.\.$n are missing" "$TMP/a" "$TMP/b"
"$LAMINA" slice "$cube" -m lpbf-cli --layers "5:6" -o "$TMP/b56"
refuse "overlapping parts" "a \(layers 1\.\.5\) and .*b56 \(layers 5\.\.6\) overlap" "$TMP/a" "$TMP/b56" "$TMP/c"
"$LAMINA" slice "$cube" -m lpbf-cli -s power=150 --layers "6:6" -o "$TMP/other"
refuse "a part of another run (another option)" "other: part of a different run" "$TMP/a" "$TMP/other" "$TMP/c"
"$LAMINA" slice "$M/thesis_cube.ug" -m lpbf-cli --layers "6:6" -o "$TMP/other" 2>/dev/null
refuse "a part of another model" "part of a different run" "$TMP/a" "$TMP/other" "$TMP/c"
cp "$TMP/c" "$TMP/flip"
size=$(stat -c %s "$TMP/flip")
printf '\x55' | dd of="$TMP/flip" bs=1 seek=$((size / 2)) conv=notrunc 2>/dev/null
cmp -s "$TMP/c" "$TMP/flip"
ok $((!$?)) "the corrupt copy differs from the part"
refuse "a corrupt part" "flip: byte [0-9]+: corrupt part file" "$TMP/a" "$TMP/b" "$TMP/flip"
head -c $((size - 100)) "$TMP/c" >"$TMP/cut"
refuse "a truncated part" "cut: byte [0-9]+: truncated part file" "$TMP/a" "$TMP/b" "$TMP/cut"
{ cat "$TMP/c"; echo x; } >"$TMP/long"
refuse "bytes after a part's end" "long: byte [0-9]+: corrupt part file: bytes after its end" "$TMP/a" "$TMP/b" "$TMP/long"
# a byte changed anywhere (header, profile, records, end): refused as
# corrupt or truncated, never a crash, never another message
bad=0
for off in 5 9 20 30 60 100 200 400 800 1600 3200 $((size / 3)) $((size - 12)) $((size - 3)); do
    cp "$TMP/c" "$TMP/flip"
    printf '\xa5' | dd of="$TMP/flip" bs=1 seek="$off" conv=notrunc 2>/dev/null
    cmp -s "$TMP/c" "$TMP/flip" || {
        run "$LAMINA" join "$TMP/a" "$TMP/b" "$TMP/flip" -o "$TMP/prog"
        [ "$RC" -eq 1 ] && [[ $ERR =~ (corrupt|truncated|not\ a\ lamina|version) ]] || {
            bad=$((bad + 1)); echo "# byte $off: rc $RC: $ERR"; }
    }
done
is "$bad" 0 "a byte changed at 14 places of a part: refused as corrupt each time"
is "$(cat "$TMP/prog")" keep "and the output untouched"
refuse "a program that is not a part" "whole: not a lamina part file" "$TMP/a" "$TMP/b" "$TMP/whole"
refuse "a part twice" "overlap" "$TMP/a" "$TMP/a" "$TMP/b" "$TMP/c"
run "$LAMINA" join "$TMP/a" "$TMP/b" "$TMP/flip"
is "$RC" 1 "join to standard output refuses a corrupt last part"
is "$OUT" "" "join to standard output: nothing written before the corrupt part is found"
"$LAMINA" join "$TMP/a" "$TMP/b" "$TMP/c" >"$TMP/stdout.cli" 2>/dev/null
"$LAMINA" slice "$cube" -m lpbf-cli -o "$TMP/whole" 2>/dev/null
cmp -s "$TMP/whole" "$TMP/stdout.cli"
ok $? "join to standard output: the whole run's program"
run "$LAMINA" join -o "$TMP/prog"
is "$RC" 2 "join without parts: usage error"

# the Slurm array job: four tasks run here in turn; the stub sbatch keeps
# the join command the first task submits, with its dependency
cat >"$TMP/sbatch" <<'STUB'
#!/usr/bin/env bash
printf '%s\n' "$@" >"$STUB_DIR/sbatch.args"
for a in "$@"; do case $a in --wrap) w=1 ;; *) [ -n "${w:-}" ] && { printf '%s\n' "$a" >"$STUB_DIR/join.sh"; w=; } ;; esac; done
STUB
chmod +x "$TMP/sbatch"
"$LAMINA" slice "$M/frame_island.stl" -m cli-ascii -o "$TMP/whole" 2>/dev/null
rm -f "$TMP/slurm.cli"
fails=0
for id in 3 4 5 6; do
    (cd "$TMP" && STUB_DIR=$TMP SBATCH=$TMP/sbatch SLURM_ARRAY_JOB_ID=77 SLURM_ARRAY_TASK_ID=$id \
        SLURM_ARRAY_TASK_MIN=3 SLURM_ARRAY_TASK_COUNT=4 bash "$EX/slurm-slice.sbatch" \
        "$M/frame_island.stl" "$TMP/slurm.cli" -m cli-ascii) || fails=$((fails + 1))
done
is "$fails" 0 "slurm-slice.sbatch: the four array tasks succeed"
like "$(cat "$TMP/sbatch.args")" "^--dependency=afterok:77$" "the join job waits for the whole array job"
[ ! -e "$TMP/slurm.cli" ]
ok $? "no program before the join job runs"
(cd "$TMP" && bash -c "$(cat "$TMP/join.sh")")
cmp -s "$TMP/whole" "$TMP/slurm.cli"
ok $? "slurm-slice.sbatch: the joined program = the whole run"
[ ! -e "$TMP/slurm.cli.parts" ]
ok $? "the join job removes the parts"

done_testing
