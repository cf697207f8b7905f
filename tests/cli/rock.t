#!/usr/bin/env bash
# The LuaRocks rock (lamina-scm-1.rockspec), as the README says to use it:
# `luarocks make --tree ./rocks` in the checkout (which makes luarocks
# default to Lua 5.4), `eval $(luarocks path --tree ./rocks)`, then a stock
# lua5.4 from another directory: require "lamina" finds the shipped
# machines and the plugin beside lamina.so in the rock tree, require
# "lamina.adaptive" the shipped module; `luarocks remove` takes it all away.
# The rock is built from the plain (not sanitized) build directory, as a
# user's would be: a stock lua5.4 cannot load an ASan build by itself.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
if ! command -v luarocks >/dev/null || ! command -v lua5.4 >/dev/null; then
    echo "# skipped: luarocks or lua5.4 (Debian luarocks, lua5.4) not installable"
    echo "1..0 # SKIP luarocks or lua5.4 missing"
    exit 0
fi
R="$TMP/my rocks" # a tree whose path has a space, as a user's may
# a make of its own, the default build directory: not the test's BUILD or
# the jobserver of a make around the test
(cd "$ROOT" && env -u BUILD -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u SAN HOME="$TMP" \
    luarocks make --tree "$R") >"$TMP/rock.out" 2>&1
rc=$?
is "$rc" 0 "luarocks make --tree DIR in the checkout"
[ $rc -eq 0 ] || sed 's/^/#   /' "$TMP/rock.out" | tail -20
like "$(cat "$TMP/rock.out")" 'lamina scm-1 is now installed' "luarocks installed lamina scm-1"
[ -f "$R/lib/lua/5.4/lamina.so" ]; ok $? "the C module in the tree's lib/lua/5.4"
[ -f "$R/share/lua/5.4/lamina/adaptive.lua" ]; ok $? "the Lua modules in share/lua/5.4/lamina"

paths=$(cd "$ROOT" && HOME="$TMP" luarocks path --tree "$R")
like "$paths" "LUA_CPATH='$R/lib/lua/5.4/\\?\\.so;" "luarocks path: Lua 5.4 paths into the tree"

W="$TMP/work"
mkdir -p "$W"
cp "$M/thesis_cube_hole.ug" "$W/part.ug"
nmach=$(ls "$ROOT"/machines/*.yaml | wc -l)
run env -i PATH=/usr/bin:/bin HOME="$TMP" bash -c 'cd "$1" && eval "$2" && lua5.4 -e "
    local l = require \"lamina\"
    print(#l.machines(), package.searchpath(\"lamina\", package.cpath))
    print(type(require \"lamina.adaptive\"), package.searchpath(\"lamina.adaptive\", package.path))
    local layers = assert(assert(l.load(\"part.ug\")):slice{width = 0.5})
    local plan = assert(assert(l.machine(\"cli-binary\")):plan(layers))
    print(#layers, assert(plan:write(\"part.cli\")))"' _ "$W" "$paths"
is "$RC" 0 "stock lua5.4 with the rock's paths"
[ $RC -eq 0 ] || echo "$ERR" | sed 's/^/#   /' | head
is "$OUT" "$nmach	$R/lib/lua/5.4/lamina.so
table	$R/share/lua/5.4/lamina/adaptive.lua
4	true" "#lamina.machines() is the shipped count; lamina.adaptive; the cli-binary plugin from the rock"
like "$(head -c 200 "$W/part.cli" 2>/dev/null | tr -c '[:print:]\n' '.')" '^\$\$HEADERSTART' "a binary CLI file"

(cd "$ROOT" && HOME="$TMP" luarocks remove --tree "$R" lamina) >"$TMP/rm.out" 2>&1
is "$?" 0 "luarocks remove lamina"
is "$(find "$R" -path '*lamina*' | sort)" "" "leaves nothing of lamina in the tree"

done_testing
