#!/usr/bin/env bash
# The recipes (recipes/*.lua) run through `lamina run` on small models, with
# their printed numbers checked against what the geometry says; bad
# arguments end every recipe with a message and exit code 1. The modules
# they share are tested in tests/lua/recipes_modules.lua.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
R="$ROOT/recipes"
MR="$M/recipes"
cd "$ROOT" || exit 1
# num TEXT REGEX: the first number captured by the (one) group of REGEX
num() { printf '%s\n' "$1" | sed -nE "s/$2/\\1/p" | head -n 1; }
# cmp_ok A OP B DESCRIPTION (floating point, with awk)
cmp_ok() {
    awk -v a="$1" -v b="$3" "BEGIN { exit !(a != \"\" && b != \"\" && a + 0 $2 b + 0) }"
    local rc=$?
    ok $rc "$4"
    [ $rc -eq 0 ] || echo "#   got: '$1' $2 '$3'"
}

# ---- every recipe: header, --help, bad arguments ----------------------------------
for r in default adaptive aligned best_axis scan_orders hatching; do
    head=$(head -n 3 "$R/$r.lua")
    like "$head" "^-- $r\.lua: .+" "$r: a header comment says what it does"
    like "$head" "lamina run recipes/$r\.lua" "$r: and how to run it"
    run "$LAMINA" run "$R/$r.lua" --help
    like "$RC $OUT" "^0 usage: lamina run recipes/$r\.lua" "$r --help prints the usage"
    run "$LAMINA" run "$R/$r.lua" --bogus 1
    like "$RC $ERR" "^2 lamina: $r\.lua: unknown option --bogus
usage: lamina run recipes/$r\.lua" "$r: an unknown option is an error with the usage, exit 2"
    case "$ERR" in *traceback*) ok 1 "$r: an option error is a message, not a traceback" ;;
                   *) ok 0 "$r: an option error is a message, not a traceback" ;; esac
    run "$LAMINA" run "$R/$r.lua" "$TMP/missing.stl"
    like "$RC $ERR" "^1 lamina: $r\.lua: .*missing\.stl" "$r: a model that does not load, exit 1"
    like "$ERR" "\A[^\n]*missing\.stl[^\n]*\z" "$r: that message is one line: no usage, no traceback"
done

