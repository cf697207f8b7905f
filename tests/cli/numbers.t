#!/usr/bin/env bash
# Numbers for people (README, Choices): what a person reads has no
# arithmetic noise (108.4, not 108.39999999999999) and reads back as typed;
# two numbers that differ print differently; layers and contours are
# counted from 1 in every message, report and picture, as Lua counts them;
# machine programs keep their own numbering.
. "$(dirname "$0")/lib.sh"

# A box from 1.7 to 110.1 on every axis: 110.1 - 1.7 is 108.39999999999999
# in doubles. Side 108.4: area 6 * 108.4^2 = 70503.36, volume 108.4^3 =
# 1273760.704.
python3 - "$TMP/box.ug" <<'PY'
import sys
lo, hi = "1.7", "110.1"
c = {"a": (lo, lo, lo), "b": (hi, lo, lo), "c": (hi, hi, lo), "d": (lo, hi, lo),
     "e": (lo, lo, hi), "f": (hi, lo, hi), "g": (hi, hi, hi), "h": (lo, hi, hi)}
with open(sys.argv[1], "w") as f:
    for k, p in c.items():
        f.write("v %s %s %s %s;\n" % ((k,) + p))
    f.write("f bottom (a d c b);\nf top (e f g h);\nf front (a b f e);\n"
            "f back (c d h g);\nf left (d a e h);\nf right (b c g f);\n")
PY
run "$LAMINA" info "$TMP/box.ug"
is "$RC" 0 "info of the box"
like "$OUT" '^bbox x +\[1\.7, 110\.1\] \(size 108\.4\)$' "info: the extent as typed, the size without noise"
like "$OUT" '^surface area +70503\.36$' "info: the area 6 * 108.4^2"
like "$OUT" '^volume +1273760\.704$' "info: the volume 108.4^3"
run "$LAMINA" info "$TMP/box.ug" --json
is "$(jq -r '.bbox.max[0] - .bbox.min[0] == 110.1 - 1.7' <<<"$OUT")" true "info --json keeps every bit (for programs)"

# layer heights: the middles of layers of 0.7 from 1.7 (1.7 + 0.35 +
# 0.7 k), each with two decimals at most
run "$LAMINA" validate "$TMP/box.ug" -w 0.7
bad=$(awk '/^layer / { k = $2; h = $3; sub(/^\(h=/, "", h); sub(/\):$/, "", h)
      want = sprintf("%.2f", 2.05 + 0.7 * (k - 1)); sub(/0+$/, "", want); sub(/\.$/, "", want)
      if (h != want) print k, h, want }' <<<"$OUT")
is "$bad" "" "validate: every layer's height as 1.7 + 0.35 + 0.7 (k - 1) to two decimals"
like "$OUT" '^layer 1 \(h=2\.05\): 1 contour, 1 confirmed, 0 disagreeing$' "... and the first layer is layer 1"
like "$OUT" '^layer 155 \(h=109\.85\): ' "... the last layer 155 (the 108.4 extent in layers of 0.7)"

# numbers that differ print differently, with as many digits as that takes
run "$LAMINA" slice "$M/thesis_cube.ug" --planes -1,0.0002,100.0002,100.0001 -o "$TMP/x.sls"
like "$ERR" 'planes must increase strictly \(plane 4 is 100\.0001 after 100\.0002\)' "a plane to 7 digits (not %g's 100 after 100)"
run "$LAMINA" slice "$M/thesis_cube.ug" --widths 1,0.9999999 -o "$TMP/x.sls"
like "$ERR" 'the widths add up to 1\.9999999 but the model spans 2 along' "widths that fall short by 1e-7"
run "$LAMINA" slice "$M/thesis_cube.ug" --widths 0.1,0.2,0.3,0.4,0.5,0.4999999999999999 -o "$TMP/x.sls"
like "$ERR" 'the widths add up to 2 but the model spans 2 along the axis \(they end at 0\.9999999999999999, the model at 1\)' \
    "widths that fall short by an ulp: the ends, exactly"

# one layer numbering for people: slice's notes, validate's report, the
# contact sheet and Lua agree that the cube with the hole in layers of 0.5
# has layer 1 at h=0.25 and layer 4 at h=1.75
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.5 -o "$TMP/h.sls" --svg "$TMP/h.svg"
is "$(grep -o 'layer [0-9]*  h=[0-9.]*' "$TMP/h.svg" | tr '\n' ';')" \
    "layer 1  h=0.25;layer 2  h=0.75;layer 3  h=1.25;layer 4  h=1.75;" "the contact sheet: layers 1 to 4"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" -w 0.5
is "$(grep -o '^layer [0-9]* (h=[0-9.]*)' <<<"$OUT" | tr '\n' ';')" \
    "layer 1 (h=0.25);layer 2 (h=0.75);layer 3 (h=1.25);layer 4 (h=1.75);" "validate: layers 1 to 4"
run "$LAMINA" -e "local ls = lamina.load('$M/thesis_cube_hole.ug'):slice{width = 0.5}
for i, l in ipairs(ls) do io.write('layer ', l.index, ' (h=', l.z, ');') end"
is "$OUT" "layer 1 (h=0.25);layer 2 (h=0.75);layer 3 (h=1.25);layer 4 (h=1.75);" "Lua: layers 1 to 4"
# contours too: the overlap of two cubes, labelled a hole, is the second
# contour of layer 3 to validate and to Lua
run "$LAMINA" validate "$M/validate/overlap_cubes.ug" -w 0.5
like "$OUT" '^  contour 2 \(hole\) disagrees at ' "validate: contour 2 of layer 3 disagrees"
like "$OUT" '^  contour 2 \(hole\) nesting: .*\(depth 1, parent contour 1; no contour around it\)' \
    "... its parent is contour 1"
run "$LAMINA" -e "local l = lamina.load('$M/validate/overlap_cubes.ug'):slice{width = 0.5}[3]
io.write(l.z, ' ', l:contour(2).kind, ' ', tostring(l:contour(2).parent == l:contour(1)))"
is "$OUT" "1.25 hole true" "Lua: layer 3 (h=1.25), its contour 2 a hole inside contour 1"

# programs keep their own numbering: the thesis's SLS dialect has no layer
# numbers; ded-gcode numbers its layers from 1 ({number}), cli-ascii's
# $$LAYER gives heights only
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.5 -m ded-gcode -o "$TMP/h.gcode"
is "$(grep -c '^; layer [1-4] ' "$TMP/h.gcode")" 4 "ded-gcode: layers numbered 1 to 4, as its template says"

done_testing
