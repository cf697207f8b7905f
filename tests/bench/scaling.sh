#!/usr/bin/env bash
# make bench, scaling section: time per triangle (sphere-like meshes of 10k,
# 100k, 1M and 5M triangles, 400 layers each) and time per layer (100 to
# 100,000 layers of one sphere), and the 5M-triangle run's peak memory
# against its file size. Programs go to /dev/null: the figures are slicing,
# planning and formatting, not the disk.
# usage: scaling.sh /path/to/lamina   (environment: SCALE_RUNS=3 runs each, medians)
set -euo pipefail
LAMINA=${1:?usage: scaling.sh LAMINA}
RUNS=${SCALE_RUNS:-3}
here=$(cd "$(dirname "$0")" && pwd)
work=${BENCH_DIR:-$(dirname "$LAMINA")/bench}
mkdir -p "$work"
gen=$work/spheregen
[ "$gen" -nt "$here/spheregen.c" ] || cc -O2 -o "$gen" "$here/spheregen.c" -lm

# median seconds and peak KB of RUNS runs of a command (3 RUNS when the
# first takes under a second: a short run is mostly noise on a busy
# machine): sets t m
timed() {
    : >"$work/scale.txt"
    local runs=$RUNS
    for ((r = 0; r < runs; r++)); do
        local t0=$EPOCHREALTIME
        /usr/bin/time -f '%M' -o "$work/scale.mem" "$@" >/dev/null 2>"$work/scale.err" || {
            echo "bench: command failed: $*" >&2; cat "$work/scale.err" >&2; exit 1; }
        local t1=$EPOCHREALTIME
        echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f", b - a }') $(cat "$work/scale.mem")" >>"$work/scale.txt"
        if ((r == 0)) && awk -v a="$t0" -v b="$t1" 'BEGIN { exit !(b - a < 1) }'; then runs=$((3 * RUNS)); fi
    done
    t=$(cut -d' ' -f1 "$work/scale.txt" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
    m=$(cut -d' ' -f2 "$work/scale.txt" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
}

# starting the process (dynamic linking of Embree, GEOS, Lua; 0.1 s on a
# loaded VM): the floor under every run, given so the small runs read right
timed "$LAMINA" --version
start=$t

echo
echo "---- scaling: time per triangle (spheres, 400 layers of 0.1, SLS contours to /dev/null) ----"
printf '%10s %10s %12s %16s %10s %10s %10s\n' triangles seconds us/triangle us/triangle_net peak_MB file_MB peak/file
for n in 10000 100000 1000000 5000000; do
    stl=$work/sphere-$n.stl
    [ -s "$stl" ] || "$gen" "$n" "$stl"
    tris=$(( ($(stat -c %s "$stl") - 84) / 50 ))
    timed "$LAMINA" slice "$stl" -w 0.1 -o /dev/null
    awk -v n="$tris" -v t="$t" -v s="$start" -v m="$m" -v f="$(stat -c %s "$stl")" 'BEGIN {
        printf "%10d %10.3f %12.3f %16.3f %10.1f %10.1f %10.2f\n", n, t, t / n * 1e6, (t - s) / n * 1e6, m / 1024,
               f / 1048576, m * 1024 / f }'
done
echo "(medians of $RUNS runs; net: less starting lamina, $start s (lamina --version); peak = resident"
echo " set, /usr/bin/time %M, in MiB; file = the binary STL, MiB)"

echo
echo "---- scaling: time per layer (the 10k sphere, 100 to 100,000 layers, SLS contours to /dev/null) ----"
stl=$work/sphere-10000.stl
timed "$LAMINA" slice "$stl" -w 40 -o /dev/null
fixed=$t
printf '%10s %10s %12s %16s\n' layers seconds us/layer us/layer_net
for layers in 100 1000 10000 100000; do
    w=$(awk -v n="$layers" 'BEGIN { printf "%.17g", 40 / n }')
    timed "$LAMINA" slice "$stl" -w "$w" -o /dev/null
    awk -v n="$layers" -v t="$t" -v f="$fixed" 'BEGIN {
        printf "%10d %10.3f %12.2f %16.2f\n", n, t, t / n * 1e6, (t - f) / n * 1e6 }'
done
echo "(net: less the run of one layer, $fixed s: reading the model and starting up)"
