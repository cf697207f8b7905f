#!/usr/bin/env bash
# The SVG contact sheet's layout (core/out/svg.h), read back with Python's
# XML parser (svgcheck.py): captions inside their cells' bands and apart
# from each other, the title, the footer and the drawings at every layer
# count and for extreme aspect ratios; the scale bar a 1, 2 or 5 x 10^k
# length in the job's units, drawn at the sheet's scale; a layer of more
# vectors than a cell can show thinned to LAM_SVG_CELL_VECTORS, with its
# caption and a note saying so; the sheet held to --max-output, no file left.
. "$(dirname "$0")/lib.sh"
C() { python3 "$TESTS/cli/svgcheck.py" "$@"; } # a function: the path may hold spaces
cd "$TMP" || exit 1

# box NAME X Y Z: a Unigrafix box 0..X, 0..Y, 0..Z
box() {
    cat >"$1.ug" <<UG
v a 0 0 0; v b $2 0 0; v c $2 $3 0; v d 0 $3 0;
v e 0 0 $4; v f $2 0 $4; v g $2 $3 $4; v h 0 $3 $4;
f bottom (a d c b); f top (e f g h); f front (a b f e);
f right (b c g f); f back (c d h g); f left (d a e h);
UG
}

# ---- captions at every layer count (contours only: sls-contours) -----------------
box cube 2 2 20
# widths giving 1, 2, 7, 50, 267 and 1143 layers over the 20 mm height
for case in "20 1" "10 2" "2.857143 7" "0.4 50" "0.0749064 267" "0.0175 1143"; do
    set -- $case
    run "$LAMINA" slice cube.ug -w "$1" -q -o c$2.sls --svg c$2.svg
    shown=$(($2 < 100 ? $2 : 100))
    is "$RC $(C captions c$2.svg | cut -d' ' -f1,2)" "0 ok $((2 * shown))" \
        "$2 layers: $((2 * shown)) caption lines, each in its cell's band, none over another, a panel, the title or the footer"
    is "$(C drawing c$2.svg)" ok "$2 layers: every drawing clipped to its panel and inside it"
done
C texts c1143.svg >t1143.txt
like "$(head -1 t1143.txt)" "\(100 of 1143 layers shown, evenly chosen\)'$" "1143 layers: the title says 100 are shown"
like "$(cat t1143.txt)" "'layer 1143  h=" "1143 layers: the last layer has a panel (1-based)"
is "$(C inert c1143.svg)" ok "the sheet only draws"
# a one-layer sheet (one cell, 220 px wide) of a model with a 120-character name
long=$(printf 'a%.0s' $(seq 117)).ug
cp cube.ug "$long"
run "$LAMINA" slice "$long" -w 20 -q -o long.sls --svg long.svg
is "$RC $(C captions long.svg | cut -d' ' -f1,2)" "0 ok 2" "a long title is sized to the sheet, clear of the caption"
# the check is not vacuous: a caption line of 48 characters at 12 px (346 px) leaves a 200 px cell
sed 's/\(<g class="caption"[^>]*font-size="\)[0-9.]*/\112/; s/(1 contour, \([0-9]*\) vectors)/(1 contour, \1 vectors, and some more characters)/' c7.svg >wide.svg
like "$(C captions wide.svg)" "outside its band" "a caption too wide for its cell is caught"

# ---- extreme aspect ratios (scan paths: longer captions) -------------------------
# tall thin section 1 x 40 mm: 180 px over 40 mm, 4.5 px/mm; 60 px is 13.3 mm: the bar is 10 mm, 45 px
# wide flat section 50 x 1.5 mm: 3.6 px/mm; 60 px is 16.7 mm: the bar is 10 mm, 36 px
# tiny 0.2 x 0.1 mm: 900 px/mm; 60 px is 0.0667 mm: the bar is 0.05 mm, 45 px
box thin 1 40 0.3
box wide 50 1.5 0.3
box tiny 0.2 0.1 0.3
for case in "thin 10 45" "wide 10 36" "tiny 0.05 45"; do
    set -- $case
    run "$LAMINA" slice $1.ug -m lpbf-cli -w 0.03 -q -o $1.cli --svg $1.svg
    is "$RC $(C captions $1.svg | cut -d' ' -f1,2)" "0 ok 20" "$1 section, 10 layers: captions in their bands, apart"
    is "$(C drawing $1.svg)" ok "$1 section: drawings inside their panels"
    is "$(C scalebar $1.svg)" "$2 mm $3" "$1 section: scale bar $2 mm, drawn $3 px (the sheet's scale)"
done
like "$(C texts thin.svg)" "'\(1 contour, [0-9]+ vectors\)'" "captions give the contours and vectors"
font=$(C captions thin.svg | cut -d' ' -f3)
awk -v f="$font" 'BEGIN { exit !(f >= 8 && f <= 12) }'; ok $? "a caption with vectors stays legible ($font px)"

# ---- the scale bar in the job's units --------------------------------------------
run "$LAMINA" slice wide.ug -m lpbf-cli -s units=inch -w 0.03 -q -o wi.cli --svg wi.svg
is "$RC $(C scalebar wi.svg)" "0 10 inch 36" "a profile in inches: the bar says inch, 10 of them 36 px"
run "$LAMINA" slice wide.ug -m creol-ladrp -w 0.1 -q -o wl.ladrp --svg wl.svg
is "$RC $(C scalebar wl.svg)" "0 10 cm 36" "creol-ladrp's cm"
run "$LAMINA" check wide.ug -m creol-ladrp --svg wc.svg
like "$(C scalebar wc.svg)" "^10 cm [0-9]+$" "check --svg: the bar in the machine's cm too (was 'model units')"

