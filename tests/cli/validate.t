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
like "$OUT" 'layer 3 \(h=1\.25\): 2 contours, 1 confirmed, 1 disagreeing' "the disagreement is reported per layer"
like "$OUT" 'contour 2 \(hole\) disagrees at \(' "... with the contour and its position"
run "$LAMINA" validate "$ov" -w 0.5 --json
is "$(jq '[.layers[] | select(.disagreeing > 0) | .index] | join(",")' -r <<<"$OUT")" "2,3" "JSON lists the disagreeing layers"
run "$LAMINA" validate "$ov" -w 0.5 --fill nonzero
is "$RC" 0 "non-zero fill: one merged outline, confirmed"
run "$LAMINA" slice "$ov" -w 0.5 --fill nonzero -m cli-ascii
is "$(grep -c POLYLINE <<<"$OUT")" 6 "non-zero: one outline per layer"
like "$OUT" '\$\$POLYLINE/1,1,9,' "the merged overlap layer is an 8-corner outline (closed: 9 points; part id 1)"

# slice --validate writes nothing when a label disagrees.
run "$LAMINA" slice "$ov" -w 0.5 --validate -o "$TMP/ov.sls"
is "$RC" 3 "slice --validate: exit 3"
like "$ERR" "disagree with the model; nothing written" "slice --validate says why"
ok "$([ ! -e "$TMP/ov.sls" ]; echo $?)" "no output file"
run "$LAMINA" slice "$ov" -w 0.5 --validate --fill nonzero -o "$TMP/ov.sls"
is "$RC" 0 "slice --validate --fill nonzero: exit 0"
ok "$([ -s "$TMP/ov.sls" ]; echo $?)" "... and the program is written"

# Faces 1e-4 above and below the cut (counterbores of a 200 x 200 x 10 plate,
# tests/models/validate/counterbores.ug): before the winding was taken at
# the section itself, test points lifted off the plane crossed them (one
# false disagreement at z = 9 for the middle cut, one at z = 2 for the
# ceiling cut). Every section is the plate minus two 20 x 20 holes
# (39200), or minus one 40 x 40 and one 20 x 20 where a counterbore is cut
# (38000).
cb="$M/validate/counterbores.ug"
for axis in x y z; do
    for cut in floor middle ceiling; do
        for w in 2 1 0.5; do
            run "$LAMINA" validate "$cb" -a $axis -w $w --cut $cut
            is "$RC" 0 "counterbores along $axis, -w $w --cut $cut: no false disagreement"
            [ "$RC" = 0 ] || echo "$OUT" | grep -m3 -A1 '^layer' | sed 's/^/# /'
        done
    done
done
run "$LAMINA" validate "$cb" -w 2 --json
# cuts at 1 (under the bottom counterbore's roof at 1.9999), 3, 5, 7 and 9
# (1e-4 under the top counterbore's floor): only the first cuts a counterbore
is "$(jq -c '[.layers[] | .net_area]' <<<"$OUT")" "[38000,39200,39200,39200,39200]" \
    "counterbores, middle cuts: net areas 38000 (a counterbore cut), then 39200 (two plain holes)"
is "$(jq -c '[.layers[] | .section_area] | map(. * 1000 | round / 1000)' <<<"$OUT")" "[38000,39200,39200,39200,39200]" \
    "... and the model's own sections agree"
is "$(jq -c '[.areas_compared, .areas_differing, .disagreeing]' <<<"$OUT")" "[5,0,0]" "every layer's area compared, none differ"

# validate --program: each shipped contour dialect read back and checked.
for model in thesis_cube_hole.ug frame_island.ug validate/counterbores.ug; do
    for mch in sls-contours cli-ascii cli-binary; do
        for opts in "-w 0.5 --cut floor" "-w 0.7" "-a x -w 0.4 --cut ceiling"; do
            "$LAMINA" slice "$M/$model" -m $mch $opts -o "$TMP/p.out" 2>/dev/null
            run "$LAMINA" validate "$M/$model" -m $mch $opts --program "$TMP/p.out"
            is "$RC" 0 "$model, $mch ($opts): the program read back passes"
            [ "$RC" = 0 ] || echo "$OUT" | grep -m4 -v '^layer.* 0 disagreeing' | sed 's/^/# /'
        done
    done
done
# the machine frame: (u, v, w) written; -a and --frame say how to read it
"$LAMINA" slice "$M/frame_island.ug" -a x -w 2 --frame machine -o "$TMP/fm.sls"
run "$LAMINA" validate "$M/frame_island.ug" -a x -w 2 --frame machine --program "$TMP/fm.sls"
is "$RC" 0 "an SLS program in the machine frame passes read as such"
run "$LAMINA" validate "$M/frame_island.ug" -a x -w 2 --program "$TMP/fm.sls"
is "$RC" 1 "... read in the model frame: an input error"
like "$ERR" "fm\.sls:2:1: point 1 of this loop is .* from its plane .*machine frame" \
    "... at the loop's file:line:column, suggesting the frame"

