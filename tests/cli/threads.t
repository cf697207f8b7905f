#!/usr/bin/env bash
# -j N (issue 15): workers slice and plan layers, the writer writes them in
# layer order, so the program, the messages and the exit status are the
# same for every number of threads. Every shipped machine (text dialects
# and the binary CLI plugin) on models that exercise what a layer's plan
# carries from the layer before: LADRP islands (the nearest island to where
# the stage stands), perimeters, raster angles per layer, SLS skins (the
# layers around), an oblique axis; then a run that fails in a middle layer.
. "$TESTS/cli/lib.sh"
ROOT=$(cd "$TESTS/.." && pwd)

python3 "$TESTS/cli/meshgen.py" sphere "$TMP/sphere.stl"
python3 "$TESTS/cli/meshgen.py" torus "$TMP/torus.stl"

# same NAME ARGS...: the run with -j 1 against -j 2, 3 and 8: program and
# standard error byte for byte, exit status
same() {
    local name=$1
    shift
    "$LAMINA" slice "$@" -j 1 -o "$TMP/$name.1" 2>"$TMP/$name.err1"
    local rc1=$? size
    size=$(stat -c %s "$TMP/$name.1" 2>/dev/null || echo 0)
    ok $(( rc1 == 0 && size > 200 ? 0 : 1 )) "$name: -j 1 writes a program (exit $rc1, $size bytes)"
    for j in 2 3 8; do
        "$LAMINA" slice "$@" -j "$j" -o "$TMP/$name.$j" 2>"$TMP/$name.err$j"
        local rc=$?
        cmp -s "$TMP/$name.1" "$TMP/$name.$j" && cmp -s "$TMP/$name.err1" "$TMP/$name.err$j" && [ "$rc" = "$rc1" ]
        ok $? "$name: -j $j writes the same program and messages as -j 1"
    done
}

machines=$(cd "$ROOT/machines" && ls *.yaml | sed 's/\.yaml$//')
is "$(echo $machines | wc -w)" 6 "six shipped machines"
for m in $machines; do
    # the raster options are the ladrp planner's (an sls profile refuses them)
    step=() islands=()
    if "$LAMINA" machines | grep -q "^$m  *ladrp "; then step=(--angle-step 30) islands=(--islands --perimeters 1); fi
    same "$m-cube-hole" "$M/thesis_cube_hole.ug" -m "$m" -w 0.25
    same "$m-sphere" "$TMP/sphere.stl" -m "$m" -w 0.2 "${step[@]}"
    same "$m-torus-oblique" "$TMP/torus.stl" -m "$m" -a 1,1,2 -w 0.25
    same "$m-frame-islands" "$M/frame_island.stl" -m "$m" -w 0.5 "${islands[@]}"
done
# hatching with islands and skins: each layer's plan looks at the layers
# around it, which a worker slices again at the start of its run of layers
same lpbf-hatch-skins "$TMP/sphere.stl" -m lpbf-cli -w 0.1 -s hatch_strategy=islands -s island_size=2 \
    -s skin_layers=2 -s hatch_distance=0.2
same binary-hatch "$TMP/torus.stl" -m cli-binary -w 0.1 -s hatch_strategy=stripes -s hatch_distance=0.2
# Text dialects are formatted by the workers, a layer into a buffer each,
# and written in order: what the text carries from the layers before must
# still come out right. The separator goes between two blocks, never before
# the program's first, also when the first layers are empty (planes below
# the part) and the first block is in a layer a worker formatted alone.
cat >"$TMP/sep.yaml" <<'EOF'
inherits: sls-contours
dialect:
  preamble: "begin {layers} {label}"
  layer: "layer {index} {number} {z:%.3f}"
  layer_end: "end {number}"
  separator: "---"
  postamble: "done {layers}"
