#!/usr/bin/env bash
# validate --program (issue 22, item 8): a program passes only when it is
# the whole part, each layer once, in the model's units; and a right program
# passes whatever contour passes and beam offset the profile asks for (the
# options given to validate say where the passes lie). Wrong programs are
# made from a right one lamina wrote (layers cut, repeated, units changed):
# each must fail, whatever else it says.
. "$(dirname "$0")/lib.sh"

gear="$TMP/gear wheel.stl"
python3 "$TESTS/cli/geargen.py" "$gear"
run "$LAMINA" validate "$gear" -w 0.5
is "$RC" 0 "the generated gear validates as sliced"

# ---- contour passes and the beam offset: right programs pass -------------------
# 2 passes 0.834 apart (the issue's gearwheel case): before, each inner
# pass was read as a boundary and disagreed
opts=(-m cli-ascii -s hatch_strategy=stripes -s contour_count=2 -s contour_distance=0.834)
"$LAMINA" slice "$gear" "${opts[@]}" -o "$TMP/c2.cli" 2>/dev/null
run "$LAMINA" validate "$gear" "${opts[@]}" --program "$TMP/c2.cli"
is "$RC" 0 "cli-ascii, contour_count=2, contour_distance=0.834, stripes: the program passes"
like "$OUT" ' 0 disagreeing; net area against the section in 100 layers, 0 differ' "... every contour and area confirmed"
for mch in sls-contours cli-ascii cli-binary lpbf-cli; do
    o=(-m $mch --beam-offset -s contour_count=3 -s contour_distance=0.3)
    "$LAMINA" slice "$gear" "${o[@]}" -o "$TMP/bo.$mch" 2>/dev/null
    run "$LAMINA" validate "$gear" "${o[@]}" --program "$TMP/bo.$mch"
    is "$RC" 0 "$mch --beam-offset, 3 passes 0.3 apart: the program passes"
    [ "$RC" = 0 ] || echo "$OUT$ERR" | grep -m3 -v ' 0 disagreeing' | sed 's/^/# /'
done
# each shipped sls profile as it is (lpbf-cli: beam offset, 2 passes, skins)
for mch in sls-contours cli-ascii cli-binary lpbf-cli; do
    "$LAMINA" slice "$gear" -m $mch -w 0.25 -o "$TMP/s.$mch" 2>/dev/null
    run "$LAMINA" validate "$gear" -m $mch -w 0.25 --program "$TMP/s.$mch"
    is "$RC" 0 "$mch as shipped: the program passes"
done
# the first pass half a spot (0.04) inside, the second 0.08 further: every
# contour of both is checked (a test point d off an inset contour used to
# land on the model's face and leave it undecided)
"$LAMINA" slice "$M/frame_island.stl" -m lpbf-cli -w 0.5 -o "$TMP/fi.cli" 2>/dev/null
run "$LAMINA" validate "$M/frame_island.stl" -m lpbf-cli -w 0.5 --program "$TMP/fi.cli"
like "$RC $OUT" '^0 (?s:.*): 40 layers, 240 contours checked, 240 confirmed, 0 disagreeing; net' \
    "lpbf-cli on the frame with an island: 2 passes x 3 contours x 40 layers, each checked and confirmed"
