#!/usr/bin/env bash
# The golden corpus: every shipped machine, every hatch strategy and order,
# skins, both frames, three axes, -j 1/2/8, a run in parts joined, and
# Lua's plan data, each written to OUT/NAME (program, .json, .html, .svg).
# tests/cli/golden.t runs it and compares every file with SHA256SUMS, made
# by this script at commit 55e94f0 (before the plan-stream redesign, issue
# 23), so a refactoring that changes one byte of any output fails.
#   corpus.sh LAMINA MODELS OUT      (MODELS: tests/models)
set -u
LAMINA=$1 MODELS=$2 OUT=$3
mkdir -p "$OUT/in" || exit 1
cp "$MODELS/thesis_cube_hole.ug" "$MODELS/frame_island.ug" "$MODELS/pinplate.ug" \
   "$MODELS/golden/sphere.obj" "$MODELS/golden/terrace.ug" "$MODELS/golden/dump.lua" "$OUT/in/" || exit 1
cd "$OUT/in" || exit 1
fail=0
# job NAME MODEL ARGS...: the program, JSON, viewer and contact sheet of one run
job() {
    local name=$1 model=$2; shift 2
    if ! "$LAMINA" slice "$model" -q "$@" -o "../$name" --json "../$name.json" \
            --html "../$name.html" --svg "../$name.svg" 2>"../$name.err"; then
        echo "corpus: $name failed: $(cat "../$name.err")" >&2; fail=1
    fi
}
for j in 1 2 8; do
    for f in model machine; do
        for a in z x 1,1,1; do
            t="j$j-$f-${a//,/_}"
            job "ladrp-hole-$t" thesis_cube_hole.ug -m creol-ladrp -w 0.25 -a "$a" --frame $f -j $j
            job "ded-frame-$t" frame_island.ug -m ded-gcode -w 0.5 -a "$a" --frame $f -j $j --islands --perimeters 1
            job "sls-pin-$t" pinplate.ug -m sls-contours -w 0.5 -a "$a" --frame $f -j $j --beam-offset
            job "clia-sphere-$t" sphere.obj -m cli-ascii -w 0.5 -a "$a" --frame $f -j $j -s hatch_strategy=lines
            job "clib-frame-$t" frame_island.ug -m cli-binary -w 0.5 -a "$a" --frame $f -j $j
        done
        for s in lines stripes islands; do
            for o in meander unidirectional greedy; do
                job "lpbf-terrace-$s-$o-j$j-$f" terrace.ug -m lpbf-cli -w 0.25 --frame $f -j $j \
                    -s hatch_strategy=$s -s hatch_order=$o -s skin_layers=2 -s stripe_width=1 \
                    -s island_size=1 -s upskin.hatch_angle=45 -s downskin.hatch_distance=0.05
            done
        done
        for io in checker random; do
            job "lpbf-sphere-$io-j$j-$f" sphere.obj -m lpbf-cli -w 1 --frame $f -j $j -s hatch_strategy=islands \
                -s island_order=$io -s island_size=3 -s hatch_distance=0.5 -s seed=7 -s skin_layers=1 -s contour_count=2
        done
    done
    job "ladrp-sphere-j$j" sphere.obj -m creol-ladrp -w 0.5 -j $j --angle-step 67.5 --perimeters 2 --first-line center
    job "ded-terrace-j$j" terrace.ug -m ded-gcode -w 0.25 -j $j --angle 30 --no-alternate --min-deposit 0.2
done
# a run in parts, joined (part files are the planner's operations)
for m in creol-ladrp lpbf-cli cli-binary; do
    skins=(); [ $m = creol-ladrp ] || skins=(-s skin_layers=2)
    for k in 1 2 3; do
        "$LAMINA" slice terrace.ug -q -m $m -w 0.25 "${skins[@]}" --layers $k/3 -o "../part-$m-$k" || fail=1
    done
    "$LAMINA" join "../part-$m-1" "../part-$m-2" "../part-$m-3" -o "../join-$m" || fail=1
done
# Lua's plan data: every layer of every plan as text
for m in creol-ladrp ded-gcode sls-contours cli-ascii lpbf-cli; do
    for j in 1 8; do
        "$LAMINA" run dump.lua $m $j terrace.ug >"../lua-$m-j$j" 2>"../lua-$m-j$j.err" || {
            echo "corpus: lua $m failed: $(cat "../lua-$m-j$j.err")" >&2; fail=1; }
    done
done
"$LAMINA" run dump.lua lpbf-cli 2 pinplate.ug islands >"../lua-lpbf-pin" || fail=1
cd .. && rm -rf in && exit $fail