EOF
same sep-empty-first "$M/thesis_cube_hole.ug" -m "$TMP/sep.yaml" --planes=-3,-2,-1,-0.5,0.5,1,1.5,1.75,2.5
same sep-sphere "$TMP/sphere.stl" -m "$TMP/sep.yaml" -w 0.1 -s hatch_strategy=lines -s hatch_distance=0.5
is "$(grep -c -- '^---$' "$TMP/sep-empty-first.1")" \
    "$(( $(grep -c '^contour ' "$TMP/sep-empty-first.1") - 1 ))" \
    "separator: one fewer than the blocks (none before the first)"
is "$(sed -n 2p "$TMP/sep-empty-first.1")" "layer 0 1 -2.500" "separator: the empty first layer is written"
# relative moves (creol-ladrp, dx dy): every move's text depends on the
# rounding of all the moves before, so that dialect is formatted in layer
# order on the main thread; an absolute one (ded-gcode) by the workers
same ladrp-relative-many "$TMP/sphere.stl" -m creol-ladrp -w 0.1 --islands
same ladrp-absolute-many "$TMP/sphere.stl" -m ded-gcode -w 0.1 --islands
# A binary STL of 25,000 facets (read and welded as it comes, a few
# hundred layers planned and formatted by the workers)
python3 - "$TMP/bsphere.stl" <<'EOF'
import math, struct, sys
nu, nv, R = 160, 80, 5.0
def p(i, j):
    th, ph = 2 * math.pi * (i % nu) / nu, -math.pi / 2 + math.pi * j / nv
    if j in (0, nv): return (0.0, 0.0, -R if j == 0 else R)
    return (R * math.cos(ph) * math.cos(th), R * math.cos(ph) * math.sin(th), R * math.sin(ph))
tris = []
for i in range(nu):
    for j in range(nv):
        a, b, c, d = p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)
        if j > 0: tris.append((a, b, c))
        if j < nv - 1: tris.append((a, c, d))
with open(sys.argv[1], "wb") as f:
    f.write(b"\0" * 80 + struct.pack("<I", len(tris)))
    for t in tris:
        f.write(struct.pack("<12fH", 0, 0, 0, *[x for v in t for x in v], 0))
EOF
same binary-sphere-big "$TMP/bsphere.stl" -w 0.2
# A binary STL of 540,800 facets (a torus of 520 x 520 quads): over the
# 524,288 from which the threads also decode and weld it (core/mesh/stl_weld.c).
# The program, `lamina info` (no -j: LAMINA_THREADS) but for its peak
# memory line, and the error for a NaN in facet 520,000 are the same for
# 1 and 3 threads.
python3 - "$TMP/btorus.stl" <<'EOF'
import math, struct, sys
nu = nv = 520
def p(i, j):
    th, ph = 2 * math.pi * (i % nu) / nu, 2 * math.pi * (j % nv) / nv
    r = 20 + 10 * math.cos(ph)
    return (r * math.cos(th), r * math.sin(th), 10 * math.sin(ph))
pts = [[p(i, j) for j in range(nv)] for i in range(nu)]
rec = struct.Struct("<12fH")
out = bytearray(b"\0" * 80 + struct.pack("<I", 2 * nu * nv))
for i in range(nu):
    for j in range(nv):
        a, b, c, d = pts[i][j], pts[(i + 1) % nu][j], pts[(i + 1) % nu][(j + 1) % nv], pts[i][(j + 1) % nv]
        out += rec.pack(0, 0, 0, *a, *b, *c, 0) + rec.pack(0, 0, 0, *a, *c, *d, 0)
open(sys.argv[1], "wb").write(out)
EOF
for j in 1 3; do
    "$LAMINA" slice "$TMP/btorus.stl" -w 2 -j $j -o "$TMP/btorus.$j" 2>"$TMP/btorus.err$j"
    echo "rc $?" >>"$TMP/btorus.err$j"
    LAMINA_THREADS=$j "$LAMINA" info "$TMP/btorus.stl" | grep -v '^peak memory' >"$TMP/binfo$j"
