#!/usr/bin/env bash
# Standard streams: a MODEL of - is standard input for every command (the
# format told by content, messages naming it <stdin>, the same size limit);
# an output FILE of - is standard output for every output option; two
# outputs to - in one run is a usage error.
. "$(dirname "$0")/lib.sh"

cube="$M/thesis_cube_hole.ug"
"$LAMINA" slice "$cube" -w 0.5 -o "$TMP/file.sls"

# ---- models from standard input --------------------------------------------
out=$(cat "$cube" | "$LAMINA" slice - -w 0.5)
is "$?" 0 "cat part.ug | lamina slice -: exit 0"
is "$out" "$(cat "$TMP/file.sls")" "... the same program as from the file"
"$LAMINA" slice - -w 0.5 -o "$TMP/stdin.sls" <"$cube"
cmp -s "$TMP/stdin.sls" "$TMP/file.sls"; ok $? "slice - -o FILE < part.ug: the same program"
for f in thesis_cube_binary.stl thesis_cube_ascii.stl thesis_cube.obj; do
    run "$LAMINA" info - <"$M/$f"
    is "$RC $(grep -c '^model *<stdin>$' <<<"$OUT")" "0 1" "info - < $f: read by content, named <stdin>"
done
run "$LAMINA" info - <"$M/thesis_cube_binary.stl"
like "$OUT" '^format +stl-binary$' "info -: binary STL told by content"
run "$LAMINA" info --json - <"$cube"
is "$(jq -r '.model' <<<"$OUT")" "<stdin>" "info --json -: the model is <stdin>"
run "$LAMINA" validate - -w 0.5 <"$cube"
like "$RC $OUT" '^0 (?s:.*)<stdin>: 4 layers, 8 contours checked, 8 confirmed' "validate -: every contour confirmed"
run "$LAMINA" check - -m sls-contours <"$cube"
like "$RC $OUT" '^0 <stdin>: 0 violations' "check -: named <stdin>"
run "$LAMINA" validate "$cube" --program "$TMP/file.sls" -w 0.5
is "$RC" 0 "(the program validates from a file)"

# errors name <stdin> with the position
printf 'v a 0 0 0;\nv b 1 0 0;\nf a b c;\n' >"$TMP/bad.ug"
run "$LAMINA" slice - <"$TMP/bad.ug"
like "$RC $ERR" "^1 lamina: <stdin>:3:5: expected '\\(' after face name" "a broken model on standard input: <stdin>:line:col"
run "$LAMINA" slice - </dev/null
like "$RC $ERR" '^1 lamina: <stdin>: empty file' "empty standard input: an error"
run "$LAMINA" info - <"$TMP/bad.ug"
is "$RC" 1 "info - with a broken model: exit 1"
head -c 3000 /dev/zero | tr '\0' ' ' >"$TMP/big.txt"
LAMINA_MAX_INPUT=2k run "$LAMINA" info - <"$TMP/big.txt"
like "$RC $ERR" '^1 lamina: <stdin>: too large for a model: over 2048 bytes, the limit is 2048' \
    "standard input has the model size limit"
# an endless pipe stops at the limit
yes 'v a 0 0 0;' | LAMINA_MAX_INPUT=1k "$LAMINA" info - 2>"$TMP/err" >/dev/null
like "$(cat "$TMP/err")" '^lamina: <stdin>: too large for a model: over 1024 bytes' "an endless pipe: refused at the limit"
run "$LAMINA" info - <"$TMP/file.sls"
like "$RC $ERR" '^1 lamina: <stdin>: unknown model format' "standard input of another format: told by content"

# ---- outputs to standard output -----------------------------------------------
cd "$TMP" || exit 1
run "$LAMINA" slice "$cube" -w 0.5 -o -
is "$RC $OUT" "0 $(cat "$TMP/file.sls")" "-o -: the program on standard output"
run "$LAMINA" slice "$cube" -w 0.5 -o "$TMP/p.sls" --svg -
is "$RC" 0 "--svg -: exit 0"
like "$OUT" '^<svg ' "--svg -: the SVG on standard output"
like "$(tail -c 7 "$TMP/out")" '^</svg>$' "... all of it"
[ ! -e "$TMP/-" ]; ok $? "... and no file named -"
cmp -s "$TMP/p.sls" "$TMP/file.sls"; ok $? "... the program went to its file"
run "$LAMINA" slice "$cube" -w 0.5 -o "$TMP/p.sls" --json -
is "$(jq -r .format <<<"$OUT") $RC" "lamina-run 0" "--json -: the run's JSON on standard output"
run "$LAMINA" check "$cube" -m sls-contours --svg -
like "$RC $OUT" '^0 (?s:.*)<svg ' "check --svg -: the sheet on standard output"
[ ! -e "$TMP/-" ]; ok $? "... and no file named -"

# two outputs to -: usage errors, nothing written
run "$LAMINA" slice "$cube" -w 0.5 -o - --svg -
like "$RC $ERR" '^2 lamina slice: -o - and --svg - both write to standard output' "-o - and --svg -: usage error"
is "$OUT" "" "... nothing written"
run "$LAMINA" slice "$cube" -w 0.5 --svg -
like "$RC $ERR" '^2 lamina slice: the program \(without -o\) and --svg - both write to standard output: give -o FILE' \
    "--svg - without -o: the program is on standard output too"
run "$LAMINA" slice "$cube" -w 0.5 -o "$TMP/q.sls" --svg - --json -
like "$RC $ERR" '^2 lamina slice: --svg - and --json - both write' "--svg - and --json -: usage error"
[ ! -e "$TMP/q.sls" ]; ok $? "... and no program written"
run "$LAMINA" slice "$cube" -w 0.5 -o ""
like "$RC $ERR" '^2 lamina slice: -o needs a file name \(or - for standard output\)' "-o '': usage error"
# a model on standard input and outputs on standard output
out=$(cat "$cube" | "$LAMINA" slice - -w 0.5 -o "$TMP/r.sls" --json - | jq -r '.job.model')
is "$out" "<stdin>" "cat part.ug | lamina slice - --json -: the JSON names the model <stdin>"

done_testing
