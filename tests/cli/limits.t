#!/usr/bin/env bash
# Whole-job limits: layers (--max-layers) and the output's estimated size
# (--max-output), refused before the work starts with the numbers and the
# option that raises the limit; and the output held to the limit as it is
# written.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
cd "$TMP" || exit 1
# a 100 mm cube (Unigrafix), 0..100 on every axis
cat >cube100.ug <<'UG'
v a 0 0 0; v b 100 0 0; v c 100 100 0; v d 0 100 0;
v e 0 0 100; v f 100 0 100; v g 100 100 100; v h 0 100 100;
f bottom (a d c b); f top (e f g h); f front (a b f e);
f right (b c g f); f back (c d h g); f left (d a e h);
UG

# ---- layers ---------------------------------------------------------------------
run "$LAMINA" slice cube100.ug -w 1e-6 -o out.sls
like "$RC $ERR" "^1 lamina: width 1e-06 makes 100000000 layers, more than the limit of 1000000
lamina: raise the limit with --max-layers N$" "-w 1e-6 on a 100 mm cube: 10^8 layers refused, with the numbers and the option"
ok $(ls | grep -q 'out\.sls' && echo 1 || echo 0) "no output file, not even a temporary"
run "$LAMINA" slice cube100.ug -w 0.1 --max-layers 999 -o out.sls
like "$RC $ERR" "^1 lamina: width 0\.1 makes 1000 layers, more than the limit of 999" "--max-layers lowers the limit"
run "$LAMINA" slice cube100.ug -w 0.1 --max-layers 1000 -o out.sls
is "$RC $(grep -c '^contour ' out.sls)" "0 1000" "a run of exactly --max-layers layers is made (1000 contour blocks)"
run "$LAMINA" slice cube100.ug --planes 0,50,100 --max-layers 1
like "$RC $ERR" "^1 lamina: the list of planes makes 2 layers, more than the limit of 1" "--planes counts too"
run "$LAMINA" validate cube100.ug -w 1e-5
like "$RC $ERR" "^1 lamina: width 1e-05 makes 10000000 layers, more than the limit of 1000000
lamina: raise the limit with --max-layers N" "validate: 10^7 layers refused"
for bad in 0 -1 1.5 x; do
    run "$LAMINA" slice cube100.ug --max-layers "$bad"
    like "$RC $ERR" "^2 lamina slice: --max-layers takes a whole number of layers >= 1 \(got '$bad'\)" "--max-layers $bad is a usage error"
done

# ---- output -------------------------------------------------------------------
cat >tiny.yaml <<'Y'
inherits: creol-ladrp
bead_width: 1e-5
Y
run "$LAMINA" slice cube100.ug -m ./tiny.yaml -w 10 -o out.ladrp
# 10 layers of 100 / 1e-5 + 1 lines, each at least a travel and a deposit
# ("0.00000 -0.00001 0.00000 uline", 31 bytes each): over 6 GB
like "$RC $ERR" "^1 lamina: the job would write about ([6-9]\.[0-9]+|[1-9][0-9]\.[0-9]+) GB \(10 layers, 1e\+08 scan lines of bead 1e-05\), more than the limit of 4 GB
lamina: raise the limit with --max-output SIZE" "bead_width 1e-5: 10^7 scan lines a layer refused before planning"
ok $(ls | grep -q 'out\.ladrp' && echo 1 || echo 0) "no output file, not even a temporary"
run "$LAMINA" slice cube100.ug -m ./tiny.yaml -w 10 --angle 90 --angle-step 45 -o out.ladrp
# 0, 90 (1e7 + 1 lines each) and 45 degrees (100 sqrt 2 / 1e-5 lines) alternate: still far over
like "$RC $ERR" "^1 lamina: the job would write about [0-9.]+ GB \(10 layers, 1\.2[0-9]*e\+08 scan lines" \
    "changing raster angles are counted layer by layer"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp -w 1 --max-output 1k -o out.ladrp
