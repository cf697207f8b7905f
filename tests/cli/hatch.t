#!/usr/bin/env bash
# Scan strategies (SPEC 4.5): golden programs on the thesis cube, the
# independent checker (tests/cli/hatchcheck.py: its own point-in-polygon,
# areas and distances) on a sphere, a torus, the thesis frame with its island
# and a thin-walled tube, skins, the build-time estimate against a
# hand-computed layer, and the CLI round trip.
. "$TESTS/cli/lib.sh"
export LAMINA_MACHINES="$M/machines"
CHECK() { python3 "$TESTS/cli/hatchcheck.py" "$@"; } # a function: the path may hold spaces

# ---- golden programs: the thesis cube ([-1,1]^3), one layer cut at z = 0 ----
# hatch distance 0.25 at 0 degrees: lines at y = (k + 1/2) 0.25, k = -4..3,
# each from x = -1 to 1 (the contour pass is the outline: no compensation).
#  lines, meander: the lines bottom up, every other one backwards;
#  unidirectional: all from -1 to 1;
#  greedy: from the first vector the nearest end is always the next line's
#   end above the last one's end: the meander again on a convex square;
#  stripes 1 wide overlapping by 0.2: bands [j - 0.1, j + 1.1], j = -2..1,
#   min_vector 0.15 drops the bands j = -2 and 1 (0.1 of the square each):
#   [-1, 0.1] then [-0.1, 1], each meandering;
#  islands 1 wide: squares [i, i+1] x [j, j+1], i, j in {-1, 0}, at 0
#   degrees when i + j is even, 90 when odd (lines at u = -(k + 1/2) 0.25
#   running along +v); sequential: row j = -1 then j = 0, each by i;
#   checker: the even squares (-1,-1), (0,0), then the odd (0,-1), (-1,0).
cube="$M/thesis_cube.ug"
base=(-m cli-ascii -w 2 -s hatch_distance=0.25 -s hatch_angle=0)
golden() { # golden NAME OPTIONS...
    local name=$1
    shift
    run "$LAMINA" slice "$cube" "${base[@]}" "$@" -o "$TMP/$name.cli"
    cmp -s "$TMP/$name.cli" "$M/hatch/$name.cli"
    ok $? "golden: $name ($*)"
}
golden cube_lines -s hatch_strategy=lines
golden cube_unidirectional -s hatch_strategy=lines -s hatch_order=unidirectional
golden cube_greedy -s hatch_strategy=lines -s hatch_order=greedy
golden cube_stripes -s hatch_strategy=stripes -s stripe_width=1 -s stripe_overlap=0.2 -s min_vector=0.15
golden cube_islands -s hatch_strategy=islands -s island_size=1
golden cube_islands_checker -s hatch_strategy=islands -s island_size=1 -s island_order=checker
# none: the contours only, as before hatching existed
run "$LAMINA" slice "$cube" -m cli-ascii -w 2 -o "$TMP/none.cli"
is "$(grep -c HATCHES "$TMP/none.cli")" 0 "hatch_strategy none: no hatches"

# the SLS text dialect: a hatches block per region, after the contour
run "$LAMINA" slice "$cube" -w 2 -s hatch_strategy=lines -s hatch_distance=1 -s hatch_angle=0
is "$OUT" "contour 0.000000
loop 4
-1.000000 -1.000000 0.000000
1.000000 -1.000000 0.000000
1.000000 1.000000 0.000000
-1.000000 1.000000 0.000000
endloop
endcontour

hatches core 2 0.000000
-1.000000 -0.500000 0.000000 1.000000 -0.500000 0.000000
1.000000 0.500000 0.000000 -1.000000 0.500000 0.000000
endhatches" "sls-contours: contour, blank line, hatches core N Z, the vectors, endhatches"
# contours last
run "$LAMINA" slice "$cube" -w 2 -s hatch_strategy=lines -s hatch_distance=1 -s contours_first=false
like "$OUT" '^hatches core 2 0.000000\n(.*\n){3}\ncontour 0.000000' "contours_first=false: the hatches come first"
# random island order: deterministic, and a permutation of the sequential blocks
"$LAMINA" slice "$cube" "${base[@]}" -s hatch_strategy=islands -s island_size=0.5 -s island_order=random -s seed=7 -o "$TMP/r1.cli" 2>/dev/null
"$LAMINA" slice "$cube" "${base[@]}" -s hatch_strategy=islands -s island_size=0.5 -s island_order=random -s seed=7 -o "$TMP/r2.cli" 2>/dev/null
"$LAMINA" slice "$cube" "${base[@]}" -s hatch_strategy=islands -s island_size=0.5 -s island_order=random -s seed=8 -o "$TMP/r3.cli" 2>/dev/null
"$LAMINA" slice "$cube" "${base[@]}" -s hatch_strategy=islands -s island_size=0.5 -o "$TMP/r0.cli" 2>/dev/null
cmp -s "$TMP/r1.cli" "$TMP/r2.cli"; ok $? "random island order: the same seed, the same program"
cmp -s "$TMP/r1.cli" "$TMP/r3.cli"; ok $((!$?)) "random island order: another seed, another order"
is "$(grep HATCHES "$TMP/r1.cli" | sort | md5sum)" "$(grep HATCHES "$TMP/r0.cli" | sort | md5sum)" \
    "random island order: the same islands as sequential"

