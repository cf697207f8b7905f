#!/usr/bin/env bash
# lamina build JOB.yaml (issue 25): several parts on one plate, several
# lasers, readable times. The runs are checked from their --json and their
# ASCII CLI program by tests/build/check_build.py, whose geometry (hulls,
# shoelace areas, point in polygon, segment distances) is its own: the
# arrangement keeps every part inside the plate less its margin and the
# parts' contours the spacing apart, fixed places are honoured, a part on
# the plate is exactly that part planned alone at the same place, four
# lasers share a layer within 5% of the ideal plus one block, no vector
# leaves its laser's field, parts go downstream of the gas flow first, the
# layers' heights and the printed time are the JSON's own sums; job file
# errors point at their line and column. The jobs live in a folder with a
# space in its name and lamina runs from another one (models are found
# from the job's folder). Models are a few mm high at 0.5 mm layers, hatch
# distance 1: every run takes well under a second. The checker is one Python
# for the whole test (check_build.py serve: a start cost more than most
# checks, 0.2-0.35 s each, some 80 of them).
. "$(dirname "$0")/lib.sh"

coproc CBS { exec python3 "$TESTS/build/check_build.py" serve; }
cb() { # cb COMMAND ARGS...: check_build.py COMMAND ARGS in the server; sets RC, OUT and ERR as run would
    local line out=""
    RC=1
    printf '%s\n' "$#" >&"${CBS[1]}" && printf '%s\0' "$@" >&"${CBS[1]}" || { OUT="" ERR="no checker"; return; }
    while IFS= read -r line <&"${CBS[0]}"; do
        if [[ $line == $'\x1e'SERVE_END\ * ]]; then
            RC=${line##* }
            break
        fi
        out+=$line$'\n'
    done
    while [[ $out == *$'\n' ]]; do out=${out%$'\n'}; done
    OUT=$out ERR=""
}
cbo() { # cbo COMMAND ARGS...: cb, its output on standard output (for $(...))
    cb "$@"
    printf '%s\n' "$OUT"
}
J="$TMP/job dir"
mkdir -p "$J" "$TMP/cwd"
cd "$TMP/cwd" || exit 1

cb selftest
is "$RC $OUT" "0 " "checker: its geometry and time parsing on hand-worked cases"

cb stl cyl "$J/cyl.stl" 20 2      # 40 mm across, 48 sides, 4 layers
cb stl cyl "$J/tall.stl" 8 4      # 16 mm across, 8 layers (a core between the skins)
cb stl cyl "$J/pin.stl" 3 3       # 6 mm across
cb stl box "$J/box.stl" 30 20 3
cb stl box "$J/big.stl" 100 100 1
cb stl ell "$J/ell.stl" 30 25 8 3 # an L: 30 x 25, arms 8 wide
cb stl ell "$J/ella.stl" 30 25 8 3 ascii # the same as ASCII STL
# the sections' areas, by hand: a 48-gon of radius r is 24 r^2 sin(7.5 deg);
# the L is 30 x 8 + 17 x 8; the box 30 x 20
A_CYL=$(cbo py 'import math; print(24 * 400 * math.sin(math.pi / 24))')
A_PIN=$(cbo py 'import math; print(24 * 9 * math.sin(math.pi / 24))')

# the head of every job: coarse hatches so that the runs stay small, and
# no supports (lpbf-cli makes them: the supported builds are at the end)
HEAD0='machine: lpbf-cli
layer_width: 0.5
hatch_distance: 1
support_type: none'
HEAD="$HEAD0
upskin: {hatch_distance: 1}
downskin: {hatch_distance: 1}"
job() { # job NAME TEXT: the job file NAME.yaml in "$J"
    printf '%s\n' "$2" >"$J/$1.yaml"
}
build() { # build NAME [ARGS]: NAME.yaml into NAME.cli, NAME.json (stderr in NAME.err)
    local n=$1
    shift
    "$LAMINA" build "$J/$n.yaml" -o "$J/$n.cli" --json "$J/$n.json" "$@" 2>"$J/$n.err"
    RC=$?
}

# ---- usage -------------------------------------------------------------------
run "$LAMINA" build --help
like "$RC $OUT" '^0 usage: lamina build JOB.yaml(?s:.*)--layout(?s:.*)-j, --jobs' "--help: the usage, exit 0"
run "$LAMINA" build -o "$TMP/x.cli"
like "$RC $ERR" '^2 lamina build: no job given' "no job: usage error, exit 2"
job one "$HEAD
parts: [{model: pin.stl}]"
run "$LAMINA" build "$J/one.yaml" "$J/one.yaml" -o "$TMP/x.cli"
like "$RC $ERR" '^2 lamina build: more than one job given' "two jobs: usage error, exit 2"
[ ! -e "$TMP/x.cli" ]
ok $? "usage errors: no output"

# a relative job path from another folder: the models are the job folder's
(cd "$TMP/cwd" && "$LAMINA" build "../job dir/one.yaml" -q -o rel.cli)
ok $? "a job given by a relative path with a space: its models found from its folder"

# ---- 1. arrangement ------------------------------------------------------------
# 25 copies of the 40 mm cylinder: 5 x 40 + 4 x 5 = 220 <= 250 - 2 x 5, a 5 x 5 grid;
# the pin fixed at (235, 235): its box 232 .. 238 clears the grid's 225 by 7 >= 5
job grid "$HEAD
lasers: [{field: [0, 0, 250, 250]}, {field: [0, 0, 250, 250]}, {field: [0, 0, 250, 250]}, {field: [0, 0, 250, 250]}]
parts:
  - model: cyl.stl
    copies: 25
  - {model: pin.stl, at: [235, 235]}   # fixed place: centre of its footprint box"
build grid --layout "$J/grid.svg"
is "$RC" 0 "25 cylinders and a fixed pin: exit 0"
cb arrange "$J/grid.json" 250x250 5 5 26 pin=235,235 "cyl~$A_CYL" "pin~$A_PIN"
# neighbours' centres 45 apart, each outer pass's vertex (at angle 0) half a spot
# (0.04) inside the model's edges, 0.04 / cos 3.75 deg inside its radius 20
D=$(cbo py 'import math; print("%.6f" % (45 - 2 * (20 - 0.04 / math.cos(math.pi / 48))))')
is "$RC $OUT" "0 # closest contours $D apart: parts 1 and 2" \
    "25 cylinders: inside the margin, contours >= 5 apart ($D), the pin at (235, 235), outlines = the sections less the beam offset"

# mixed sizes, rotations, an L, two fixed parts
job mixed "$HEAD
parts:
  - {model: ell.stl, copies: 4}
  - {model: box.stl, copies: 3, rotate: z:30}
  - {model: cyl.stl, copies: 6}
  - {model: pin.stl, copies: 5, rotate: [x:90, z:45]}
  - {model: pin.stl, at: [120.25, 200.5], name: fixed_a}
  - {model: box.stl, at: [30, 220], name: fixed_b}"
build mixed
is "$RC" 0 "mixed sizes: exit 0"
cb arrange "$J/mixed.json" 250x250 5 5 20 fixed_a=120.25,200.5 fixed_b=30,220 ell~376 box~600 \
    fixed_b~600 "cyl~$A_CYL"
like "$RC $OUT" '^0 # closest contours 5\.\d+ apart' "mixed sizes: inside the margin, >= 5 apart, fixed parts where the job says, outlines = sections"

# a round plate (coordinates from its centre), spacing 8
job round "$HEAD
plate: {diameter: 200, margin: 5}
spacing: 8
lasers: [{field: [-100, -100, 100, 100]}]
parts:
  - {model: cyl.stl, copies: 4}
  - {model: ell.stl, copies: 3}
  - {model: box.stl, copies: 3, rotate: z:30}
  - {model: pin.stl, at: [0, 0], name: centre}
  - {model: pin.stl, at: [-60.5, 20.25], name: side}"
build round --layout "$J/round.svg"
is "$RC" 0 "round plate: exit 0"
cb arrange "$J/round.json" d200 5 8 12 centre=0,0 side=-60.5,20.25 ell~376 box~600 "cyl~$A_CYL"
like "$RC $OUT" '^0 # closest contours 8\.\d+ apart' "round plate: within 95 of the centre, >= 8 apart, fixed parts honoured"

# edge cases of the packing. 44 mm cylinders: 5 x 44 + 4 x 5 = 240 fills the plate
# less its margins exactly, so 25 fit and not 26
cb stl cyl "$J/c44.stl" 22 1
cb stl box "$J/sq.stl" 20 20 1
job exact "$HEAD
parts: [{model: c44.stl, copies: 25}]"
build exact -q
cb arrange "$J/exact.json" 250x250 5 5 25
like "$RC $OUT" '^0 # closest contours 5\.08' "25 cylinders of 44 mm exactly filling 240 mm: all fit, inside, apart"
job exact26 "$HEAD
parts: [{model: c44.stl, copies: 26}]"
build exact26
like "$RC $(cat "$J/exact26.err")" '^1 lamina: only 25 of 26 parts fit' "26 of them: only 25 fit"
# 20 mm squares on the round plate: a square grid of pitch 25 centred on the plate
# holds as many as the corners within 95 of the centre allow (counted here); the
# packing must place at least as many
N=$(cbo py 'import math
print(max(sum(all(math.hypot(o + 25 * i + a, o + 25 * j + b) <= 95 for a in (-10, 10) for b in (-10, 10))
              for i in range(-5, 6) for j in range(-5, 6)) for o in (0, 12.5)))')
job roundsq "$HEAD
plate: {diameter: 200, margin: 5}
lasers: [{field: [-100, -100, 100, 100]}]
parts: [{model: sq.stl, copies: $N}]"
build roundsq -q
cb arrange "$J/roundsq.json" d200 5 5 "$N" sq~400
like "$RC $OUT" '^0 # closest contours 5\.08' "round plate: $N squares (a centred grid's count) fit, inside, apart"
job fixnear "$HEAD
parts: [{model: pin.stl, at: [50, 50]}, {model: pin.stl, at: [60.5, 50], name: near}]"
rm -f "$J/fixnear.cli"
build fixnear
like "$RC $(cat "$J/fixnear.err")" '^1 lamina: fixed parts pin and near are closer than the spacing \(5 mm\)' \
    "fixed parts 4.5 mm apart (boxes 47 .. 53, 57.5 .. 63.5): an error"
is "$(ls "$J" | grep -c '^fixnear\.\(cli\|json\)$')" 0 "fixed parts too close: no output"

# units and scale: a cylinder of radius 0.5 in (12.7 mm, 0.1 in high), a 10 x 5 x 1
# box scaled 2 (20 x 10 x 2), the same turned; -s spacing=10 over the machine's 5
cb stl cyl "$J/inch.stl" 0.5 0.1
cb stl box "$J/b10.stl" 10 5 1
job units "$HEAD
parts: [{model: inch.stl, units: in, name: inch}, {model: b10.stl, scale: 2, name: twice},
        {model: b10.stl, scale: 2, rotate: z:90, name: turned}]"
build units -q -s spacing=10
is "$(jq -c '[.job.build.spacing, [.job.build.parts[] | [((.box[2] - .box[0]) * 1e6 | round), ((.box[3] - .box[1]) * 1e6 | round), .layers[1]]]]' "$J/units.json")" \
    '[10,[[25400000,25400000,6],[20000000,10000000,4],[10000000,20000000,4]]]' \
    "units: in and scale: 2: footprints 25.4 x 25.4, 20 x 10, 10 x 20; 2.54 mm high in 6 layers, 2 mm in 4"
cb arrange "$J/units.json" 250x250 5 10 3 \
    "inch~$(cbo py 'import math; print(24 * 12.7 ** 2 * math.sin(math.pi / 24))')" twice~200 turned~200
like "$RC $OUT" '^0 # closest contours 10\.08' "units, scale, -s spacing=10: inside, 10 apart, the sections' areas"

# the same L as ASCII STL (integer corners: the same in float32): the same program
job round_ascii "$(sed 's/{model: ell.stl, copies: 3}/{model: ella.stl, copies: 3, name: ell}/' "$J/round.yaml")"
build round_ascii -q
cmp -s "$J/round.cli" "$J/round_ascii.cli"
ok $? "round plate with the L read from ASCII STL: the same program"

# the checker finds what it is there to find: two pins (boxes x 5 .. 11, 16 .. 22),
# the second moved 3 mm towards the first (its vectors' x less 3; one vector a line)
job pair "$HEAD
parts: [{model: pin.stl, copies: 2}]"
build pair -q
cb arrange "$J/pair.json" 250x250 5 5 2
like "$RC $OUT" '^0 # closest contours 5\.08\d* apart' "two pins: 5 + 2 x 0.04 apart"
perl -pe 's/"(from|to)": \[([-\d.e]+)/sprintf(q("%s": [%.17g), $1, $2 - 3)/ge if /"part": 2,/' "$J/pair.json" >"$TMP/moved.json"
cb arrange "$TMP/moved.json" 250x250 5 5 2
like "$RC $OUT" '^1 (?s:.*)parts 1 and 2: contours 2\.08\d* apart, closer than the spacing 5' \
    "checker: two parts 2 mm apart fail the spacing"

# ten 100 mm boxes: 100 + 5 + 100 = 205 <= 240 but 310 > 240: 2 x 2 = 4 fit
job nofit "$HEAD
parts: [{model: big.stl, copies: 10}]"
rm -f "$J/nofit.cli" "$J/nofit.json"
build nofit --layout "$J/nofit.svg"
like "$RC $(cat "$J/nofit.err")" '^1 lamina: only 4 of 10 parts fit on the plate \(250 x 250 mm, margin 5, spacing 5\)' \
    "ten 100 mm parts: only 4 of 10 fit, exit 1"
is "$(ls "$J" | grep -c '^nofit\.\(cli\|json\|svg\)$')" 0 "no fit: no output file"
# 24 of 25 cylinders fit around a pin fixed at (200, 200): a row meeting the pin's
# 189 .. 211 (spacing included) holds 4 (x 5 .. 180), below it 4 rows of 5 (45 n - 5 <= 184)
job pinned "$HEAD
parts: [{model: cyl.stl, copies: 25}, {model: pin.stl, at: [200, 200]}]"
build pinned
like "$RC $(cat "$J/pinned.err")" '^1 lamina: only 25 of 26 parts fit ' "a fixed pin in the grid's way: only 25 of 26 (24 + the pin)"

# ---- 2. a part on the plate = the part planned alone at its place -------------
STYLES='styles:
  fast: {power: 300, speed: 1400}
  fine: {power: 150, speed: 500, hatch_distance: 0.4}
  core: {power: 250, speed: 1000}'
job styled "$HEAD
$STYLES
parts:
  - {model: tall.stl, style: fast, name: quick}
  - {model: tall.stl, style: {core: fine}, name: careful}
  - {model: tall.stl, copies: 2}
  - {model: ell.stl, z: 1, name: lifted, rotate: z:90}
  - {model: box.stl, rotate: z:30, copies: 2}"
build styled
is "$RC" 0 "styled plate (one laser): exit 0"
for spec in 'careful|style: {core: fine}, model: tall.stl' 'lifted|z: 1, rotate: z:90, model: ell.stl' \
    'box_2|rotate: z:30, model: box.stl'; do
    name=${spec%%|*}
    job "alone_$name" "$HEAD
$STYLES
parts:
  - {${spec#*|}, name: $name, at: [$(cbo at "$J/styled.json" "$name")]}"
    build "alone_$name" -q
    cb alone "$J/styled.json" "$name" "$J/alone_$name.json"
    is "$RC $OUT" "0 " "part $name on the plate = planned alone at its at: every vector, in order, its style"
done
is "$(jq -c '[.job.build.parts[] | select(.name == "quick" or .name == "lifted") | .layers]' "$J/styled.json")" \
    '[[1,8],[3,8]]' "parts' layers: quick 0 .. 4 mm is layers 1 .. 8, lifted (z 1, 3 mm high) 3 .. 8"
cb alone "$J/styled.json" careful "$J/alone_lifted.json"
like "$RC $OUT" '^1 part careful: alone at' "checker: another part's program fails"

# ---- 3. four lasers ----------------------------------------------------------------
cb balance "$J/grid.json" "$J/grid.cli" 0.05
like "$RC $OUT" '^0 # worst balance' "four lasers over the plate: each layer's busiest <= 1.05 ideal + its largest block"
job mix4 "$HEAD
lasers: [{field: [0, 0, 250, 250]}, {field: [0, 0, 250, 250]}, {field: [0, 0, 250, 250]}, {field: [0, 0, 250, 250]}]
parts:
  - {model: cyl.stl, copies: 12}
  - {model: ell.stl, copies: 5}
  - {model: tall.stl, copies: 3}
  - {model: pin.stl, at: [235, 235]}"
build mix4
cb balance "$J/mix4.json" "$J/mix4.cli" 0.05
like "$RC $OUT" '^0 # worst balance' "four lasers, mixed parts: busiest <= 1.05 ideal + one block"
# a part of the plate planned alone with the same four lasers: the same vectors (as sets:
# the lasers share them differently)
job alone4 "$HEAD
$(grep '^lasers:' "$J/grid.yaml")
parts:
  - {model: cyl.stl, name: cyl_13, at: [$(cbo at "$J/grid.json" cyl_13)]}"
build alone4 -q
cb alone "$J/grid.json" cyl_13 "$J/alone4.json"
is "$RC $OUT" "0 " "four lasers: cyl_13 of the plate = cyl_13 alone with the same lasers (sets of vectors)"
for n in grid mix4; do
    cb gas "$J/$n.json"
    is "$RC $OUT" "0 " "$n: each laser's parts downstream first (gas flow -x: smallest x first; ties by number)"
done
# quadrant fields (the middle column of cylinders, x 95 .. 135, is cut at x = 125),
# the gas flowing towards +y
job quad "$HEAD
lasers: [{field: [0, 0, 125, 125]}, {field: [125, 0, 250, 125]}, {field: [0, 125, 125, 250]}, {field: [125, 125, 250, 250]}]
gas_flow: [0, 1]
parts:
  - {model: cyl.stl, copies: 25}
  - {model: pin.stl, at: [235, 235]}"
build quad --layout "$J/quad.svg"
is "$RC" 0 "quadrant fields: exit 0"
cb fields "$J/quad.json"
is "$RC $OUT" "0 " "quadrant fields: every vector inside its laser's field"
cb gas "$J/quad.json"
is "$RC $OUT" "0 " "quadrant fields, gas towards +y: each laser's parts largest y first"
job quad1 "$(grep -v '^lasers:' "$J/quad.yaml")"
build quad1 -q
job aloneq "$HEAD
$(grep '^lasers:\|^gas_flow:' "$J/quad.yaml")
parts:
  - {model: cyl.stl, name: cyl_13, at: [$(cbo at "$J/quad.json" cyl_13)]}"
build aloneq -q
cb alone "$J/quad.json" cyl_13 "$J/aloneq.json"
is "$RC $OUT" "0 " "quadrant fields: cyl_13 (x 95 .. 135, cut at 125) of the plate = alone with the same fields"
cb lengths "$J/quad.json" "$J/quad1.json"
is "$RC $OUT" "0 " "quadrant fields: every part's exposed length per kind and layer = one laser's (nothing lost at the cuts)"
# the first contour vector of laser 1 (one vector a line) given to laser 4
perl -pe 'if (!$done && /"kind": "contour".*"laser": 1,/) { s/"laser": 1,/"laser": 4,/; $done = 1 }' "$J/quad.json" \
    >"$TMP/swapped.json"
cb fields "$TMP/swapped.json"
like "$RC $OUT" '^1 layer 1: a contour vector of part \d+ on laser 4 at' "checker: a vector given to another quadrant's laser fails"

# ---- 4. layer heights -------------------------------------------------------------
for n in grid quad styled; do
    cb layers "$J/$n.json" "$J/$n.cli" 0.5
    is "$RC $OUT" "0 " "$n: \$\$LAYER k at k x 0.5, JSON z = top, cut = middle of floor and ceiling"
    cb labels "$J/$n.json" "$J/$n.cli"
    is "$RC $OUT" "0 " "$n: the program's \$\$LABEL table = the JSON's, blocks' ids = the vectors' labels, PART:STYLE:LASER"
done
sed 's|^\$\$LAYER/1\.00000$|$$LAYER/1.10000|' "$J/grid.cli" >"$TMP/bad.cli"
cb layers "$J/grid.json" "$TMP/bad.cli" 0.5
like "$RC $OUT" '^1 \$\$LAYER #2 at 1\.1, the layer.s top is 1' "checker: a \$\$LAYER off by 0.1 fails"
job quarter "$(sed 's/^layer_width: 0.5/layer_width: 0.25/' "$J/one.yaml")"
build quarter -q
cb layers "$J/quarter.json" "$J/quarter.cli" 0.25
is "$RC $OUT" "0 " "layer width 0.25: 12 layers of the 3 mm pin at k x 0.25"
build one -q -s layer_width=1.5
cb layers "$J/one.json" "$J/one.cli" 1.5
is "$RC $OUT" "0 " "-s layer_width=1.5 over the job's: 2 layers at 1.5 and 3"

# ---- 5. times ------------------------------------------------------------------------
for n in grid quad mixed round; do
    cb time "$J/$n.json" "$J/$n.err" 8
    like "$RC $OUT" '^0 # ' "$n: printed time = sum of each layer's busiest laser + 8 s recoat = JSON total"
done
# slow speeds for days and hours, a pin without recoat for tenths of a second
for sp in 0.01 0.5; do
    job "slow$sp" "$HEAD0
contour: {speed: $sp}
upskin: {hatch_distance: 1, speed: $sp}
downskin: {hatch_distance: 1, speed: $sp}
speed: $sp
parts: [{model: tall.stl}]"
    build "slow$sp"
    cb time "$J/slow$sp.json" "$J/slow$sp.err" 8
    like "$RC $OUT" "^0 # $([ "$sp" = 0.5 ] && echo '1 h \d+ min \d+ s' || echo '\d+ d \d+ h \d+ min') = " \
        "speed $sp mm/s: the printed time ($([ "$sp" = 0.5 ] && echo 'h min s' || echo 'd h min')) = the layers' sum"
done
job fastpin "$HEAD
recoat_time: 0
parts: [{model: pin.stl}]"
build fastpin
cb time "$J/fastpin.json" "$J/fastpin.err" 0
like "$RC $OUT" '^0 # \d\.\d s = ' "a pin, no recoat: tenths of a second, = the layers' sum"
build fastpin -s recoat_time=2.5
cb time "$J/fastpin.json" "$J/fastpin.err" 2.5
like "$RC $OUT" '^0 # \d+ s = ' "-s recoat_time=2.5: 6 layers x 2.5 s recoat in the total"
job nospeed "$HEAD0
speed: 0
contour: {speed: 0}
upskin: {speed: 0}
downskin: {speed: 0}
support: {speed: 0}
parts: [{model: pin.stl}]"
build nospeed
like "$RC $(cat "$J/nospeed.err")" '^0 lamina: .*nospeed\.yaml: 1 part, 6 layers, 1 laser, (?s:.*)estimated build time unknown: lpbf-cli sets no speeds$' \
    "no speeds: the time is unknown"
printf 'lamina: x: estimated build time 9 s (scanning' >"$TMP/wrong.err"
cb time "$J/fastpin.json" "$TMP/wrong.err" 2.5
like "$RC $OUT" '^1 (?s:.*)printed .9 s.' "checker: a wrong printed time fails"

# ---- 6. determinism -----------------------------------------------------------------------
for t in 1 2 4; do
    "$LAMINA" build "$J/mix4.yaml" -q -j "$t" -o "$TMP/j$t.cli" --json "$TMP/j$t.json"
done
cmp -s "$TMP/j1.cli" "$TMP/j2.cli" && cmp -s "$TMP/j1.cli" "$TMP/j4.cli" && cmp -s "$TMP/j1.cli" "$J/mix4.cli"
ok $? "-j 1, 2, 4: the same program"
cmp -s "$TMP/j1.json" "$TMP/j2.json" && cmp -s "$TMP/j1.json" "$TMP/j4.json"
ok $? "-j 1, 2, 4: the same JSON"
"$LAMINA" build "$J/quad.yaml" -q -j 4 -o "$TMP/q4.cli" --json "$TMP/q4.json"
cmp -s "$TMP/q4.cli" "$J/quad.cli" && cmp -s "$TMP/q4.json" "$J/quad.json"
ok $? "quadrant fields (cut vectors): -j 4 = -j 1"

# ---- 7. job file errors --------------------------------------------------------------
pos() { # pos FILE TEXT: LINE:COL (1-based) of TEXT's first occurrence
    cbo py 'import sys
t = open(sys.argv[1]).read(); i = t.index(sys.argv[2])
print("%d:%d" % (t.count("\n", 0, i) + 1, i - t.rfind("\n", 0, i)))' "$1" "$2"
}
jerr() { # jerr NAME TEXT REGEX DESCRIPTION: exit 1, "JOB:REGEX", no output
    job "$1" "$2"
    rm -f "$J/$1.cli" "$J/$1.json"
    build "$1"
    local e
    e=$(cat "$J/$1.err")
    like "$RC $e" "^1 lamina: $(perl -e 'print quotemeta shift' "$J/$1.yaml"):$3" "$4"
    is "$(ls "$J" | grep -c "^$1\.\(cli\|json\)\$")" 0 "$4: no output"
}
T="machine: lpbf-cli
layer_width: 0.5
partz:
  - model: pin.stl"
printf '%s\n' "$T" >"$TMP/t"
jerr e_key "$T" "$(pos "$TMP/t" partz): unknown key 'partz' in the job \\(did you mean parts\\?\\)" "unknown top-level key"
T="machine: lpbf-cli
parts:
  - {model: pin.stl}
  - copies: 2
    modle: pin.stl"
printf '%s\n' "$T" >"$TMP/t"
jerr e_part "$T" "$(pos "$TMP/t" modle): unknown key 'modle' in a part \\(did you mean model\\?\\)" "unknown part key"
T="machine: lpbf-cli
styles:
  fast: {power: 300}
  slow: {speed: 100, powr: 50}
parts: [{model: pin.stl}]"
printf '%s\n' "$T" >"$TMP/t"
jerr e_skey "$T" "$(pos "$TMP/t" powr):.*powr is not a build style key \\(did you mean power\\?\\)" "a style key that is not one"
T="machine: lpbf-cli
styles:
  fast: {power: 300}
parts:
  - {model: pin.stl, style: {core: fast, upskin: fats}}"
printf '%s\n' "$T" >"$TMP/t"
jerr e_style "$T" "$(pos "$TMP/t" fats):.*style fats is not defined" "a style not defined"
T="layer_width: 0.5
parts: [{model: pin.stl}]"
jerr e_machine "$T" "1:1: the job names no machine" "missing machine (the job as a whole)"
T="machine: lpbf-cli
parts:
  - {model: pin.stl}
  - {copies: 2, name: x}"
printf '%s\n' "$T" >"$TMP/t"
jerr e_model "$T" "$(pos "$TMP/t" '{copies'): the part names no model" "missing model (the part's mapping)"
T="machine: lpbf-cli
parts:
  - {model: pin.stl, copies: 0}"
printf '%s\n' "$T" >"$TMP/t"
jerr e_copies "$T" "$(pos "$TMP/t" 0}): copies must be a whole number from 1 to 10000, got '0'" "copies: 0 (the value)"
T="machine: lpbf-cli
parts:
  - model: pin.stl
    copies: 2
    at: [50, 50]"
printf '%s\n' "$T" >"$TMP/t"
jerr e_at "$T" "$(pos "$TMP/t" at:): a part with at has one copy" "at with copies 2 (the at key)"
T="machine: lpbf-cli
layer_width: -1
parts: [{model: pin.stl}]"
printf '%s\n' "$T" >"$TMP/t"
jerr e_value "$T" "$(pos "$TMP/t" -1): layer_width must be greater than 0, got '-1'" "layer_width: -1 (the value)"
T="machine: lpbf-cli
parts:
  - {model: pin.stl"
# libyaml finds the flow mapping unclosed at the end of the text (line 4, column 1)
jerr e_yaml "$T" "4:1: malformed YAML: .*\\(while parsing a flow mapping at line 3, column 5\\)" "malformed YAML"
job e_file "machine: lpbf-cli
parts: [{model: nothere.stl}]"
build e_file
like "$RC $(cat "$J/e_file.err")" "^1 lamina: .*e_file\\.yaml:$(pos "$J/e_file.yaml" '{model'): model .*nothere\\.stl: cannot open" \
    "a model that does not exist: exit 1, the error names the model where the job lists the part"
is "$(ls "$J" | grep -c '^e_file\.\(cli\|json\)$')" 0 "a model that does not exist: no output"
T="layer_width: 0.5
machine:   ded-gcode
parts: [{model: pin.stl}]"
printf '%s\n' "$T" >"$TMP/t"
# the machine line, at its key or its value (as an unknown machine's error is)
jerr e_ded "$T" "(?:$(pos "$TMP/t" machine)|$(pos "$TMP/t" ded-gcode)): machine ded-gcode is a ladrp profile" \
    "a non-powder-bed machine, on line 2"
# a plate the machine's lasers do not reach: lpbf-cli's field [0, 0, 250, 250] and a
# round plate of its own (coordinates from its centre): the parts placed left of and
# below the centre are outside it, said before anything is planned
T="machine: lpbf-cli
plate: {diameter: 200, margin: 5}
parts:
  - {model: pin.stl, copies: 4}"
printf '%s\n' "$T" >"$TMP/t"
jerr e_reach "$T" "$(pos "$TMP/t" '{model'): part pin_1 .* is not within the lasers' fields \\(1 laser\\)" \
    "parts the lasers do not reach: refused at the part, nothing written"

# ---- 8. build styles -----------------------------------------------------------------
# lpbf-cli: contour 120 W 600 mm/s, upskin 150/700, downskin 100/1200; the job's
# core style 250/1000 replaces the profile's core (200/900) for every part that
# names no other; fast 300/1400 on every region of quick; fine 150/500 on careful's core
cb styles "$J/styled.json" "$J/styled.cli" quick:contour=300/1400 quick:core=300/1400 \
    quick:upskin=300/1400 quick:downskin=300/1400 careful:core=150/500 careful:contour=120/600 \
    careful:upskin=150/700 careful:downskin=100/1200 tall:core=250/1000 tall:contour=120/600 \
    box:contour=120/600 box:downskin=100/1200 lifted:contour=120/600
is "$RC $OUT" "0 " "styles: each block's //REGION power P speed S// is its part's style for that region"
is "$(jq -c '[.job.build.styles[].name], [.job.build.parts[] | select(.name == "quick" or .name == "careful" or .name == "tall_1") | .styles]' "$J/styled.json")" \
    '["contour","core","upskin","downskin","fast","fine"]
[{"contour":5,"core":5,"upskin":5,"downskin":5},{"contour":1,"core":6,"upskin":3,"downskin":4},{"contour":1,"core":2,"upskin":3,"downskin":4}]' \
    "styles: numbered 1-4 for the regions, then the job's; quick all fast, careful's core fine"
is "$(jq -r '[.job.build.labels[].name | select(startswith("quick:") or startswith("careful:"))] | join(" ")' "$J/styled.json")" \
    "quick:fast:1 careful:contour:1 careful:fine:1 careful:upskin:1 careful:downskin:1" \
    "labels: PART:STYLE:LASER, one per style a part uses"
# the same plate without the core style: the plain parts' core is the profile's 200/900
job plain "$(grep -v '^  core: {power: 250' "$J/styled.yaml")"
build plain -q
cb styles "$J/plain.json" "$J/plain.cli" tall:core=200/900 careful:core=150/500
is "$RC $OUT" "0 " "styles: without a core style the parts' core is the profile's own"
cb styles "$J/plain.json" "$J/plain.cli" tall:core=250/1000
like "$RC $OUT" '^1 tall_\d:core:1 core: core power 200 speed 900, expected power 250' "checker: a wrong exposure fails"

# ---- 9. --layout ----------------------------------------------------------------------
for n in grid quad round; do
    cb layout "$J/$n.svg" "$J/$n.json"
    is "$RC $OUT" "0 " "$n --layout: one footprint and one name per part, one field per laser where it is"
done
is "$(grep -c 'class="part"' "$J/grid.svg") $(grep -c 'class="field"' "$J/quad.svg")" "26 4" \
    "--layout: 26 footprints on the grid, 4 quadrant fields"

# -v: a line per layer, its lasers' times and balance, as the JSON has them
run "$LAMINA" build "$J/quad.yaml" -v -o "$J/quadv.cli"
is "$(printf '%s\n' "$ERR" | grep -c '^lamina: .*quad\.yaml: layer [0-9]*: .*; laser 1 .*, laser 4 .*; balance [0-9.]*$')" \
    "$(cbo py 'import json,sys; print(len(json.load(open(sys.argv[1]))["layers"]))' "$J/quad.json")" \
    "-v: one line per layer with the four lasers' times and the balance"
first=$(cbo py 'import json,sys; print("%.3f" % json.load(open(sys.argv[1]))["layers"][0]["stats"]["balance"])' "$J/quad.json")
like "$ERR" "layer 1: .*; balance $first" "-v: layer 1's balance is the JSON's ($first)"

# ---- the README's example plate (examples/plate.yaml), coarse (layers, hatches) to be quick ----
EX="$TESTS/../examples/plate.yaml"
run "$LAMINA" build "$EX" -s layer_width=2 -s hatch_distance=1 -s skin_layers=0 -o "$J/example.cli" \
    --json "$J/example.json" --layout "$J/example.svg"
is "$RC" 0 "examples/plate.yaml builds (its models from the job's folder)"
like "$ERR" "11 parts, 10 layers, 2 lasers" "examples/plate.yaml: 11 parts, 20 mm at 2 mm, 2 lasers"
cb layout "$J/example.svg" "$J/example.json"
is "$RC $OUT" "0 " "examples/plate.yaml: the layout shows every part and both fields"

# ---- 10. supports: each part's own, from the plate up ---------------------------------
# two tees (tests/cli/supportgen.py: a 5 mm stem 10 high under a 20 x 8 bar
# 4 thick) on lpbf-cli's block supports, raised by support_height 2: every
# layer of each part's run stands (supportcheck.py, its own polygons), the
# run starts on the plate (layers 1 .. 2 / 0.5 = 4 are support alone, under
# the stem's whole footprint), support contours carry their part, every
# support vector lies in its part's footprint box (what the arrangement
# keeps apart), and the printed time is the layers' sum with the supports
# in it, more than without them.
python3 "$TESTS/cli/supportgen.py" tee "$J/tee.stl"
job teesup "machine: lpbf-cli
layer_width: 0.5
hatch_distance: 1
support_height: 2
recoat_time: 0
support_teeth: {height: 0}
spacing: 5
parts:
  - {model: tee.stl, copies: 2}"
build teesup
is "$RC" 0 "supported tees: exit 0"
python3 "$TESTS/cli/supportcheck.py" stands "$J/teesup.json" >"$J/stands.out" 2>&1
ok $? "supported tees: every point of every layer stands on the layer below ($(tail -1 "$J/stands.out"))"
is "$(jq -c '[.job.build.parts[].layers[0]]' "$J/teesup.json")" "[1,1]" "supported tees: each part's run starts on the plate"
is "$(jq -c '[.layers[] | select([.contours[] | select(.region == null)] | length == 0) | .index]' "$J/teesup.json")" \
   "[1,2,3,4]" "supported tees: layers 1 .. 4 hold supports only (the parts raised by 2 mm)"
is "$(jq -c '[.layers[0].contours[] | select(.region == "support") | .part] | unique' "$J/teesup.json")" "[1,2]" \
   "supported tees: the support contours say their part"
out=$(jq -r '.job.build.parts as $p | .layers[].vectors[] | select(.kind == "support") | . as $v | $p[$v.part - 1].box as $b
  | select($v.from[0] < $b[0] - 1e-9 or $v.from[0] > $b[2] + 1e-9 or $v.from[1] < $b[1] - 1e-9 or $v.from[1] > $b[3] + 1e-9
      or $v.to[0] < $b[0] - 1e-9 or $v.to[0] > $b[2] + 1e-9 or $v.to[1] < $b[1] - 1e-9 or $v.to[1] > $b[3] + 1e-9) | .order' "$J/teesup.json" | head -3)
is "$out" "" "supported tees: every support vector within its part's footprint box"
is "$(jq '[.layers[].vectors[] | select(.kind == "support")] | length > 100' "$J/teesup.json")" true \
   "supported tees: support vectors are planned"
cb time "$J/teesup.json" "$J/teesup.err" 0
like "$RC $OUT" '^0 # ' "supported tees: the printed time is the layers' sum (supports in it)"
cp "$J/teesup.yaml" "$J/teenone.yaml"
printf 'support_type: none\n' >>"$J/teenone.yaml"
build teenone
with=$(jq '.totals.time.total' "$J/teesup.json") without=$(jq '.totals.time.total' "$J/teenone.json")
ok "$(cbo py "import sys; print(0 if float(sys.argv[1]) > float(sys.argv[2]) else 1)" "$with" "$without")" \
   "supported tees: the build takes longer with supports ($with s) than without ($without s)"

done_testing
