#!/usr/bin/env bash
# Hatching holds on ordinary parts (issue 22, item 1): parts with
# near-coincident edges, generated here (tests/cli/meshgen.py: rotated and
# jittered copies of a box, a comb of thin slots, text in overlapping
# strokes, eccentric faceted tubes whose walls thin to a hair and to the
# beam's inset), through every shipped powder-bed profile and every hatch
# strategy with skins on. Each run must exit 0 and be sane by the test's
# own geometry (tests/cli/robustcheck.py): every layer present once and in
# place, every hatch vector inside its layer's region. Before the GEOS
# booleans worked on a fixed grid with valid inputs, the tubes failed with
# "TopologyException: found non-noded intersection".
. "$TESTS/cli/lib.sh"
export LAMINA_MACHINES="$TESTS/../machines"
CHECK() { python3 "$TESTS/cli/robustcheck.py" "$@"; } # a function: the path may hold spaces

# the shipped powder-bed profiles, and every strategy the program knows
mapfile -t profiles < <("$LAMINA" machines | awk '$2 == "sls" { print $1 }')
strategies=$("$LAMINA" machines --keys |
    perl -ne 'print join(" ", $1 =~ /`(\w+)`/g) if /^\| `hatch_strategy` \| (.*?) (?<!\\)\|/')
read -r -a strategies <<<"$strategies"
[ "${#profiles[@]}" -ge 3 ]; ok $? "shipped powder-bed profiles: ${profiles[*]}"
[ "${#strategies[@]}" -ge 4 ]; ok $? "hatch strategies: ${strategies[*]}"

# PART SEED WIDTH FILL: the seeds are fixed, so each part is the same on
# every run (tubes 19 is one the old booleans failed on with lpbf-cli).
# Overlapping bodies need the non-zero rule to be one part. Hatch lines
# 0.3 apart: the booleans before the scan are the same at any distance,
# and the check has fewer vectors to look at.
parts=("boxes 1 0.35 nonzero" "slots 2 0.35 nonzero" "text 3 0.45 nonzero" "tubes 19 0.1 evenodd")
for spec in "${parts[@]}"; do
    read -r kind seed w fill <<<"$spec"
    stl="$TMP/$kind$seed.stl"
    python3 "$TESTS/cli/meshgen.py" "$kind" "$stl" "$seed"
    for p in "${profiles[@]}"; do
        runs=() fails=()
        for s in "${strategies[@]}"; do
            json="$TMP/$kind$seed-$p-$s.json"
            "$LAMINA" slice "$stl" -m "$p" -w "$w" --fill "$fill" -q -s skin_layers=3 -s hatch_strategy="$s" \
                -s upskin.hatch_strategy="$s" -s downskin.hatch_strategy="$s" \
                -s hatch_distance=0.3 -s upskin.hatch_distance=0.3 -s downskin.hatch_distance=0.3 \
                --json "$json" -o "$TMP/prog" 2>"$TMP/err"
            rc=$?
            if [ $rc -eq 0 ] && [ -s "$TMP/prog" ]; then runs+=("$json")
            else fails+=("$s: exit $rc: $(head -c 200 "$TMP/err")"); fi
        done
        is "${fails[*]}" "" "$kind $seed, $p, every strategy with skins: exit 0 and a program"
        out=$(CHECK "$stl" "$w" "${runs[@]}" 2>&1)
        ok $? "$kind $seed, $p: ${out##*# }"
        [ "${out%%#*}" = "" ] || printf '%s\n' "$out" | head -3 | sed 's/^/#   /'
    done
done

# the checker itself: a layer left out, a vector moved out of its region
good="$TMP/tubes19-lpbf-cli-lines.json"
python3 - "$good" "$TMP/bad1.json" "$TMP/bad2.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
d["layers"].pop(3)
json.dump(d, open(sys.argv[2], "w"))
d = json.load(open(sys.argv[1]))
v = next(v for L in d["layers"] for v in L["vectors"] if v["kind"] == "core")
v["from"][0] += 40
v["to"][0] += 40
json.dump(d, open(sys.argv[3], "w"))
EOF
CHECK "$TMP/tubes19.stl" 0.1 "$TMP/bad1.json" >/dev/null; ok $((!$?)) "checker: a missing layer fails"
CHECK "$TMP/tubes19.stl" 0.1 "$TMP/bad2.json" >/dev/null; ok $((!$?)) "checker: a vector out of its region fails"
done_testing