# ---- the independent checker ---------------------------------------------
python3 "$TESTS/cli/meshgen.py" sphere "$TMP/sphere.stl"
python3 "$TESTS/cli/meshgen.py" torus "$TMP/torus.stl"
python3 "$TESTS/cli/meshgen.py" thinwall "$TMP/wall.stl"
check() { # check MODEL SLICE-OPTIONS -- CHECK-OPTIONS
    local model=$1 name
    shift
    local sopts=()
    while [ "$1" != "--" ]; do sopts+=("$1"); shift; done
    shift
    name=$(basename "$model")
    rm -f "$TMP/c.cli"
    "$LAMINA" slice "$model" -m cli-kinds "${sopts[@]}" -o "$TMP/c.cli" 2>"$TMP/c.err"
    local rc=$?
    out=$(CHECK "$TMP/c.cli" "$@" 2>&1)
    local crc=$? # the checker's verdict (it used to be dropped: the line below took $?)
    [ $rc -eq 0 ] && [ $crc -eq 0 ] && [ "$(grep -vc '^lamina: .*estimated build time' "$TMP/c.err")" = 0 ]
    ok $? "$name ${sopts[*]}: ${out##*# }"
    [ $? -eq 0 ] || printf '%s\n' "$out" | head -5 | sed 's/^/#   /'
}
for model in "$TMP/sphere.stl" "$TMP/torus.stl" "$M/frame_island.ug"; do
    case $model in
        *frame*) w=4 h=0.5 S=7 W=9 ;;
        *) w=1 h=0.1 S=1.5 W=2 ;;
    esac
    check "$model" -w $w -s hatch_strategy=lines -s hatch_distance=$h -s hatch_angle=10 -- \
        --distance $h --angle 10 --increment 67 --coverage 1
    check "$model" -w $w -s hatch_strategy=lines -s hatch_distance=$h -s hatch_order=greedy -s layer_angle_increment=90 -- \
        --distance $h --angle 0 --increment 90
    # stripes and islands: without overlap the area, with it the tiling
    check "$model" -w $w -s hatch_strategy=stripes -s hatch_distance=$h -s stripe_width=$W -- \
        --distance $h --angle 0 --increment 67 --stripes $W,0
    check "$model" -w $w -s hatch_strategy=stripes -s hatch_distance=$h -s stripe_width=$W -s stripe_overlap=$h -- \
        --distance $h --angle 0 --increment 67 --stripes $W,$h --no-area
    check "$model" -w $w -s hatch_strategy=islands -s hatch_distance=$h -s island_size=$S -s island_order=random -- \
        --distance $h --angle 0 --increment 67 --islands --island-grid $S,0
    check "$model" -w $w -s hatch_strategy=islands -s hatch_distance=$h -s island_size=$S -s island_overlap=$h -s island_order=checker -- \
        --distance $h --angle 0 --increment 67 --islands --island-grid $S,$h --no-area
    # a hatch offset: every vector that far from the contour pass
    check "$model" -w $w -s hatch_strategy=lines -s hatch_distance=$h -s hatch_offset=0.2 -- \
        --distance $h --inset 0.2 --no-area
done
# thin walls: 0.3 wide, 3 hatch distances
check "$TMP/wall.stl" -w 0.5 -s hatch_strategy=lines -s hatch_distance=0.1 -s hatch_angle=30 -- \
    --distance 0.1 --angle 30 --increment 67
check "$TMP/wall.stl" -w 0.5 -s hatch_strategy=islands -s hatch_distance=0.1 -s island_size=2 -- \
    --distance 0.1 --angle 0 --increment 67 --islands --island-grid 2,0
check "$TMP/wall.stl" -w 0.5 -s hatch_strategy=stripes -s hatch_distance=0.05 -s stripe_width=1 -s stripe_overlap=0.1 -- \
    --distance 0.05 --angle 0 --increment 67 --stripes 1,0.1

