#!/usr/bin/env bash
# The build's machine keys (issue 25, items 2 and 5): the plate (`plate:`
# with width and depth, or a diameter, and a margin), `spacing`, `gas_flow`
# ([dx, dy]) and `lasers` ([{field: [x0, y0, x1, y1]}, ...]) load from YAML,
# are written by `machines --show` in a form that loads again, are set with
# --set (a list's value as YAML flow text), are refused with the loader's
# file:line:column messages when wrong, and read in Lua; a profile without
# them dumps as before.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

# ---- load, dump, reload ------------------------------------------------------------
cat >p.yaml <<'EOF'
inherits: cli-ascii
name: p
plate: {width: 250, depth: 200, margin: 5}
spacing: 2.5
gas_flow: [-1, 0]
lasers: [{field: [0, 0, 125, 200]}, {field: [125, 0, 250, 200]}]
EOF
run "$LAMINA" machines --show ./p.yaml
is "$RC" 0 "a profile with the build keys loads"
like "$OUT" $'\nplate:\n  width: 250\n  depth: 200\n  margin: 5\nspacing: 2\\.5\n' \
    "--show writes the plate as a section and the spacing"
like "$OUT" $'\ngas_flow: \\[-1, 0\\]\nlasers: \\[\\{field: \\[0, 0, 125, 200\\]\\}, \\{field: \\[125, 0, 250, 200\\]\\}\\]\n' \
    "--show writes gas_flow and lasers in flow style"
printf '%s\n' "$OUT" >dump.yaml
run "$LAMINA" machines --show ./dump.yaml
is "$(printf '%s\n' "$OUT" | grep -v '^#')" "$(grep -v '^#' dump.yaml)" "the dump loads again as the same profile"
printf 'inherits: cli-ascii\nname: r\nplate: {diameter: 300}\n' >round.yaml
run "$LAMINA" machines --show ./round.yaml
like "$RC $OUT" $'^0 [\\s\\S]*\nplate:\n  diameter: 300\n' "a round plate: plate.diameter"
# a profile that gives a shape replaces the inherited one
printf 'inherits: ./p.yaml\nname: q\nplate: {diameter: 300}\n' >q.yaml
run "$LAMINA" machines --show ./q.yaml
like "$RC $OUT" $'^0 [\\s\\S]*\nplate:\n  diameter: 300\n  margin: 5\n' \
    "a round plate over an inherited rectangular one replaces its width and depth, keeps the margin"

# shipped profiles: cli-ascii has none of the keys, lpbf-cli and cli-binary a plate
run "$LAMINA" machines --show cli-ascii
! printf '%s' "$OUT" | grep -q -e '^plate:' -e '^spacing:' -e '^gas_flow:' -e '^lasers:'
ok $? "a profile without the keys dumps none of them"
run "$LAMINA" machines --show lpbf-cli
like "$OUT" $'\nplate:\n  width: 250\n  depth: 250\n  margin: 5\nspacing: 5\ngas_flow: \\[-1, 0\\]\nlasers: \\[\\{field: \\[0, 0, 250, 250\\]\\}\\]\n' \
    "lpbf-cli: a 250 x 250 plate, margin 5, spacing 5, gas towards -x, one laser over the plate"
run "$LAMINA" machines --show cli-binary
like "$OUT" $'\nplate:\n  width: 250\n  depth: 250\n  margin: 5\nspacing: 5\n' "cli-binary: the same plate and spacing"

# ---- --set ---------------------------------------------------------------------------
run "$LAMINA" machines --show cli-ascii --set plate.width=100 --set plate.depth=80 --set plate.margin=1 \
    --set spacing=3 --set gas_flow=[0,1] --set 'lasers=[{field: [0, 0, 50, 80]}, {field: [40, 0, 100, 80]}]'
like "$RC $OUT" $'^0 [\\s\\S]*\nplate:\n  width: 100\n  depth: 80\n  margin: 1\nspacing: 3\ngas_flow: \\[0, 1\\]\nlasers: \\[\\{field: \\[0, 0, 50, 80\\]\\}, \\{field: \\[40, 0, 100, 80\\]\\}\\]\n' \
    "--set of each key"
