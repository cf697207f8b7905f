#!/usr/bin/env bash
# Every output of the golden corpus (tests/golden/corpus.sh: every shipped
# machine, strategy, order, frame, three axes, -j 1/2/8, a run in parts
# joined, Lua's plan data) is byte-identical to what commit 55e94f0 wrote
# (tests/golden/SHA256SUMS), so a refactoring of the plan stream proves
# itself against the commit before it. A file whose output changes on
# purpose gets its new sum in the same commit, with the reason in its message.
. "$(dirname "$0")/lib.sh"
G="$TESTS/golden"
bash "$G/corpus.sh" "$LAMINA" "$M" "$TMP/gold" 2>"$TMP/corpus.err"
ok $? "the corpus runs (every job exits 0)"
sed -n 's/^/# /p' "$TMP/corpus.err" | head -20
(cd "$TMP/gold" && ls | grep -v -e '\.err$' -e '^part-' | sort) >"$TMP/made"
awk '{print $2}' "$G/SHA256SUMS" | sort >"$TMP/want"
cmp -s "$TMP/made" "$TMP/want"
ok $? "the corpus makes the $(wc -l <"$TMP/want") files of SHA256SUMS, no more, no fewer"
diff "$TMP/want" "$TMP/made" | head -10 | sed 's/^/# /'
(cd "$TMP/gold" && sha256sum --quiet -c "$G/SHA256SUMS") >"$TMP/bad" 2>&1
ok $? "every output is byte-identical to the reference commit's"
head -20 "$TMP/bad" | sed 's/^/# /'
# the sums are not vacuous: the corpus's -j 1 and -j 8 runs agree, and
# different jobs differ
cmp -s "$TMP/gold/lpbf-terrace-islands-greedy-j1-model.json" "$TMP/gold/lpbf-terrace-islands-greedy-j8-model.json"
ok $? "-j 1 and -j 8 write the same JSON"
cmp -s "$TMP/gold/lpbf-terrace-islands-greedy-j1-model" "$TMP/gold/lpbf-terrace-lines-greedy-j1-model"
[ $? -eq 1 ]; ok $? "islands and lines write different programs"
cmp -s "$TMP/gold/join-lpbf-cli" "$TMP/gold/lpbf-terrace-lines-meander-j1-model"
[ $? -eq 1 ]; ok $? "the joined run is not the skinless run's program (skins reach the joined parts)"
done_testing