# ---- a mesh that is not closed ------------------------------------------------
# the bundled sphere less a band of 40 faces: with --no-repair its outlines
# stay open on many layers. Every recipe that slices stops with the
# slicer's message on one line (no traceback, exit 1); adaptive.lua takes
# --allow-open. Repaired on load (the default), every recipe runs.
python3 -c 'import sys
lines = open(sys.argv[1]).read().splitlines()
faces = [i for i, l in enumerate(lines) if l.startswith("f ")]
drop = set(faces[len(faces) // 2 - 20:len(faces) // 2 + 20])
sys.stdout.write("".join(l + "\n" for i, l in enumerate(lines) if i not in drop))' "$R/parts/sphere.obj" >"$TMP/open.obj"
for r in default adaptive aligned scan_orders hatching; do
    run "$LAMINA" run "$R/$r.lua" --no-repair "$TMP/open.obj" --out "$TMP/open-out"
    [ "$r" != default ] && run "$LAMINA" run "$R/$r.lua" --no-repair "$TMP/open.obj"
    like "$RC $ERR" "\A1 lamina: $r\.lua: [^\n]*open\.obj: layer [0-9]+ [^\n]*open outline[^\n]*\z" \
        "$r: an open mesh stops it with the slicer's message on one line, exit 1"
    run "$LAMINA" run "$R/$r.lua" "$TMP/open.obj" --out "$TMP/open-out"
    [ "$r" != default ] && run "$LAMINA" run "$R/$r.lua" "$TMP/open.obj"
    is "$RC" 0 "$r: repaired on load, the open mesh runs"
done
run "$LAMINA" run "$R/adaptive.lua" --allow-open --no-repair "$TMP/open.obj"
like "$RC $OUT" "\\A0 (?s:.*)^open mesh: [1-9][0-9]* outlines stayed open in [1-9][0-9]* layers and were dropped" \
    "adaptive --allow-open: runs, and says how many outlines it dropped"
like "$OUT" "^adaptive: [1-9][0-9]* layers" "adaptive --allow-open: the layers it made"

# ---- default.lua -------------------------------------------------------------
run "$LAMINA" run "$R/default.lua" --out "$TMP/res"
is "$RC" 0 "default: runs"
for ext in ladrp sls svg; do
    f="$TMP/res/thesis_cube_hole.$ext"
    ok $([ -s "$f" ] && echo 0 || echo 1) "default: writes $ext, not empty"
    like "$OUT" "thesis_cube_hole\.$ext" "default: names the $ext output"
done
is "$(head -n 1 "$TMP/res/thesis_cube_hole.ladrp")" "start_plot" "default: the LADRP program starts with start_plot"
is "$(head -n 2 "$TMP/res/thesis_cube_hole.sls" | tr '\n' ' ')" "contour 0.000000 loop 4 " "default: the SLS program starts with the first contour"
like "$OUT" "creol-ladrp +25 layers +50 contours +[0-9]+ lines +[0-9]+ bytes" "default: LADRP 25 layers of 0.08, 2 contours each"
like "$OUT" "sls-contours +8 layers +16 contours +143 lines" "default: SLS 8 layers of 0.25"
lines=$(wc -l <"$TMP/res/thesis_cube_hole.sls")
like "$OUT" "sls-contours .* $lines lines" "default: the line count printed is the file's"
svg=$(cat "$TMP/res/thesis_cube_hole.svg")
is "$(grep -c '<path class="section"' "$TMP/res/thesis_cube_hole.svg")" 8 "default: the contact sheet has 8 layer panels"
like "$svg" 'fill-rule="evenodd"' "default: holes drawn with fill-rule evenodd"
if command -v rsvg-convert >/dev/null; then
    rsvg-convert "$TMP/res/thesis_cube_hole.svg" -o "$TMP/sheet.png" 2>/dev/null
    ok $? "default: the contact sheet renders (rsvg-convert)"
fi
# the SLS program equals `lamina slice` with the same profile and options
"$LAMINA" slice "$R/parts/thesis_cube_hole.ug" -m sls-contours -w 0.25 --cut floor -o "$TMP/cli.sls"
cmp -s "$TMP/cli.sls" "$TMP/res/thesis_cube_hole.sls"
ok $? "default: the SLS program is what lamina slice writes"
run "$LAMINA" run "$R/default.lua" --out "$TMP/res2/deeper" "$MR/pillars.ug"
ok $([ "$RC" -eq 0 ] && [ -s "$TMP/res2/deeper/pillars.ladrp" ] && [ -s "$TMP/res2/deeper/pillars.svg" ] && echo 0 || echo 1) \
    "default: another model, a new output directory"
like "$OUT" "sls-contours +16 layers +64 contours" "default: four pillars, 16 SLS layers"
run "$LAMINA" run "$R/default.lua" --sls-width 0
like "$RC $ERR" "^2 lamina: default\.lua: --sls-width must be greater than 0, got 0" "default: --sls-width 0 is an error"

# ---- adaptive.lua ------------------------------------------------------------
"$LAMINA" run "$MR/uv_sphere.lua" "$TMP/sphere.obj" 10 48 24
run "$LAMINA" run "$R/adaptive.lua" --cusp 0.05 --min 0.02 --max 0.5 --list "$TMP/sphere.obj"
is "$RC" 0 "adaptive: runs on a UV sphere (48 x 24)"
na=$(num "$OUT" '^adaptive: ([0-9]+) layers.*')
ca=$(num "$OUT" '^adaptive: .*worst cusp ([0-9.e-]+),.*')
nu=$(num "$OUT" '^uniform: ([0-9]+) layers.*')
cu=$(num "$OUT" '^uniform: .*worst cusp ([0-9.e-]+)$')
echo "# adaptive $na layers (worst cusp $ca), uniform $nu layers (worst cusp $cu)"
cmp_ok "$na" "<=" "$(awk -v u="$nu" 'BEGIN { print 0.75 * u }')" "adaptive: at least 25% fewer layers than uniform"
cmp_ok "$ca" "<=" 0.05000001 "adaptive: worst cusp within --cusp"
cmp_ok "$(awk -v a="$ca" -v b="$cu" 'BEGIN { d = a - b; print d < 0 ? -d : d }')" "<" 1e-6 \
    "adaptive: the uniform slicing has the same worst cusp"
# R/c without the --max clamp: about 10 / 0.05 = 200 layers; uniform about 2R/c = 400
cmp_ok "$na" ">=" 190 "adaptive: not fewer layers than the sphere allows (R/c)"
cmp_ok "$nu" ">=" 380 "adaptive: uniform needs about 2R/c"
printf '%s\n' "$OUT" | awk '/^layer / { print $3, $4, $5 }' >"$TMP/layers"
is "$(wc -l <"$TMP/layers" | tr -d ' ')" "$na" "adaptive: --list prints every layer"
awk -v min=0.02 -v max=0.5 '
    NR == 1 && ($1 + 10 > 1e-9 || $1 + 10 < -1e-9) { bad = "first floor " $1 }
    NR > 1 && (($1 - prev) > 1e-9 || (prev - $1) > 1e-9) { bad = "gap at " $1 }
    $3 < min - 1e-12 || $3 > max + 1e-12 { bad = "width " $3 }
    { prev = $2 } END { if (prev < 10 - 1e-9) bad = "ends at " prev; if (bad) { print bad; exit 1 } }' "$TMP/layers"
ok $? "adaptive: widths in [0.02, 0.5], contiguous, from -10 to at least 10"
# flat faces off the uniform grid: the comparison is at the same worst cusp
# (terrace.ug: flat faces at 0, 1, 1.05 and 2.5, walls only: adaptive has no
# cusp at all, and so must uniform: 0.05 puts every flat face on a boundary)
run "$LAMINA" run "$R/adaptive.lua" "$R/parts/terrace.ug"
like "$OUT" '^adaptive: 6 layers, worst cusp 0,' "adaptive on the terrace: 6 layers, no cusp"
like "$OUT" '^uniform: 50 layers of 0\.05, worst cusp 0$' "... uniform at the same (zero) worst cusp: 50 layers of 0.05"
like "$OUT" 'uniform takes 5 layers but leaves a cusp of 0\.5 at flat faces off its grid' \
    "... and says what the wider uniform slicing would leave"
like "$OUT" '^adaptive uses 88\.0% fewer layers than uniform at the same worst cusp$' "... and says which is compared"
# the same with a tighter cusp along another axis: still within the limits
run "$LAMINA" run "$R/adaptive.lua" --cusp 0.02 --min 0.01 --max 0.3 --axis x "$TMP/sphere.obj"
na=$(num "$OUT" '^adaptive: ([0-9]+) layers.*'); nu=$(num "$OUT" '^uniform: ([0-9]+) layers.*')
echo "# along x, cusp 0.02: adaptive $na layers, uniform $nu"
cmp_ok "$na" "<=" "$(awk -v u="$nu" 'BEGIN { print 0.75 * u }')" "adaptive: along x too, at least 25% fewer"
run "$LAMINA" run "$R/adaptive.lua" "$R/parts/thesis_cube_hole.ug"
like "$OUT" "adaptive: 4 layers, worst cusp 0, widths 0.5 \.\. 0.5" "adaptive: walls and flat faces only: max-wide layers, no cusp"
run "$LAMINA" run "$R/adaptive.lua" --min 0.6 --max 0.5
like "$RC $ERR" "^2 lamina: adaptive\.lua: --min \(0\.6\) is greater than --max \(0\.5\)" "adaptive: min > max is an error"
run "$LAMINA" run "$R/adaptive.lua" --cusp abc
like "$RC $ERR" "^2 lamina: adaptive\.lua: --cusp expects a number, got 'abc'" "adaptive: a bad number"
run "$LAMINA" run "$R/adaptive.lua" --cusp -0.1
like "$RC $ERR" "^2 lamina: adaptive\.lua: --cusp must be greater than 0, got -0\.1" "adaptive: a negative cusp"
run "$LAMINA" run "$R/adaptive.lua" --axis w
like "$RC $ERR" "^2 lamina: adaptive\.lua: --axis: axis must be x, y, z" "adaptive: a bad axis"
run "$LAMINA" run "$R/adaptive.lua" a.stl b.stl
like "$RC $ERR" "^2 lamina: adaptive\.lua: unexpected argument 'b\.stl'" "adaptive: two models"

# ---- aligned.lua -------------------------------------------------------------
# every flat height among the planes (as numbers), printed and checked by slicing
flats_in_planes() {
    local flats planes
    flats=$(num "$OUT" '^flat heights: [0-9]+: (.*)$')
    planes=$(num "$OUT" '^planes: [0-9]+: (.*)$')
    awk -v f="$flats" -v p="$planes" 'BEGIN {
        nf = split(f, F, " "); np = split(p, P, " "); if (nf == 0) exit 1
        for (i = 1; i <= nf; i++) { hit = 0
            for (j = 1; j <= np; j++) if (F[i] - P[j] < 1e-6 && P[j] - F[i] < 1e-6) hit = 1
            if (!hit) exit 1 }
        for (j = 2; j <= np; j++) if (P[j] <= P[j - 1]) exit 1 }'
}
run "$LAMINA" run "$R/aligned.lua" "$MR/terrace.ug"
is "$RC" 0 "aligned: runs on the terrace"
like "$OUT" "^model: .*terrace\.ug" "aligned: names the model"
like "$OUT" "flat heights: 4: 0 1 1\.05 2\.5" "aligned: the terrace's four flat heights"
like "$OUT" "planes: 7: 0 0\.5 1 1\.05 1\.53333 2\.01667 2\.5" "aligned: equal layers of at most 0.5 between them"
flats_in_planes; ok $? "aligned: every flat height is a plane"
like "$OUT" "note: 1 \.\. 1\.05 is narrower than --min 0\.1: one layer" "aligned: says when an interval is under --min"
like "$OUT" "layers: 6, every flat height on a boundary: yes" "aligned: checked by slicing with the planes"
run "$LAMINA" run "$R/aligned.lua" --min 0.3 --max 0.4 "$M/slice/step.ug"
like "$OUT" "flat heights: 3: 0 1 2" "aligned: the step's flat heights"
like "$OUT" "planes: 7: 0 0\.333333 0\.666667 1 1\.33333 1\.66667 2" "aligned: three layers of 1/3 per tier"
flats_in_planes; ok $? "aligned: the step's flat heights are planes"
run "$LAMINA" run "$R/aligned.lua" --axis x --max 0.3 "$R/parts/thesis_cube_hole.ug"
like "$OUT" "flat heights: 4: -1 -0\.5 0\.5 1" "aligned: along x the cavity's walls are flat faces"
flats_in_planes; ok $? "aligned: along x every flat height is a plane"
like "$OUT" "layers: 8, every flat height on a boundary: yes" "aligned: along x, 8 layers"
run "$LAMINA" run "$R/aligned.lua" --max 0
like "$RC $ERR" "^2 lamina: aligned\.lua: --max must be greater than 0, got 0" "aligned: --max 0 is an error"

# ---- best_axis.lua -----------------------------------------------------------
row() { printf '%s\n' "$OUT" | awk -v a="$1" '$1 == a { print $2, $3, $4, $5 }'; }
run "$LAMINA" run "$R/best_axis.lua" "$MR/plate.ug"
is "$RC" 0 "best_axis: runs on a 10 x 10 x 1 plate"
is "$(row z)" "1 10 0 0" "best_axis: the plate along z: height 1, 10 layers, no stairs, no overhang"
is "$(row x)" "10 100 0 0" "best_axis: along x: height 10, 100 layers"
is "$(row y)" "10 100 0 0" "best_axis: along y: the same"
like "$OUT" "best: z$" "best_axis: picks z, the thin direction"
run "$LAMINA" run "$R/best_axis.lua" "$MR/plate_x.ug"
like "$OUT" "best: x$" "best_axis: the plate on its edge: picks x"
run "$LAMINA" run "$R/best_axis.lua" "$MR/tee.ug"
is "$(row z)" "10 100 0 96" "best_axis: the T along z: its underside (96) overhangs"
is "$(row x)" "10 100 0 16" "best_axis: along x the stem's side (16)"
like "$OUT" "best: x$" "best_axis: the T picks x among x, y, z"
run "$LAMINA" run "$R/best_axis.lua" --more "$MR/tee.ug"
is "$(row -z)" "10 100 0 0" "best_axis --more: upside down nothing overhangs"
like "$OUT" "best: -z$" "best_axis --more: picks -z"
like "$OUT" "1,1,-1 " "best_axis --more: the body diagonals"
run "$LAMINA" run "$R/best_axis.lua" --w-overhang 0 "$MR/tee.ug"
like "$OUT" "best: z$" "best_axis: overhang weight 0: a tie, the first candidate"
run "$LAMINA" run "$R/best_axis.lua" --w-stair -1
like "$RC $ERR" "^2 lamina: best_axis\.lua: --w-stair must be 0 or more, got -1" "best_axis: a negative weight"
run "$LAMINA" run "$R/best_axis.lua" --overhang-deg 100
like "$RC $ERR" "^2 lamina: best_axis\.lua: --overhang-deg must be between 0 and 90" "best_axis: a bad angle"

# ---- scan_orders.lua ---------------------------------------------------------
run "$LAMINA" run "$R/scan_orders.lua" --width 0.5 "$MR/pillars.ug"
is "$RC" 0 "scan_orders: runs on four pillars"
like "$OUT" "8 layers, 32 solid contours" "scan_orders: 8 layers of four islands"
travel() { printf '%s\n' "$OUT" | awk -v r="$1" -v o="$2" '$1 == r && $2 == o { print $3 }'; }
deposit() { printf '%s\n' "$OUT" | awk -v r="$1" -v o="$2" '$1 == r && $2 == o { print $4 }'; }
for r in 0 0/90 +67.5; do
    b=$(travel "$r" boustrophedon); i=$(travel "$r" islands)
    echo "# raster $r: travel $b by whole lines, $i by islands"
    cmp_ok "$i" "<" "$b" "scan_orders: raster $r: island by island travels less than whole lines"
done
is "$(deposit 0 boustrophedon)" "1600.0000" "scan_orders: deposit 8 layers x 4 pillars x 2 x 2 / 0.08 x 2 = 1600"
like "$OUT" "islands +[0-9.]+ +1600\.0000 +800 +[0-9.]+%" "scan_orders: the same deposit in the same 800 lines by islands"
like "$OUT" "0/90 +boustrophedon" "scan_orders: alternating 0/90"
like "$OUT" "\+67\.5 +islands" "scan_orders: turning 67.5 per layer"
run "$LAMINA" run "$R/scan_orders.lua" --machine sls-contours
like "$RC $ERR" "^2 lamina: scan_orders\.lua: sls-contours is an sls machine, not ladrp" "scan_orders: an SLS machine is an error"
run "$LAMINA" run "$R/scan_orders.lua" --machine no-such-machine
like "$RC $ERR" "^1 lamina: scan_orders\.lua: .*unknown machine" "scan_orders: an unknown machine"

# ---- hatching.lua ------------------------------------------------------------
run "$LAMINA" run "$R/hatching.lua" --width 4 --distance 0.5 --skins 0
is "$RC" 0 "hatching: runs on the frame with its island"
like "$OUT" "5 layers, machine lpbf-cli \(hatch distance 0.5, no skins\)" "hatching: 5 layers of 4, no skins"
col() { awk -v s="$1" -v c="$2" '{ l = substr($0, 1, 22); sub(/ +$/, "", l) } l == s { n = split($0, f, / +/); print f[n - 4 + c] }' <<<"$OUT"; }
for s in "lines" "lines unidirectional" "lines greedy" "lines, recipe order"; do
    is "$(col "$s" 1) $(col "$s" 2)" "$(col lines 1) $(col lines 2)" "hatching: $s: the same vectors as lines"
done
# the frame's volume is 16000: the 5 layers of 4 hold 4000 of area; the
# hatches (0.5 apart) cover it but for the contour passes' band (0.16 in)
cmp_ok "$(col lines 2)" ">" 7200 "hatching: length x 0.5 covers over 90% of the 4000"
cmp_ok "$(col lines 2)" "<" 8000 "hatching: ... and not more than all of it"
cmp_ok "$(col 'lines greedy' 3)" "<" "$(col lines 3)" "hatching: greedy jumps less than meander"
cmp_ok "$(col lines 3)" "<" "$(col 'lines unidirectional' 3)" "hatching: meander jumps less than unidirectional"
cmp_ok "$(col stripes 1)" ">" "$(col lines 1)" "hatching: stripes cut the lines into more vectors"
cmp_ok "$(col 'islands checker' 1)" ">" "$(col stripes 1)" "hatching: islands (5 wide) more than stripes (10)"
like "$OUT" "islands random +[0-9]+ +[0-9.]+ +[0-9.]+ +[0-9.]+" "hatching: every island order"
run "$LAMINA" run "$R/hatching.lua" --machine creol-ladrp
like "$RC $ERR" "^2 .*creol-ladrp is an ladrp machine, not sls" "hatching: an LADRP machine is refused"
done_testing
