#!/usr/bin/env bash
# One attribute more on every vector, end to end (issue 23): a copy of the
# source with a test-only attribute `demo` (one row of core/plan/vocab.h's
# LAM_ATTRS, set by the SLS and LADRP planners: three files) is built, and
# the attribute is found in the JSON, the viewer's data, Lua's plan data
# and the part files, with no other file edited.
#   attr_demo.sh SRCDIR LAMINA   (tests/cli/attr_demo.t; prints TAP; LAMINA:
# the lamina of SRCDIR as built, which has no such attribute)
set -u
SRC=$(cd "$1" && pwd) OLD=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
n=0 failed=0
ok() { n=$((n + 1)); if [ "$1" -eq 0 ]; then echo "ok $n - $2"; else echo "not ok $n - $2"; failed=$((failed + 1)); fi; }
# the sources with their times (cp -p), so that a build of the tree seeds
# the copy's (below)
(cd "$SRC" && git ls-files -z | xargs -0 cp -p --parents -t "$T/") 2>/dev/null || cp -rp "$SRC/." "$T/"
mkdir -p "$T/orig" && cp "$T/core/plan/vocab.h" "$T/core/plan/plan_sls.c" "$T/core/plan/plan_ladrp.c" "$T/orig/"
sed -i 's|^#define LAM_ATTRS(X) \(.*\))$|#define LAM_ATTRS(X) \1) X(demo, "demo", 0, "a test'"'"'s attribute")|' "$T/core/plan/vocab.h"
sed -i 's|^\(    memset(&st->time, 0, sizeof st->time);\)$|    st->attrs.demo = (long long)L->index + 7;\n\1|' "$T/core/plan/plan_sls.c"
sed -i 's|^\(    lam_move_info m = { .attrs = lam_attrs_default(), .deposit = deposit };\)$|\1\n    m.attrs.demo = 5;|' "$T/core/plan/plan_ladrp.c"
changed=0
for f in vocab.h plan_sls.c plan_ladrp.c; do cmp -s "$T/orig/$f" "$T/core/plan/$f" || changed=$((changed + 1)); done
[ "$changed" -eq 3 ]; ok $? "the attribute is three edits, in vocab.h, plan_sls.c and plan_ladrp.c"
rm -rf "$T/orig"
# The tree's build (BUILD, as make check names it: build or build-san, with
# make check's LAZY) seeds the copy's: its objects and their .d files, older
# than the three edited files, so make recompiles exactly the objects the
# edits reach (about 70 of 120) and links. Without one, from nothing.
B=${BUILD:+$(basename "$BUILD")}
if { [ "$B" = build ] || [ "$B" = build-san ]; } && [ -x "$BUILD/lamina" ]; then
    san=0
    [ "$B" = build-san ] && san=1
    mkdir -p "$T/$B"
    find "$BUILD/" -mindepth 1 -maxdepth 1 ! -name tests -exec cp -a -t "$T/$B/" {} +
    (unset MAKEFLAGS MFLAGS MAKELEVEL; make -C "$T" -j2 LAZY="${LAZY:-1}" BUILD="$B" SAN=$san "$B/lamina") >"$T/make.log" 2>&1
else
    B=build
    (unset MAKEFLAGS MFLAGS MAKELEVEL; make -C "$T" -j2 LAZY=1 BUILD="$T/build" "$T/build/lamina") >"$T/make.log" 2>&1
fi
ok $? "the copy builds" || { tail -20 "$T/make.log" | sed 's/^/# /'; echo "1..$n"; exit 1; }
L=$T/$B/lamina M=$SRC/tests/models
cd "$T" || exit 1
"$L" slice "$M/thesis_cube_hole.ug" -q -m lpbf-cli -w 0.5 -s hatch_strategy=lines -o prog --json run.json --html run.html
ok $? "an SLS run with --json and --html"
grep -Eq '"kind": "(core|upskin|downskin)", .*"demo": 7}' run.json; ok $? "JSON: the first layer's hatch vectors carry demo 7 (its index + 7)"
grep -q '"kind": "contour", .*"demo": 8}' run.json; ok $? "JSON: the second layer's contour edges carry demo 8"
grep -q '"kind": "jump", .*"demo": ' run.json; ok $? "JSON: jumps carry the next path's"
# the page (docs/viewer.md): its head names the attribute, and every block's
# rows hold what the JSON's vectors say (the test's own decoder)
grep -q '"attrs": \[[^]]*"demo"' run.html && python3 "$SRC/tests/cli/viewercheck.py" compare run.html run.json >/dev/null
ok $? "the viewer's data carries it"
"$L" slice "$M/thesis_cube_hole.ug" -q -m creol-ladrp -w 0.5 --json ladrp.json -o /dev/null
grep -q '"kind": "deposit", .*"demo": 5}' ladrp.json; ok $? "JSON: LADRP deposits carry demo 5"
cat >data.lua <<'LUA'
local m = lamina.load(arg[1])
local p = lamina.machine("cli-ascii"):plan(m:slice{width = 0.5}, {hatch_strategy = "lines"})
local l = p:layer(2)
print(l.vectors[1].demo, l.contours[1].demo, l.vectors[1].part)
LUA
out=$("$L" run data.lua "$M/thesis_cube_hole.ug")
[ "$out" = "8	8	nil" ]; ok $? "Lua plan data: vectors and contours carry demo (8 on layer 2); part at its default is absent (got '$out')"
"$L" slice "$M/thesis_cube_hole.ug" -q -m lpbf-cli -w 0.5 -s hatch_strategy=lines --layers 1/2 -o p1 &&
    "$L" slice "$M/thesis_cube_hole.ug" -q -m lpbf-cli -w 0.5 -s hatch_strategy=lines --layers 2/2 -o p2 &&
    "$L" join p1 p2 -o joined 2>/dev/null && cmp -s joined prog
ok $? "part files carry it: two parts join into the whole run's program"
grep -aq demo p1; ok $? "a part's header names the attribute"
"$OLD" join p1 p2 -o /dev/null 2>err; rc=$?
[ $rc -eq 1 ] && grep -q 'another set of attributes' err; ok $? "a lamina without the attribute refuses the parts: $(cat err)"
echo "1..$n"
[ "$failed" -eq 0 ]
