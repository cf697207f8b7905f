#!/usr/bin/env bash
# slice --html and build --html: one self-contained page (docs/viewer.md): a
# head, each layer's geometry as a base64 block of varints, the run's JSON
# with vectors summarised. The test reads the page its own way
# (viewercheck.py: base64, varints, zigzag and the one cursor decoded from
# docs/viewer.md, not from the encoder) and holds every layer against the
# --json twin of the same run: contours, every vector's kind, order and
# attributes, from and to within half a quantum, the jumps where the JSON
# has them; the run element's figures equal the twin's. Runs: contours
# only, hatched lines, islands with skins, a slanted axis, cm units, LADRP,
# a build with parts and two lasers. The page of a hatched job is at most
# twice its binary CLI. A real browser draws it: headless Chromium opens
# the page at a chosen layer (#layer=N), and the screenshot's pixels must
# show that layer of the stepped ring (tests/models/viewer/stepped.ug: 6 x 6
# below z = 1, 4 x 4 above, a 2 x 2 hole through both), as the test
# computes it.
. "$(dirname "$0")/lib.sh"
V() { python3 "$TESTS/cli/viewercheck.py" "$@"; } # a function: the path may hold spaces
PART="$M/viewer/stepped.ug"
D="$TMP/with space"
mkdir -p "$D"

run V selftest
is "$RC $OUT" "0 " "viewercheck: its decoder on a block worked out by hand, and what it refuses"

run "$LAMINA" slice "$PART" -w 0.5 --html "$D/s.html" --json "$D/s.json" -o "$D/s.sls"
is "$RC" 0 "slice --html: exit 0"
# areas from the geometry: 36 - 4 below, 16 - 4 above
is "$(V json "$D/s.html" | tr '\n' '|')" "1 32 1 1 True|2 32 1 1 True|3 12 1 1 True|4 12 1 1 True|deposits 0|" \
   "the page: 4 layers, 1-based, a solid and its hole each (nested as their depths say), net areas 32, 32, 12, 12"
run V compare "$D/s.html" "$D/s.json"
like "$RC $OUT" "^0 ok: 4 layers, 8 contours, [1-9][0-9]* vectors" "every layer's contours and vectors are the --json twin's"
# the head: the quantum is 0.1 um in the job's units, mm here
hd() { V head "$1" | python3 -c 'import json, sys; h = json.load(sys.stdin); print(eval(sys.argv[1]))' "$2"; }
is "$(hd "$D/s.html" '"%r %s %d %s %s" % (h["quantum"], h["units"], h["layers"], h["kinds"][:4], h["attrs"][0])')" \
   "0.0001 mm 4 ['contour', 'core', 'upskin', 'downskin'] part" "the head: quantum 1e-4 mm, 4 layers, the kinds and attributes named"
# the run element is the layer interchange JSON: the schema accepts it
V run "$D/s.html" >"$D/run.json"
run python3 -c 'import json, sys, jsonschema
jsonschema.validate(json.load(open(sys.argv[2])), json.load(open(sys.argv[1])))' \
    "$TESTS/../schema/lamina-run-1.schema.json" "$D/run.json"
is "$RC $ERR" "0 " "the run element validates against schema/lamina-run-1"
# nothing fetched: the blocks' base64 left out (an "src=" could end one)
blank() { sed -E 's/(id="lamina-layer-[0-9]+">)[^<]*/\1/g' "$1"; }
is "$(blank "$D/s.html" | grep -cE '(src|href)=|https?:|@import|url\(')" 0 "nothing fetched: no src, href, URL or import"
# docs/viewer.md: the head, the viewer's script, two a layer, the run, loaded(); the
# layers counted in the --json twin
NL=$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["layers"]))' "$D/s.json")
NS=$((2 * NL + 4))
is "$(grep -o '</script>' "$D/s.html" | wc -l) $(grep -o '<script' "$D/s.html" | wc -l)" "$NS $NS" \
   "$NL layers: 2 x $NL + 4 script elements, each closed once"

# a path that holds "</script>" cannot close an element early
mkdir -p "$TMP/a</script>"
cp "$PART" "$TMP/a</script>/p.ug"
run "$LAMINA" slice "$TMP/a</script>/p.ug" -w 0.5 --html "$TMP/tricky.html" -o "$TMP/tricky.sls"
is "$(grep -o '</script>' "$TMP/tricky.html" | wc -l)" "$NS" "a model path with </script> in it stays inside the JSON"
is "$(V run "$TMP/tricky.html" | python3 -c 'import json, sys; print(json.load(sys.stdin)["job"]["model"])')" \
   "$TMP/a</script>/p.ug" "... and reads back as given"

