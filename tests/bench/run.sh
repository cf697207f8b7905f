#!/usr/bin/env bash
# make bench: lamina slice against slic3r --export-svg on the same meshes.
# usage: run.sh /path/to/lamina   (environment: RUNS=5 alternating runs each)
set -euo pipefail
LAMINA=${1:?usage: run.sh LAMINA}
RUNS=${RUNS:-5}
here=$(cd "$(dirname "$0")" && pwd)
work=${BENCH_DIR:-$(dirname "$LAMINA")/bench}
mkdir -p "$work"

need=""
for p in openscad slic3r prusa-slicer admesh time; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || need="$need $p"
done
if [ -n "$need" ]; then
    echo "bench: installing$need"
    sudo=""; [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $need >/dev/null
fi

# Meshes: openscad writes ASCII STL; admesh rewrites it as binary.
. "$here/mesh.sh"
make_mesh sphere 'sphere(r=20, $fn=400);'
make_mesh torus 'rotate_extrude($fn=425) translate([20,0,0]) circle(r=8, $fn=425);'

measure() { # prints "seconds kilobytes"
    # wall time from bash's microsecond clock: /usr/bin/time's %e has only
    # 10 ms steps, too coarse for runs of a few tens of milliseconds
    local t0=$EPOCHREALTIME
    /usr/bin/time -f '%M' -o "$work/time.txt" "$@" >/dev/null 2>"$work/stderr.txt" || {
        echo "bench: command failed: $*" >&2; cat "$work/stderr.txt" >&2; exit 1; }
    local t1=$EPOCHREALTIME
    awk -v a="$t0" -v b="$t1" -v m="$(cat "$work/time.txt")" 'BEGIN { printf "%.4f %d\n", b - a, m }'
}
# Each measured run writes a new file: an output left by the previous run
# is removed first (untimed), for both tools. Replacing an existing file
# costs the writer's file system work (ext4 starts writing back a file
# renamed or truncated over an old one), not slicing.
fresh() { rm -f "$@"; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

# compare NAME STL RUNS: lamina slice against slic3r on STL, alternating
# runs; sets lt st (median seconds) and lm sm (median peak KB).
compare() {
    local name=$1 stl=$2 runs=$3
    : >"$work/l.txt"; : >"$work/s.txt"
    for ((r = 0; r < runs; r++)); do
        fresh "$work/$name.sls"
        measure "$LAMINA" slice "$stl" -w 0.1 --cut middle -j 2 -o "$work/$name.sls" >>"$work/l.txt"
        fresh "$work/$name.slic3r.svg"
        measure slic3r --export-svg --layer-height 0.1 "$stl" -o "$work/$name.slic3r.svg" >>"$work/s.txt"
    done
    lt=$(cut -d' ' -f1 "$work/l.txt" | median); lm=$(cut -d' ' -f2 "$work/l.txt" | median)
    st=$(cut -d' ' -f1 "$work/s.txt" | median); sm=$(cut -d' ' -f2 "$work/s.txt" | median)
}

printf '%-8s %10s %10s %10s %10s %10s %10s %8s\n' mesh triangles lamina_s slic3r_s speedup lamina_MB slic3r_MB mem_ratio
for mesh in sphere torus; do
    stl="$work/$mesh.stl"
    tris=$(( ($(stat -c %s "$stl") - 84) / 50 ))
    compare "$mesh" "$stl" "$RUNS"
    awk -v m="$mesh" -v n="$tris" -v lt="$lt" -v st="$st" -v lm="$lm" -v sm="$sm" 'BEGIN {
        printf "%-8s %10d %10.3f %10.3f %9.1fx %10.1f %10.1f %8.2f\n", m, n, lt, st, st / (lt > 0 ? lt : 0.001),
               lm / 1024, sm / 1024, lm / sm }'
done
echo "(medians of $RUNS alternating runs; speedup = slic3r time / lamina time; mem_ratio = lamina peak RSS / slic3r peak RSS)"

# A comb: 1000 separate teeth side by side, so every layer holds 1000
# contours all spanning the same heights (contour classification must stay
# O(N log N) per layer); the same comparison, three runs each.
comb="$work/comb.stl"
[ -s "$comb" ] || python3 "$here/comb.py" 1000 "$comb"
compare comb "$comb" 3
awk -v lt="$lt" -v st="$st" 'BEGIN {
    printf "comb (1000 teeth, 100 layers of 1000 contours): lamina %.3f s, slic3r %.3f s (%.1fx)\n", lt, st, st / lt }'

