#!/usr/bin/env bash
# The command-line tests from a checkout whose path is over 150
# characters and holds spaces: a link to the checkout inside a deliberately
# deep folder whose names have spaces (as "My Documents" has), with LAMINA
# and TESTS named through it. A test that matches a path on a wrapped
# terminal line, builds names from the current directory or leaves a path
# unquoted fails here and not from a short checkout (CI clones into a
# folder of its own choosing). Each script is one test; its failing lines
# are shown.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
LONG="$TMP/a folder/$(printf 'a%.0s' $(seq 1 70))/b $(printf 'b%.0s' $(seq 1 70))"
mkdir -p "$LONG"
ln -s "$ROOT" "$LONG/lamina-checkout"
R="$LONG/lamina-checkout"
[ ${#R} -ge 150 ]; ok $? "the checkout's path is ${#R} characters"
case "$R" in *" "*) ok 0 "the checkout's path holds spaces" ;; *) ok 1 "the checkout's path holds spaces" ;; esac

# the executable through the link when it lies in the checkout
case "$LAMINA" in
    "$ROOT"/*) L="$R/${LAMINA#"$ROOT"/}" ;;
    *) L=$LAMINA ;;
esac
case "${BUILD:-}" in
    "$ROOT"/*) B="$R/${BUILD#"$ROOT"/}" ;;
    *) B=${BUILD:-} ;;
esac

# make check itself from there (one unit test: the rest run below)
B0=${BUILD:-build}
case "$B0" in "$ROOT"/*) B0=${B0#"$ROOT"/} ;; esac
san=0
[ "$(basename "$B0")" = build-san ] && san=1
(unset MAKEFLAGS MFLAGS MAKELEVEL; cd "$R" && make -s --no-print-directory check BUILD="$B0" SAN=$san \
    CHECK_TESTS="$B0/tests/test_fmt.t") >"$TMP/make.out" 2>&1
rc=$?
is "$rc $(grep -c '^Result: PASS' "$TMP/make.out")" "0 1" "make check runs from the path with spaces"
[ $rc -eq 0 ] || sed 's/^/#   /' "$TMP/make.out" | tail -10

self=$(basename "$0")
for t in "$R"/tests/cli/*.t; do
    name=$(basename "$t")
    [ "$name" = "$self" ] && continue
    (cd "$LONG" && LAMINA="$L" TESTS="$R/tests" BUILD="$B" bash "$t") >"$TMP/tap" 2>&1
    rc=$?
    failed=$(grep -c '^not ok' "$TMP/tap")
    plan=$(grep -c '^1\.\.[1-9]' "$TMP/tap")
    [ $rc -eq 0 ] && [ "$failed" -eq 0 ] && [ "$plan" -eq 1 ]
    ok $? "$name from a ${#R}-character path with spaces"
    if [ $rc -ne 0 ] || [ "$failed" -ne 0 ]; then
        grep -A6 '^not ok' "$TMP/tap" | sed 's/^/#   /' | head -40
    fi
done

done_testing
