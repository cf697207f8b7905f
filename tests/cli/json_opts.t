#!/usr/bin/env bash
# What --json holds (issue 26): --json-vectors summary|none, --json-contours
# none and --json-layers A:B on lamina slice and lamina build, and the job's
# exposures (job.exposure). Every figure is recomputed here from the full
# JSON of the same run, by this test's own Python (summary counts and
# lengths, layers and totals), or read from the machine profile as `lamina
# machines --show` and the job file give it (exposures); the default output
# is byte for byte the one without the options, and its numbers are the
# shortest that read back as Python's repr writes them (the JSON writer's
# own number formatting, issue 26).
. "$(dirname "$0")/lib.sh"

SCHEMA="$TESTS/../schema/lamina-run-1.schema.json"
CUBE="$M/thesis_cube_hole.ug"
cd "$TMP" || exit 1

# check.py: the independent checks, one subcommand each; prints what is wrong
cat >check.py <<'PY'
import json, math, sys
import jsonschema, yaml

def load(p):
    with open(p) as f:
        return json.load(f)

def valid(schema, *runs):
    s = load(schema)
    for r in runs:
        jsonschema.validate(load(r), s)

ATTRS = ("region", "part", "style", "laser", "label")

def groups(layer):
    """The layer's vectors grouped by kind and attributes, in order of first
    appearance: [key, count, length] with lengths summed in order."""
    out, at = [], {}
    for v in layer["vectors"]:
        key = (v["kind"],) + tuple((a, v[a]) for a in ATTRS if a in v)
        d = [v["to"][i] - v["from"][i] for i in range(3)]
        n = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        if key not in at:
            at[key] = len(out)
            out.append([key, 0, 0.0])
        g = out[at[key]]
        g[1] += 1
        g[2] += n
    return out

def summary(full, summ):
    """summ's layers are full's with a summary recomputed from full's vectors
    instead of the vectors; job and totals the same."""
    F, S = load(full), load(summ)
    assert F["job"] == S["job"] and F["totals"] == S["totals"], "job or totals differ"
    assert len(F["layers"]) == len(S["layers"]), "layer count"
    ngroups = 0
    for fl, sl in zip(F["layers"], S["layers"]):
        assert "vectors" not in sl, "layer %d keeps its vectors" % fl["index"]
        want = groups(fl)
        got = sl["summary"]
        assert len(want) == len(got), "layer %d: %d groups, want %d" % (fl["index"], len(got), len(want))
        for (key, n, length), g in zip(want, got):
            gkey = (g["kind"],) + tuple((a, g[a]) for a in ATTRS if a in g)
            assert gkey == key, "layer %d: group %s, want %s" % (fl["index"], gkey, key)
            assert set(g) == {"kind", "count", "length"} | {a for a, _ in key[1:]}, "keys %s" % sorted(g)
            assert g["count"] == n, "layer %d %s: count %d, want %d" % (fl["index"], key, g["count"], n)
            assert abs(g["length"] - length) <= 1e-9 * max(1, length), "layer %d %s: length %r, want %r" % (
                fl["index"], key, g["length"], length)
        assert sum(g["count"] for g in got) == fl["stats"]["vectors"], "counts sum to the layer's vectors"
        ngroups += len(got)
        rest = {k: v for k, v in fl.items() if k != "vectors"}
        assert rest == {k: v for k, v in sl.items() if k != "summary"}, "layer %d: other keys" % fl["index"]
    assert ngroups > len(F["layers"]), "more groups than layers"

def layers(full, part, first, last):
    """part holds layers first..last of full, each exactly; job and totals
    are full's (the whole run)."""
    F, P = load(full), load(part)
    first, last = int(first), int(last)
    assert F["job"] == P["job"] and F["totals"] == P["totals"], "job or totals differ"
    assert [l["index"] for l in P["layers"]] == list(range(first, last + 1)), [l["index"] for l in P["layers"]]
    assert P["layers"] == F["layers"][first - 1:last], "the layers differ"