# the checker itself finds a vector that leaves its region, a wrong angle
# and a hole in the coverage
"$LAMINA" slice "$TMP/sphere.stl" -m cli-kinds -w 1 -s hatch_strategy=lines -s support_type=none -o "$TMP/s.cli" 2>/dev/null
perl -pe 'if (!$d && s{^(\$\$HATCHES/1,\d+,)([-0-9.]+)}{$1 . ($2 - 0.5)}e) { $d = 1 }' "$TMP/s.cli" >"$TMP/bad.cli"
CHECK "$TMP/bad.cli" --distance 0.1 >/dev/null; ok $((!$?)) "checker: a vector moved 0.5 out of its region fails"
CHECK "$TMP/s.cli" --distance 0.1 --angle 0 --increment 66 >/dev/null; ok $((!$?)) "checker: a wrong angle increment fails"
perl -ne 'print unless /^\$\$HATCHES/ && ++$n == 3' "$TMP/s.cli" >"$TMP/hole.cli"
CHECK "$TMP/hole.cli" --distance 0.1 --coverage 1 >/dev/null; ok $((!$?)) "checker: a block left out fails (area, coverage)"

# ---- skins: every vector's kind from the layers around it -----------------
skin=(-s hatch_strategy=lines -s hatch_distance=0.1 -s upskin.hatch_distance=0.05 -s downskin.hatch_distance=0.05)
check "$TMP/sphere.stl" -w 0.5 "${skin[@]}" -s skin_layers=2 -- --distance 0.1 --skin-distance 0.05 --skins 2
check "$TMP/torus.stl" -w 0.25 "${skin[@]}" -s skin_layers=3 -- --distance 0.1 --skin-distance 0.05 --skins 3
check "$M/frame_island.ug" -w 2 -s hatch_strategy=lines -s hatch_distance=0.5 -s skin_layers=1 -- --distance 0.5 --skins 1
"$LAMINA" slice "$TMP/torus.stl" -m cli-kinds -w 0.25 "${skin[@]}" -s skin_layers=3 -o "$TMP/k.cli" 2>/dev/null
kinds=$(grep '^//' "$TMP/k.cli" | sort -u | tr '\n' ' ')
# (and the supports of the shipped powder-bed profiles: the torus's lower
# half overhangs, down to the plate)
is "$kinds" "//core// //downskin// //support// //upskin// " "torus: core, up-skin and down-skin blocks, and supports"
# skins get their section's values, the rest the top level's
run "$LAMINA" slice "$TMP/torus.stl" -m lpbf-cli -w 0.25 -o "$TMP/l.cli"
is "$RC" 0 "lpbf-cli: exit 0"
like "$(grep '^//' "$TMP/l.cli" | sort -u)" '^//contour power 120 speed 600//\n//core power 200 speed 900//\n//downskin power 100 speed 1200//\n//support power 150 speed 1500//\n//upskin power 150 speed 700//$' \
    "lpbf-cli: each vector type with its own exposure (supports: lpbf-cli's support section)"

# ---- the build-time estimate, by hand ------------------------------------
# The cube's one layer, hatch distance 0.25: the contour (perimeter 8) at
# speed 4 takes 2 s; 8 lines of 2 at speed 2 take 8 s. Jumps: the contour
# ends where it starts, (-1, -1); to the first line's start (-1, -0.875)
# 0.125, then 7 x 0.25 between lines: 1.875 at 10 per second = 0.1875 s,
# plus 8 jumps x 0.01 s delay = 0.08 s. Recoating 5 s. Total 15.2675 s.
# Printed for people (fmt.h): lengths to three digits in mm (1.875 is a
# tie: 1.88), times below 10 s in tenths (0.2675: 0.3 s; 5: 5.0 s), from
# 10 s in whole seconds (15 s); the JSON below has the exact figures.
t=(-s speed=2 -s contour.speed=4 -s jump_speed=10 -s jump_delay=0.01 -s recoat_time=5)
run "$LAMINA" slice "$cube" "${base[@]}" -s hatch_strategy=lines "${t[@]}" -o "$TMP/t.cli"
like "$ERR" '1 layers, 1 contour passes, 8 hatch vectors, 24 mm exposed, 1.88 mm jumped; estimated build time 15 s \(exposure 10 s, jumps 0.3 s, recoating 5.0 s\)' \
    "slice: the estimate of the hand-computed layer"
