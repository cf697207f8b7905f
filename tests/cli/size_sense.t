#!/usr/bin/env bash
# Size sense (lua/cli/size_sense.h): before a run, a warning with the
# numbers when the layer count or the model's extent is far beyond the
# part's scale: more than 100,000 layers; a model more than 2000 mm or
# less than 0.5 mm across in the machine profile's units. Warnings only:
# the run goes on and writes its program; --max-layers refuses.
. "$(dirname "$0")/lib.sh"

# cube S: a cube of side S centred on the origin, as Unigrafix
cube() {
    local h
    h=$(echo "$1 / 2" | bc -l)
    awk -v h="$h" '{ for (i = 1; i <= NF; i++) { if ($i == "-1" || $i == "-1;") sub(/-1/, -h, $i); else if ($i == "1" || $i == "1;") sub(/1/, h, $i) } print }' \
        "$M/thesis_cube.ug" >"$2"
}
cube 3000 "$TMP/big.ug"
cube 0.2 "$TMP/tiny.ug"
run "$LAMINA" info "$TMP/big.ug"
like "$OUT" '^bbox x +\[-1500, 1500\] \(size 3000\)$' "the big cube is 3000 across"
run "$LAMINA" info "$TMP/tiny.ug"
like "$OUT" '^bbox z +\[-0\.1, 0\.1\] \(size 0\.2\)$' "the tiny cube is 0.2 across"

# a part of sensible size: no warning
run "$LAMINA" slice "$M/thesis_cube.ug" -m sls-contours -w 0.5 -o "$TMP/ok.sls"
is "$RC.$ERR" "0." "a 2 mm cube in 4 layers: no warning"

# 3000 units in a mm profile: 3 m
run "$LAMINA" slice "$TMP/big.ug" -m sls-contours -w 500 -o "$TMP/big.sls"
is "$RC" 0 "a 3000 mm part: the run goes on"
like "$ERR" "^lamina: warning: .*big\.ug: the model is 3000 across \(x 3000, y 3000, z 3000\) and sls-contours's units are mm: 3000 mm, larger than 2000 mm; was it drawn in another unit\? If it was drawn in micrometres, --units um makes it 3 mm$" \
    "... with a warning that gives the extent, the unit and the bound"
is "$(grep -c '^contour' "$TMP/big.sls")" 6 "... and writes its program: 3000 / 500 = 6 layers"
run "$LAMINA" slice "$TMP/big.ug" -m creol-ladrp -w 500 -o "$TMP/big.nc"
like "$ERR" "and creol-ladrp's units are cm: 30000 mm, larger than 2000 mm" "in a cm profile it is 30 m"
run "$LAMINA" slice "$TMP/big.ug" -m sls-contours -w 500 -o "$TMP/big.sls" -q
like "$ERR" "^lamina: warning: .*big\.ug: the model is 3000 across" "-q keeps warnings"
run "$LAMINA" slice "$TMP/big.ug" -w 500 -o "$TMP/big.sls"
is "$RC.$ERR" "0." "the built-in profile is no machine: no unit to check, no warning"
run "$LAMINA" validate "$TMP/big.ug" -m sls-contours -w 500
is "$RC" 0 "validate: the big cube checks out"
like "$ERR" "^lamina: warning: .*big\.ug: the model is 3000 across" "... and validate warns too"

# 0.2 units: 0.2 mm in a mm profile, 2 mm in a cm one
run "$LAMINA" slice "$TMP/tiny.ug" -m sls-contours -w 0.05 -o "$TMP/tiny.sls"
is "$RC" 0 "a 0.2 mm part: the run goes on"
like "$ERR" "^lamina: warning: .*tiny\.ug: the model is 0\.2 across \(x 0\.2, y 0\.2, z 0\.2\) and sls-contours's units are mm: 0\.2 mm, smaller than 0\.5 mm; was it drawn in another unit\? If it was drawn in metres, --units m makes it 200 mm$" \
    "... with a warning: smaller than 0.5 mm"
run "$LAMINA" slice "$TMP/tiny.ug" -m creol-ladrp -w 0.05 -o "$TMP/tiny.nc"
ok "$(grep -q warning <<<"$ERR"; [ $? = 1 ]; echo $?)" "0.2 cm is 2 mm: no warning"

# more than 100,000 layers: 2 units in layers of 1e-5 make 200,000
run "$LAMINA" slice "$M/thesis_cube.ug" -w 0.00001 -o "$TMP/thin.sls"
is "$RC" 0 "200000 layers: the run goes on"
like "$ERR" "^lamina: warning: .*thesis_cube\.ug: 200000 layers \(2 along the axis in layers of 1e-05 on average\), more than 100000: is the layer width in the model's units\? \(--max-layers N refuses runs of more than N layers\)$" \
    "... with a warning that gives the count, the extent and the width"
is "$(grep -c '^contour' "$TMP/thin.sls")" 200000 "... and writes all 200000 layers"
rm -f "$TMP/thin.sls"
run "$LAMINA" slice "$M/thesis_cube.ug" -w 0.00002 -o "$TMP/thin.sls"
is "$RC.$ERR" "0." "100000 layers: no warning"
rm -f "$TMP/thin.sls"
run "$LAMINA" slice "$M/thesis_cube.ug" -w 0.00001 --max-layers 150000 -o "$TMP/capped.sls"
is "$RC" 1 "--max-layers 150000 refuses the 200000 layers"
like "$ERR" "200000 layers, more than the limit of 150000" "... saying so"
ok "$([ ! -e "$TMP/capped.sls" ]; echo $?)" "... and writes nothing"

done_testing
