#!/usr/bin/env bash
# slice --html: one self-contained page with the run's layer interchange
# JSON, checked by the test's own reading (viewercheck.py), and drawn by a
# real browser: headless Chromium opens the page at a chosen layer
# (#layer=N), and the screenshot's pixels must show that layer of the
# stepped ring (tests/models/viewer/stepped.ug: 6 x 6 below z = 1, 4 x 4
# above, a 2 x 2 hole through both), as the test computes it.
. "$(dirname "$0")/lib.sh"
V() { python3 "$TESTS/cli/viewercheck.py" "$@"; } # a function: the path may hold spaces
PART="$M/viewer/stepped.ug"

run "$LAMINA" slice "$PART" -w 0.5 --html "$TMP/s.html" -o "$TMP/s.sls"
is "$RC" 0 "slice --html: exit 0"
# areas from the geometry: 36 - 4 below, 16 - 4 above
is "$(V json "$TMP/s.html" | tr '\n' '|')" "1 32 1 1 True|2 32 1 1 True|3 12 1 1 True|4 12 1 1 True|deposits 0|" \
   "the embedded run: 4 layers, 1-based, a solid and its hole each, net areas 32, 32, 12, 12"
# the data is the layer interchange JSON: the schema and the JSON's own checker accept it
python3 -c 'import re, sys; s = open(sys.argv[1]).read(); sys.stdout.write(re.search(r"id=\"lamina-run\">(.*?)</script>", s, re.S).group(1))' \
    "$TMP/s.html" > "$TMP/s.json"
run python3 "$TESTS/cli/jsoncheck.py" "$TESTS/../schema/lamina-run-1.schema.json" "$TMP/s.json" --sls "$TMP/s.sls"
is "$RC $OUT" "0 " "the embedded run validates against schema/lamina-run-1 and matches the program (jsoncheck.py)"
is "$(grep -cE '(src|href)=|https?:|@import|url\(' "$TMP/s.html")" 0 "nothing fetched: no src, href, URL or import"
is "$(grep -o '</script>' "$TMP/s.html" | wc -l)" 2 "two script elements, each closed once"

# a path that holds "</script>" cannot close the data early
mkdir -p "$TMP/a</script>"
cp "$PART" "$TMP/a</script>/p.ug"
run "$LAMINA" slice "$TMP/a</script>/p.ug" -w 0.5 --html "$TMP/tricky.html" -o "$TMP/tricky.sls"
is "$(grep -o '</script>' "$TMP/tricky.html" | wc -l)" 2 "a model path with </script> in it stays inside the JSON"
is "$(python3 -c 'import json,re,sys; s=open(sys.argv[1]).read(); print(json.loads(re.search(r"id=\"lamina-run\">(.*?)</script>", s, re.S).group(1))["job"]["model"])' "$TMP/tricky.html")" \
   "$TMP/a</script>/p.ug" "... and reads back as given"

# LADRP: the page's deposits are the program's
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -m creol-ladrp -w 0.5 --html "$TMP/l.html" -o "$TMP/l.ladrp"
deposits=$(awk '/pendown/ {d = 1; next} /penup/ {d = 0; next} d && /uline/ {n++} END {print n + 0}' "$TMP/l.ladrp")
is "$(V json "$TMP/l.html" | tail -1)" "deposits $deposits" "LADRP: as many deposit vectors as the program has deposits"

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
# shot HASH OUT: the page at #HASH, once the browser has run it to the end
# (virtual time: no sleep, however loaded the machine)
shot() {
    HOME="$TMP" timeout 300 "$CHROME" --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run \
        --force-device-scale-factor=1 --user-data-dir="$TMP/chromium" --window-size=$W,$H \
        --virtual-time-budget=30000 --screenshot="$2" "file://$TMP/s.html#$1" >/dev/null 2>&1
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
