#!/usr/bin/env bash
# make bench: a supported part against the same part unsupported (issue 27:
# "supports should cost a small fraction of the run"). The recipes' sphere
# (its lower half needs support from the plate) on lpbf-cli (stripes,
# skins, ASCII CLI; block supports with teeth) at LW layers, -j 2, RUNS
# alternating runs each: the median wall time and peak memory with the
# profile's supports and with support_type none, and the program's size.
#   supports.sh LAMINA   (environment: RUNS=5; LW=0.03)
set -euo pipefail
LAMINA=${1:?usage: supports.sh LAMINA}
RUNS=${RUNS:-5}
LW=${LW:-0.03}
here=$(cd "$(dirname "$0")" && pwd)
work=${BENCH_DIR:-$(dirname "$LAMINA")/bench}/supports
mkdir -p "$work"
model="$here/../../recipes/parts/sphere.obj"
measure() { # prints "seconds kilobytes"
    local t0=$EPOCHREALTIME
    /usr/bin/time -f '%M' -o "$work/time.txt" "$@" >/dev/null 2>"$work/err.txt" || {
        echo "supports: command failed: $*" >&2; cat "$work/err.txt" >&2; exit 1; }
    local t1=$EPOCHREALTIME
    awk -v a="$t0" -v b="$t1" -v m="$(cat "$work/time.txt")" 'BEGIN { printf "%.4f %d\n", b - a, m }'
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
S=(slice "$model" -q -m lpbf-cli -j 2 -s layer_width="$LW")
: >"$work/with.t"; : >"$work/without.t"
for ((r = 0; r < RUNS; r++)); do
    rm -f "$work/with.cli" "$work/without.cli"
    measure "$LAMINA" "${S[@]}" -o "$work/with.cli" >>"$work/with.t"
    measure "$LAMINA" "${S[@]}" -s support_type=none -o "$work/without.cli" >>"$work/without.t"
done
wt=$(cut -d' ' -f1 "$work/with.t" | median); wm=$(cut -d' ' -f2 "$work/with.t" | median)
nt=$(cut -d' ' -f1 "$work/without.t" | median); nm=$(cut -d' ' -f2 "$work/without.t" | median)
"$LAMINA" "${S[@]}" -o "$work/with.cli" 2>"$work/with.err" >/dev/null
"$LAMINA" "${S[@]}" -s support_type=none -o "$work/without.cli" 2>"$work/without.err" >/dev/null
walls=$(grep -c '^//support' "$work/with.cli" || true)
printf '%-12s %10s %10s %12s\n' supports seconds MB program_MB
printf '%-12s %10.3f %10.1f %12.1f\n' block "$wt" "$(awk -v m="$wm" 'BEGIN{print m/1024}')" \
    "$(awk -v b="$(stat -c %s "$work/with.cli")" 'BEGIN{print b/1048576}')"
printf '%-12s %10.3f %10.1f %12.1f\n' none "$nt" "$(awk -v m="$nm" 'BEGIN{print m/1024}')" \
    "$(awk -v b="$(stat -c %s "$work/without.cli")" 'BEGIN{print b/1048576}')"
awk -v a="$wt" -v b="$nt" -v n="$walls" 'BEGIN { printf "supports cost %.1f%% of the unsupported run (%d support blocks)\n", 100 * (a - b) / b, n }'
sed -n 's/^lamina: /with supports: /p' "$work/with.err"
sed -n 's/^lamina: /without:       /p' "$work/without.err"
