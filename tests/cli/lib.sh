# Shared helpers for the command-line tests (TAP). Source it; set LAMINA
# and TESTS in the environment (make test does).
: "${LAMINA:?LAMINA must name the lamina executable}"
: "${TESTS:?TESTS must name the tests directory}"
M="$TESTS/models"
T_N=0
T_FAILED=0
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

ok() { # ok COND-STATUS DESCRIPTION
    T_N=$((T_N + 1))
    if [ "$1" -eq 0 ]; then echo "ok $T_N - $2"; else echo "not ok $T_N - $2"; T_FAILED=$((T_FAILED + 1)); fi
}
is() { # is GOT EXPECTED DESCRIPTION
    T_N=$((T_N + 1))
    if [ "$1" = "$2" ]; then echo "ok $T_N - $3"
    else echo "not ok $T_N - $3"; echo "#   got:      '$1'"; echo "#   expected: '$2'"; T_FAILED=$((T_FAILED + 1)); fi
}
like() { # like TEXT REGEX DESCRIPTION
    # The whole text against one Perl regex, ^ and $ at every line: a
    # pattern may span lines (grep would take each of its lines as a
    # separate alternative and pass when any one of them matched).
    T_N=$((T_N + 1))
    if printf '%s' "$1" | RE="$2" perl -0777 -ne 'exit(/$ENV{RE}/m ? 0 : 1)'; then echo "ok $T_N - $3"
    else echo "not ok $T_N - $3"; echo "#   '$1'"; echo "#   does not match /$2/"; T_FAILED=$((T_FAILED + 1)); fi
}
# run CMD...: sets OUT, ERR, RC
run() {
    "$@" >"$TMP/out" 2>"$TMP/err"
    RC=$?
    OUT=$(cat "$TMP/out")
    ERR=$(cat "$TMP/err")
}
done_testing() {
    echo "1..$T_N"
    [ "$T_FAILED" -eq 0 ]
}
