#!/usr/bin/env bash
# lamina validate and slice --validate: every label of every model checked
# along x, y and z (planes through vertices and flat faces included); the
# overlapping-cubes case proves the check can fail, and non-zero fill mends it.
. "$(dirname "$0")/lib.sh"

for model in thesis_cube_hole.ug frame_island.ug thesis_cube.ug cube_hole.stl frame_island.stl; do
    for axis in x y z; do
        for opts in "-w 0.5 --cut floor" "-w 1 --cut ceiling" "-w 0.3"; do
            run "$LAMINA" validate "$M/$model" -a $axis $opts
            is "$RC" 0 "$model along $axis ($opts): every label confirmed"
            [ "$RC" = 0 ] || echo "$OUT" | grep -m3 disagree | sed 's/^/# /'
        done
    done
done
run "$LAMINA" validate "$M/thesis_cube_hole.ug" -w 1 --cut floor --json
jq -e . >/dev/null <<<"$OUT"; ok $? "--json is valid JSON"
is "$(jq -c '[.checked, .confirmed, .disagreeing]' <<<"$OUT")" "[4,4,0]" "the cavity's hole confirmed: 4 contours checked, 4 confirmed"
run "$LAMINA" validate "$M/frame_island.ug" -w 5 --json
is "$(jq -c '[.layers[0].contours, .layers[0].confirmed]' <<<"$OUT")" "[3,3]" "frame with island: depths 0/1/2 confirmed"

# Two overlapping cubes as separate shells.
ov="$M/validate/overlap_cubes.ug"
run "$LAMINA" validate "$ov" -w 0.5
is "$RC" 3 "even-odd: the overlap is labelled a hole and validation disagrees (exit 3)"
like "$OUT" 'layer 2 \(h=1\.25\): 2 contours, 1 confirmed, 1 disagreeing' "the disagreement is reported per layer"
like "$OUT" 'contour 1 \(hole\) disagrees at \(' "... with the contour and its position"
run "$LAMINA" validate "$ov" -w 0.5 --json
is "$(jq '[.layers[] | select(.disagreeing > 0) | .index] | join(",")' -r <<<"$OUT")" "2,3" "JSON lists the disagreeing layers"
run "$LAMINA" validate "$ov" -w 0.5 --fill nonzero
is "$RC" 0 "non-zero fill: one merged outline, confirmed"
run "$LAMINA" slice "$ov" -w 0.5 --fill nonzero -m cli-ascii
is "$(grep -c POLYLINE <<<"$OUT")" 6 "non-zero: one outline per layer"
like "$OUT" '\$\$POLYLINE/3,1,9,' "the merged overlap layer is an 8-corner outline (closed: 9 points)"

# slice --validate writes nothing when a label disagrees.
run "$LAMINA" slice "$ov" -w 0.5 --validate -o "$TMP/ov.sls"
is "$RC" 3 "slice --validate: exit 3"
like "$ERR" "disagree with the model; nothing written" "slice --validate says why"
ok "$([ ! -e "$TMP/ov.sls" ]; echo $?)" "no output file"
run "$LAMINA" slice "$ov" -w 0.5 --validate --fill nonzero -o "$TMP/ov.sls"
is "$RC" 0 "slice --validate --fill nonzero: exit 0"
ok "$([ -s "$TMP/ov.sls" ]; echo $?)" "... and the program is written"

run "$LAMINA" validate "$M/thesis_cube.ug" --fill odd
is "$RC" 2 "bad --fill: usage error"
run "$LAMINA" validate "$M/thesis_cube.ug" -o x
is "$RC" 2 "an option of another command: usage error"
done_testing
