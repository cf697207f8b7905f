#!/usr/bin/env bash
# lua/API.md: every ```lua block is a complete script; run each one with
# `lamina run` from the repository root (its asserts are the documented
# behaviour), and check that every function and method of the module is
# documented with an example.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
DOC="$ROOT/lua/API.md"

# Split the document into one file per example, named after its heading.
mkdir -p "$TMP/ex"
awk -v dir="$TMP/ex" '
    /^#+ / { heading = $0; sub(/^#+ /, "", heading) }
    /^```lua[ \t]*$/ { n++; file = sprintf("%s/%03d.lua", dir, n); names[n] = heading
                       printf "%s\n", heading > (file ".name"); inblock = 1; next }
    /^```/ && inblock { inblock = 0; close(file); next }
    inblock { print > file }
' "$DOC"

count=$(ls "$TMP/ex"/*.lua 2>/dev/null | wc -l)
ok $([ "$count" -ge 30 ] && echo 0 || echo 1) "API.md has examples ($count)"

for ex in "$TMP/ex"/*.lua; do
    name=$(cat "$ex.name")
    (cd "$ROOT" && "$LAMINA" run "$ex") >"$TMP/out" 2>"$TMP/err"
    rc=$?
    ok $rc "example: $name"
    if [ $rc -ne 0 ]; then sed 's/^/#   /' "$TMP/err"; fi
done

# Every module function and every method appears in an example, as does
# every function of the shipped Lua modules (lua/lamina/*.lua); every
# method has a heading of its own (what help(x) shows).
cat "$TMP/ex"/*.lua > "$TMP/all_examples.lua"
modules=$(cd "$ROOT/lua/lamina" && ls *.lua | sed 's/\.lua$//')
run "$LAMINA" run - "$TMP/all_examples.lua" "$DOC" $modules <<'LUA'
local f = assert(io.open(arg[1]))
local text = f:read("a")
f:close()
f = assert(io.open(arg[2]))
local doc = f:read("a")
f:close()
local missing = {}
for name, v in pairs(lamina) do
  if type(v) == "function" and not text:find("lamina." .. name .. "(", 1, true)
     and not text:find("lamina." .. name .. "{", 1, true) then
    missing[#missing + 1] = "lamina." .. name
  end
end
for _, class in ipairs{"model", "layer", "contour", "machine", "plan"} do
  local mt = debug.getregistry()["lamina." .. class]
  local _, methods = debug.getupvalue(mt.__index, 1)
  for name in pairs(methods) do
    if not text:find(":" .. name .. "(", 1, true) and not text:find(":" .. name .. "{", 1, true) then
      missing[#missing + 1] = class .. ":" .. name
    end
  end
end
-- and lamina's own Lua modules (lua/lamina/*.lua), by their short names
for i = 3, #arg do
  local mod = arg[i]
  for name, v in pairs(require("lamina." .. mod)) do
    if type(v) == "function" and not text:find(mod .. "." .. name .. "(", 1, true) then
      missing[#missing + 1] = "lamina." .. mod .. "." .. name
    end
  end
end
for _, class in ipairs{"model", "layer", "contour", "machine", "plan"} do
  local mt = debug.getregistry()["lamina." .. class]
  local _, methods = debug.getupvalue(mt.__index, 1)
  for name in pairs(methods) do
    if not doc:find("### `" .. class .. ":" .. name, 1, true) then
      missing[#missing + 1] = class .. ":" .. name .. " (no heading: help cannot find it)"
    end
  end
end
table.sort(missing)
io.write(table.concat(missing, " "))
LUA
is "$RC" 0 "introspection ran"
is "$OUT" "" "every function and method has an example"

done_testing