# ... and the passes must be where the options say
run "$LAMINA" validate "$gear" -m sls-contours -s contour_count=3 -s contour_distance=0.3 --program "$TMP/bo.sls-contours"
is "$RC" 3 "a beam-offset program validated without --beam-offset: exit 3"
"$LAMINA" slice "$gear" -m sls-contours -s contour_count=3 -s contour_distance=0.3 -o "$TMP/nobo.sls" 2>/dev/null
run "$LAMINA" validate "$gear" -m sls-contours --beam-offset -s contour_count=3 -s contour_distance=0.3 --program "$TMP/nobo.sls"
is "$RC" 3 "a program without beam offset validated with --beam-offset: exit 3"
run "$LAMINA" validate "$gear" -m sls-contours -s contour_count=3 -s contour_distance=0.5 --program "$TMP/nobo.sls"
is "$RC" 3 "passes 0.3 apart validated as 0.5 apart: exit 3"
run "$LAMINA" validate "$gear" --beam-offset
like "$RC $ERR" "^2 .*--beam-offset applies to --program only" "--beam-offset without --program: a usage error"
run "$LAMINA" validate "$gear" -m sls-contours -s contour_count=0 --program "$TMP/nobo.sls"
like "$RC $ERR" "^2 .*contour_count is 0" "contour_count=0: nothing to check, a usage error"

# ---- programs that are not the whole part: each fails --------------------------
"$LAMINA" slice "$gear" -m cli-ascii -o "$TMP/a.cli" 2>/dev/null
"$LAMINA" slice "$gear" -m cli-binary -o "$TMP/a.bcli" 2>/dev/null
"$LAMINA" slice "$gear" -o "$TMP/a.sls" 2>/dev/null
"$LAMINA" slice "$gear" -m cli-ascii --json "$TMP/a.json" -o "$TMP/j.cli" 2>/dev/null
is "$(grep -c '^\$\$LAYER/' "$TMP/a.cli")" 100 "the right CLI has 100 layers"
for f in a.cli a.bcli a.sls a.json; do
    m=(); case $f in *.sls) ;; *.bcli) m=(-m cli-binary) ;; *) m=(-m cli-ascii) ;; esac
    run "$LAMINA" validate "$gear" "${m[@]}" --program "$TMP/$f"
    is "$RC" 0 "the right program $f passes"
done
: >"$TMP/empty.sls"
run "$LAMINA" validate "$gear" --program "$TMP/empty.sls"
like "$RC $ERR" "^3 .*empty\.sls: layer 1 of the slicing \(h=0\.01\) is not in the program, which has no layers" \
    "a 0-byte .sls: exit 3, no layers"
