#!/usr/bin/env bash
# validate -j N (issue 15): workers slice (or make the layers of a program
# read back) and check them, the main thread reports them in layer order,
# so the text report, the JSON, the messages and the exit status are the
# same for every number of threads. Models with a cavity, an island, an
# oblique axis, flat faces on the cut planes, labels that disagree
# (overlapping shells under even-odd; a solid written clockwise in a
# program), programs of each contour dialect, and a program whose third
# and fourth layers cannot be read (the first error, after the layers
# before it, for every N).
. "$TESTS/cli/lib.sh"

python3 "$TESTS/cli/meshgen.py" sphere "$TMP/sphere.stl"
python3 "$TESTS/cli/meshgen.py" torus "$TMP/torus.stl"

# same NAME ARGS...: validate ARGS with -j 1, then 2, 3 and 8: standard
# output and standard error byte for byte, exit status
same() {
    local name=$1
    shift
    "$LAMINA" validate "$@" -j 1 >"$TMP/$name.1" 2>"$TMP/$name.err1"
    local rc1=$? size
    size=$(stat -c %s "$TMP/$name.1")
    ok $(( size > 100 ? 0 : 1 )) "$name: -j 1 reports (exit $rc1, $size bytes)"
    for j in 2 3 8; do
        "$LAMINA" validate "$@" -j "$j" >"$TMP/$name.$j" 2>"$TMP/$name.err$j"
        local rc=$?
        cmp -s "$TMP/$name.1" "$TMP/$name.$j" && cmp -s "$TMP/$name.err1" "$TMP/$name.err$j" && [ "$rc" = "$rc1" ]
        ok $? "$name: -j $j reports what -j 1 does (exit $rc)"
        if ! cmp -s "$TMP/$name.1" "$TMP/$name.$j"; then
            diff "$TMP/$name.1" "$TMP/$name.$j" | head -5 | sed 's/^/# /'
        fi
    done
    RC1=$rc1
}

# -v: a line for every layer (the stage times on standard error vary, so
# the verbose runs compare standard output and the exit status only)
same_v() {
    local name=$1
    shift
    "$LAMINA" validate "$@" -v -j 1 >"$TMP/$name.1" 2>/dev/null
    local rc1=$?
    for j in 2 3 8; do
        "$LAMINA" validate "$@" -v -j "$j" >"$TMP/$name.$j" 2>/dev/null
        local rc=$?
        cmp -s "$TMP/$name.1" "$TMP/$name.$j" && [ "$rc" = "$rc1" ]
        ok $? "$name -v: -j $j reports every layer as -j 1 does"
    done
}

# the JSON report has every layer's figures (the text one only the layers
# that disagree): all the models in JSON, two in text
same "cube-hole-json" "$M/thesis_cube_hole.ug" -w 0.3 --json
same "frame-island-json" "$M/frame_island.ug" -w 0.5 --cut floor --json
same "frame-oblique-json" "$M/frame_island.stl" -a 1,1,2 -w 0.25 --json
same "cube-hole-x-json" "$M/cube_hole.stl" -a x -w 0.1 --cut ceiling --json
same "counterbores-json" "$M/validate/counterbores.ug" -w 0.5 --cut middle --json
same "sphere-json" "$TMP/sphere.stl" -w 0.05 --json
same "torus-oblique-json" "$TMP/torus.stl" -a 1,1,2 -w 0.05 --json
for fmt in "" --json; do
    same "overlap${fmt:+-json}" "$M/validate/overlap_cubes.ug" -w 0.25 $fmt
    is "$RC1" 3 "overlapping shells under even-odd disagree (exit 3), for every N above"
done
same "counterbores" "$M/validate/counterbores.ug" -w 0.5
is "$(jq -c '[(.layers | length), .checked, .confirmed]' "$TMP/sphere-json.1")" "[160,160,160]" \
    "the sphere: 160 layers, one contour each, all confirmed"
is "$(jq -c '[.layers[] | .index] == [range(160)]' "$TMP/sphere-json.8")" true \
    "... and -j 8 lists them in layer order"
like "$(cat "$TMP/overlap.1")" 'contour 2 \(hole\) disagrees at \(' "the overlap's disagreement is named"
same_v "frame-island" "$M/frame_island.ug" -w 0.5
same_v "overlap" "$M/validate/overlap_cubes.ug" -w 0.25 --fill nonzero