# --json FILE: the same in the run's JSON, each layer's too (two layers of 1:
# the first is the hand-computed one; the job's total is the layers' sum)
run "$LAMINA" slice "$cube" -m cli-ascii -w 1 -s hatch_distance=0.25 -s hatch_angle=0 -s hatch_strategy=lines "${t[@]}" \
    -o "$TMP/j.cli" --json "$TMP/j.json"
is "$(jq -c '[.totals.layers, ([.layers[].vectors[] | select(.kind == "core")] | length > 8), .layers[0].stats.time, .totals.time.recoat, (.totals.time.total - ([.layers[].stats.time] | add) | fabs < 1e-9)]' "$TMP/j.json")" \
    '[2,true,15.2675,10,true]' "slice --json: layers, the first layer's 15.2675 s, the total is the layers' sum"
like "$ERR" 'estimated build time' "slice --json: the estimate is still a line on standard error"
# point exposure (the contour's follows the core's): 2 / 0.5 + 1 = 5 points
# a line, 0.1 s each: 8 x 0.5 = 4 s; the closed contour 8 / 0.5 = 16 points,
# 1.6 s; with jumps and recoating 10.8675 s (printed: 11 s)
run "$LAMINA" slice "$cube" "${base[@]}" -s hatch_strategy=lines "${t[@]}" -s point_distance=0.5 -s exposure_time=0.1 -o "$TMP/t.cli"
like "$ERR" 'estimated build time 11 s \(exposure 5.6 s' "slice: point exposure counts points x exposure time"

# ---- CLI round trip: ASCII and binary, one part id -----------------------
for model in "$M/frame_island.ug" "$TMP/torus.stl"; do
    opts=(-w 1 -s hatch_strategy=islands -s hatch_distance=0.5 -s island_size=3)
    "$LAMINA" slice "$model" -m cli-ascii "${opts[@]}" -o "$TMP/a.cli" 2>/dev/null
    run "$LAMINA" slice "$model" -m cli-binary "${opts[@]}" -o "$TMP/b.cli"
    is "$RC" 0 "cli-binary with hatches: exit 0 ($(basename "$model"))"
    python3 "$TESTS/cli/clidecode.py" "$TMP/b.cli" >"$TMP/b.txt"
    python3 "$TESTS/cli/clicompare.py" "$TMP/a.cli" "$TMP/b.txt" >/dev/null
    ok $? "binary CLI with hatches decodes to the ASCII CLI, numbers as float32 ($(basename "$model"))"
    ids=$(grep -E '^\$\$(POLYLINE|HATCHES)/' "$TMP/b.txt" | sed 's/^[^/]*\///; s/,.*//' | sort -u)
    is "$ids" 1 "one part id for every polyline and hatch block ($(basename "$model"))"
    is "$(grep -c '^\$\$LABEL/1,' "$TMP/b.txt")" 1 "one \$\$LABEL for the model"
    run "$LAMINA" validate "$model" -w 1 --program "$TMP/b.cli"
    is "$RC" 0 "validate --program reads the hatched binary program back ($(basename "$model"))"
done

# the SLS text program with hatches reads back (hatch blocks read over)
"$LAMINA" slice "$M/frame_island.ug" -w 2 -s hatch_strategy=islands -s hatch_distance=1 -o "$TMP/h.sls" 2>/dev/null
run "$LAMINA" validate "$M/frame_island.ug" -w 2 --program "$TMP/h.sls"
is "$RC" 0 "validate --program reads a hatched SLS program back"
like "$OUT" "10 layers, 30 contours checked, 30 confirmed" "... every contour of it"
printf 'hatches core 1 0\n1 2 3 4 5 6\n' >"$TMP/open.sls"
run "$LAMINA" validate "$M/frame_island.ug" -w 2 --program "$TMP/open.sls"
like "$RC $ERR" "^1 .*open\.sls:3:1: the file ends where 'endhatches' was expected \(in the hatches at 1:1\)" \
    "an unfinished hatch block: file:line:column"

# errors: a hatch distance that would make an endless program
run "$LAMINA" slice "$M/frame_island.ug" -s hatch_strategy=lines -s hatch_distance=1e-7 -o "$TMP/x.cli"
ok $((RC == 0)) "a hatch distance of 1e-7: an error, not an endless program"
like "$ERR" "hatch_distance must be 1e-06 or more, got '1e-7'" "... refused with the key's least value (test_hatch: the planner's own guard)"
[ ! -e "$TMP/x.cli" ]; ok $? "... and no output file"
run "$LAMINA" slice "$cube" -s hatch_strategy=zigzag
like "$ERR" "hatch_strategy must be none, lines, stripes or islands, got 'zigzag'" "an unknown strategy is named"
done_testing