run "$LAMINA" machines --show ./p.yaml --set plate.diameter=180
like "$RC $OUT" $'^0 [\\s\\S]*\nplate:\n  diameter: 180\n  margin: 5\nspacing' "--set plate.diameter makes the plate round"
run "$LAMINA" machines --show ./p.yaml --set 'gas_flow=[0.5, -2]' --set 'lasers=[{field: [1, 2, 3, 4]}]'
like "$RC $OUT" $'^0 [\\s\\S]*\ngas_flow: \\[0\\.5, -2\\]\nlasers: \\[\\{field: \\[1, 2, 3, 4\\]\\}\\]\n' \
    "--set replaces the profile's lists"
run "$LAMINA" machines --show cli-ascii --set plate.width=100
like "$RC $ERR" "^2 lamina machines: plate\\.width and plate\\.depth go together" "--set: a width without a depth is refused"
run "$LAMINA" machines --show cli-ascii --set gas_flow=[1,0,0]
like "$RC $ERR" "^2 lamina machines: --set gas_flow=\\[1,0,0\\]: gas_flow must be a list of 2 numbers, got a list of 3" \
    "--set: a gas flow of 3 numbers"
run "$LAMINA" machines --show cli-ascii --set 'lasers=[{field: [5, 0, 1, 1]}]'
like "$RC $ERR" "^2 .*a laser's field must have x0 < x1 and y0 < y1, got \\[5, 0, 1, 1\\]" "--set: a field with x0 > x1"
run "$LAMINA" machines --show cli-ascii --set 'lasers=[{feild: [0, 0, 1, 1]}]'
like "$RC $ERR" "^2 .*unknown key 'feild' in lasers \\(did you mean 'field'\\?" "--set: a misspelt field"

# ---- errors in a profile file: file:line:column ---------------------------------------
bad() { # bad LINE3 WANT DESCRIPTION: the profile's third line is LINE3
    printf 'inherits: cli-ascii\nname: e\n%s\n' "$1" >e.yaml
    run "$LAMINA" machines --show ./e.yaml
    like "$RC $ERR" "^1 lamina: \\./e\\.yaml:$2" "$3"
}
bad 'plate: {width: 0, depth: 5}' "3:16: plate\\.width must be greater than 0, got '0'" "width 0"
bad 'plate: {width: 5, depth: -1}' "3:26: plate\\.depth must be greater than 0, got '-1'" "depth -1"
bad 'plate: {diameter: 0}' "3:19: plate\\.diameter must be greater than 0" "diameter 0"
bad 'plate: {width: 5, depth: 5, margin: -1}' "3:37: plate\\.margin must be 0 or more, got '-1'" "margin -1"
bad 'spacing: -0.5' "3:10: spacing must be 0 or more, got '-0\\.5'" "spacing -0.5"
bad 'plate: {width: 10}' "3:8: plate\\.width and plate\\.depth go together" "a width without a depth"
bad 'plate: {diameter: 10, width: 5, depth: 5}' "3:19: plate\\.diameter excludes plate\\.width and plate\\.depth" \
    "a diameter with a width and depth"
bad 'plate: {wdith: 10}' "3:9: unknown key 'wdith' in plate \\(did you mean 'width'\\?" "a misspelt plate key"
bad 'plate: 250' "3:8: plate must be a mapping" "plate not a mapping"
bad 'gas_flow: [1]' "3:11: gas_flow must be a list of 2 numbers, got a list of 1" "gas_flow of one number"
bad 'gas_flow: [1, x]' "3:15: gas_flow must be a list of 2 numbers, got 'x' in it" "gas_flow with text"
bad 'gas_flow: ["1", 0]' "3:12: gas_flow must be a list of 2 numbers, got '1' in it" "gas_flow with a quoted number"
bad 'gas_flow: -1' "3:11: gas_flow must be a list of 2 numbers, got '-1'" "gas_flow not a list"
bad 'lasers: []' "3:9: lasers must be a list of 1 to 16 lasers .*got an empty list" "no lasers"
bad "lasers: [$(for i in $(seq 17); do printf '{field: [0, 0, 1, 1]}, '; done)]" \
    "3:9: lasers must be a list of 1 to 16 lasers .*got a list of 17" "17 lasers"
bad 'lasers: {field: [0, 0, 1, 1]}' "3:9: lasers must be a list .*got a mapping" "lasers a mapping, not a list"
bad 'lasers: [[0, 0, 1, 1]]' "3:10: a laser must be a mapping \\{field: \\[x0, y0, x1, y1\\]\\}, got a list" "a laser not a mapping"
bad 'lasers: [{fild: [0, 0, 1, 1]}]' \
    "3:11: unknown key 'fild' in lasers \\(did you mean 'field'\\? allowed: field\\)" "a misspelt key in a laser: did you mean"
