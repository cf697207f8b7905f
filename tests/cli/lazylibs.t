#!/usr/bin/env bash
# Embree and GEOS are opened on first use (core/base/lazylib.h), not by the
# loader at every start: neither the executable nor the Lua module names
# them, a plain slice never maps them (the dynamic loader's own trace,
# LD_DEBUG=files, says what it opened), validation opens Embree and
# hatching GEOS. A library that cannot be loaded is a clear error where it
# is first needed, with a non-zero exit and no output file; the rest of the
# program runs without it. The broken library is an empty file of the
# library's name in a folder on LD_LIBRARY_PATH, which the loader searches
# before the system's folders: no test hook in the program.
. "$TESTS/cli/lib.sh"
export LAMINA_MACHINES="$M/machines"
cube="$M/thesis_cube.ug"
hatch=(-m cli-ascii -w 2 -s hatch_distance=0.25 -s hatch_strategy=islands -s island_size=1)

needed() { readelf -d "$1" 2>/dev/null | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | tr '\n' ' '; }
# make LAZY=0 (which make check passes on) links them as before
if [ "${LAZY:-1}" = 0 ]; then
    echo "1..0 # SKIP built with LAZY=0: Embree and GEOS are linked"
    exit 0
fi

for bin in "$LAMINA" ${BUILD:+"$BUILD/lamina.so"}; do
    [ -f "$bin" ] || continue
    deps=$(needed "$bin")
    [ -n "$deps" ] && [[ "$deps" != *embree* && "$deps" != *geos* && "$deps" != *tbb* ]]
    ok $? "$(basename "$bin") does not link Embree, TBB or GEOS (needs: $deps)"
done

# loaded CMD...: runs CMD (exit status in RC) and sets LIBS to which of
# Embree, TBB and GEOS the loader opened, from its trace in files of its own
loaded() {
    rm -f "$TMP"/ld.*
    LD_DEBUG=files LD_DEBUG_OUTPUT="$TMP/ld" "$@" >"$TMP/out" 2>"$TMP/err"
    RC=$?
    LIBS=$(cat "$TMP"/ld.* 2>/dev/null | sed -n 's/.*file=\(lib[a-z0-9_]*\)\.so.*/\1/p' |
        grep -E '^lib(embree3|tbb|geos_c|geos)$' | sort -u | tr '\n' ' ')
}

loaded "$LAMINA" slice "$cube" -w 0.5 -o "$TMP/plain.sls"
is "$RC" 0 "a plain slice runs"
# the trace must be there for the other checks to mean anything
[ -n "$(cat "$TMP"/ld.* 2>/dev/null | grep -F 'file=libyaml')" ]
ok $? "the loader's trace lists the libraries it opened (libyaml)"
is "$LIBS" "" "a plain slice opens neither Embree, TBB nor GEOS"

loaded "$LAMINA" validate "$cube" -w 0.5
is "$RC" 0 "validate runs"
like "$LIBS" '\blibembree3 .*\blibtbb\b' "validate opens Embree (and TBB) ($LIBS)"

loaded "$LAMINA" slice "$cube" "${hatch[@]}" -o "$TMP/hatch.cli"
is "$RC" 0 "a hatched slice runs"
like "$LIBS" '\blibgeos_c\b' "hatching opens GEOS ($LIBS)"
[[ "$LIBS" != *embree* ]]; ok $? "hatching does not open Embree"
cmp -s "$TMP/hatch.cli" "$M/hatch/cube_islands.cli"
ok $? "the hatched program is the golden one (tests/cli/hatch.t)"

# ---- libraries that cannot be loaded ----
mkdir -p "$TMP/broken" "$TMP/o"
: >"$TMP/broken/libgeos_c.so.1"
: >"$TMP/broken/libembree3.so.3"
export LD_LIBRARY_PATH="$TMP/broken${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

run "$LAMINA" slice "$cube" -w 0.5 -o "$TMP/o/plain.sls"
is "$RC" 0 "without Embree and GEOS a plain slice still runs"
cmp -s "$TMP/o/plain.sls" "$TMP/plain.sls"
ok $? "... and writes the same program"

run "$LAMINA" slice "$cube" "${hatch[@]}" -o "$TMP/o/hatch.cli"
[ "$RC" -ne 0 ]; ok $? "a hatched slice without GEOS fails (exit $RC)"
like "$ERR" 'cannot load libgeos_c\.so\.1: .*broken/libgeos_c\.so\.1: .*; install libgeos-c1v5' \
    "... saying which library, why, and which package ships it"
is "$(ls -A "$TMP/o" | tr '\n' ' ')" "plain.sls " "... and leaves no output file behind"

run "$LAMINA" validate "$cube" -w 0.5
[ "$RC" -ne 0 ]; ok $? "validate without Embree fails (exit $RC)"
like "$ERR" 'cannot load libembree3\.so\.3: .*; install libembree3-3' "... saying which library is missing"
[[ "$ERR" != *Sanitizer* ]]; ok $? "... without a crash"

# a library that loads but lacks a function lamina calls (an old GEOS):
# the same error, naming the function, instead of a crash at the call
mkdir -p "$TMP/old"
echo 'int lamina_test_not_geos;' >"$TMP/old/empty.c"
cc -shared -fPIC -o "$TMP/old/libgeos_c.so.1" "$TMP/old/empty.c"
ok $? "an empty library named libgeos_c.so.1 builds"
rm -f "$TMP/o"/*
LD_LIBRARY_PATH="$TMP/old" run "$LAMINA" slice "$cube" "${hatch[@]}" -o "$TMP/o/hatch.cli"
[ "$RC" -ne 0 ]; ok $? "a hatched slice with a GEOS lacking its functions fails (exit $RC)"
like "$ERR" 'cannot load libgeos_c\.so\.1: .*undefined symbol: GEOS\w+_r; install libgeos-c1v5' \
    "... naming the missing function"
is "$(ls -A "$TMP/o")" "" "... and leaves no output file behind"

done_testing
