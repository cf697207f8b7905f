#!/usr/bin/env bash
# make bench, build plates (issue 25): `lamina build JOB.yaml` on plates of
# many parts, against the same parts planned alone.
#  (a) a plate of 25 gear rings (24.4 mm across, 10 mm high: 334 layers of
#      0.03 mm) on lpbf-cli, against the sum of 25 one-part jobs, each part
#      `at` the place the plate gave it (read once from the plate's --json);
#      the bound: the plate takes at most 1.2 times the sum. The hatch
#      vectors of the 25 alone must add up to the plate's (the same parts in
#      the same places: the plate plans nothing more nor less).
#  (b) peak memory, -j 1 and -j 2: the plate against one part alone (the
#      first of (a)'s), and plates of one height against four times that
#      height (25 gears, 84 and 334 layers) and sixteen (100 small rings, 10,
#      40 and 160 layers): bounded by the models and the layers in flight,
#      the peak must stay nearly flat as layers x parts grows.
#  (c) hatch vectors planned and written per second on cli-binary (stripes,
#      0.1 apart, 0.03 layers), -j 1 against -j 2, without skins and with
#      skins 3 layers deep.
# lpbf-cli's skins (skin_layers 3) are left out of (a) and (b): with them a
# gear ring costs about 60 ms a layer against 0.1 ms without (see (c)), so
# the 25 parts alone plus the plate would take over 15 minutes here; (c)
# measures them on a plate 0.51 mm high (17 layers).
# Programs for (a) and (b) go to /dev/null (the ASCII plate is 480 MB: the
# figures are planning and formatting, not the disk); (c) writes its file.
# usage: plate.sh /path/to/lamina   (environment: PLATE_RUNS=3 runs each,
# medians, one for a run over 5 s; the 25 alone and the plate in (a) run
# once each). Needs openscad and admesh (run.sh installs them).
set -euo pipefail
LAMINA=${1:?usage: plate.sh LAMINA}
RUNS=${PLATE_RUNS:-3}
here=$(cd "$(dirname "$0")" && pwd)
work=${BENCH_DIR:-$(dirname "$LAMINA")/bench}/plate
mkdir -p "$work"

# Meshes: openscad writes ASCII STL; admesh rewrites it as binary.
. "$here/mesh.sh"
# a gear ring: a 22 mm disc with 20 round teeth (24.4 mm across), a 10 mm
# bore, H high; and a small ring, 15 mm across with a 6 mm bore
gear() { # name height
    make_mesh "$1" "difference() {
  union() { cylinder(d=22, h=$2, \$fn=120);
    for (i=[0:19]) rotate(i*18) translate([11,0,0]) cylinder(d=2.4, h=$2, \$fn=24); }
  translate([0,0,-1]) cylinder(d=10, h=$2+2, \$fn=96);
}"
}
ring() { make_mesh "$1" "difference() { cylinder(d=15, h=$2, \$fn=96); translate([0,0,-1]) cylinder(d=6, h=$2+2, \$fn=64); }"; }
gear gear10 10
gear gear2.5 2.5
gear gear0.51 0.51
ring ring0.3 0.3
ring ring1.2 1.2
ring ring4.8 4.8