# 2 layers of 2 / 0.08 + 1 = 26 lines, each a travel, the laser on (and its
# feed) and off, a deposit: about 90 bytes, so 4 to 5 kB
like "$RC $ERR" "^1 lamina: the job would write about [45]\.[0-9]+ kB \(2 layers, 52 scan lines of bead 0\.08\), more than the limit of 1 kB" \
    "--max-output lowers the limit (k = 1024)"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp -w 1 --max-output 1M -o out.ladrp
is "$RC" 0 "--max-output 1M: the same job runs"
# The writer holds the limit too, for what the estimate misses: it slices
# 32 layers spread over the run (the middles of 32 equal runs of layers),
# and a plate 1 thick at height 49 of a run of 1000 layers of 0.1 (layers
# 490-499) lies between the samples at layers 484 and 515: the estimate
# sees only the 0.2-wide pin beside it, which has no room for hatches.
cp "$M/pinplate.ug" pinplate.ug # tests/models: also threads.t's
run "$LAMINA" slice pinplate.ug -m lpbf-cli -w 0.1 -o pp.cli
is "$RC" 0 "the pin and plate are sliced"
size=$(wc -c <pp.cli)
run "$LAMINA" slice pinplate.ug -m lpbf-cli -w 0.1 --max-output $((size - 1)) -o pp2.cli
like "$RC $ERR" "^1 lamina: pp2\.cli: cannot write output: output exceeds the limit of $((size - 1)) bytes
lamina: raise the limit with --max-output" "a program one byte over the limit is stopped as it is written"
ok $(ls | grep -q 'pp2\.cli' && echo 1 || echo 0) "and leaves no file"
run "$LAMINA" slice pinplate.ug -m lpbf-cli -w 0.1 --max-output "$size" -o pp3.cli
is "$RC" 0 "a program of exactly the limit is written"
cmp -s pp.cli pp3.cli
ok $? "the same program"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp -w 1 --max-output 100
like "$RC $ERR" "more than the limit of 100 bytes" "the limit holds for standard output too"
for bad in 0 -5 1X 1.5k; do
    run "$LAMINA" slice cube100.ug --max-output "$bad"
    like "$RC $ERR" "^2 lamina slice: --max-output takes a size in bytes" "--max-output $bad is a usage error"
done
run "$LAMINA" validate cube100.ug --max-output 1M
like "$RC $ERR" "^2 lamina validate: option --max-output does not apply to 'validate'" "validate writes no program: no --max-output"

# ---- the estimate counts what the planners write --------------------------------
# Every shipped profile on parts of different kinds (boxes, a frame with an
# island, a hole, a sphere of facets): the estimate `info` gives (the one
# `slice` checks) within a factor of 2 of the program written.
python3 "$TESTS/cli/meshgen.py" sphere sphere.stl
for prof in "$ROOT"/machines/*.yaml; do
    pn=$(basename "$prof" .yaml)
    for part in "$M/frame_island.stl" "$M/cube_hole.stl" "$M/thesis_cube.ug" sphere.stl; do
        est=$("$LAMINA" info "$part" -m "$pn" --json 2>/dev/null | sed -n 's/.*"run":{[^}]*"bytes":\([0-9]*\)}.*/\1/p')
        "$LAMINA" slice "$part" -m "$pn" -q -o est.out 2>/dev/null
        act=$(wc -c <est.out 2>/dev/null || echo 0)
        rm -f est.out
        ok "$(awk -v e="${est:-0}" -v a="$act" 'BEGIN { print (a > 0 && e >= a / 2 && e <= 2 * a) ? 0 : 1 }')" \
            "$pn, $(basename "$part"): estimate $est bytes, program $act bytes: within 2x"
    done
done

