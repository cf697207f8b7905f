#!/usr/bin/env bash
# The viewer's views (issue 26) in headless Chromium, driven over the
# DevTools pipe (cdp.py) by viewerbrowser.py: every colouring mode, every
# plot, the hover, the ruler and the lasers' fields, each a screenshot whose
# pixels are checked against the test's own expectation from the same run's
# --json (which vector passes where, in which colour by the documented
# palettes and layout), and the time to the first layer and to step.
# Jobs: the T (tests/models/recipes/tee.ug: a core in the stem, down-skin
# under the cap, up-skin on it) and a plate of three parts, three build
# styles of known power, speed and hatch distance (the energy view reads
# the run's job.exposure), two lasers.
. "$(dirname "$0")/lib.sh"
CHROME=$(command -v chromium || command -v chromium-browser)
if [ -z "$CHROME" ]; then
    echo "1..0 # skip chromium is not installed (make deps could not install it)"
    exit 0
fi
VC() { python3 "$TESTS/cli/viewerbrowser.py" "$@"; }
# relay viewerbrowser.py's "ok ..." / "not ok ...: why" lines as tests
relay() {
    local line
    while IFS= read -r line; do
        case $line in
        "ok "*) ok 0 "${line#ok }" ;;
        "not ok "*) ok 1 "${line#not ok }" ;;
        "#"*) echo "$line" ;;
        *) ok 1 "viewerbrowser.py said: $line" ;;
        esac
    done
}
CB=(python3 "$TESTS/build/check_build.py")

# ---- one part with skins: region and scan order ------------------------------------
# hatches 0.02 apart: closer than 2 px at the fitted zoom, so drawn as filled strips
run "$LAMINA" slice "$M/recipes/tee.ug" -m lpbf-cli -w 0.5 -s hatch_distance=0.02 \
    -s upskin.hatch_distance=0.02 -s downskin.hatch_distance=0.02 \
    --html "$TMP/tee.html" --json "$TMP/tee.json" -o "$TMP/tee.cli"
is "$RC" 0 "the T: slice --html --json, exit 0"

# ---- a plate: part, build style, laser, energy density, plots ----------------------
J="$TMP/plate"
mkdir -p "$J"
"${CB[@]}" stl box "$J/box.stl" 30 20 3
"${CB[@]}" stl cyl "$J/cyl.stl" 10 2
"${CB[@]}" stl box "$J/sq.stl" 20 20 1
cat >"$J/plate.yaml" <<'EOF'
machine: lpbf-cli
layer_width: 0.5
hatch_distance: 0.25
lasers: [{field: [0, 0, 130, 250]}, {field: [120, 0, 250, 250]}]
styles:
  cool: {power: 100, speed: 1000, hatch_distance: 0.25}
  hot: {power: 400, speed: 500, hatch_distance: 0.2}
  mid: {power: 200, speed: 1000, hatch_distance: 0.25}
parts:
  - {model: box.stl, at: [40, 40], name: left, style: cool}
  - {model: cyl.stl, at: [200, 40], name: right, style: hot}
  - {model: sq.stl, at: [60, 160], name: mid, style: {core: mid, upskin: mid, downskin: mid}}
EOF
run "$LAMINA" build "$J/plate.yaml" -o "$J/plate.cli" --json "$J/plate.json" --html "$J/plate.html"
is "$RC" 0 "the plate: build --html --json, exit 0"

# ---- a bigger job: every layer drawn, the first before the page is read -------------
"${CB[@]}" stl box "$TMP/big.stl" 40 40 3
run "$LAMINA" slice "$TMP/big.stl" -m lpbf-cli -w 0.375 -s hatch_strategy=islands -s hatch_distance=0.02 \
    -s upskin.hatch_distance=0.02 -s downskin.hatch_distance=0.02 --html "$TMP/big.html" --json "$TMP/big.json" \
    -o "$TMP/big.cli"
is "$RC" 0 "a bigger job: slice --html, exit 0"

# ---- in one browser -----------------------------------------------------------------
# the T, layer 17: core in the stem, down-skin under the cap; 18: down-skin and up-skin.
# The bigger job's times are printed, not asserted: make bench (tests/bench/viewer.sh) measures them.
relay < <(VC "$CHROME" "$TMP/tee.html" "$TMP/tee.json" colour region 17 colour region 18 colour order 18 \
    wrong region order 18 pick 18 ruler legend region 17 scale order 18 \
    page "$J/plate.html" "$J/plate.json" colour part 2 colour style 2 colour laser 2 colour energy 2 \
    hotter 2 wrong laser part 2 wrong style laser 2 \
    plot time 3 plot area 2 plot vectors 4 plot travel 1 plotclick 5 fields 2 pick 2 legend part 6 legend style 2 legend laser 2 scale energy 2 \
    page "$TMP/big.html" "$TMP/big.json" steps early 2>&1)
done_testing