# twin RUN ARGS...: slice with --html and --json of one run, compared
twin() {
    local n=$1
    shift
    "$LAMINA" "$@" -q --html "$D/$n.html" --json "$D/$n.json" 2>"$D/$n.err"
    RC=$?
    [ "$RC" -eq 0 ] || { cat "$D/$n.err"; return; }
    run V compare "$D/$n.html" "$D/$n.json"
}
python3 "$TESTS/cli/geargen.py" "$D/gear.stl"  # 20 mm across, 12 teeth, a bore, 2 high
twin lines slice "$PART" -m lpbf-cli -w 0.5 -s hatch_strategy=lines -o "$D/lines.cli"
like "$RC $OUT" "^0 ok: 4 layers, 8 contours, [0-9]+ vectors \([1-9][0-9]* jumps\)" "lpbf-cli, lines and skins: the page is the JSON"
twin islands slice "$D/gear.stl" -m lpbf-cli -w 0.25 -s hatch_strategy=islands -s skin_layers=2 -o "$D/islands.cli"
like "$RC $OUT" "^0 ok: 8 layers, 16 contours, [0-9]+ vectors \([1-9][0-9]* jumps\)" "the gear, islands, a core between skins: the page is the JSON"
up=$(grep -c '"kind": "upskin"' "$D/islands.json") core=$(grep -c '"kind": "core"' "$D/islands.json")
ok $([ "$up" -gt 0 ] && [ "$core" -gt 0 ] && echo 0 || echo 1) "(... it has up-skin and core vectors: $up and $core)"
twin slant slice "$PART" -m lpbf-cli -a 1,2,3 -w 0.5 -o "$D/slant.cli"
like "$RC $OUT" "^0 ok: [1-9][0-9]* layers, [0-9]+ contours, [1-9][0-9]* vectors" "a slanted axis (1, 2, 3): the page is the JSON in the layer plane"
twin cm slice "$PART" -m lpbf-cli -s units=cm -w 0.5 -o "$D/cm.cli"
like "$RC $OUT" "^0 ok: 4 layers" "cm units: the page is the JSON"
is "$(hd "$D/cm.html" '"%s %s" % (h["units"], abs(h["quantum"] / 1e-5 - 1) < 1e-9)')" "cm True" \
   "... its quantum 0.1 um in cm: 1e-5"
twin ladrp slice "$M/thesis_cube_hole.ug" -m creol-ladrp -w 0.5 -o "$D/l.ladrp"
like "$RC $OUT" "^0 ok: [1-9][0-9]* layers" "LADRP: the page's deposits and travel are the JSON's"
deposits=$(awk '/pendown/ {d = 1; next} /penup/ {d = 0; next} d && /uline/ {n++} END {print n + 0}' "$D/l.ladrp")
is "$(V json "$D/ladrp.html" | tail -1)" "deposits $deposits" "LADRP: as many deposit vectors in the page as the program has deposits"
twin plate build "$TESTS/../examples/plate.yaml" -s layer_width=2 -s hatch_distance=1 -s skin_layers=0 -o "$D/plate.cli"
like "$RC $OUT" "^0 ok: 10 layers, [0-9]+ contours, [1-9][0-9]* vectors \([1-9][0-9]* jumps\)" \
   "build: examples/plate.yaml (11 parts, 2 lasers): the page is the JSON, with every vector's part, style, laser and label"
is "$(python3 -c 'import json, sys
r = json.load(open(sys.argv[1]))
print(len({v["part"] for L in r["layers"] for v in L["vectors"]}), len({v["laser"] for L in r["layers"] for v in L["vectors"]}))' "$D/plate.json")" \
   "11 2" "(... its vectors belong to 11 parts and 2 lasers)"

# the check fails on a twin one step off: a vector moved by one quantum, a
# jump left out, another part, another area in a layer's figures
python3 - "$D/lines.json" "$D" <<'EOF'
import copy, json, sys
run = json.load(open(sys.argv[1]))
L = run["layers"][1]
i = next(i for i, v in enumerate(L["vectors"]) if v["kind"] in ("core", "upskin", "downskin"))
j = next(j for j, v in enumerate(L["vectors"]) if v["kind"] == "jump")
def out(name, r):
    json.dump(r, open("%s/bad_%s.json" % (sys.argv[2], name), "w"))
r = copy.deepcopy(run); r["layers"][1]["vectors"][i]["from"][0] += 1e-4; out("moved", r)
r = copy.deepcopy(run); vs = r["layers"][1]["vectors"]; del vs[j]
for v in vs[j:]:
    v["order"] -= 1
