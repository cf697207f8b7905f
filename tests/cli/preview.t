#!/usr/bin/env bash
# slice --svg draws the planned scan paths: checked against the program
# written by the same run and against the part's geometry, by the test's
# own reading of the SVG (svgcheck.py, Python's XML parser).
. "$(dirname "$0")/lib.sh"
C() { python3 "$TESTS/cli/svgcheck.py" "$@"; } # a function: the path may hold spaces
CUBE="$M/thesis_cube_hole.ug"   # 2 x 2 (-1..1), a 1 x 1 hole through it, units: cm for creol-ladrp

# LADRP: one path per deposit, as many as the program deposits
run "$LAMINA" slice "$CUBE" -m creol-ladrp -w 0.5 --svg "$TMP/l.svg" -o "$TMP/l.ladrp"
is "$RC" 0 "LADRP with --svg: exit 0"
deposits=$(awk '/pendown/ {d = 1; next} /penup/ {d = 0; next} d && /uline/ {n++} END {print n + 0}' "$TMP/l.ladrp")
ok $([ "$deposits" -gt 100 ] && echo 0 || echo 1) "the program deposits ($deposits moves with the pen down)"
is "$(C count "$TMP/l.svg" deposit)" "$deposits" "one deposit path per deposit of the program"
travels=$(C count "$TMP/l.svg" travel)
ok $([ "$travels" -gt 0 ] && echo 0 || echo 1) "travel is drawn ($travels paths)"
is "$(C dashes "$TMP/l.svg")" "$travels/$travels 0/$deposits" "every travel dashed, no deposit dashed"
# Panels are 180 px inside for the cube's 2 cm: 90 px a centimetre.
is "$(C scale "$TMP/l.svg")" "90 cm" "the scale bar: 90 px per cm, labelled in the job's units"
# deposit midpoints, mapped back to the model: all on material, none in the hole
is "$(C outside "$TMP/l.svg" 90 -1 1 "-1,-1,1,1;-0.5,-0.5,0.5,0.5")" 0 "no deposit outside the part or in its hole"
is "$(C outside "$TMP/l.svg" 90 -1 1 "-1,-1,1,1;-2,-2,2,2")" "$deposits" \
   "(the check can fail: a hole over the whole part catches every deposit)"
is "$(C order "$TMP/l.svg")" ok "deposit colours run from dark blue to orange along each layer's order"
is "$(grep -o '<text[^>]*>[xy]</text>' "$TMP/l.svg" | sed 's/<[^>]*>//g' | tr -d '\n')" xy "axes named x and y (slicing along z)"
is "$(grep -c 'class="hole"' "$TMP/l.svg")" 4 "each of the 4 panels outlines its hole"
# 4 equal layers: each has a quarter of the deposits and travels
is "$(grep -c "(2 contours, $(((deposits + travels) / 4)) vectors)" "$TMP/l.svg")" 4 "panels say their vector count"

# SLS with hatching (lpbf-cli): one path per hatch vector, jumps dashed
run "$LAMINA" slice "$CUBE" -m lpbf-cli -w 0.5 --svg "$TMP/h.svg" -o "$TMP/h.cli"
is "$RC" 0 "SLS hatching with --svg: exit 0"
hatches=$(grep -o '^\$\$HATCHES/[0-9]*,[0-9]*' "$TMP/h.cli" | awk -F, '{n += $2} END {print n + 0}')
ok $([ "$hatches" -gt 50 ] && echo 0 || echo 1) "the program has hatch vectors ($hatches)"
is "$(C count "$TMP/h.svg" core upskin downskin)" "$hatches" "one path per hatch vector of the program"
contours=$(grep -c '^\$\$POLYLINE' "$TMP/h.cli")
is "$(C count "$TMP/h.svg" contour)" "$contours" "one path per contour pass of the program"
jumps=$(C count "$TMP/h.svg" jump)
is "$(C dashes "$TMP/h.svg")" "$jumps/$jumps 0/$((hatches + contours))" "jumps dashed, exposures not"
is "$(C scale "$TMP/h.svg")" "90 mm" "scale bar in mm"
is "$(C outside "$TMP/h.svg" 90 -1 1 "-1,-1,1,1;-0.5,-0.5,0.5,0.5")" 0 "every hatch vector on material"
is "$(C order "$TMP/h.svg")" ok "hatch colours follow the order"
rsvg-convert -f png -o "$TMP/h.png" "$TMP/h.svg"; ok $? "the sheet renders (rsvg-convert)"

# the sheet and the JSON of one run: the same vectors in every layer
for mach in lpbf-cli creol-ladrp; do
    run "$LAMINA" slice "$CUBE" -m $mach -w 0.5 --svg "$TMP/j.svg" --json "$TMP/j.json" -o "$TMP/j.out"
    from_json=$(python3 -c 'import json, sys; print(" ".join(str(L["stats"]["vectors"]) for L in json.load(open(sys.argv[1]))["layers"]))' "$TMP/j.json")
    from_svg=$(grep -o 'contours\?, [0-9]* vectors' "$TMP/j.svg" | sed 's/.*, \([0-9]*\) vectors/\1/' | tr '\n' ' ' | sed 's/ $//')
    like "$RC $from_svg" "^0 $from_json\$" "$mach, --svg and --json in one run: each panel's vector count is its layer's in the JSON ($from_json)"
done

# a machine frame (u, v) keeps the drawing; a sheet from a contour-only run
# keeps its strong fill (lamina.preview) — the sheets of check and preview
# have no scan paths
run "$LAMINA" slice "$CUBE" -m creol-ladrp -w 0.5 --frame machine --svg "$TMP/m.svg" -o "$TMP/m.ladrp"
is "$(C count "$TMP/m.svg" deposit)" "$deposits" "machine frame: the same deposits drawn"
is "$(grep -o '<text[^>]*>[uv]</text>' "$TMP/m.svg" | sed 's/<[^>]*>//g' | tr -d '\n')" uv "machine frame: axes u and v"
done_testing