# one run: "seconds kilobytes hatch-vectors cpu-seconds" (vectors from the
# summary line on standard error: "..., N hatch vectors, ..."; CPU, user
# and system, next to the wall time: this machine is shared, and a busy
# neighbour lengthens the wall time of a run, hardly its CPU time)
run1() {
    local t0=$EPOCHREALTIME
    /usr/bin/time -f '%M %U %S' -o "$work/time.txt" "$@" >/dev/null 2>"$work/stderr.txt" || {
        echo "bench: command failed: $*" >&2; cat "$work/stderr.txt" >&2; exit 1; }
    local t1=$EPOCHREALTIME
    local v
    v=$(grep -o '[0-9]* hatch vectors' "$work/stderr.txt" | head -1 | cut -d' ' -f1)
    awk -v a="$t0" -v b="$t1" -v v="${v:-0}" '{ printf "%.4f %d %d %.2f\n", b - a, $1, v, $2 + $3 }' "$work/time.txt"
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
# runs N CMD...: median seconds, median KB, the vectors and median CPU
# seconds of N runs (one when the first takes over 5 s): sets t m v c
runs() {
    local n=$1; shift
    : >"$work/runs.txt"
    for ((r = 0; r < n; r++)); do
        run1 "$@" >>"$work/runs.txt"
        awk '{ exit !($1 > 5) }' "$work/runs.txt" && break
    done
    t=$(cut -d' ' -f1 "$work/runs.txt" | median); m=$(cut -d' ' -f2 "$work/runs.txt" | median)
    v=$(cut -d' ' -f3 "$work/runs.txt" | head -1); c=$(cut -d' ' -f4 "$work/runs.txt" | median)
}

# job FILE MACHINE MODEL COPIES [KEY: VALUE ...]: a plate of COPIES of MODEL
job() {
    local file=$1 machine=$2 model=$3 copies=$4; shift 4
    { echo "machine: $machine"; for kv in "$@"; do echo "$kv"; done
      echo "parts:"; echo "  - model: $model.stl"; echo "    copies: $copies"; } >"$file"
}

# ---- (a) the plate against its parts alone ---------------------------------
plate_vs_parts() {
    local plate="$work/plate25.yaml"
    job "$plate" lpbf-cli gear10 25 "skin_layers: 0"
    # where the plate puts each part: the JSON's parts come before its layers
    "$LAMINA" build "$plate" -q -o /dev/null --json /dev/stdout 2>/dev/null |
        python3 "$here/plate_at.py" 25 >"$work/at.txt" || true
    [ "$(wc -l <"$work/at.txt")" -eq 25 ] || { echo "bench: could not read the plate's 25 places" >&2; exit 1; }
    local i=0 name x y
    : >"$work/alone.txt"
    while read -r name x y; do
        i=$((i + 1))
        { echo "machine: lpbf-cli"; echo "skin_layers: 0"; echo "parts:"
          echo "  - {model: gear10.stl, name: $name, at: [$x, $y]}"; } >"$work/alone$i.yaml"
        run1 "$LAMINA" build "$work/alone$i.yaml" -j 2 -o /dev/null >>"$work/alone.txt"
    done <"$work/at.txt"
    runs 1 "$LAMINA" build "$plate" -j 2 -o /dev/null
    pt=$t
    local pv=$v pc=$c st sv sc
    st=$(awk '{s += $1} END {printf "%.4f", s}' "$work/alone.txt")
    sv=$(awk '{s += $3} END {print s}' "$work/alone.txt")
    sc=$(awk '{s += $4} END {printf "%.2f", s}' "$work/alone.txt")
    printf '%-44s %9s %9s %12s\n' job wall_s cpu_s hatch_vectors
    awk -v pt="$pt" -v st="$st" -v pv="$pv" -v sv="$sv" -v pc="$pc" -v sc="$sc" 'BEGIN {
        r = pt / (st > 0 ? st : 0.001)
        printf "%-44s %9.3f %9.2f %12d\n", "25 parts alone (334 layers each), summed", st, sc, sv
        printf "%-44s %9.3f %9.2f %12d\n", "plate of 25 (lpbf-cli, 0.03, no skins)", pt, pc, pv
        printf "plate / sum of the parts alone: wall %.3f, CPU %.3f: %s (bound 1.2)%s\n", r, pc / (sc > 0 ? sc : 0.01),
               r <= 1.2 ? "PASS" : "FAIL", pv == sv ? "; the same hatch vectors" : "; the hatch vectors differ: plate " pv ", alone " sv }'
    echo "(one run each, -j 2, programs to /dev/null; each part alone is a one-part job 'at' the plate's place)"
}

# ---- (b) peak memory ---------------------------------------------------------
# mem_row NAME LAYERS PARTS JOB: the job at -j 1 and -j 2
mem_row() {
    local name=$1 layers=$2 parts=$3 jobfile=$4 m1 t1
    runs "$RUNS" "$LAMINA" build "$jobfile" -j 1 -o /dev/null
    m1=$m t1=$t
    runs "$RUNS" "$LAMINA" build "$jobfile" -j 2 -o /dev/null
    awk -v n="$name" -v l="$layers" -v p="$parts" -v t1="$t1" -v t2="$t" -v m1="$m1" -v m2="$m" 'BEGIN {
        printf "%-36s %7d %12d %8.3f %8.3f %8.1f %8.1f\n", n, l, p * l, t1, t2, m1 / 1024, m2 / 1024 }'
    row_j1=$m1 row_j2=$m
}