done
cmp -s "$TMP/btorus.1" "$TMP/btorus.3" && cmp -s "$TMP/btorus.err1" "$TMP/btorus.err3" && grep -q '^rc 0$' "$TMP/btorus.err1" &&
    [ "$(stat -c %s "$TMP/btorus.1")" -gt 100000 ]
ok $? "binary STL over the threaded reader's threshold: the same program for -j 1 and -j 3"
cmp -s "$TMP/binfo1" "$TMP/binfo3" && grep -q '^vertices  *270400$' "$TMP/binfo1" && grep -q '^edges  *811200$' "$TMP/binfo1"
ok $? "binary STL: info reads the same model (270,400 vertices, 811,200 edges) with 1 and 3 threads"
python3 - "$TMP/btorus.stl" "$TMP/bnan.stl" <<'EOF'
import struct, sys
b = bytearray(open(sys.argv[1], "rb").read())
at = 84 + 50 * 519999 + 12 + 12 * 2 + 4  # facet 520,000, vertex 3, y
b[at:at + 4] = struct.pack("<f", float("nan"))
open(sys.argv[2], "wb").write(b)
EOF
for j in 1 3; do
    rm -f "$TMP/bnan.out"
    run "$LAMINA" slice "$TMP/bnan.stl" -w 2 -j $j -o "$TMP/bnan.out"
    echo "$RC $ERR" >"$TMP/bnan.$j"
    [ ! -e "$TMP/bnan.out" ]
    ok $? "binary STL with a NaN, -j $j: no output file"
done
like "$(cat "$TMP/bnan.1")" '^1 lamina: .*bnan.stl: byte 26000074: facet 520000, vertex 3: y coordinate is not a finite number \(nan\)' \
    "binary STL with a NaN, -j 1: exit 1, the float's offset and facet"
cmp -s "$TMP/bnan.1" "$TMP/bnan.3"
ok $? "binary STL with a NaN: the same message and exit for -j 1 and -j 3"
rm -f "$TMP/btorus.stl" "$TMP/bnan.stl"
# fewer layers than threads, and one layer
same cube-two-layers "$M/thesis_cube_hole.ug" -w 1
same cube-one-layer "$M/thesis_cube_hole.ug" -w 2

# The per-layer reports run on the main thread in layer order: the contact
# sheet and --validate's messages are the same too
for j in 1 3; do
    "$LAMINA" slice "$TMP/torus.stl" -w 0.3 --validate --svg "$TMP/sheet$j.svg" -j $j -o "$TMP/v$j.sls" 2>"$TMP/v$j.err"
    echo "rc $?" >>"$TMP/v$j.err"
done
cmp -s "$TMP/sheet1.svg" "$TMP/sheet3.svg" && grep -q '<path' "$TMP/sheet1.svg"
ok $? "--svg: the same contact sheet for -j 1 and -j 3"
cmp -s "$TMP/v1.err" "$TMP/v3.err" && cmp -s "$TMP/v1.sls" "$TMP/v3.sls" && grep -q '^rc 0$' "$TMP/v1.err"
ok $? "--validate: the same messages, status and program for -j 1 and -j 3"

# The estimate as JSON (layer times summed in layer order): the same numbers
for j in 1 3; do
    "$LAMINA" slice "$TMP/sphere.stl" -m lpbf-cli -w 0.2 -s hatch_strategy=lines -j $j -o "$TMP/e$j.cli" \
        --json "$TMP/e$j.json" 2>/dev/null
done
cmp -s "$TMP/e1.json" "$TMP/e3.json" && grep -q '"time": [0-9]' "$TMP/e1.json"
ok $? "--json: the same run, layer times included, for -j 1 and -j 3"

