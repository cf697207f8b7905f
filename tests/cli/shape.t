#!/usr/bin/env bash
# The code's shape (issue 23): no function over 80 lines in core/, lua/ and
# plugins/ (tests/shape/funclen.py), and no cycle among modules, by
# includes or by the calls the linker sees (tests/shape/cycles.py, on the
# objects of this build).
. "$(dirname "$0")/lib.sh"
: "${BUILD:?BUILD must name the build directory}"
ROOT="$TESTS/.."
mapfile -t src < <(cd "$ROOT" && find core lua plugins -name '*.c' | sort)
run bash -c 'cd "$1" && shift && python3 tests/shape/funclen.py 80 "$@"' _ "$ROOT" "${src[@]}"
is "$RC $OUT" "0 " "no function over 80 lines in ${#src[@]} C files"
run python3 "$ROOT/tests/shape/cycles.py" "$ROOT" "$BUILD"
is "$RC $OUT" "0 " "no include or call cycle among modules"
# the checks can fail: a made-up long function and a made-up cycle
{ echo 'int f(void)'; echo '{'; for i in $(seq 81); do echo "    int x$i = $i;"; done; echo '}'; } >"$TMP/long.c"
run python3 "$ROOT/tests/shape/funclen.py" 80 "$TMP/long.c"
like "$RC $OUT" "^1 .*long.c:2: f 81 lines" "funclen.py finds a function of 81 lines"
mkdir -p "$TMP/tree/core" "$TMP/build"
printf '#include "b.h"\n' >"$TMP/tree/core/a.h"
printf '#include "a.h"\n' >"$TMP/tree/core/b.h"
run python3 "$ROOT/tests/shape/cycles.py" "$TMP/tree" "$TMP/build"
like "$RC $OUT" "^1 include cycle: core/a <-> core/b" "cycles.py finds a cycle of two headers"
done_testing