# A stripe width of 1e-4 on the 40 x 40 frame: 400,000 stripes a layer cut
# every hatch line (400 of them) into 400,000 pieces: over 10^11 vectors in
# 667 layers, terabytes. Refused before planning with the estimate; and
# with no memory to speak of: under a 1 GB address space (not under the
# sanitizers, whose shadow memory needs terabytes of it).
for sw in 1e-4 1e-6; do
    printf 'inherits: lpbf-cli\nstripe_width: %s\n' "$sw" >fine.yaml
    if ldd "$LAMINA" 2>/dev/null | grep -q libasan; then
        run "$LAMINA" slice "$M/frame_island.stl" -m ./fine.yaml -j 4 -o fine.cli
    else
        run bash -c 'ulimit -v 1048576 && exec "$@"' - "$LAMINA" slice "$M/frame_island.stl" -m ./fine.yaml -j 4 -o fine.cli
    fi
    like "$RC $ERR" "^1 lamina: the job would write about [0-9.]+ [TP]B \(667 layers, [0-9.e+]+ contour points, [0-9.]+e\+1[0-9] hatch vectors\), more than the limit of 4 GB
lamina: raise the limit with --max-output SIZE" "stripe_width $sw: refused before planning, within 1 GB of memory"
    ok $(ls | grep -q 'fine\.cli' && echo 1 || echo 0) "stripe_width $sw: no output file, not even a temporary"
done
printf 'inherits: lpbf-cli\nhatch_distance: 2e-5\n' >fine.yaml
run "$LAMINA" slice "$M/frame_island.stl" -m ./fine.yaml -j 4 -o fine.cli
like "$RC $ERR" "^1 lamina: the job would write about [0-9.]+ [GT]B .*hatch vectors\), more than the limit of 4 GB" \
    "hatch_distance 2e-5: 5000 times the lines, refused before planning"

# ---- the other outputs ---------------------------------------------------------
# --json writes every vector as an object with its kind and ends; the
# viewer's page is compact (smaller than a hatched program: docs/viewer.md)
# but carries its own 40 kB script: both several times a contour-only CLI
# program's bytes. Each is estimated by its own writer and held to
# --max-output as the program is.
"$LAMINA" slice "$M/frame_island.stl" -m cli-ascii -w 0.5 -q -o fr.cli --json fr.json --html fr.html --svg fr.svg
prog=$(wc -c <fr.cli) json=$(wc -c <fr.json) html=$(wc -c <fr.html) svg=$(wc -c <fr.svg)
ok $((json > 2 * prog && html > 2 * prog ? 0 : 1)) "the JSON ($json) and the viewer ($html) are over twice the program ($prog)"
rm -f fr.*
for o in json html; do
    run "$LAMINA" slice "$M/frame_island.stl" -m cli-ascii -w 0.5 --max-output $((2 * prog)) -o fr.cli --$o fr.$o
    like "$RC $ERR" "^1 lamina: --$o fr\.$o would write about [0-9.]+ [kM]B \(40 layers, .*\), more than the limit of [0-9.]+ [kM]B
lamina: raise the limit with --max-output SIZE" "--$o: refused before planning when its estimate passes --max-output"
    ok $(ls | grep -q '^fr\.' && echo 1 || echo 0) "--$o: no file written"
done
# the SVG sheet draws every layer of a 40-layer run: over the program here
"$LAMINA" slice "$M/thesis_cube.ug" -m sls-contours -q -o tc.sls --svg tc.svg
prog=$(wc -c <tc.sls) svg=$(wc -c <tc.svg)
ok $((svg > prog + 1000 ? 0 : 1)) "the thesis cube's sheet ($svg bytes) is larger than its program ($prog)"
rm -f tc.*
run "$LAMINA" slice "$M/thesis_cube.ug" -m sls-contours --max-output $((prog + 1000)) -o tc.sls --svg tc.svg
like "$RC $ERR" "^1 lamina: tc\.svg: cannot write output: output exceeds the limit of $((prog + 1000)) bytes
lamina: raise the limit with --max-output" "--svg: held to --max-output as it is written"
ok $(ls | grep -q '^tc\.' && echo 1 || echo 0) "--svg: no file written, the program neither"

done_testing