# Embree validation of every label: the sphere at 0.1 layers with -j 1 and
# -j 2 alternately (the two reports compared byte for byte first), and the
# model load + slice alone for comparison.
"$LAMINA" validate "$work/sphere.stl" -w 0.1 --json -j 1 >"$work/v1.json"
"$LAMINA" validate "$work/sphere.stl" -w 0.1 --json -j 2 >"$work/v2.json"
cmp -s "$work/v1.json" "$work/v2.json" || { echo "bench: validate -j 2 reports differently from -j 1" >&2; exit 1; }
: >"$work/v1.txt"; : >"$work/v2.txt"; : >"$work/s.txt"
for ((r = 0; r < RUNS; r++)); do
    measure "$LAMINA" validate "$work/sphere.stl" -w 0.1 -j 1 >>"$work/v1.txt"
    measure "$LAMINA" validate "$work/sphere.stl" -w 0.1 -j 2 >>"$work/v2.txt"
    fresh "$work/sphere.sls"
    measure "$LAMINA" slice "$work/sphere.stl" -w 0.1 -o "$work/sphere.sls" >>"$work/s.txt"
done
v1t=$(cut -d' ' -f1 "$work/v1.txt" | median); v1m=$(cut -d' ' -f2 "$work/v1.txt" | median)
v2t=$(cut -d' ' -f1 "$work/v2.txt" | median); v2m=$(cut -d' ' -f2 "$work/v2.txt" | median)
st=$(cut -d' ' -f1 "$work/s.txt" | median)
awk -v a="$v1t" -v am="$v1m" -v b="$v2t" -v bm="$v2m" -v st="$st" 'BEGIN {
    printf "validate sphere (400 layers): -j 1 %.3f s, -j 2 %.3f s (%.2fx), %.1f / %.1f MB peak (slice alone %.3f s)\n",
           a, b, a / (b > 0 ? b : 0.001), am / 1024, bm / 1024, st }'

# Hatching: the sphere at 0.03 layers, hatch distance 0.1, islands (5 mm,
# checker order), binary CLI; against PrusaSlicer writing 100% rectilinear
# G-code for the same part and layer height, when it is installed.
hatch=(slice "$work/sphere.stl" -m cli-binary -w 0.03 -s hatch_strategy=islands -s hatch_distance=0.1
       -s island_size=5 -s island_order=checker)
: >"$work/h.txt"; : >"$work/p.txt"
prusa=$(command -v prusa-slicer || command -v PrusaSlicer || true)
for ((r = 0; r < 3; r++)); do
    fresh "$work/sphere.cli"
    measure "$LAMINA" "${hatch[@]}" -o "$work/sphere.cli" >>"$work/h.txt"
    if [ -n "$prusa" ]; then
        fresh "$work/sphere.gcode"
        measure "$prusa" --export-gcode --layer-height 0.03 --first-layer-height 0.03 --fill-density 100% \
            --fill-pattern rectilinear --top-solid-layers 0 --bottom-solid-layers 0 \
            "$work/sphere.stl" -o "$work/sphere.gcode" >>"$work/p.txt"
    fi
