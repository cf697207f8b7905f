#!/usr/bin/env bash
# The JSON writer against the program writer, per byte (issue 26: "no
# slower than the program writer per byte"). One hatched part (the
# recipes' sphere on lpbf-cli: stripes, skins, ASCII CLI) planned three
# ways on one thread, each run's CPU time (user + sys):
#   null   the plan with a program of constant text (a profile inheriting
#          lpbf-cli whose layer, polyline and hatches templates print no
#          number): planning alone, nearly;
#   cli    the ASCII CLI program (lpbf-cli);
#   json   the ASCII CLI program and --json.
# The program writer's cost is cli - null for the CLI's bytes, the JSON
# writer's json - cli for the JSON's bytes (both include decoding the plan
# for their sink); also --json-vectors summary's cost and size.
#   json_speed.sh LAMINA   (environment: RUNS=5 alternating runs each; LW=0.03 layer width)
set -euo pipefail
LAMINA=${1:?usage: json_speed.sh LAMINA}
RUNS=${RUNS:-5}
LW=${LW:-0.03}
here=$(cd "$(dirname "$0")" && pwd)
work=${BENCH_DIR:-$(dirname "$LAMINA")/bench}/json
mkdir -p "$work"
model="$here/../../recipes/parts/sphere.obj"
cat >"$work/null-cli.yaml" <<'YAML'
name: null-cli
inherits: lpbf-cli
dialect:
  layer: "L"
  polyline: "P"
  hatches: "H"
YAML

cpu() { # cpu CMD...: prints the run's user + sys seconds
    /usr/bin/time -f '%U %S' -o "$work/time.txt" "$@" >/dev/null 2>"$work/err.txt" || {
        echo "json_speed: command failed: $*" >&2; cat "$work/err.txt" >&2; exit 1; }
    awk '{ printf "%.3f\n", $1 + $2 }' "$work/time.txt"
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

S=(slice "$model" -q -j 1 -s layer_width="$LW")
: >"$work/null.t"; : >"$work/cli.t"; : >"$work/json.t"; : >"$work/sum.t"
for ((r = 0; r < RUNS; r++)); do
    rm -f "$work"/out.*
    cpu "$LAMINA" "${S[@]}" -m "$work/null-cli.yaml" -o "$work/out.null" >>"$work/null.t"
    cpu "$LAMINA" "${S[@]}" -m lpbf-cli -o "$work/out.cli" >>"$work/cli.t"
    cpu "$LAMINA" "${S[@]}" -m lpbf-cli -o "$work/out.cli2" --json "$work/out.json" >>"$work/json.t"
    cpu "$LAMINA" "${S[@]}" -m lpbf-cli -o "$work/out.cli3" --json "$work/out.sum.json" --json-vectors summary \
        >>"$work/sum.t"
done
cmp -s "$work/out.cli" "$work/out.cli2" || { echo "json_speed: --json changed the program" >&2; exit 1; }
tn=$(median <"$work/null.t") tc=$(median <"$work/cli.t") tj=$(median <"$work/json.t") ts=$(median <"$work/sum.t")
bn=$(stat -c %s "$work/out.null") bc=$(stat -c %s "$work/out.cli") bj=$(stat -c %s "$work/out.json")
bs=$(stat -c %s "$work/out.sum.json")
awk -v tn="$tn" -v tc="$tc" -v tj="$tj" -v ts="$ts" -v bn="$bn" -v bc="$bc" -v bj="$bj" -v bs="$bs" -v lw="$LW" 'BEGIN {
    pc = tc - tn; pj = tj - tc; ps = ts - tc
    printf "JSON writer (sphere, lpbf-cli, layers %s, -j 1; CPU seconds, medians):\n", lw
    printf "  plan with a constant program  %7.3f s\n", tn
    printf "  ASCII CLI program             %7.3f s  %8.1f MB  program writer %7.1f MB/s\n", tc, bc / 1e6,
           (pc > 0 ? (bc - bn) / 1e6 / pc : 0)
    printf "  and --json                    %7.3f s  %8.1f MB  JSON writer    %7.1f MB/s (%.2f x the program writer per byte)\n",
           tj, bj / 1e6, (pj > 0 ? bj / 1e6 / pj : 0), (pc > 0 && pj > 0 ? (bj / pj) / ((bc - bn) / pc) : 0)
    printf "  and --json --json-vectors summary %5.3f s  %8.3f MB  (%.4f of the full JSON; %.3f s over the program)\n",
           ts, bs / 1e6, bs / bj, ps
}'
echo "(medians of $RUNS alternating runs)"
