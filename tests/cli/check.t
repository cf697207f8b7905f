#!/usr/bin/env bash
# lamina check: walls thinner than the bead and overhangs steeper than the
# profile's limit are violations (exit 3); thicker walls and a chamfer pass.
. "$(dirname "$0")/lib.sh"
D="$M/drc"
P="$D/ladrp45.yaml"   # creol-ladrp (bead 0.08) with max_overhang_deg 45

run "$LAMINA" check "$D/plate_thin.ug" -m "$P"
is "$RC" 3 "a 0.05 plate under a 0.08 bead: exit 3"
like "$OUT" 'min_wall: wall 0\.05 thick at \(' "the thin wall is reported with its thickness and position"
like "$OUT" 'plate_thin\.ug:5:' "... and the source face"
run "$LAMINA" check "$D/plate_thick.ug" -m "$P"
is "$RC" 0 "the same plate 0.5 thick passes"
like "$OUT" '0 violations' "no violation reported"

run "$LAMINA" check "$D/shelf.ug" -m "$P"
is "$RC" 3 "a flat shelf underside: exit 3"
like "$OUT" "max_overhang: overhang 90 degrees from vertical at \(3, 1\.33333, 3\), limit 45 \(face 'underside'" "the overhang is reported on the underside face"
run "$LAMINA" check "$D/chamfer.ug" -m "$P"
is "$RC" 0 "a chamfer 39.8 degrees from vertical passes"
run "$LAMINA" check "$D/shelf.ug" -m creol-ladrp
is "$RC" 0 "without max_overhang_deg the overhang rule is off"

run "$LAMINA" check "$D/shelf.ug" -m "$P" --json
jq -e . >/dev/null <<<"$OUT"; ok $? "--json is valid JSON"
is "$(jq -c '[.violations[0].rule, .violations[0].value, .violations[0].limit, .violations[0].area]' <<<"$OUT")" \
   '["max_overhang",90,45,6]' "JSON: rule, measured value, limit, area"

# the check works for every earlier model without false alarms
for f in thesis_cube.ug thesis_cube_hole.ug frame_island.ug cube_hole.stl; do
    run "$LAMINA" check "$M/$f" -m "$P"
    is "$RC" 0 "$f: no violation"
done

# --svg rings the violation on the layer that holds it
run "$LAMINA" check "$D/plate_thin.ug" -m "$P" -w 0.025 --svg "$TMP/plate.svg"
is "$RC" 3 "--svg: still exit 3"
is "$(grep -c '<circle' "$TMP/plate.svg")" 2 "two rings: the plate's bottom on layer 0, its top on layer 1"
rsvg-convert -f png -o "$TMP/plate.png" "$TMP/plate.svg"; ok $? "the sheet renders"

run "$LAMINA" check "$D/plate_thin.ug"
is "$RC" 2 "no machine: usage error"
# powder bed (issue 27): each layer's overhang that does not stand within the
# reach (w tan 45 = 1 at -w 1) of the layer below. The tee (supportgen.py:
# a stem 5 wide, 8 deep, 10 high under a bar 20 x 8): on layer 11, its
# bar's first, the bar less the stem grown by the reach, (20 - 5 - 2) x 8 =
# 104 mm², does not stand without supports; lpbf-cli's block supports hold it
python3 "$TESTS/cli/supportgen.py" tee "$TMP/tee.stl"
run "$LAMINA" check "$TMP/tee.stl" -m lpbf-cli -w 1 -s support_type=none
is "$RC" 3 "powder bed, no supports: an unsupported overhang, exit 3"
like "$OUT" '^unsupported: layer 11 \(z 10\.5\): 104 mm² of overhang beyond the reach of the layer below \(support_angle 45, supports: none\)$' \
    "... its layer, height and area"
like "$OUT" 'tee\.stl: unsupported overhangs on 1 layer, 104 mm² in all' "... and the summary"
run "$LAMINA" check "$TMP/tee.stl" -m lpbf-cli -w 1
is "$RC" 0 "lpbf-cli's own block supports: every overhang stands (exit 0)"
like "$OUT" 'tee\.stl: every overhang stands \(support_angle 45; supports: block, on 10 layers' "... on the 10 layers under the bar"
run "$LAMINA" check "$TMP/tee.stl" -m lpbf-cli -w 1 -s support_type=none -s support_angle=90
is "$RC" 0 "support_angle 90: nothing needs support"
run "$LAMINA" check "$TMP/tee.stl" -m lpbf-cli -w 1 -s support_type=none --json
is "$(jq -c '[.overhangs.unsupported_layers, (.overhangs.layers[] | select(.unsupported > 0) | [.layer, (.unsupported | round)])]' <<<"$OUT")" \
   '[1,[11,104]]' "--json: the overhangs member names the layer and its area"
done_testing
