#!/usr/bin/env bash
# make install into a staging folder (DESTDIR, PREFIX=/usr), then a small C
# program built against the installed library with nothing but
# `pkg-config --cflags --libs lamina`: the public headers are complete, the
# internal ones are not installed, and the program slices a model right.
# Then the installed tree on its own, from a working directory outside the
# source tree with no LAMINA_* variables: the executable runs a shipped
# recipe and finds the binary-CLI plugin, a stock lua5.4 loads the C module
# and a shipped Lua module and finds the machines beside lamina.so, every man
# page renders and lints clean, the completion completes; `make uninstall`
# leaves no file behind.
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
for h in nest.h enclose.h test_hooks.h geos.h prefetch.h grow.h lazylib.h geos_lazy.h embree_lazy.h; do
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
    "$(sed -n 's/.*LAMINA_VERSION "\(.*\)"/\1/p' "$ROOT/core/base/version.h")" "pkg-config knows lamina's version"
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


# ---- the installed tree on its own -----------------------------------------
U="$D/usr"
for f in bin/lamina lib/lua/5.4/lamina.so share/lua/5.4/lamina/adaptive.lua share/lua/5.4/lamina/axes.lua \
    lib/lamina/plugins/cli-binary.so share/doc/lamina/README.md share/doc/lamina/lua/API.md \
    share/doc/lamina/machines/README.md share/doc/lamina/recipes/README.md \
    share/man/man1/lamina.1 share/man/man1/lamina-slice.1 share/bash-completion/completions/lamina; do
    [ -f "$U/$f" ]; ok $? "installed: $f"