# CLI with no layers: the header and the geometry's start and end only
sed -e '/^\$\$LAYER\//,$d' -e 's/^\$\$LAYERS\/100/$$LAYERS\/0/' "$TMP/a.cli" >"$TMP/none.cli"
echo '$$GEOMETRYEND' >>"$TMP/none.cli"
run "$LAMINA" validate "$gear" -m cli-ascii --program "$TMP/none.cli"
like "$RC $ERR" "^3 .*none\.cli: .*has no layers" "a CLI with no layers: exit 3"
jq -c '.layers = []' "$TMP/a.json" >"$TMP/none.json"
run "$LAMINA" validate "$gear" --program "$TMP/none.json"
like "$RC $ERR" "^3 .*none\.json: .*no layers" 'JSON with "layers": []: exit 3'
jq -c '.layers |= .[0:1]' "$TMP/a.json" >"$TMP/one.json"
run "$LAMINA" validate "$gear" --program "$TMP/one.json"
like "$RC $ERR" "^3 .*one\.json:[0-9:]* the last layer ends at 0\.02, below the model's top \(2\)" "JSON with its first layer only: exit 3"
jq -c '.layers |= [.[] | ., .]' "$TMP/a.json" >"$TMP/twice.json"
run "$LAMINA" validate "$gear" --program "$TMP/twice.json"
like "$RC $ERR" "^3 .*twice\.json:[0-9:]* layer 2 starts at 0, not where the layer before it ends" "JSON with every layer twice: exit 3"
# CLI ASCII: the first of the 100 layers only ($$LAYERS says 1, as a
# writer cut short would), every layer twice (and $$LAYERS 200)
awk '/^\$\$LAYER\//{n++} n<=1 && !/^\$\$GEOMETRYEND/' "$TMP/a.cli" | sed 's/^\$\$LAYERS\/100/$$LAYERS\/1/' >"$TMP/one.cli"
echo '$$GEOMETRYEND' >>"$TMP/one.cli"
run "$LAMINA" validate "$gear" -m cli-ascii --program "$TMP/one.cli"
like "$RC $ERR" "^3 .*one\.cli:[0-9]+:1: layer 2 of the slicing \(h=0\.03\) is not in the program" "CLI, the first of 100 layers only: exit 3"
python3 - "$TMP/a.cli" "$TMP/twice.cli" <<'PY'
import re, sys
t = open(sys.argv[1]).read().replace("$$LAYERS/100", "$$LAYERS/200")
head, body = t.split("$$GEOMETRYSTART\n")
layers = [l for l in re.split(r"(?m)^(?=\$\$LAYER/)", body.replace("$$GEOMETRYEND\n", "")) if l]
assert len(layers) == 100
open(sys.argv[2], "w").write(head + "$$GEOMETRYSTART\n" + "".join(l + l for l in layers) + "$$GEOMETRYEND\n")
PY
run "$LAMINA" validate "$gear" -m cli-ascii --program "$TMP/twice.cli"
like "$RC $ERR" "^3 .*twice\.cli:[0-9]+:1: layer 2 \(h=0\.01\) is not above the layer before it" "CLI, every layer twice: exit 3"
# binary CLI: the same two, its commands cut after the first layer or each
# layer's commands written twice ($$LAYERS made to agree)
python3 - "$TMP/a.bcli" "$TMP" <<'PY'
import struct, sys
d = open(sys.argv[1], "rb").read()
p = d.index(b"$$HEADEREND") + len(b"$$HEADEREND")
head, layers = d[:p], []
while p < len(d):
    cmd, = struct.unpack_from("<H", d, p)
    if cmd == 127: n = 6
    elif cmd == 130: n = 14 + 8 * struct.unpack_from("<i", d, p + 10)[0]
    elif cmd == 132: n = 10 + 16 * struct.unpack_from("<i", d, p + 6)[0]
    else: raise SystemExit("command %d" % cmd)
    if cmd == 127: layers.append(b"")
    layers[-1] += d[p:p + n]
    p += n
assert len(layers) == 100 and head.count(b"$$LAYERS/100\n") == 1
open(sys.argv[2] + "/one.bcli", "wb").write(head.replace(b"$$LAYERS/100\n", b"$$LAYERS/1\n") + layers[0])
open(sys.argv[2] + "/twice.bcli", "wb").write(head.replace(b"$$LAYERS/100\n", b"$$LAYERS/200\n") + b"".join(l + l for l in layers))
PY
run "$LAMINA" validate "$gear" -m cli-binary --program "$TMP/one.bcli"
like "$RC $ERR" "^3 .*one\.bcli: byte [0-9]+: layer 2 of the slicing \(h=0\.03\) is not in the program" "binary CLI, the first of 100 layers only: exit 3"
run "$LAMINA" validate "$gear" -m cli-binary --program "$TMP/twice.bcli"
like "$RC $ERR" "^3 .*twice\.bcli: byte [0-9]+: layer 2 \(h=0\.0[0-9]*\) is not above the layer before it" "binary CLI, every layer twice: exit 3 (the height as float32 holds it)"
# every layer twice, the second run after the first (the sequence repeated)
python3 - "$TMP/a.sls" "$TMP/twice.sls" <<'PY'
import sys
t = open(sys.argv[1]).read()
open(sys.argv[2], "w").write(t + "\n" + t)
PY
run "$LAMINA" validate "$gear" --program "$TMP/twice.sls"
like "$RC $ERR" "^3 .*twice\.sls:[0-9]+:1: layer 101 \(h=0\.01\) is not above the layer before it \(h=1\.99\)" \
    "SLS, the whole program twice: exit 3"