def none(full, other, drop):
    """other's layers are full's without the keys in drop (comma separated)."""
    F, O = load(full), load(other)
    drop = drop.split(",")
    assert F["job"] == O["job"] and F["totals"] == O["totals"], "job or totals differ"
    for fl, ol in zip(F["layers"], O["layers"]):
        assert ol == {k: v for k, v in fl.items() if k not in drop}, "layer %d" % fl["index"]
    assert len(F["layers"]) == len(O["layers"])

def exposure(show, run):
    """job.exposure of a single part's run: each region the profile hatches
    or passes, style 0, with the profile's power, speed and hatch distance
    (the spot width for the contour)."""
    p = yaml.safe_load(open(show))
    want = [{"style": 0, "region": "contour", "power": p["contour"]["power"], "speed": p["contour"]["speed"],
             "distance": p["spot_width"]},
            {"style": 0, "region": "core", "power": p["power"], "speed": p["speed"], "distance": p["hatch_distance"]}]
    for r in ("upskin", "downskin"):
        want.append({"style": 0, "region": r, "power": p[r]["power"], "speed": p[r]["speed"],
                     "distance": p[r]["hatch_distance"]})
    if p["support_type"] != "none":  # its walls: the support section's exposure, support_spacing apart
        want.append({"style": 0, "region": "support", "power": p["support"]["power"], "speed": p["support"]["speed"],
                     "distance": p["support_spacing"]})
    got = load(run)["job"]["exposure"]
    assert got == want, "got %s\nwant %s" % (got, want)

def build_exposure(show, job, run, hatch):
    """A build's exposures: styles 1 and 2 (contour, core) the profile's,
    the job's style for the pillars' core its own keys, no skins (skin_layers
    0); every (style, region) of the run's exposed vectors is listed."""
    p = yaml.safe_load(open(show))
    j = yaml.safe_load(open(job))
    fine = j["styles"]["fine"]
    want = [{"style": 1, "region": "contour", "power": p["contour"]["power"], "speed": p["contour"]["speed"],
             "distance": p["spot_width"]},
            {"style": 2, "region": "core", "power": p["power"], "speed": p["speed"], "distance": float(hatch)},
            {"style": 5, "region": "core", "power": fine["power"], "speed": fine["speed"],
             "distance": fine["hatch_distance"]}]
    R = load(run)
    if p["support_type"] != "none":  # the support's style is numbered last: after the job's
        names = {s["name"]: s["style"] for s in R["job"]["build"]["styles"]}
        assert max(names.values()) == names["support"], names
        want.append({"style": names["support"], "region": "support", "power": p["support"]["power"],
                     "speed": p["support"]["speed"], "distance": p["support_spacing"]})
    got = R["job"]["exposure"]
    assert got == want, "got %s\nwant %s" % (got, want)
    names = {s["style"]: s["name"] for s in R["job"]["build"]["styles"]}
    assert names[5] == "fine", names
    used = {(v["style"], v["region"]) for l in R["layers"] for v in l["vectors"] if "region" in v}
    listed = {(e["style"], e["region"]) for e in got}
    assert used == listed, "vectors use %s, listed %s" % (sorted(used), sorted(listed))

def shortest(run, least):
    """Every number of run's text with a point or an exponent is the
    shortest that reads back as its double, as Python's repr writes it
    (David Gay's algorithm: an independent formatter); at least `least`."""
    import re
    n = long = 0
    for t in re.findall(r'(?<![\w."])-?\d+\.\d+(?:e[-+]\d+)?|(?<![\w."])-?\d+e[-+]\d+', open(run).read()):
        n += 1
        long += len(re.sub(r'^[-0.]*|e.*$|\.', '', t)) >= 16
        assert repr(float(t)) == t, "%s is not %s" % (t, repr(float(t)))
    assert n >= int(least) and long >= n // 4, "only %d numbers, %d of 16 or 17 digits" % (n, long)

try:
    globals()[sys.argv[1]](*sys.argv[2:])
except AssertionError as e:
    print(e)
    sys.exit(1)
PY
CHECK=(python3 "$TMP/check.py")