done
nmach=$(ls "$ROOT"/machines/*.yaml | wc -l)
is "$(ls "$U"/share/lamina/machines/*.yaml | wc -l)" "$nmach" "every shipped profile in share/lamina/machines"
[ ! -e "$U/share/lamina/lua" ]; ok $? "no Lua modules outside the Lua path (share/lamina/lua)"

W="$TMP/work"
mkdir -p "$W"
cp "$M/thesis_cube_hole.ug" "$W/part.ug"
# a clean environment: no LAMINA_* variables, nothing pointing into the checkout
clean() { (cd "$W" && env -i PATH=/usr/bin:/bin HOME="$TMP" LANG=C.UTF-8 ${ASAN_OPTIONS:+ASAN_OPTIONS=$ASAN_OPTIONS} \
    ${UBSAN_OPTIONS:+UBSAN_OPTIONS=$UBSAN_OPTIONS} "$@"); }

run clean "$U/bin/lamina" machines
is "$RC" 0 "installed lamina machines"
is "$(printf '%s\n' "$OUT" | wc -l)" "$nmach" "lists the $nmach installed profiles"

# the shipped default recipe on the copied part: the SLS program of the
# 2-high cube with its through hole at layers 0.25 (floor cut) has 8 layers
# of 2 contours each (the square and the hole) at heights 0, 0.25, ..., 1.75
run clean "$U/bin/lamina" run "$U/share/doc/lamina/recipes/default.lua" --out out part.ug
is "$RC" 0 "installed lamina runs the installed default recipe"
[ $RC -eq 0 ] || echo "$ERR" | sed 's/^/#   /' | head
is "$(grep -c '^contour ' "$W/out/part.sls" 2>/dev/null)" 16 "its SLS program: 16 contours"
is "$(sed -n 's/^contour //p' "$W/out/part.sls" 2>/dev/null | sort -u | tr '\n' ' ')" \
    "0.000000 0.250000 0.500000 0.750000 1.000000 1.250000 1.500000 1.750000 " "at the 8 layer heights"
[ -s "$W/out/part.ladrp" ] && [ -s "$W/out/part.svg" ]; ok $? "and its LADRP program and contact sheet"

# a sandboxed recipe may require lamina's modules from the installed Lua
# tree, and nothing else of that tree (other packages' modules live there)
printf 'return 1\n' >"$U/share/lua/5.4/otherpkg.lua"
printf 'print(type(require "lamina.axes"))\nprint(pcall(require, "otherpkg"))\n' >"$W/req.lua"
run clean "$U/bin/lamina" run --safe --allow . req.lua
is "$(printf '%s\n' "$OUT" | head -1)" "table" "lamina run --safe: require \"lamina.axes\" from share/lua/5.4"
like "$OUT" "^false\t.*module 'otherpkg' not found" "but not another package's module there"
rm -f "$U/share/lua/5.4/otherpkg.lua"

# binary CLI through the plugin, found beside the installed executable
run clean "$U/bin/lamina" slice part.ug -m cli-binary -w 0.5 -o part.cli
is "$RC" 0 "installed lamina slices with the cli-binary profile (no LAMINA_PLUGINS)"
[ $RC -eq 0 ] || echo "$ERR" | sed 's/^/#   /' | head
like "$(head -c 400 "$W/part.cli" 2>/dev/null | tr -c '[:print:]\n' '.')" '^\$\$HEADERSTART' "a binary CLI file"
like "$(head -c 400 "$W/part.cli" 2>/dev/null | tr -c '[:print:]\n' '.')" '\$\$LAYERS/4\b' "of 4 layers (height 2, width 0.5)"

# a stock lua5.4 with LUA_PATH/LUA_CPATH on the installed tree
if command -v lua5.4 >/dev/null; then
    preload=""
    [ $san -eq 1 ] && preload="$(cc -print-file-name=libasan.so):$(cc -print-file-name=libubsan.so)"
    run clean env LD_PRELOAD=$preload ASAN_OPTIONS=detect_leaks=0 LUA_PATH="$U/share/lua/5.4/?.lua;;" \
        LUA_CPATH="$U/lib/lua/5.4/?.so;;" lua5.4 -e '
        local l = require "lamina"
        local ad = require "lamina.adaptive"
        print(#l.machines(), package.searchpath("lamina", package.cpath), package.searchpath("lamina.adaptive", package.path))
        print(type(ad), l.machine("ded-gcode") ~= nil)
        local m = assert(l.load("part.ug"))
        local layers = assert(m:slice{width = 0.5})
        local plan = assert(assert(l.machine("cli-binary")):plan(layers))
        print(#layers, assert(plan:write("lua.cli")))'
    is "$RC" 0 "stock lua5.4: require lamina, lamina.adaptive, plan cli-binary"
    [ $RC -eq 0 ] || echo "$ERR" | sed 's/^/#   /' | head
    is "$OUT" "$nmach	$U/lib/lua/5.4/lamina.so	$U/share/lua/5.4/lamina/adaptive.lua
table	true
4	true" "the machines found beside lamina.so, the modules from the installed tree, the plugin too"
    cmp -s "$W/lua.cli" "$W/part.cli"; ok $? "the Lua plan's CLI file is the command line's"
    # loaded by a relative path (package.cpath "./?.so" in lib/lua/5.4)
    run env -i PATH=/usr/bin:/bin LD_PRELOAD=$preload ASAN_OPTIONS=detect_leaks=0 \
        bash -c 'cd "$1" && LUA_CPATH="./?.so" lua5.4 -e "print(#require(\"lamina\").machines())"' _ "$U/lib/lua/5.4"
    is "$OUT" "$nmach" "lamina.so loaded as ./lamina.so finds the machines too"
else
    echo "# skipped: stock lua5.4 (Debian lua5.4) not installable"
fi

# man pages: each renders with man -l (NAME and every command it documents)
# and lints clean; the option lists themselves are compared in man.t
if command -v man >/dev/null && command -v mandoc >/dev/null; then
    for p in "$U"/share/man/man1/*.1; do
        n=$(basename "$p" .1)
        run env MANWIDTH=80 man -l "$p"
        is "$RC" 0 "man -l $n.1"
        like "$OUT" "^NAME\n +$n +- +\S" "$n.1 renders its NAME"
        run mandoc -T lint -W warning "$p"
        is "$OUT$ERR" "" "mandoc -T lint: $n.1 has no warnings"
        run groff -man -ww -z "$p"
        is "$ERR" "" "groff -ww: $n.1 has no warnings"
    done
    is "$(ls "$U"/share/man/man1/ | tr '\n' ' ')" \
        "$(for c in $("$U/bin/lamina" --help | sed -n 's/^  lamina \([a-z][a-z0-9-]*\) .*/\1/p'); do
            echo "lamina-$c.1"; done | sort | tr '\n' ' ')lamina.1 " "a page per command of lamina --help, and lamina(1)"