out("nojump", r)
r = copy.deepcopy(run); r["layers"][1]["vectors"][i]["part"] = 2; out("part", r)
r = copy.deepcopy(run); r["layers"][2]["stats"]["area"] += 1e-9; out("area", r)
EOF
for bad in moved nojump part area; do
    run V compare "$D/lines.html" "$D/bad_$bad.json"
    like "$RC $OUT" "^1 (?s:.*)differences$" "the check fails on a twin with $bad changed"
done

# size: a hatched job's page is at most twice its binary CLI (the gear at
# 0.05, lines 0.02 apart: about 70,000 hatch vectors, a 1.2 MB program)
run "$LAMINA" slice "$D/gear.stl" -m cli-binary -w 0.05 -s hatch_strategy=lines -s hatch_distance=0.02 -q \
    --html "$D/big.html" -o "$D/big.cli"
is "$RC $ERR" "0 " "a hatched job on cli-binary with --html"
h=$(stat -c %s "$D/big.html" 2>/dev/null || echo 0) c=$(stat -c %s "$D/big.cli" 2>/dev/null || echo 0)
ok $([ "$c" -gt 1000000 ] && [ "$h" -gt 0 ] && [ "$h" -le $((2 * c)) ] && echo 0 || echo 1) \
   "its page ($h bytes) is at most twice its binary CLI ($c bytes)"

run "$LAMINA" slice "$PART" -w 0.5 --html "$PART" -o "$TMP/x.sls"
like "$RC $ERR" "^2 lamina slice: --html .* is an input of this command" "--html onto the model: refused"
run "$LAMINA" slice "$PART" -w 0.5 --html -
like "$RC $ERR" "^2 lamina slice: the program \\(without -o\\) and --html - both write to standard output" "--html - with the program on standard output: refused"
run "$LAMINA" slice "$PART" -w 0.5 --html "$TMP/nodir/v.html" -o "$TMP/y.sls"
ok $([ "$RC" -ne 0 ] && [ ! -e "$TMP/y.sls" ] && echo 0 || echo 1) "an unwritable --html: an error, no program left"

# ---- in the browser --------------------------------------------------------
CHROME=$(command -v chromium || command -v chromium-browser)
if [ -z "$CHROME" ]; then
    for i in 1 2 3 4 5; do T_N=$((T_N + 1)); echo "ok $T_N # skip chromium is not installed (make deps could not install it)"; done
    done_testing; exit
fi
W=800 H=600
URL=$(python3 -c 'import pathlib, sys; print(pathlib.Path(sys.argv[1]).as_uri())' "$D/s.html") # the space quoted
# shot HASH OUT: the page at #HASH, once the browser has run it to the end
# (virtual time: no sleep, however loaded the machine)
shot() {
    HOME="$TMP" timeout 300 "$CHROME" --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run \
        --force-device-scale-factor=1 --user-data-dir="$TMP/chromium" --window-size=$W,$H \
        --virtual-time-budget=30000 --screenshot="$2" "$URL#$1" >/dev/null 2>&1
    [ -s "$2" ]
}
# check PNG Z: every grid point shows what the part at height Z must
check() {
    local pts got
    pts=$(V grid "$2" $W $H)
    got=$(python3 "$TESTS/cli/pixel.py" "$1" $(echo "$pts" | cut -d' ' -f1))
    paste -d' ' <(echo "$pts") <(echo "$got" | tr ' ' '\n') |
        awk '{n++; if ($2 != $3) {bad++; if (bad <= 3) ex = ex " (" $1 ": " $3 ", expected " $2 ")"}}
             END {print (bad + 0) " of " n " wrong" ex}'
}
shot "layer=3&vectors=0&travel=0" "$TMP/l3.png"; ok $? "chromium takes a screenshot of layer 3"
r=$(check "$TMP/l3.png" 1.25)
like "$r" "^0 of [0-9]{3} wrong$" "layer 3 (z 1.25): the 4 x 4 ring filled, its hole and the rest background: $r"
shot "layer=1&vectors=0&travel=0" "$TMP/l1.png"; ok $? "chromium takes a screenshot of layer 1"
r=$(check "$TMP/l1.png" 0.25)
like "$r" "^0 of [0-9]{3} wrong$" "layer 1 (z 0.25): the 6 x 6 ring filled: $r"
# the other layer's picture is wrong for each: the check tells them apart
r=$(check "$TMP/l1.png" 1.25)
like "$r" "^[1-9][0-9]* of" "(layer 1's picture fails layer 3's check: $r)"
done_testing
