#!/usr/bin/env bash
# make bench, the viewer page (issue 26, docs/viewer.md): `--html` on big jobs.
#  (a) a plate of 24 gearwheels (tests/cli/geargen.py's gear scaled to 42 mm
#      across and 8 mm high: 267 layers of 0.03) on cli-binary, stripes 0.05
#      apart: over 20 million vectors. Written with -o x.cli (binary CLI)
#      alone and with --html, alternating runs: the page's size against the
#      program's (bound: 2x) and the time --html adds (bound: 30%, medians;
#      CPU time beside the wall time: the machine is shared). Then the page in
#      headless Chromium (tests/bench/viewer_bench.py, DevTools protocol over
#      a pipe): the time to the first drawn layer (lamina.firstDrawn, from the
#      navigation's start; bound 3 s) and lamina.show(K) to far layers not
#      shown before, once the page is in (bound 200 ms).
#  (b) the gearwheel-sized job of the issue: one such gear, islands, on
#      lpbf-cli (its skins 3 deep), the program as binary CLI (-s
#      writer=cli-binary): the page against the program (bound 2x), the page
#      decoded and held against the --json twin (tests/cli/viewercheck.py
#      compare), the JSON with vectors summarised against the full JSON
#      (bound 1/10, when lamina has --json-vectors), and the page opened.
# usage: viewer.sh /path/to/lamina   (environment: VIEWER_RUNS=3 alternating
# runs of each write, 3 browser openings). Needs chromium for the openings.
set -euo pipefail
LAMINA=${1:?usage: viewer.sh LAMINA}
RUNS=${VIEWER_RUNS:-3}
here=$(cd "$(dirname "$0")" && pwd)
work=${BENCH_DIR:-$(dirname "$LAMINA")/bench}/viewer
mkdir -p "$work"
VB=(python3 "$here/viewer_bench.py")

# the gearwheel: 12 trapezoid teeth round a bore, 20 mm across and 2 high,
# scaled by the jobs to 42 mm and 8 mm
[ -s "$work/gear.stl" ] || python3 "$here/../cli/geargen.py" "$work/gear.stl"

# one run: "seconds kilobytes cpu-seconds"
run1() {
    local t0=$EPOCHREALTIME
    /usr/bin/time -f '%M %U %S' -o "$work/time.txt" "$@" >/dev/null 2>"$work/stderr.txt" || {
        echo "bench: command failed: $*" >&2; cat "$work/stderr.txt" >&2; exit 1; }
    local t1=$EPOCHREALTIME
    awk -v a="$t0" -v b="$t1" '{ printf "%.4f %d %.2f\n", b - a, $1, $2 + $3 }' "$work/time.txt"
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
col() { cut -d' ' -f"$2" "$1" | median; }
colmin() { cut -d' ' -f"$2" "$1" | sort -g | head -1; }
size() { stat -c %s "$1"; }

# opened PAGE NAME: the page in Chromium, RUNS times: medians of the first
# drawn layer, the worst step
opened() {
    if ! command -v chromium >/dev/null && ! command -v chromium-browser >/dev/null; then
        echo "  $2 in Chromium: skipped (no chromium)"; return
    fi
    "${VB[@]}" open "$1" "$RUNS" >"$work/open.txt"
    if grep -q 'first_ms none' "$work/open.txt"; then
        echo "  $2 in Chromium: the page has no lamina.firstDrawn ($(head -1 "$work/open.txt"))"; return
    fi
    awk -v name="$2" '{ f[NR] = $2; r[NR] = $4; n = split($6, s, ","); for (i = 1; i <= n; i++) { st[++m] = s[i] } }
        function med(a, k,   i, j, t) { for (i = 1; i <= k; i++) for (j = i + 1; j <= k; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
                                      return (k % 2) ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2 }
        END { fm = med(f, NR); rm = med(r, NR); sm = med(st, m); sx = st[m]
              printf "  %s in Chromium: first layer drawn %.0f ms (median of %d; bound 3000: %s), whole page in %.0f ms;\n", name, fm, NR, fm < 3000 ? "PASS" : "FAIL", rm
              printf "    lamina.show(K) to the last, middle, 1/4 and 3/4 layers: median %.0f ms, worst %.0f ms (bound 200: %s)\n", sm, sx, sx < 200 ? "PASS" : "FAIL" }' "$work/open.txt"
}

# ---- (a) a plate of over 20 million vectors ----------------------------------
plate() {
    local job="$work/plate24.yaml"
    printf '%s\n' "machine: cli-binary" "layer_width: 0.03" "hatch_strategy: stripes" "hatch_distance: 0.05" \
        "parts:" "  - {model: gear.stl, scale: [2.1, 2.1, 4], copies: 24}" >"$job"
    : >"$work/cli.txt"; : >"$work/html.txt"
    local r
    for ((r = 0; r < RUNS; r++)); do
        rm -f "$work/a.cli" "$work/b.cli" "$work/b.html"
        run1 "$LAMINA" build "$job" -j 2 -o "$work/a.cli" >>"$work/cli.txt"
        run1 "$LAMINA" build "$job" -j 2 -o "$work/b.cli" --html "$work/b.html" >>"$work/html.txt"
    done
    cmp -s "$work/a.cli" "$work/b.cli" || { echo "bench: --html changed the program" >&2; exit 1; }
    local tot hv c h
    tot=$("${VB[@]}" totals "$work/b.html")
    hv=$(grep -o '[0-9]* hatch vectors' "$work/stderr.txt" | head -1 | cut -d' ' -f1)
    c=$(size "$work/a.cli") h=$(size "$work/b.html")
    echo "viewer (issue 26): the --html page"
    awk -v tot="$tot" -v hv="${hv:-0}" -v c="$c" -v h="$h" 'BEGIN { split(tot, t, " ")
        printf "plate of 24 gearwheels (cli-binary, 0.03 layers, stripes 0.05): %d layers, %d vectors (%d hatch vectors)\n", t[2], t[4], hv
        printf "  page %.1f MB, binary CLI %.1f MB: %.2fx (bound 2: %s); %.2f bytes of page a vector\n", h / 1e6, c / 1e6, h / c,
               h <= 2 * c ? "PASS" : "FAIL", h / t[4] }'
    awk -v a="$(col "$work/cli.txt" 1)" -v b="$(col "$work/html.txt" 1)" -v am="$(colmin "$work/cli.txt" 1)" \
        -v bm="$(colmin "$work/html.txt" 1)" -v ac="$(col "$work/cli.txt" 3)" -v bc="$(col "$work/html.txt" 3)" \
        -v ak="$(col "$work/cli.txt" 2)" -v bk="$(col "$work/html.txt" 2)" -v n="$RUNS" 'BEGIN {
        printf "  write: -o x.cli %.2f s (min %.2f, CPU %.2f s), with --html %.2f s (min %.2f, CPU %.2f s): +%.0f%% wall, +%.0f%% CPU (bound 30%%: %s)\n",
               a, am, ac, b, bm, bc, (b / a - 1) * 100, (bc / ac - 1) * 100, b <= 1.3 * a ? "PASS" : "FAIL"
        printf "  peak memory %.1f MB without, %.1f MB with --html (medians of %d alternating runs, -j 2)\n", ak / 1024, bk / 1024, n }'
    opened "$work/b.html" "the plate's page"
    rm -f "$work/a.cli" "$work/b.cli" "$work/b.html"
}