else
    echo "# skipped: man pages (Debian man-db and mandoc) not installable"
fi

# the installed completion, sourced into a bash
comp=$(cd "$W" && bash -c '. "$1"
    COMP_WORDS=("$2" sl); COMP_CWORD=1; _lamina; echo "${COMPREPLY[*]}"
    COMP_WORDS=("$2" slice -m ""); COMP_CWORD=3; _lamina; echo "${COMPREPLY[*]}"
    COMP_WORDS=("$2" info ""); COMP_CWORD=2; _lamina; echo "${COMPREPLY[*]}"' _ \
    "$U/share/bash-completion/completions/lamina" "$U/bin/lamina" 2>&1)
is "$comp" "slice
$(ls "$ROOT"/machines/*.yaml | sed 's|.*/||; s|\.yaml$||' | tr '\n' ' ' | sed 's/ $//')
out part.ug" "installed completion: commands, machine names, models"

# ---- make uninstall ----------------------------------------------------------
(unset MAKEFLAGS MFLAGS MAKELEVEL; make -s --no-print-directory -C "$ROOT" uninstall \
    DESTDIR="$D" PREFIX=/usr BUILD="$B" SAN=$san) >"$TMP/make.out" 2>&1
is "$?" 0 "make uninstall DESTDIR=... PREFIX=/usr"
is "$(cd "$D" && find . -type f -o -type l | sort)" "" "make uninstall leaves no file"
is "$(cd "$D" && find . -name '*lamina*' | sort)" "" "nor a directory of lamina's"

# ---- another prefix, with a space ----------------------------------------------
# lamina.pc is made again for the new prefix (it used to depend only on
# lamina.pc.in and keep the first prefix), and every destination may hold
# spaces (make splits its lists at spaces: the shell puts them in)
(unset MAKEFLAGS MFLAGS MAKELEVEL; make -s --no-print-directory -C "$ROOT" install \
    DESTDIR="$D" PREFIX="/opt/my lamina" BUILD="$B" SAN=$san) >"$TMP/make.out" 2>&1
is "$?" 0 "make install PREFIX='/opt/my lamina' after PREFIX=/usr"
like "$(cat "$D/opt/my lamina/lib/pkgconfig/lamina.pc" 2>&1)" '^prefix=/opt/my lamina$' "lamina.pc names the new prefix"
[ -x "$D/opt/my lamina/bin/lamina" ] && [ -f "$D/opt/my lamina/share/lamina/machines/sls-contours.yaml" ]
ok $? "the executable and the profiles under the prefix with a space"
is "$(cd "$D" && find . -type f | grep -vc '^\./opt/my lamina/')" 0 "nothing installed elsewhere"
(unset MAKEFLAGS MFLAGS MAKELEVEL; make -s --no-print-directory -C "$ROOT" uninstall \
    DESTDIR="$D" PREFIX="/opt/my lamina" BUILD="$B" SAN=$san) >"$TMP/make.out" 2>&1
is "$?$(cd "$D" && find . -type f -o -type l | sort)" "0" "make uninstall from it leaves no file"

done_testing