# ---- a hatched part: every option against the full JSON ----
"$LAMINA" slice "$CUBE" -m lpbf-cli -q -o full.cli --json full.json
ok $? "lpbf-cli cube: the full JSON"
n=$(jq '.layers | length' full.json)
ok $(( !(n > 10) )) "it has more than 10 layers ($n)"
for opt in "--json-vectors all" "--json-contours all" "--json-layers 1:" "--json-layers :$n" "--json-layers 1:$n"; do
    "$LAMINA" slice "$CUBE" -m lpbf-cli -q -o same.cli --json same.json $opt
    cmp -s full.json same.json
    ok $? "$opt: the JSON is byte for byte the default's"
done
cmp -s full.cli same.cli
ok $? "and so is the program"

"$LAMINA" slice "$CUBE" -m lpbf-cli -q -o sum.cli --json sum.json --json-vectors summary
ok $? "--json-vectors summary"
cmp -s full.cli sum.cli
ok $? "the program is the same"
run "${CHECK[@]}" summary full.json sum.json
is "$RC $OUT" "0 " "each layer's summary: the full JSON's vectors grouped by kind, counted and measured"
full_size=$(stat -c %s full.json) sum_size=$(stat -c %s sum.json)
ok $(( !(sum_size * 10 <= full_size) )) "the summary is at most a tenth of the full JSON ($sum_size of $full_size bytes)"

"$LAMINA" slice "$CUBE" -m lpbf-cli -q -o x.cli --json none.json --json-vectors none
run "${CHECK[@]}" none full.json none.json vectors
is "$RC $OUT" "0 " "--json-vectors none: the layers without their vectors, all else the same"
"$LAMINA" slice "$CUBE" -m lpbf-cli -q -o x.cli --json nc.json --json-contours none
run "${CHECK[@]}" none full.json nc.json contours
is "$RC $OUT" "0 " "--json-contours none: the layers without their contours"
"$LAMINA" slice "$CUBE" -m lpbf-cli -q -o x.cli --json bare.json --json-contours none --json-vectors none
run "${CHECK[@]}" none full.json bare.json contours,vectors
is "$RC $OUT" "0 " "both: each layer its figures only"

for r in "3:5 3 5" "4:4 4 4" ":2 1 2" "$((n - 1)): $((n - 1)) $n"; do
    set -- $r
    "$LAMINA" slice "$CUBE" -m lpbf-cli -q -o x.cli --json part.json --json-layers "$1"
    run "${CHECK[@]}" layers full.json part.json "$2" "$3"
    is "$RC $OUT" "0 " "--json-layers $1: layers $2 to $3 as in the full JSON; job and totals the whole run's"
done
"$LAMINA" slice "$CUBE" -m lpbf-cli -q -o x.cli --json both.json --json-layers 2:3 --json-vectors summary
is "$(jq -c '[.layers[].index, (.layers[0] | has("summary"), has("vectors"))]' both.json)" '[2,3,true,false]' \
    "--json-layers with --json-vectors summary: both apply"

run "${CHECK[@]}" valid "$SCHEMA" full.json sum.json none.json bare.json part.json both.json
is "$RC $ERR" "0 " "every one of them is valid against the schema"
run "${CHECK[@]}" shortest full.json 20000
is "$RC $OUT" "0 " "its numbers are the shortest that read back (hatch ends at 67 degrees: 16 and 17 digits)"
run python3 "$TESTS/cli/jsoncheck.py" "$SCHEMA" full.json --cli full.cli
is "$RC $OUT" "0 " "the default JSON still passes jsoncheck.py"

# ---- exposures ----
"$LAMINA" machines --show lpbf-cli >lpbf.yaml
run "${CHECK[@]}" exposure lpbf.yaml full.json
is "$RC $OUT" "0 " "job.exposure: each region's power, speed and distance as the profile gives them"
"$LAMINA" slice "$CUBE" -m lpbf-cli -q -o x.cli --json pt.json -s upskin.point_distance=0.05 -s upskin.exposure_time=2e-05
is "$(jq -c '.job.exposure[] | select(.region == "upskin") | [.point_distance, .exposure_time]' pt.json)" '[0.05,2e-05]' \
    "point exposure: the region's point distance and time too"
