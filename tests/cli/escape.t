#!/usr/bin/env bash
# Strings from the user in the pictures (--svg, --html): a unit name, a
# model path with markup, quotes, a byte that is not UTF-8 and a control
# byte. The SVG must be well-formed XML (Python's parser), draw only (no
# script, no handler: svgcheck.py inert) and show each string as text;
# the HTML must be the viewer's own page around the run's JSON, nothing
# else; and a real browser must run none of it (headless Chromium's
# console, with a page that does log as the control).
. "$(dirname "$0")/lib.sh"
svgcheck() { python3 "$TESTS/cli/svgcheck.py" "$@"; }
PART="$M/viewer/stepped.ug"   # 4 layers at -w 0.5
LOG='console.log(7)'

# a unit name with markup (-s): refused by the profile's check, or drawn as text
for u in "<script>$LOG</script>" "<svg onload=$LOG>" "a&b\"c'd"; do
    rm -f "$TMP/u.svg"
    run "$LAMINA" slice "$PART" -w 0.5 -s "units=$u" --svg "$TMP/u.svg" -o "$TMP/u.sls"
    if [ "$RC" -eq 0 ]; then
        is "$(svgcheck inert "$TMP/u.svg")" ok "units=$u: the sheet is well-formed and only draws"
        is "$(svgcheck scale "$TMP/u.svg" | cut -d' ' -f2-)" "$u" "... and its scale bar says the units as given, as text"
        cp "$TMP/u.svg" "$TMP/units-$((T_N / 2)).svg"
    else
        like "$RC $ERR" "^[12] .*units" "units=$u: refused, the error names units"
        ok $([ ! -e "$TMP/u.svg" ] && echo 0 || echo 1) "... and no sheet is written"
    fi
done

# a model path with markup, quotes, a byte not UTF-8 and control bytes
D="$TMP/<script>$LOG<"          # mkdir -p: a directory "script>" inside it
name=$'a<b&c"d\'e\xff\x01\x7f\tf.ug'
mkdir -p "$D/script>" && cp "$PART" "$D/script>/$name"
P="$D/script>/$name"
run "$LAMINA" slice "$P" -w 0.5 --svg "$TMP/p.svg" --html "$TMP/p.html" -o "$TMP/p.sls"
is "$RC" 0 "a model path with <, &, quotes, \\xff and control bytes: exit 0"
is "$(svgcheck inert "$TMP/p.svg")" ok "the sheet is well-formed XML and only draws"
# what the title must say: the path as UTF-8, each byte that is not (and
# each control character) one U+FFFD, computed here by Python's decoder
want=$(python3 -c 'import os, sys
p = os.fsencode(sys.argv[1]).decode("utf-8", "replace")
p = "".join("\ufffd" if ord(c) < 32 or 0x7f <= ord(c) <= 0x9f else c for c in p)
print(ascii("lamina: %s (4 layers)" % p))' "$P")
is "$(svgcheck texts "$TMP/p.svg" | sed -n 1p)" "$want" "the sheet's title is the path, as text, U+FFFD for what XML cannot hold"
# the page: the viewer's own, byte for byte, around the run's data (docs/viewer.md):
# a head and the run's JSON holding no '<', and base64 layer blocks
run python3 -c 'import re, sys
page = open(sys.argv[1], "rb").read()
a, rest = open(sys.argv[2], "rb").read().split(b"@LAMINA_HEAD@")
b, c = rest.split(b"@LAMINA_DATA@")
head = re.match(rb"<script type=\"application/json\" id=\"lamina-head\">[^<]*</script>\n", page[len(a):])
data = page[len(a) + len(head.group(0)) + len(b):len(page) - len(c)] if head else b""
blocks = rb"(<script type=\"application/octet-stream\" id=\"lamina-layer-\d+\">[A-Za-z0-9+/=]*</script><script>lamina.arrived\(\d+\)</script>\n)*"
run = rb"<script type=\"application/json\" id=\"lamina-run\">[^<]{100,}</script>\n<script>lamina.loaded\(\)</script>"
print(page.startswith(a), page.endswith(c), bool(head) and page[len(a) + len(head.group(0)):].startswith(b),
      re.fullmatch(blocks + run, data) is not None)' "$TMP/p.html" "$TESTS/../core/out/viewer.html"
is "$OUT" "True True True True" "the HTML is core/out/viewer.html around its head, blocks and JSON, which hold no '<': no script but the viewer's"
is "$(python3 -c 'import json, re, sys
s = open(sys.argv[1], encoding="utf-8").read()
print(ascii(json.loads(re.search(r"id=\"lamina-run\">(.*?)</script>", s, re.S).group(1))["job"]["model"]))' "$TMP/p.html")" \
   "$(python3 -c 'import os, sys; print(ascii(os.fsencode(sys.argv[1]).decode("utf-8", "replace")))' "$P")" \
   "the page's JSON holds the path as given (U+FFFD for the byte not UTF-8)"

# ---- in the browser --------------------------------------------------------
CHROME=$(command -v chromium || command -v chromium-browser)
if [ -z "$CHROME" ]; then
    for i in 1 2 3 4 5; do T_N=$((T_N + 1)); echo "ok $T_N # skip chromium is not installed (make deps could not install it)"; done
    done_testing; exit
fi
# logged FILE: what the page logs to the console once the browser has run it
# to the end (virtual time: no sleep), one line a message; its DOM in $TMP/dom
logged() {
    HOME="$TMP" timeout 300 "$CHROME" --headless --no-sandbox --disable-gpu --no-first-run \
        --user-data-dir="$TMP/chromium" --enable-logging=stderr --v=0 --virtual-time-budget=30000 \
        --dump-dom "file://$1" >"$TMP/dom" 2>"$TMP/chrome.err"
    grep -o 'CONSOLE[^"]*"[^"]*"' "$TMP/chrome.err"
}
printf '<!DOCTYPE html><html><body><script>%s</script></body></html>\n' "$LOG" > "$TMP/control.html"
printf '<svg xmlns="http://www.w3.org/2000/svg"><script>%s</script></svg>\n' "$LOG" > "$TMP/control.svg"
like "$(logged "$TMP/control.html"; logged "$TMP/control.svg")" '"7"(.|\n)*"7"' \
   "(the check can fail: pages that log 7, an HTML and an SVG, are seen doing it)"
got=""
for f in "$TMP/p.svg" "$TMP"/units-*.svg; do [ -e "$f" ] && got="$got$(logged "$f")"; done
is "$got" "" "the sheets with hostile strings run nothing in the browser"
is "$(logged "$TMP/p.html")" "" "the page with a hostile model path runs nothing in the browser"
# the viewer did run: it put the path in its title bar, as text
like "$(grep -ao '<span id="title"[^>]*>[^<]*</span>' "$TMP/dom")" "&lt;script&gt;console\\.log\\(7\\)&lt;/script&gt;" \
     "... and the viewer ran, showing the path as text in its title bar"
like "$(grep -ao '<title>[^<]*</title>' "$TMP/dom")" "^<title>lamina: .*&lt;/script&gt;/a&lt;b&amp;c" \
     "... and in the page's title"
done_testing