# programs read back, each contour dialect and a run's JSON (validate
# given the options they were sliced with: their layers must be those)
for mch in sls-contours cli-ascii cli-binary; do
    "$LAMINA" slice "$M/frame_island.ug" -m $mch -w 0.4 -o "$TMP/p.$mch" 2>/dev/null
    same "program-$mch-json" "$M/frame_island.ug" -m $mch -w 0.4 --program "$TMP/p.$mch" --json
done
same_v "program-cli-binary" "$M/frame_island.ug" -m cli-binary -w 0.4 --program "$TMP/p.cli-binary"
"$LAMINA" slice "$TMP/torus.stl" -a 1,1,2 -w 0.1 --json "$TMP/torus.json" -o "$TMP/torus.sls" 2>/dev/null
same "program-run-json" "$TMP/torus.stl" --program "$TMP/torus.json" --json
same "program-oblique-sls" "$TMP/torus.stl" -a 1,1,2 -w 0.1 --program "$TMP/torus.sls" --json
# a solid written clockwise (its loop's vertices reversed): exit 3, the
# contour named with its line, for every N
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.5 -o "$TMP/ok.sls"
awk 'NR >= 21 && NR <= 24 { b[NR] = $0; if (NR == 24) for (i = 24; i >= 21; i--) print b[i]; next } { print }' \
    "$TMP/ok.sls" >"$TMP/flip.sls"
same "program-flipped" "$M/thesis_cube_hole.ug" -w 0.5 --program "$TMP/flip.sls"
is "$RC1" 3 "a solid written clockwise in layer 2: exit 3"
like "$(cat "$TMP/program-flipped.1")" '^layer 2 \(h=0\.75\): 2 contours, 1 confirmed, 1 disagreeing$' \
    "... layer 2 named"
# one point of layers 3 and 4 off their planes: the error is layer 3's,
# after layers 1 and 2 were reported, for every N
awk 'NR == 39 || NR == 57 { $3 = "1.500000" } { print }' "$TMP/ok.sls" >"$TMP/bad.sls"
same_v "program-bad" "$M/thesis_cube_hole.ug" -w 0.5 --program "$TMP/bad.sls"
is "$(cat "$TMP/program-bad.8")" "layer 1 (h=0.25): 2 contours, 2 confirmed, 0 disagreeing
layer 2 (h=0.75): 2 contours, 2 confirmed, 0 disagreeing" "... layers 1 and 2 reported, nothing after"
for j in 1 2 3 8; do
    run "$LAMINA" validate "$M/thesis_cube_hole.ug" -w 0.5 --program "$TMP/bad.sls" -j $j
    like "$RC $ERR" "^1 lamina: \S*bad\.sls:38:1: point 1 of this loop is 0\.25 from its plane" \
        "-j $j: the first error is layer 3's, at its loop (exit 1)"
done

# LAMINA_THREADS when -j is not given
LAMINA_THREADS=3 "$LAMINA" validate "$TMP/sphere.stl" -w 0.05 --json >"$TMP/env3" 2>&1
cmp -s "$TMP/env3" "$TMP/sphere-json.1"
ok $? "LAMINA_THREADS=3: the report of -j 1"
LAMINA_THREADS=lots run "$LAMINA" validate "$M/thesis_cube_hole.ug"
like "$RC $ERR" "^2 .*LAMINA_THREADS must be a number of threads .*'lots'" "LAMINA_THREADS=lots: an error naming it"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" -j 0
like "$RC $ERR" '^2 .*-j takes a number of threads from 1 to 256' "-j 0: usage error"

# bad layer options: the same message and status for every N, no report
for opts in "--widths 0.5,0.5" "--planes 1" "-w 0"; do
    run "$LAMINA" validate "$M/thesis_cube_hole.ug" $opts -j 1
    rc1=$RC err1=$ERR out1=$OUT
    ok $(( rc1 == 2 && ${#out1} == 0 ? 0 : 1 )) "$opts: usage error with -j 1 (exit $rc1), nothing on standard output"
    for j in 2 3 8; do
        run "$LAMINA" validate "$M/thesis_cube_hole.ug" $opts -j $j
        [ "$RC" = "$rc1" ] && [ "$ERR" = "$err1" ] && [ -z "$OUT" ]
        ok $? "$opts: -j $j gives the same message"
    done
done
done_testing