is "$(jq -c '[.job.exposure[] | select(.region != "upskin") | has("point_distance")] | unique' pt.json)" '[false]' \
    "and only where it is on"
"$LAMINA" slice "$M/frame_island.ug" -m creol-ladrp -w 2 -q -o x.ladrp --json ladrp.json
is "$(jq -c '.job | has("exposure")' ladrp.json)" false "LADRP: no exposure"
"$LAMINA" slice "$CUBE" -w 0.25 -q -o x.sls --json sls.json
is "$(jq -c '[.job.exposure[] | [.style, .region, .distance]]' sls.json)" '[[0,"contour",0.1]]' \
    "the built-in SLS profile: contours only (it hatches nothing), at its 0.1 spot"

# ---- a build: exposures per style, summaries with the vectors' attributes ----
EX="$TESTS/../examples/plate.yaml"
B=(build "$EX" -q -s layer_width=2 -s hatch_distance=1 -s skin_layers=0)
"$LAMINA" "${B[@]}" -o plate.cli --json plate.json
ok $? "examples/plate.yaml builds"
run "${CHECK[@]}" build_exposure lpbf.yaml "$EX" plate.json 1
is "$RC $OUT" "0 " "build: an exposure per style and region, the job's style with its own keys"
"$LAMINA" "${B[@]}" -o plate2.cli --json plate_sum.json --json-vectors summary
run "${CHECK[@]}" summary plate.json plate_sum.json
is "$RC $OUT" "0 " "build: summaries grouped by kind, region, part, style, laser and label"
cmp -s plate.cli plate2.cli
ok $? "build: the program is the same"
"$LAMINA" "${B[@]}" -o x.cli --json plate_part.json --json-layers 3:4
run "${CHECK[@]}" layers plate.json plate_part.json 3 4
is "$RC $OUT" "0 " "build --json-layers 3:4: those layers; the totals the whole plate's (its lasers and parts)"

# ---- usage errors: exit 2, nothing written ----
for bad in "--json-layers 0:3|A:B, A: or :B" "--json-layers 5:3|A <= B" "--json-layers 3|A:B, A: or :B" \
           "--json-layers x:4|A:B, A: or :B" "--json-layers 1:$((n + 1))|the run has $n layers" \
           "--json-layers $((n + 1)):|the run has $n layers" "--json-vectors some|all, summary or none" \
           "--json-contours some|all or none"; do
    opt=${bad%%|*} want=$(printf '%s' "${bad#*|}" | sed 's/[][\.*^$(){}+?|/]/\\&/g')
    rm -f bad.json bad.cli
    run "$LAMINA" slice "$CUBE" -m lpbf-cli -o bad.cli --json bad.json $opt
    like "$RC $ERR" "^2 lamina slice: .*$want" "slice $opt: usage error naming it"
    ok $([ ! -e bad.json ] && [ ! -e bad.cli ]; echo $?) "slice $opt: nothing written"
done
for opt in "--json-layers 1:2" "--json-vectors summary" "--json-contours none"; do
    run "$LAMINA" slice "$CUBE" -m lpbf-cli -o bad.cli $opt
    like "$RC $ERR" "^2 lamina slice: --json-\w+ says what --json FILE holds: give --json FILE too" \
        "slice $opt without --json: usage error"
done
run "$LAMINA" "${B[@]}" -o bad.cli --json-vectors none
like "$RC $ERR" "^2 lamina build: --json-vectors says what --json FILE holds" "build --json-vectors without --json"
run "$LAMINA" "${B[@]}" -o bad.cli --json bad.json --json-layers 4:99
like "$RC $ERR" "^2 lamina build: --json-layers 4:99: the run has \d+ layers" "build --json-layers past the plate"
ok $([ ! -e bad.json ]; echo $?) "build: nothing written"

done_testing