done
ht=$(cut -d' ' -f1 "$work/h.txt" | median); hm=$(cut -d' ' -f2 "$work/h.txt" | median)
"$LAMINA" "${hatch[@]}" -o "$work/sphere.cli" 2>"$work/hatch.err"
awk -v t="$ht" -v m="$hm" 'BEGIN { printf "hatch sphere (1334 layers of 0.03, islands, 0.1 apart): lamina %.3f s, %.1f MB peak\n", t, m / 1024 }'
sed 's/^lamina: [^:]*: /  /' "$work/hatch.err"
if [ -n "$prusa" ]; then
    pt=$(cut -d' ' -f1 "$work/p.txt" | median); pm=$(cut -d' ' -f2 "$work/p.txt" | median)
    awk -v t="$ht" -v m="$hm" -v pt="$pt" -v pm="$pm" 'BEGIN {
        printf "  PrusaSlicer 100%% rectilinear: %.3f s, %.1f MB peak: lamina %.1fx faster at %.2f of its memory\n",
               pt, pm / 1024, pt / t, m / pm }'
else
    echo "  (PrusaSlicer could not be installed: the hatching comparison is skipped)"
fi

# ---- threads (issue 15, part 1): -j 2 against -j 1 --------------------------
# The same jobs with two worker threads and with one, alternating runs,
# medians; the programs must be byte-identical. Kept in this one function so
# other bench sections stay apart.
bench_threads() {
    local runs=$1 name stl out a b
    printf '%-34s %9s %9s %8s %9s %9s\n' job j1_s j2_s speedup j1_MB j2_MB
    for job in sphere torus hatch; do
        case $job in
        sphere|torus) stl="$work/$job.stl"; out="$work/$job.j"; args=(slice "$stl" -w 0.1 --cut middle)
                      name="$job -w 0.1 (sls-contours)" ;;
        hatch) out="$work/hatch.j"; args=("${hatch[@]}"); name="hatch sphere (cli-binary, islands)" ;;
        esac
        : >"$work/j1.txt"; : >"$work/j2.txt"
        for ((r = 0; r < runs; r++)); do
            fresh "$out.1" "$out.2"
            measure "$LAMINA" "${args[@]}" -j 1 -o "$out.1" >>"$work/j1.txt"
            measure "$LAMINA" "${args[@]}" -j 2 -o "$out.2" >>"$work/j2.txt"
        done
        cmp -s "$out.1" "$out.2" || { echo "bench: -j 2 wrote a different program than -j 1 for $name" >&2; exit 1; }
        a=$(cut -d' ' -f1 "$work/j1.txt" | median); b=$(cut -d' ' -f1 "$work/j2.txt" | median)
        am=$(cut -d' ' -f2 "$work/j1.txt" | median); bm=$(cut -d' ' -f2 "$work/j2.txt" | median)
        awk -v n="$name" -v a="$a" -v b="$b" -v am="$am" -v bm="$bm" 'BEGIN {
            printf "%-34s %9.3f %9.3f %7.2fx %9.1f %9.1f\n", n, a, b, a / (b > 0 ? b : 0.001), am / 1024, bm / 1024 }'
    done
    echo "(medians of $runs alternating runs; speedup = -j 1 time / -j 2 time; the programs are identical)"
}
bench_threads "$RUNS"