plate_memory() {
    echo
    printf '%-36s %7s %12s %8s %8s %8s %8s\n' job layers parts*layers j1_s j2_s j1_MB j2_MB
    local a1 a2 b1 b2 g1 g2 one1 one2
    mem_row "one gear ring alone, 10 mm" 334 1 "$work/alone1.yaml"
    one1=$row_j1 one2=$row_j2
    job "$work/plate25s.yaml" lpbf-cli gear2.5 25 "skin_layers: 0"
    mem_row "plate of 25 gear rings, 2.5 mm" 84 25 "$work/plate25s.yaml"
    a1=$row_j1 a2=$row_j2
    mem_row "plate of 25 gear rings, 10 mm" 334 25 "$work/plate25.yaml"
    g1=$row_j1 g2=$row_j2
    local h
    for h in 0.3:10 1.2:40 4.8:160; do
        job "$work/plate100.yaml" lpbf-cli "ring${h%:*}" 100 "skin_layers: 0"
        mem_row "plate of 100 small rings, ${h%:*} mm" "${h#*:}" 100 "$work/plate100.yaml"
        [ -n "${b1:-}" ] || { b1=$row_j1 b2=$row_j2; }
    done
    awk -v g1="$g1" -v g2="$g2" -v o1="$one1" -v o2="$one2" -v a1="$a1" -v a2="$a2" -v b1="$b1" -v b2="$b2" \
        -v c1="$row_j1" -v c2="$row_j2" 'BEGIN {
        printf "peak, -j 1 / -j 2: plate of 25 against one part alone %.2fx / %.2fx;\n", g1 / o1, g2 / o2
        printf "  25 gears at 334 against 84 layers %.2fx / %.2fx; 100 rings at 160 against 10 layers %.2fx / %.2fx\n",
               g1 / a1, g2 / a2, c1 / b1, c2 / b2 }'
    echo "(medians of $RUNS runs, one for runs over 5 s; lpbf-cli without skins, programs to /dev/null)"
}

# ---- (c) hatch vectors a second, binary CLI, -j 1 against -j 2 ---------------
plate_rate() {
    echo
    printf '%-36s %9s %8s %8s %7s %7s %9s %9s %7s\n' job vectors j1_s j2_s j1_cpu j2_cpu j1_Mvec/s j2_Mvec/s speedup
    local spec model skin name a b ac bc
    for spec in gear10:0 gear0.51:3; do
        model=${spec%:*} skin=${spec#*:}
        job "$work/rate.yaml" cli-binary "$model" 25 "layer_width: 0.03" "hatch_strategy: stripes" \
            "hatch_distance: 0.1" "skin_layers: $skin"
        local n=$RUNS
        [ "$skin" = 0 ] || n=1
        : >"$work/r1.txt"; : >"$work/r2.txt"
        for ((r = 0; r < n; r++)); do
            rm -f "$work/rate.1.cli" "$work/rate.2.cli"
            run1 "$LAMINA" build "$work/rate.yaml" -j 1 -o "$work/rate.1.cli" >>"$work/r1.txt"
            run1 "$LAMINA" build "$work/rate.yaml" -j 2 -o "$work/rate.2.cli" >>"$work/r2.txt"
        done
        cmp -s "$work/rate.1.cli" "$work/rate.2.cli" || { echo "bench: build -j 2 wrote a different program than -j 1" >&2; exit 1; }
        a=$(cut -d' ' -f1 "$work/r1.txt" | median); b=$(cut -d' ' -f1 "$work/r2.txt" | median)
        ac=$(cut -d' ' -f4 "$work/r1.txt" | median); bc=$(cut -d' ' -f4 "$work/r2.txt" | median)
        v=$(cut -d' ' -f3 "$work/r1.txt" | head -1)
        case $model in
        gear10) name="25 gears, 334 layers, no skins" ;;
        *) name="25 gears, 17 layers, skins 3 deep" ;;
        esac
        awk -v nm="$name" -v v="$v" -v a="$a" -v b="$b" -v ac="$ac" -v bc="$bc" 'BEGIN {
            printf "%-36s %9d %8.3f %8.3f %7.2f %7.2f %9.3f %9.3f %6.2fx\n", nm, v, a, b, ac, bc,
                   v / a / 1e6, v / b / 1e6, a / b }'
    done
    rm -f "$work/rate.1.cli" "$work/rate.2.cli"
    echo "(cli-binary, stripes 0.1 apart, 0.03 layers, written to a file; Mvec/s = hatch vectors / wall s;"
    echo " medians of $RUNS alternating runs without skins, one with skins; the -j 1 and -j 2 programs identical)"
}

echo
echo "build plates (issue 25): lamina build"
plate_vs_parts
plate_memory
plate_rate