# ---- (b) the gearwheel-sized job -------------------------------------------------
gearwheel() {
    local args=(slice "$work/gear.stl" --scale 2.1,2.1,4 -m lpbf-cli -s hatch_strategy=islands -s writer=cli-binary -j 2 -q)
    rm -f "$work/g.cli" "$work/g.html" "$work/g.json" "$work/gs.json" "$work/gn.json"
    "$LAMINA" "${args[@]}" -o "$work/g.cli" --html "$work/g.html" --json "$work/g.json"
    local c h j
    c=$(size "$work/g.cli") h=$(size "$work/g.html") j=$(size "$work/g.json")
    echo
    echo "gearwheel (42 mm, 267 layers of 0.03, islands and skins on lpbf-cli, binary CLI): $("${VB[@]}" totals "$work/g.html")"
    awk -v c="$c" -v h="$h" -v j="$j" 'BEGIN {
        printf "  page %.1f MB, binary CLI %.1f MB: %.2fx (bound 2: %s); the full --json %.1f MB\n", h / 1e6, c / 1e6, h / c,
               h <= 2 * c ? "PASS" : "FAIL", j / 1e6 }'
    echo "  the page against its --json twin (viewercheck.py compare): $(python3 "$here/../cli/viewercheck.py" compare "$work/g.html" "$work/g.json" | tail -1)"
    local help
    help=$("$LAMINA" slice --help 2>&1) # not piped into grep -q: lamina would take a SIGPIPE
    if [[ $help == *--json-vectors* ]]; then
        "$LAMINA" "${args[@]}" -o /dev/null --json-vectors summary --json "$work/gs.json"
        "$LAMINA" "${args[@]}" -o /dev/null --json-vectors summary --json-contours none --json "$work/gn.json"
        awk -v s="$(size "$work/gs.json")" -v n="$(size "$work/gn.json")" -v j="$j" 'BEGIN {
            printf "  --json-vectors summary %.2f MB: 1/%.0f of the full JSON (bound 1/10: %s); without contours too %.2f MB: 1/%.0f\n",
                   s / 1e6, j / s, s * 10 <= j ? "PASS" : "FAIL", n / 1e6, j / n }'
    else
        echo "  --json-vectors summary: skipped (this lamina has no --json-vectors)"
    fi
    opened "$work/g.html" "the gearwheel's page"
    rm -f "$work/g.json" "$work/gs.json" "$work/gn.json"
}

plate
gearwheel