# ---- a scan as users have it (issue 24): the Stanford bunny ----------------
# tests/models/bunny: 69,451 triangles open at the bottom, in metres, sliced
# as a user would (--units m, 0.5 mm layers: 242 along z), repaired on load;
# next to a closed UV sphere of as many triangles (spheregen) sliced into as
# many layers (binary STL), and the bunny as `lamina repair` wrote it
# (closed; OBJ like the scan, so the reading costs the same) sliced with
# --no-repair: what repair costs on top of reading and slicing.
bench_bunny() {
    local runs=$1 bunny="$work/bun_zipper.obj" sph="$work/sphere69k.stl" fixed="$work/bunny.repaired.obj"
    [ -s "$bunny" ] || gunzip -c "$here/../models/bunny/bun_zipper.obj.gz" >"$bunny"
    [ "$work/spheregen" -nt "$here/spheregen.c" ] || cc -O2 -o "$work/spheregen" "$here/spheregen.c" -lm
    [ -s "$sph" ] || "$work/spheregen" 69451 "$sph" >/dev/null
    "$LAMINA" repair "$bunny" -o "$fixed" 2>"$work/bunny.err" || { echo "bench: lamina repair failed" >&2; cat "$work/bunny.err" >&2; exit 1; }
    local sph_tris=$(( ($(stat -c %s "$sph") - 84) / 50 ))
    # the sphere (radius 20) at the bunny's layer count
    local layers sw
    "$LAMINA" slice "$bunny" --units m -w 0.5 --json "$work/bunny.json" -o "$work/bunny.sls" 2>"$work/bunny.err"
    layers=$(grep -o '"layers": [0-9]*' "$work/bunny.json" | head -1 | grep -o '[0-9]*$')
    sw=$(awk -v n="$layers" 'BEGIN { printf "%.6g", 40 / n }')
    : >"$work/bu.txt"; : >"$work/bs.txt"; : >"$work/bf.txt"
    for ((r = 0; r < runs; r++)); do
        fresh "$work/bunny.sls" "$work/sphere69k.sls" "$work/bunny.fixed.sls"
        measure "$LAMINA" slice "$bunny" --units m -w 0.5 -o "$work/bunny.sls" >>"$work/bu.txt"
        measure "$LAMINA" slice "$sph" -w "$sw" -o "$work/sphere69k.sls" >>"$work/bs.txt"
        measure "$LAMINA" slice "$fixed" --units m --no-repair -w 0.5 -o "$work/bunny.fixed.sls" >>"$work/bf.txt"
    done
    local bt bm st sm ft
    bt=$(cut -d' ' -f1 "$work/bu.txt" | median); bm=$(cut -d' ' -f2 "$work/bu.txt" | median)
    st=$(cut -d' ' -f1 "$work/bs.txt" | median); sm=$(cut -d' ' -f2 "$work/bs.txt" | median)
    ft=$(cut -d' ' -f1 "$work/bf.txt" | median)
    awk -v bt="$bt" -v bm="$bm" -v st="$st" -v sm="$sm" -v ft="$ft" -v n="$layers" -v s="$sph_tris" -v sw="$sw" 'BEGIN {
        printf "bunny scan (69451 triangles, open, --units m -w 0.5, repaired on load, %d layers): %.3f s, %.1f MB peak\n", n, bt, bm / 1024
        printf "  closed sphere (%d triangles, -w %s, %d layers): %.3f s, %.1f MB peak (bunny / sphere %.2fx)\n", s, sw, n, st, sm / 1024, bt / (st > 0 ? st : 0.001)
        printf "  the bunny as lamina repair wrote it (closed OBJ), --no-repair: %.3f s (repair on load adds %.3f s)\n", ft, bt - ft }'
    sed -n 's/^lamina: [^:]*: repaired: /  repair: /p' "$work/bunny.err"
    echo "(medians of $runs alternating runs)"
}
bench_bunny "$RUNS"

# Scaling (time per triangle, time per layer, the 5M-triangle run's memory):
# its own script, tests/bench/scaling.sh.
bash "$here/scaling.sh" "$LAMINA"

# Build plates (issue 25): a plate of 25 parts against the parts alone, peak
# memory against parts x layers, hatch vectors a second: tests/bench/plate.sh.
bash "$here/plate.sh" "$LAMINA"

# The JSON writer against the program writer, per byte (issue 26):
# tests/bench/json_speed.sh.
bash "$here/json_speed.sh" "$LAMINA"

# The viewer's page (issue 26): its size against the binary CLI, its write
# time, and its opening in headless Chromium: tests/bench/viewer.sh.
bash "$here/viewer.sh" "$LAMINA"

# Supports (issue 27): a supported part against the same part unsupported,
# tests/bench/supports.sh.
bash "$here/supports.sh" "$LAMINA"