# each contour block written twice: the layers are right, their contours doubled
awk 'BEGIN { RS = ""; ORS = "\n\n" } { print; print }' "$TMP/a.sls" >"$TMP/dup.sls"
is "$(grep -c '^contour ' "$TMP/dup.sls")" "$(( 2 * $(grep -c '^contour ' "$TMP/a.sls") ))" "every SLS contour block twice"
run "$LAMINA" validate "$gear" --program "$TMP/dup.sls"
like "$RC $OUT" "^3 (?s:.*) 100 differ" "SLS, every contour twice: exit 3, every layer's area off"
head -c "$(grep -b -m3 '^contour ' "$TMP/a.sls" | tail -1 | cut -d: -f1)" "$TMP/a.sls" >"$TMP/one.sls"
run "$LAMINA" validate "$gear" --program "$TMP/one.sls"
like "$RC $ERR" "^3 .*one\.sls:.* layer 2 of the slicing .* not in the program, which ends before it" "SLS, its first layer only (the gear and its bore, 2 blocks): exit 3"
# units: $$UNITS/1000 says a unit is a metre: the part 1000x too large
sed 's/^\$\$UNITS\/1$/$$UNITS\/1000/' "$TMP/a.cli" >"$TMP/m.cli"
ok "$(grep -q '^\$\$UNITS/1000$' "$TMP/m.cli"; echo $?)" "\$\$UNITS/1000 written in"
run "$LAMINA" validate "$gear" -m cli-ascii --program "$TMP/m.cli"
like "$RC $ERR" '^3 .*m\.cli:10:1: layer 1 of the slicing \(h=0\.01\) is not in the program, which goes on at h=10 \(\$\$UNITS/1000: one unit of the program is 1000 of the model' \
    "CLI ASCII \$\$UNITS/1000: exit 3, the units named"
python3 - "$TMP/a.bcli" "$TMP/m.bcli" <<'PY'
import sys
d = open(sys.argv[1], "rb").read()
old = b"$$UNITS/00000001.000000"
assert d.count(old) == 1
open(sys.argv[2], "wb").write(d.replace(old, b"$$UNITS/00001000.000000"))
PY
run "$LAMINA" validate "$gear" -m cli-binary --program "$TMP/m.bcli"
like "$RC $ERR" '^3 .*m\.bcli: byte [0-9]+: layer 1 of the slicing .* \(\$\$UNITS/1000:' "CLI binary \$\$UNITS/1000: exit 3"
# the same program read in the right units: a profile in metres
printf 'name: metres\ninherits: cli-ascii\nunits: m\n' >"$TMP/metres.yaml"
"$LAMINA" slice "$gear" -m cli-ascii -o "$TMP/mm.cli" 2>/dev/null
sed 's/^\$\$UNITS\/1$/$$UNITS\/1000/' "$TMP/mm.cli" >"$TMP/metres.cli"
run "$LAMINA" validate "$gear" -m "$TMP/metres.yaml" --program "$TMP/metres.cli"
is "$RC" 0 "\$\$UNITS/1000 against a profile in metres (the model in metres): passes"

# ---- a file that is not a program: nothing of it quoted (item 11) --------------
printf 'password=hunter2 do not print\n' >"$TMP/secret.txt"
run "$LAMINA" validate "$gear" --program "$TMP/secret.txt"
is "$RC" 1 "validate --program secret.txt: exit 1"
like "$ERR" 'secret\.txt:1:1: not a program lamina reads' "... says it is not a program, where"
ok "$(printf '%s%s' "$OUT" "$ERR" | grep -q -e hunter -e password; [ $? = 1 ]; echo $?)" "... and quotes nothing of it"
printf '{"format": "hunter2-secret"}\n' >"$TMP/secret.json"
run "$LAMINA" validate "$gear" --program "$TMP/secret.json"
ok "$(printf '%s%s' "$OUT" "$ERR" | grep -q hunter; [ $? = 1 ]; echo $?)" "another JSON document: its format is not quoted"
done_testing
