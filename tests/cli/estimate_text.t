#!/usr/bin/env bash
# The build-time summary `lamina slice` prints on standard error, for
# people: its lengths and times are the run's own figures (from its --json)
# rounded by the rules of core/base/fmt.h, which estimate_ref.py below
# implements again on its own (Python's exact decimals of the doubles, half
# to even), and a DED job's time is recomputed here from its JSON lengths
# and the profile's rates (per minute, as G-code's F). A profile without
# speeds or feed rates says the time is unknown instead of printing 0 s.
. "$(dirname "$0")/lib.sh"

cat >"$TMP/estimate_ref.py" <<'PY'
"""estimate_ref.py sls|ladrp RUN.json LINE [NAME | FEED TRAVEL]: the summary line
lamina should print for the run, from its JSON; the counts and the model
path that the JSON does not hold are taken from LINE (checked where it
can: the hatch vectors); NAME: the profile sets no speeds. `rules`: the
rules on hand-reasoned values. Prints the expected line, or why not."""
import json, math, re, sys
from decimal import Decimal, ROUND_HALF_EVEN, getcontext

getcontext().prec = 200  # every double's exact decimal and a 60th of it
MM = {"mm": 1, "cm": 10, "m": 1000, "um": 1e-3, "\u00b5m": 1e-3, "in": 25.4, "inch": 25.4, "ft": 304.8}


def q(d, exp):  # d rounded half to even at 10^exp
    return d.quantize(Decimal(1).scaleb(exp), rounding=ROUND_HALF_EVEN)