# ---- a run that fails in a middle layer ------------------------------------
# The sphere with a band of facets around its equator removed on one side:
# the layers through the band have open outlines (far wider than the gap
# tolerance), the ones above and below are closed.
python3 - "$TMP/sphere.stl" "$TMP/open.stl" <<'EOF'
import sys
src, out = sys.argv[1], sys.argv[2]
lines = open(src).read().split("\n")
res, i = [], 0
while i < len(lines):
    if lines[i].startswith("facet"):
        block = lines[i:i + 7]
        zs = [float(l.split()[3]) for l in block if l.startswith("vertex")]
        xs = [float(l.split()[1]) for l in block if l.startswith("vertex")]
        if not (all(abs(z) < 0.6 for z in zs) and min(xs) > 1.0):
            res.extend(block)
        i += 7
    else:
        res.append(lines[i])
        i += 1
open(out, "w").write("\n".join(res))
EOF
for j in 1 2 3 8; do
    rm -f "$TMP/open.out"
    run "$LAMINA" slice --no-repair "$TMP/open.stl" -w 0.2 -j $j -o "$TMP/open.out"
    echo "$RC" >"$TMP/open.rc$j"
    printf '%s' "$ERR" >"$TMP/open.err$j"
    [ ! -e "$TMP/open.out" ]
    ok $? "open outline, -j $j: no output file"
done
is "$(cat "$TMP/open.rc1")" 1 "open outline, -j 1: exit 1"
like "$(cat "$TMP/open.err1")" 'layer 1[0-9] \(h=-?0\.[0-9]+\): open outline from .* could not be closed' \
    "open outline, -j 1: the middle layers are named"
for j in 2 3 8; do
    is "$(cat "$TMP/open.rc$j")" 1 "open outline, -j $j: exit 1"
    cmp -s "$TMP/open.err1" "$TMP/open.err$j"
    ok $? "open outline, -j $j: the same messages as -j 1"
done
# with --allow-open the layers are written without those outlines, the same for every N
same open-allowed "$TMP/open.stl" -w 0.2 --allow-open --no-repair
# repaired on load (the default) the hole is filled: the same program for every N
same open-repaired "$TMP/open.stl" -w 0.2

# the binary CLI writer (a plugin) formats layers on the workers too; one
# refusing a middle layer (a square bipyramid 2e39 across: from layer 4 on
# the contours pass float32's 3.4e38) fails the same way for every N (no
# supports: walls 1 apart under a part 2e39 across are refused first, as
# more vectors than a layer may have)
cat >"$TMP/huge.obj" <<'OBJ'
v 0 0 -10
v 0 0 10
v 1e39 0 0
v 0 1e39 0
v -1e39 0 0
v 0 -1e39 0
f 2 3 4
f 2 4 5
f 2 5 6
f 2 6 3
f 1 4 3
f 1 5 4
f 1 6 5
f 1 3 6
OBJ
for j in 1 2 8; do
    rm -f "$TMP/huge.cli"
    run "$LAMINA" slice "$TMP/huge.obj" -m cli-binary -s support_type=none -w 1 -j $j -o "$TMP/huge.cli"
    echo "$RC $ERR" >"$TMP/huge.$j"
    [ ! -e "$TMP/huge.cli" ]
    ok $? "a plugin writer refusing layer 4, -j $j: no output file"
done
like "$(cat "$TMP/huge.1")" '(?s)^1 .*cli-binary: contour 1 point 1 \(0, -3\.5e\+38\) does not fit float32' \
    "a plugin writer refusing layer 4, -j 1: exit 1 and the writer's reason"
cmp -s "$TMP/huge.1" "$TMP/huge.2" && cmp -s "$TMP/huge.1" "$TMP/huge.8"
ok $? "a plugin writer refusing layer 4: the same message and exit for -j 1, 2 and 8"