# one solid reversed (written clockwise) in an SLS program: exit 3, naming
# the layer and the contour with its place in the file
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.5 -o "$TMP/ok.sls"
awk 'NR >= 3 && NR <= 6 { b[NR] = $0; if (NR == 6) for (i = 6; i >= 3; i--) print b[i]; next } { print }' \
    "$TMP/ok.sls" >"$TMP/flip.sls"
ok "$(cmp -s "$TMP/ok.sls" "$TMP/flip.sls"; [ $? = 1 ]; echo $?)" "the first loop's vertices reversed"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" -w 0.5 --program "$TMP/flip.sls"
is "$RC" 3 "a solid written clockwise in an SLS program: exit 3"
like "$OUT" '^layer 1 \(h=0\.25\): 2 contours, 1 confirmed, 1 disagreeing$' "... the layer named"
like "$OUT" '^  contour 1 \(hole, \S*flip\.sls:2:1\) disagrees at \(' "... the contour named with its line (a hole to the machine)"
like "$OUT" '^  net area -5 \(solids minus holes\) but the model.s section has 3: off by -8' \
    "... and the layer's net area against the section (4 - 1 = 3, not -4 - 1)"
# the same in CLI: the direction field says solid, the points run clockwise
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.5 -m cli-ascii -o "$TMP/ok.cli"
perl -pe 'if (!$done && s{^\$\$POLYLINE/(\d+),1,(\d+),(.*)$}{my @p = split /,/, $3; my @q; while (@p) { unshift @q, splice(@p, 0, 2) } "\$\$POLYLINE/$1,1,$2," . join(",", @q)}e) { $done = 1 }' \
    "$TMP/ok.cli" >"$TMP/flip.cli"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" -w 0.5 --program "$TMP/flip.cli"
is "$RC" 3 "a CLI polyline labelled solid (dir 1) but written clockwise: exit 3"
like "$OUT" '^  contour 1 \(solid, \S*flip\.cli:11:1\) direction: written clockwise but labelled solid' \
    "... named as written clockwise but labelled solid, at its line"
# and its direction field flipped instead (points right, label wrong)
sed '0,/^\$\$POLYLINE\/1,1,/s//$$POLYLINE\/1,0,/' "$TMP/ok.cli" >"$TMP/dir.cli"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" -w 0.5 --program "$TMP/dir.cli" --json
is "$RC" 3 "a CLI polyline with its direction field flipped: exit 3"
is "$(jq -c '[.layers[0].disagreements[0] | .contour, .line, (.problems | map(.check) | join(","))]' <<<"$OUT")" \
    '[0,11,"material,direction,nesting"]' "... JSON names the contour, its line and each check that fails"
# a binary CLI with one polyline's direction byte flipped
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.5 -m cli-binary -o "$TMP/ok.bcli"
python3 - "$TMP/ok.bcli" "$TMP/flip.bcli" <<'PY'
import struct, sys
d = bytearray(open(sys.argv[1], "rb").read())
p = d.index(b"$$HEADEREND") + len(b"$$HEADEREND")
while True:
    cmd, = struct.unpack_from("<H", d, p)
    if cmd == 127: p += 6; continue
    assert cmd == 130
    struct.pack_into("<i", d, p + 6, 0)  # the first polyline (a solid) now says hole
    break
open(sys.argv[2], "wb").write(d)
PY
run "$LAMINA" validate "$M/thesis_cube_hole.ug" -w 0.5 --program "$TMP/flip.bcli"
is "$RC" 3 "binary CLI, a solid's direction set to hole: exit 3"
like "$OUT" '^  contour 1 \(hole, \S*flip\.bcli: byte \d+\) direction: written counter-clockwise but labelled hole' \
    "... named with its byte offset"

# programs that cannot be read: file:line:column, exit 1, nothing checked
printf 'contour 0.25\nloop 3\n0 0 0.25\n1 0 0.25\nendloop\n' >"$TMP/short.sls"
run "$LAMINA" validate "$M/thesis_cube.ug" --program "$TMP/short.sls"
like "$RC $ERR" '^1 lamina: \S*short\.sls:5:1: .*not a number|^1 lamina: \S*short\.sls:5:1: vertex 3 of 3' \
    "a loop one vertex short: file:line:column"
printf '$$HEADERSTART\n$$ASCII\n$$LAYERS/1\n$$HEADEREND\n$$GEOMETRYSTART\n$$LAYER/0.5\n$$POLYLINE/1,1,4,0,0,1,0,1,1,0,1\n$$GEOMETRYEND\n' >"$TMP/open.cli"
run "$LAMINA" validate "$M/thesis_cube.ug" --program "$TMP/open.cli"
like "$RC $ERR" '^1 lamina: \S*open\.cli:7:1: the polyline is not closed' "an unclosed CLI polyline: file:line:column"
run "$LAMINA" validate "$M/thesis_cube.ug" --frame machine
is "$RC" 2 "--frame without --program: usage error"

run "$LAMINA" validate "$M/thesis_cube.ug" --fill odd
is "$RC" 2 "bad --fill: usage error"
run "$LAMINA" validate "$M/thesis_cube.ug" -o x
is "$RC" 2 "an option of another command: usage error"
done_testing
