#!/usr/bin/env bash
# make install into a staging folder (DESTDIR, PREFIX=/usr), then a small C
# program built against the installed library with nothing but
# `pkg-config --cflags --libs lamina`: the public headers are complete, the
# internal ones are not installed, and the program slices a model right.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
B=${BUILD:?BUILD must name the build directory}
case "$B" in "$ROOT"/*) B=${B#"$ROOT"/} ;; esac
san=0
[ "$(basename "$B")" = build-san ] && san=1
D="$TMP/stage"
# a make of its own: not the jobserver or variables of a make around the test
(unset MAKEFLAGS MFLAGS MAKELEVEL; make -s --no-print-directory -C "$ROOT" install \
    DESTDIR="$D" PREFIX=/usr BUILD="$B" SAN=$san) >"$TMP/make.out" 2>&1
rc=$?
is "$rc" 0 "make install DESTDIR=... PREFIX=/usr"
[ $rc -eq 0 ] || sed 's/^/#   /' "$TMP/make.out" | tail -20

inc="$D/usr/include/lamina"
[ -f "$inc/lamina.h" ]; ok $? "lamina.h installed"
[ -f "$D/usr/lib/liblamina.a" ]; ok $? "liblamina.a installed"
[ -f "$D/usr/lib/pkgconfig/lamina.pc" ]; ok $? "lamina.pc installed"
for h in nest.h enclose.h test_hooks.h geos.h prefetch.h grow.h; do
    [ ! -e "$inc/$h" ]; ok $? "internal $h not installed"
done
# every header an installed header includes is installed
missing=""
for h in "$inc"/*.h; do
    for dep in $(sed -n 's/^#include "\(.*\)"/\1/p' "$h"); do
        [ -f "$inc/$dep" ] || missing="$missing $(basename "$h")->$dep"
    done
done
is "$missing" "" "the installed headers include only installed headers"
like "$(cat "$D/usr/lib/pkgconfig/lamina.pc")" '^prefix=/usr$' "lamina.pc names the prefix given"

export PKG_CONFIG_PATH="$D/usr/lib/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$D" PKG_CONFIG_LIBDIR="$D/usr/lib/pkgconfig"
is "$(pkg-config --modversion lamina)" \
    "$(sed -n 's/.*LAMINA_VERSION "\(.*\)"/\1/p' "$ROOT/core/version.h")" "pkg-config knows lamina's version"
flags=$(pkg-config --cflags --libs lamina)
ok $? "pkg-config --cflags --libs lamina"
[[ " $flags" == *" -I$D/usr/include"* ]]; ok $? "the include path lies in the staging folder"
# only the flags pkg-config gives: no -I into the checkout
cc -std=c11 -Wall -Werror -o "$TMP/slice_area" "$TESTS/cli/install/slice_area.c" $flags 2>"$TMP/cc.err"
rc=$?
is "$rc" 0 "a program builds against the installed library"
[ $rc -eq 0 ] || sed 's/^/#   /' "$TMP/cc.err" | head -20

# The cube of side 2 with a square through hole of side 1 (volume 6):
# every layer is the 2x2 square minus the 1x1 hole, net area 4 - 1 = 3,
# by lamina's measure and by the program's own shoelace sum.
run "$TMP/slice_area" "$M/thesis_cube_hole.ug" 0.5
is "$RC" 0 "the program runs"
is "$OUT" "lamina $(pkg-config --modversion lamina): 4 layers
layer 0 at 0.25: 2 contours, net area 3.000000 (shoelace 3.000000)
layer 1 at 0.75: 2 contours, net area 3.000000 (shoelace 3.000000)
layer 2 at 1.25: 2 contours, net area 3.000000 (shoelace 3.000000)
layer 3 at 1.75: 2 contours, net area 3.000000 (shoelace 3.000000)" "four layers of net area 3 at the slab middles"
run "$TMP/slice_area" "$M/bad/no_such_model.ug" 0.5
is "$RC" 1 "a missing model: exit 1"
like "$ERR" 'no_such_model' "with lamina's message naming the file"

done_testing