# an output limit reached while writing (the estimate passes): the same
# error and no file, whoever planned the layers. The estimate slices 32
# layers spread over the run (limits.t): a plate 1 thick at height 49 of
# 1000 layers of 0.1 lies between two of them (layers 484 and 515), so it
# sees the thin pin only, about 280 kB; the plate's hatches are 2 MB (no
# supports: their walls under the plate, on every layer below it, would
# show the estimate the plate).
cp "$M/pinplate.ug" "$TMP/pinplate.ug" # the pin and plate of limits.t
for j in 1 2 8; do
    rm -f "$TMP/lim.out"
    run "$LAMINA" slice "$TMP/pinplate.ug" -m lpbf-cli -s support_type=none -w 0.1 --max-output 500k -j $j \
        -o "$TMP/lim.out"
    echo "$RC $ERR" >"$TMP/lim.$j"
    [ ! -e "$TMP/lim.out" ]
    ok $? "output limit, -j $j: no output file"
done
like "$(cat "$TMP/lim.1")" '^1 lamina: .*lim.out: cannot write output: output exceeds the limit of 512000 bytes' \
    "output limit, -j 1: exit 1, the limit passed while writing"
cmp -s "$TMP/lim.1" "$TMP/lim.2" && cmp -s "$TMP/lim.1" "$TMP/lim.8"
ok $? "output limit: the same message and exit for -j 1, 2 and 8"

# ---- layers too big to hold: streamed on one thread ---------------------------
# LADRP with a bead of 1e-7: 2 * 10^7 scan lines (about 1.3 GB) in each of
# the 2 layers. With workers nothing would be written until a whole layer
# was recorded in memory; the run streams instead, on one thread, from the start.
printf 'inherits: creol-ladrp\nbead_width: 1e-7\n' >"$TMP/fine.yaml"
mkdir "$TMP/big"
"$LAMINA" slice "$M/thesis_cube.ug" -m "$TMP/fine.yaml" -w 1 -j 4 -o "$TMP/big/out" 2>/dev/null &
pid=$!
written() { local f; for f in "$TMP"/big/out.tmp-*; do [ -s "$f" ] && return 0; done; return 1; }
for _ in $(seq 1 6000); do written && break; sleep 0.01; done
written
ok $? "huge layers, -j 4: the program is being written while the first layer is planned"
is "$(awk '/^Threads:/ {print $2}' /proc/$pid/status 2>/dev/null)" 1 "huge layers, -j 4: one thread"
kill "$pid"
{ wait "$pid"; } 2>/dev/null

# ---- the option ------------------------------------------------------------
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -j 0 -o "$TMP/x"
like "$RC $ERR" '^2 .*-j takes a number of threads from 1 to 256' "-j 0: usage error"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" --jobs=two -o "$TMP/x"
like "$RC $ERR" "^2 .*--jobs takes a number of threads .*'two'" "--jobs=two: usage error"
LAMINA_THREADS=lots run "$LAMINA" slice "$M/thesis_cube_hole.ug" -o "$TMP/x"
like "$RC $ERR" "^2 .*LAMINA_THREADS must be a number of threads .*'lots'" "LAMINA_THREADS=lots: an error naming it"
# every command reads LAMINA_THREADS the same way, also those without -j
for v in abc 0 -1 257; do
    for c in "info" "check -m sls-contours" "validate" "machines"; do
        model=("$M/thesis_cube_hole.ug")
        [ "$c" = machines ] && model=()
        # shellcheck disable=SC2086 # $c is the command and its options
        LAMINA_THREADS=$v run "$LAMINA" $c "${model[@]}"
        like "$RC $ERR" "^2 lamina ${c%% *}: LAMINA_THREADS must be a number of threads .*'$v'" \
            "LAMINA_THREADS=$v: lamina ${c%% *} refuses it (exit 2)"
    done
done
LAMINA_THREADS=3 run "$LAMINA" slice "$TMP/sphere.stl" -w 0.2 -o "$TMP/env3"
[ "$RC" = 0 ] && "$LAMINA" slice "$TMP/sphere.stl" -w 0.2 -j 1 -o "$TMP/env1" 2>/dev/null && cmp -s "$TMP/env3" "$TMP/env1"
ok $? "LAMINA_THREADS=3: the program of -j 1"

done_testing