def duration(x):
    if not (x >= 0) or math.isinf(x):
        return "unknown"
    if x == 0:
        return "0 s"
    d = Decimal(x)  # exact
    if d < Decimal("0.1"):  # two significant digits
        r = q(d, d.adjusted() - 1)
        if r < Decimal("0.1"):
            return format(r, "f") + " s"
    r = q(d, -1)
    if r < 10:  # tenths
        return format(r, "f") + " s"
    s = int(q(d, 0))
    if s < 86400:
        h, m, sec = s // 3600, s // 60 % 60, s % 60
        return "%d h %d min %d s" % (h, m, sec) if h else "%d min %d s" % (m, sec) if m else "%d s" % sec
    m = int(q(d / 60, 0))
    return "%d d %d h %d min" % (m // 1440, m // 60 % 24, m % 60)


def length(x, mm):
    v = abs(x) * mm  # as lamina multiplies, in doubles
    if v == 0:
        return "0 mm"
    d = Decimal(v)
    r = q(d, d.adjusted() - 2)  # three significant digits
    e = r.adjusted()
    shift, unit = (6, "km") if e >= 6 else (3, "m") if e >= 3 else (0, "mm") if e >= -1 else (-3, "\u00b5m")
    text = format(r.scaleb(-shift).normalize(), "f")
    return ("-" if x < 0 else "") + text + " " + unit


def main():
    if sys.argv[1] == "rules":  # hand-reasoned cases of the rules themselves
        return print("|".join([duration(540.672), duration(3.80372), duration(0.868351), duration(536),
                               duration(3599.6), duration(59.6), duration(0.05), duration(183930),
                               length(2926.01, 1), length(334.959, 1), length(0.05, 1), length(950, 10)]))
    kind, path, line = sys.argv[1:4]
    run = json.load(open(path))
    tot, mm = run["totals"], MM[run["job"]["units"]]
    if kind == "sls":
        m = re.match(r"lamina: (.*): (\d+) layers, (\d+) contour passes, (\d+) hatch vectors, ", line)
        if not m:
            return print("no SLS summary in: " + line)
        hatches = sum(1 for L in run["layers"] for v in L["vectors"] if v["kind"] in ("core", "upskin", "downskin"))
        if int(m.group(4)) != hatches:
            return print("%s hatch vectors printed, the JSON has %d" % (m.group(4), hatches))
        t = tot["time"]
        head = "lamina: %s: %d layers, %s contour passes, %d hatch vectors, %s exposed, %s jumped; " % (
            m.group(1), tot["layers"], m.group(3), hatches, length(tot["deposit_length"], mm),
            length(tot["travel_length"], mm))
        if len(sys.argv) > 4:  # the profile's name: it sets no speeds
            return print(head + "estimated build time unknown: %s sets no speeds" % sys.argv[4])
        print(head + "estimated build time %s (exposure %s, jumps %s, recoating %s)" % (
            duration(t["total"]), duration(t["exposure"]), duration(t["jumps"]), duration(t["recoat"])))
    else:
        m = re.match(r"lamina: (.*): \d+ layers, ", line)
        if not m:
            return print("no LADRP summary in: " + line)
        feed, travel = float(sys.argv[4]), float(sys.argv[5])
        dep, trav = tot["deposit_length"], tot["travel_length"]
        td, tt = dep / feed * 60, trav / travel * 60  # units per minute
        print("lamina: %s: %d layers, %s deposited, %s travelled; estimated build time %s (depositing %s, travel %s)" % (
            m.group(1), tot["layers"], length(dep, mm), length(trav, mm), duration(td + tt), duration(td),
            duration(tt)))


main()
PY
ref() { python3 "$TMP/estimate_ref.py" "$@"; }

# seconds of a printed duration ("1 h 2 min 3 s", "2 d 3 h 4 min", "3.8 s")
seconds() {
    printf '%s\n' "$1" | perl -ne 'my $s = 0; my %u = (d => 86400, h => 3600, min => 60, s => 1);
        $s += $1 * $u{$2} while /([\d.]+) (d|h|min|s)\b/g; print "$s\n"'
}

# ---- the reference's rules, by hand (the same cases as tests/unit/test_fmt.c)
got=$(ref rules)
is "$got" "9 min 1 s|3.8 s|0.9 s|8 min 56 s|1 h 0 min 0 s|1 min 0 s|0.050 s|2 d 3 h 6 min|2.93 m|335 mm|50 µm|9.5 m" \
    "the test's own rounding gives the hand-reasoned texts"

cube=$M/thesis_cube_hole.ug

# ---- powder bed: the printed line is the JSON's figures for people --------
for extra in "" "-s recoat_time=100" "-s recoat_time=3000"; do
    # shellcheck disable=SC2086
    run "$LAMINA" slice "$cube" -m lpbf-cli $extra -o "$TMP/p.cli" --json "$TMP/p.json"
    is "$RC" 0 "lpbf-cli $extra: exit 0"
    line=$(grep 'estimated build time' <<<"$ERR")
    is "$line" "$(ref sls "$TMP/p.json" "$line")" "lpbf-cli $extra: the summary is the JSON's totals, rounded for people"
    # the printed total against the layers' own times, added here
    sum=$(jq '[.layers[].stats.time] | add' "$TMP/p.json")
    total=${line#*estimated build time }
    total=${total%% (*}
    res=1
    case $total in *.*) res=0.1 ;; *" d "*) res=60 ;; esac
    perl -e 'exit(abs($ARGV[0] - $ARGV[1]) <= $ARGV[2] / 2 + 1e-6 ? 0 : 1)' "$(seconds "$total")" "$sum" "$res"
    ok $? "lpbf-cli $extra: '$total' is the layers' $sum s to its resolution ($res s)"
done
like "$line" 'estimated build time 2 d [0-9]+ h [0-9]+ min \(' "a build over a day: days, hours and minutes"

# ---- no speeds: unknown, not 0 s -------------------------------------------
nospeed=(-s speed=0 -s contour.speed=0 -s upskin.speed=0 -s downskin.speed=0 -s support.speed=0)
run "$LAMINA" slice "$cube" -m lpbf-cli "${nospeed[@]}" -o "$TMP/n.cli" --json "$TMP/n.json"
line=$(grep 'estimated build time' <<<"$ERR")
is "$line" "$(ref sls "$TMP/n.json" "$line" lpbf-cli)" "lpbf-cli without speeds: lengths, and the time unknown"
cat >"$TMP/nospeed.yaml" <<'YAML'
name: hatch-nospeed
inherits: cli-ascii
hatch_strategy: lines
hatch_distance: 0.5
recoat_time: 10
YAML
run "$LAMINA" slice "$cube" -m "$TMP/nospeed.yaml" -o "$TMP/n.cli"
like "$ERR" '^lamina: .*: [0-9]+ layers, .* exposed, .* jumped; estimated build time unknown: hatch-nospeed sets no speeds$' \
    "a profile that hatches and recoats but sets no speed: unknown, named"
[[ $ERR != *" 0 s"* ]]
ok $? "... and no '0 s' anywhere"

# ---- DED / LADRP: the time from the feeds -----------------------------------
# ded-gcode: feed 600 and travel 3000 mm per minute (its G-code F words)
run "$LAMINA" slice "$M/frame_island.stl" -m ded-gcode --islands -o "$TMP/d.gcode" --json "$TMP/d.json"
is "$RC" 0 "ded-gcode: exit 0"
line=$(grep 'estimated build time' <<<"$ERR")
is "$line" "$(ref ladrp "$TMP/d.json" "$line" 600 3000)" \
    "ded-gcode: deposit_length / 600 + travel_length / 3000 minutes, from the JSON"
want=$(jq '.totals.deposit_length / 10 + .totals.travel_length / 50' "$TMP/d.json") # seconds
total=${line#*estimated build time }
total=${total%% (*}
perl -e 'exit(abs($ARGV[0] - $ARGV[1]) <= 0.5 + 1e-6 ? 0 : 1)' "$(seconds "$total")" "$want"
ok $? "ded-gcode: '$total' is $want s to the second"
n=$(grep -c '^G1 ' "$TMP/d.gcode")
f=$(grep -c '^G1 .* F600$' "$TMP/d.gcode")
ok $((!(n > 0 && f == n))) "ded-gcode's program deposits at F600 (G-code: mm per minute), the rate the estimate takes ($f of $n deposits)"
# the thesis's stage: centimetres (lengths printed in metric units), 0.15 a minute
run "$LAMINA" slice "$cube" -m creol-ladrp -o "$TMP/c.txt" --json "$TMP/c.json"
line=$(grep 'estimated build time' <<<"$ERR")
is "$line" "$(ref ladrp "$TMP/c.json" "$line" 0.15 0.15)" "creol-ladrp: cm lengths in m, the time at 0.15 units a minute"
# a rate of 0
run "$LAMINA" slice "$cube" -m ded-gcode -s feed_rate=0 -o "$TMP/z.gcode"
like "$ERR" '^lamina: .* deposited, .* travelled; estimated build time unknown: ded-gcode sets no feed rate$' \
    "ded-gcode, feed_rate 0 (travel_rate follows it): unknown"
run "$LAMINA" slice "$cube" -m ded-gcode -s travel_rate=0 -o "$TMP/z.gcode"
like "$ERR" 'estimated build time unknown: ded-gcode sets no travel rate$' "ded-gcode, travel_rate 0: unknown"
run "$LAMINA" slice "$cube" -m ded-gcode -q -o "$TMP/z.gcode"
is "$ERR" "" "ded-gcode -q: no summary"

# ---- join prints what the whole run prints (LADRP: measured from the parts)
run "$LAMINA" slice "$M/frame_island.stl" -m ded-gcode --islands -o "$TMP/whole.gcode"
whole=$ERR
"$LAMINA" slice "$M/frame_island.stl" -m ded-gcode --islands --layers 1/2 -o "$TMP/p1" &&
    "$LAMINA" slice "$M/frame_island.stl" -m ded-gcode --islands --layers 2/2 -o "$TMP/p2"
ok $? "ded-gcode: two parts"
run "$LAMINA" join "$TMP/p2" "$TMP/p1" -o "$TMP/joined.gcode"
is "$ERR" "$whole" "join of the DED parts: the whole run's summary"
done_testing