bad 'lasers: [{field: [0, 0, 1, 1], power: 3}]' "3:32: unknown key 'power' in lasers" "a second key in a laser"
bad 'lasers: [{}]' "3:10: a laser needs its field" "a laser without a field"
bad 'lasers: [{field: [0, 0, 1]}]' "3:18: a laser's field must be a list of 4 numbers, got a list of 3" "a field of 3 numbers"
bad 'lasers: [{field: [0, 0, 1, 1]}, {field: [0, 3, 1, 3]}]' \
    "3:41: a laser's field must have x0 < x1 and y0 < y1, got \\[0, 3, 1, 3\\]" "the second laser's field has no depth"
printf 'inherits: cli-ascii\nname: e\nlasers:\n  - field: [0, 0, 1, 1]\n  - field: [2, 0, 1, 1]\n' >e.yaml
run "$LAMINA" machines --show ./e.yaml
like "$RC $ERR" "^1 lamina: \\./e\\.yaml:5:12: a laser's field must have x0 < x1" "a block list: the field's line and column"

# ---- Lua -----------------------------------------------------------------------------
cat >t.lua <<'EOF'
-- numbers as %g, lists joined by spaces, nil as nil
local function say(...)
  local t = table.pack(...)
  for i = 1, t.n do
    local v = t[i]
    if type(v) == "table" then
      local parts = {}
      for j, x in ipairs(v) do parts[j] = ("%g"):format(x) end
      t[i] = table.concat(parts, " ")
    else
      t[i] = type(v) == "number" and ("%g"):format(v) or tostring(v)
    end
  end
  print(table.concat(t, " ", 1, t.n))
end
local m = assert(lamina.machine("./p.yaml"))
local g, l = m.gas_flow, m.lasers
say("plate", m["plate.width"], m["plate.depth"], m["plate.diameter"], m["plate.margin"], "spacing", m.spacing)
say("gas", g, "#" .. #g)
say("lasers", #l .. ":", l[1].field, "/", l[2].field)
local a = assert(lamina.machine("cli-ascii"))
say("cli-ascii", a["plate.width"], a["plate.margin"], a.spacing, a.gas_flow, a.lasers)
local r = m:override{["plate.diameter"] = 90, spacing = 1}
say("override", r["plate.diameter"], r["plate.width"], r.spacing, m["plate.width"])
print(select(2, pcall(m.override, m, {gas_flow = {1, 0}})))
print(select(2, pcall(a.override, a, {["plate.width"] = 10})))
print(select(2, pcall(m.override, m, {["plate.width"] = -1})))
EOF
run "$LAMINA" run t.lua
is "$RC" 0 "Lua: the recipe runs"
like "$OUT" '^plate 250 200 nil 5 spacing 2\.5$' "Lua: the plate keys by their whole names, the spacing"
like "$OUT" '^gas -1 0 #2$' "Lua: machine.gas_flow is {dx, dy}"
like "$OUT" '^lasers 2: 0 0 125 200 / 125 0 250 200$' "Lua: machine.lasers is { {field = {x0, y0, x1, y1}}, ... }"
like "$OUT" '^cli-ascii nil 0 0 nil nil$' "Lua: without the keys: nil, a margin and spacing of 0"
like "$OUT" '^override 90 nil 1 250$' "Lua: override makes the plate round and leaves the machine as it was"
like "$OUT" 'gas_flow cannot be changed here \(give it in the profile, or with --set\)' \
    "Lua: override refuses a list, saying where to give it"
like "$OUT" 'plate\.width and plate\.depth go together' "Lua: override checks the plate it leaves"
like "$OUT" 'plate\.width must be greater than 0' "Lua: override checks the range"
run "$LAMINA" machines --keys
like "$OUT" $'\n\\| `gas_flow` \\| list of 2 numbers \\| none \\|' "--keys: gas_flow's type"
like "$OUT" $'\n\\| `lasers` \\| list of 1\\.\\.16 lasers \\| none \\|' "--keys: lasers' type"
like "$OUT" $'\n\\| `plate\\.margin` \\| number >= 0 \\| `0` \\|' "--keys: the plate's margin"
done_testing