# ---- thinning: a 40 x 40 mm layer hatched at 0.1 mm is ~1600 vectors -------------
box big 40 40 0.09
run "$LAMINA" slice big.ug -m lpbf-cli -w 0.03 -o big.cli --svg big.svg
is "$RC" 0 "a 40 mm square in lpbf-cli: exit 0"
C thinned big.svg >thin.txt
is "$(tail -1 thin.txt)" note "the sheet says it was thinned"
is "$(grep -vc note thin.txt)" 3 "three panels"
bad=$(grep -v note thin.txt | awk '!($1 > 1000 && $2 <= 1000 && $2 < $1 && $3 <= $2 && $3 > 200 && $4 == 0)')
is "$bad" "" "each panel: over 1000 vectors, at most 1000 drawn (said in its caption), no travel, hundreds drawn"
is "$(C order big.svg)" ok "the drawn vectors keep the layer's colour order"
is "$(C captions big.svg | cut -d' ' -f1,2)" "ok 6" "thinned captions (', N drawn') fit too"
# a drawn element is under 80 bytes (a hatch: class, colour, two points): 3 panels of at
# most 1000 and the frame (under 10 kB) are under 250 kB; drawn whole, the sheet was 307 kB
size=$(wc -c <big.svg)
ok $((size < 3 * 1000 * 80 + 10000 ? 0 : 1)) "the thinned sheet is $size bytes, under 250 kB"
# a layer within the budget is drawn whole (preview.t checks every vector against the
# program), one past it is thinned: the thin part's layers have 105 to 1001 vectors
C thinned thin.svg | grep -v note >thin2.txt
is "$(awk '($1 <= 1000) != ($1 == $2)' thin2.txt)" "" "the thin part: panels of at most 1000 vectors drawn whole, others thinned"
is "$(awk '$1 > 1000' thin2.txt | wc -l) $(awk '$1 <= 1000' thin2.txt | wc -l)" "1 9" "(one of its 10 layers is past 1000)"

# 100 islands of 1 x 1 mm: two contour passes of 4 edges each, 800 edges, more than half the
# budget: the panels draw no contour pass (the section outlines them), only one in k hatches
python3 - >islands.ug <<'PY'
for i in range(100):
    x, y = 2 * (i % 10), 2 * (i // 10)
    c = [(x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1)]
    print(" ".join("v p%d_%d %g %g %g;" % (i, k, c[k % 4][0], c[k % 4][1], 0.09 * (k // 4)) for k in range(8)))
    f = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    print(" ".join("f q%d_%d (%s);" % (i, j, " ".join("p%d_%d" % (i, k) for k in q)) for j, q in enumerate(f)))
PY
run "$LAMINA" slice islands.ug -m lpbf-cli -w 0.03 -q -o islands.cli --svg islands.svg
is "$RC $(C count islands.svg contour)" "0 0" "100 islands: no contour pass drawn"
C thinned islands.svg | grep -v note >isl.txt
is "$(awk '!($1 > 1000 && $2 <= 1000 && $3 == $2 && $3 > 100 && $4 == 0)' isl.txt)" "" \
    "each island panel: over 1000 vectors, at most 1000 drawn, all of them hatches"
is "$(grep -c 'class="section"' islands.svg)" 3 "the sections are drawn"

# ---- held to --max-output: refused, no file ---------------------------------------
prog=$(wc -c <c50.sls) svg=$(wc -c <c50.svg)
ok $((svg > prog + 1000 ? 0 : 1)) "the 50-layer sheet ($svg bytes) is larger than its program ($prog)"
rm -f c50.sls c50.svg
run "$LAMINA" slice cube.ug -w 0.4 --max-output $((prog + 1000)) -o c50.sls --svg c50.svg
like "$RC $ERR" "^1 lamina: c50\.svg: cannot write output: output exceeds the limit of $((prog + 1000)) bytes
lamina: raise the limit with --max-output" "--svg past --max-output: exit 1, the limit named"
is "$(ls | grep -c '^c50\.')" 0 "no sheet left, partial or whole, nor the program"
# a build's sheet too
printf 'machine: cli-ascii\nplate: {width: 100, depth: 100}\nparts:\n  - {model: cube.ug, units: mm}\n' > job.yaml
run "$LAMINA" build job.yaml -s layer_width=0.4 -o b.cli --svg b.svg
prog=$(wc -c <b.cli) svg=$(wc -c <b.svg)
ok $((RC == 0 && svg > prog + 1000 ? 0 : 1)) "a build's sheet ($svg bytes) is larger than its program ($prog)"
rm -f b.cli b.svg
run "$LAMINA" build job.yaml -s layer_width=0.4 --max-output $((prog + 1000)) -o b.cli --svg b.svg
like "$RC $ERR" "^1 lamina: b\.svg: cannot write output: output exceeds the limit of $((prog + 1000)) bytes" \
    "build --svg past --max-output: exit 1, the limit named"
is "$(ls | grep -c '^b\.')" 0 "... no sheet left"
done_testing
