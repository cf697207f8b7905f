-- lamina.build{...}: a build plate from Lua (issue 25, item 1). Placements,
-- times and ids are checked with the test's own arithmetic on cubes; the
-- program against `lamina build` of the same job written as YAML (the
-- other front end of the same core calls). Needs $LAMINA (the executable).
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M
local cube = M .. "thesis_cube.ug" -- [-1, 1]^3
local eps = 1e-9

-- ---- four copies on a plate ------------------------------------------------------
-- a cube scaled by 4 is 8 x 8 x 8; lpbf-cli keeps parts 5 apart (spacing);
-- no supports here (they have their own test at the end)
local p = assert(lamina.build{machine = "lpbf-cli", layer_width = 0.5, plate = {width = 100, depth = 100, margin = 5},
                              support_type = "none", parts = {{model = cube, copies = 4, scale = 4}}})
T.like(tostring(p), "^lamina%.plan %(lpbf%-cli, sls, 16 layers", "a lamina.plan: 8 mm of 0.5 mm layers")
T.is(p.layers, 16, "p.layers: the plate's layers")
T.is(#p.parts, 4, "four parts on the plate")
local placed, inside = true, true
for i, a in ipairs(p.parts) do
  placed = placed and a.part == i and a.entry == 1 and a.name == "thesis_cube_" .. i
           and math.abs(a.box[3] - a.box[1] - 8) < eps and math.abs(a.box[4] - a.box[2] - 8) < eps
           and math.abs((a.box[1] + a.box[3]) / 2 - a.at[1]) < eps and math.abs((a.box[2] + a.box[4]) / 2 - a.at[2]) < eps
           and a.layers[1] == 1 and a.layers[2] == 16
  inside = inside and a.box[1] >= 5 - eps and a.box[2] >= 5 - eps and a.box[3] <= 95 + eps and a.box[4] <= 95 + eps
end
T.ok(placed, "each part: its number, name, an 8 x 8 box centred on at, layers 1 to 16")
T.ok(inside, "every box inside the plate less its margin of 5")
local apart = true
for i = 1, 4 do
  for k = i + 1, 4 do
    local a, b = p.parts[i].at, p.parts[k].at
    apart = apart and math.max(math.abs(a[1] - b[1]), math.abs(a[2] - b[2])) >= 8 + 5 - eps
  end
end
T.ok(apart, "the parts' centres are pairwise at least the box (8) and the spacing (5) apart")

local sum, sum_data = 0, 0
for i = 1, p.layers do
  sum = sum + p.time.layers[i]
  sum_data = sum_data + p:layer(i).time
end
T.is(#p.time.layers, 16, "p.time.layers: one time per plate layer")
T.near(sum, p.time.total, "p.time.total is the sum of the layers' times", 1e-9 * p.time.total)
T.near(sum_data, p.time.total, "and of p:layer(i).time", 1e-9 * p.time.total)
T.ok(p.time.total > p.time.recoat and p.time.recoat > 0, "the time has scanning and recoating")
T.near(p.lasers[1].time, p.time.total - p.time.recoat, "one laser: its time is the scanning time",
       1e-9 * p.time.total)
local psum = 0
for _, a in ipairs(p.parts) do psum = psum + a.time end
T.ok(psum > 0 and psum <= p.lasers[1].time + eps, "the parts' own times add up to at most the laser's (jumps between)")
T.is(#p.lasers, 1, "p.lasers: lpbf-cli has one laser")
local f1 = p.lasers[1].field
T.ok(#f1 == 4 and f1[1] == 0 and f1[2] == 0 and f1[3] == 250 and f1[4] == 250, "its field (the profile's)")
T.is(table.concat(p.styles, ","), "contour,core,upskin,downskin", "p.styles: the regions' own")
T.is(#p.labels, 16, "p.labels: 4 parts x 4 styles x 1 laser")
T.is(p.labels[6], "thesis_cube_2:core:1", "labels are PART:STYLE:LASER, part by part")

-- every operation of layer 1 names its part, style, laser and label
local l1 = p:layer(1)
local ids_ok, seen, nops = true, {}, 0
local function check_op(o, kind)
  local part = o.part or 1 -- a default (1) is left out of the vector
  seen[part] = true
  nops = nops + 1
  ids_ok = ids_ok and o.laser == 1 and p.styles[o.style] == kind
           and p.labels[o.label] == ("%s:%s:%d"):format(p.parts[part].name, kind, o.laser)
end
for _, v in ipairs(l1.vectors) do check_op(v, v.kind) end
for _, c in ipairs(l1.contours) do check_op(c, "contour") end
T.ok(nops > 0 and ids_ok, "each vector and contour of layer 1: laser 1, its region's style, its label", nops)
T.ok(seen[1] and seen[2] and seen[3] and seen[4], "layer 1 has operations of all four parts")
T.is(p:layer(17), nil, "no layer 17")

T.is(lamina.build{machine = "lpbf-cli", layer_width = 0.5, plate = {width = 100, depth = 100, margin = 5}, threads = 3,
                  support_type = "none", parts = {{model = cube, copies = 4, scale = 4}}}:text(), p:text(),
     "threads = 3: the same program")

-- ---- the same job as `lamina build` of YAML -------------------------------------------
local LAMINA = os.getenv("LAMINA")
local function q(s) return "'" .. s:gsub("'", "'\\''") .. "'" end
local function read(path)
  local f = io.open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end
local yq = '"' .. cube:gsub('[\\"]', "\\%0") .. '"'
local yaml = ([[
machine: lpbf-cli
layer_width: 0.25
support_type: none
plate: {width: 120, depth: 100, margin: 4}
spacing: 3
gas_flow: [1, 0]
lasers: [{field: [0, 0, 70, 100]}, {field: [50, 0, 120, 100]}]
hatch_strategy: lines
contour: {power: 110}
styles:
  fast: {power: 300, speed: 1400}
  slow: {hatch_distance: 0.2, speed: 500}
parts:
  - {model: CUBE, copies: 3, scale: 4, style: fast}
  - {model: CUBE, name: pin, scale: [2, 2, 3], rotate: [x:90, z:45], at: [90, 70], style: {core: slow, upskin: fast}}
  - {model: CUBE, units: cm, scale: 0.2, z: 1}
]]):gsub("CUBE", function() return yq end)
local job = {
  machine = "lpbf-cli", layer_width = 0.25, support_type = "none", plate = {width = 120, depth = 100, margin = 4},
  spacing = 3,
  gas_flow = {1, 0}, lasers = {{field = {0, 0, 70, 100}}, {field = {50, 0, 120, 100}}}, hatch_strategy = "lines",
  contour = {power = 110},
  styles = {fast = {power = 300, speed = 1400}, slow = {hatch_distance = 0.2, speed = 500}},
  parts = {
    {model = cube, copies = 3, scale = 4, style = "fast"},
    {model = cube, name = "pin", scale = {2, 2, 3}, rotate = {"x:90", "z:45"}, at = {90, 70},
     style = {core = "slow", upskin = "fast"}},
    {model = cube, units = "cm", scale = 0.2, z = 1},
  },
}
local b = assert(lamina.build(job))
if LAMINA then
  local f = assert(io.open("job.yaml", "w"))
  f:write(yaml)
  f:close()
  os.remove("job.cli")
  os.execute(q(LAMINA) .. " build job.yaml -o job.cli -q")
  local cli = read("job.cli")
  T.ok(cli and #cli > 0 and cli == b:text(), "the program is `lamina build` of the job as YAML, byte for byte",
       cli and ("%d bytes from the CLI, %d from Lua"):format(#cli, #b:text()))
else
  T.ok(false, "LAMINA names the executable (to compare with lamina build)")
end
T.is(table.concat(b.styles, ","), "contour,core,upskin,downskin,fast,slow", "the job's styles after the regions'")
T.is(#b.parts, 5, "3 copies, the pin and the small cube")
T.ok(b.parts[4].name == "pin" and b.parts[4].at[1] == 90 and b.parts[4].at[2] == 70, "the pin where at puts it")
-- the small cube: 10 x 0.2 = 4 mm (cm to the machine's mm), lifted by 1:
-- plate layers of 0.25 from 1 to 5 mm are 5 to 20
local small = b.parts[5]
T.ok(math.abs(small.box[3] - small.box[1] - 4) < eps, "units = cm and scale 0.2: a 4 mm cube")
T.ok(small.layers[1] == 5 and small.layers[2] == 20, "z = 1: its layers are plate layers 5 to 20",
     small.layers[1] .. ".." .. small.layers[2])
T.is(#b.lasers, 2, "two lasers")
local f2 = b.lasers[2].field
T.ok(#f2 == 4 and f2[1] == 50 and f2[2] == 0 and f2[3] == 120 and f2[4] == 100, "laser 2's field")
local fields_ok, styles_ok, lasers_seen = true, true, {}
for i = 1, b.layers do
  local l = b:layer(i)
  for _, v in ipairs(l.vectors) do
    local f, part = b.lasers[v.laser].field, v.part or 1
    lasers_seen[v.laser] = true
    for k = 0, 1 do
      local x, y = v[1 + 2 * k], v[2 + 2 * k]
      fields_ok = fields_ok and x >= f[1] - 1e-6 and x <= f[3] + 1e-6 and y >= f[2] - 1e-6 and y <= f[4] + 1e-6
    end
    local want = part <= 3 and "fast" or part == 4 and ({core = "slow", upskin = "fast"})[v.kind] or v.kind
    styles_ok = styles_ok and b.styles[v.style] == want
  end
end
T.ok(fields_ok, "every vector lies in its laser's field")
T.ok(lasers_seen[1] and lasers_seen[2], "both lasers expose something")
T.ok(styles_ok, "styles: fast for the copies' every region, the pin's core slow and upskin fast, else the region's")

-- a lamina.machine: its overrides apply
local m = lamina.machine("lpbf-cli"):override{speed = 1000}
-- (an 8 mm cube: a core under the 3 skin layers of 0.5)
local by_obj = lamina.build{machine = m, layer_width = 0.5, parts = {{model = cube, scale = 4}}}:text()
local by_key = lamina.build{machine = "lpbf-cli", speed = 1000, layer_width = 0.5, parts = {{model = cube, scale = 4}}}:text()
T.ok(by_obj == by_key and by_obj:find("core power 200 speed 1000", 1, true),
     "machine = a lamina.machine: its overrides apply (as the key given to the build)")

-- ---- errors ---------------------------------------------------------------------------------
local function build(extra, parts)
  local t = {machine = "lpbf-cli", layer_width = 0.5, parts = parts or {{model = cube}}}
  for k, v in pairs(extra) do t[k] = v end
  return function() return lamina.build(t) end
end
T.raises("unknown key 'layr_width' in the build (did you mean layer_width?)", "an unknown key: did you mean",
         build{layr_width = 1})
T.raises("parts[2].copies must be a whole number from 1 to 10000, got 0", "copies 0",
         build({}, {{model = cube}, {model = cube, copies = 0}}))
T.raises("unknown key 'copys' in parts[1] (did you mean copies?)", "a part's unknown key",
         build({}, {{model = cube, copys = 2}}))
T.raises("parts[1].style: style fsat is not defined in styles (did you mean fast?)", "an undefined style",
         build({styles = {fast = {power = 300}}}, {{model = cube, style = "fsat"}}))
T.raises("styles.fast: powr is not a build style key (did you mean power?)", "a style's unknown key",
         build{styles = {fast = {powr = 3}}})
T.raises("unknown key 'plate.widht' in plate (did you mean plate.width?)", "a section's unknown key",
         build{plate = {widht = 3}})
T.raises("layer_width must be greater than 0, got '-1'", "a value out of range: the profile's message",
         build{layer_width = -1})
T.raises("gas_flow must be a list of 2 numbers", "a list key's bad value", build{gas_flow = {1, 2, 3}})
T.raises("layer_width is given twice (as layer_thickness and as layer_width)", "one key by two names",
         build{layer_thickness = 0.5})
T.raises("machine is missing", "no machine", function() return lamina.build{parts = {{model = cube}}} end)
T.raises("is a ladrp profile", "a machine that is not powder-bed", build{machine = "creol-ladrp"})
T.raises("parts is empty", "no parts", build({}, {}))
T.raises("parts[1] names no model", "a part without a model", build({}, {{copies = 2}}))
T.raises("parts[1].at: a part with at has one copy", "at with copies", build({}, {{model = cube, at = {50, 50}, copies = 2}}))
T.raises("angle is read by the ladrp planner only", "a key the powder-bed planner does not read", build{angle = 3})
T.fails("nonexistent%.stl", "a model that does not load: nil and the message",
        lamina.build, {machine = "lpbf-cli", parts = {{model = "nonexistent.stl"}}})
T.fails("margin", "parts that do not fit: nil and the arrangement's message",
        lamina.build, {machine = "lpbf-cli", plate = {width = 10, depth = 10}, parts = {{model = cube, scale = 4}}})
T.fails("exceeds the limit of 1000 bytes %(raise the limit with the option max_output%)",
        "a program past max_output: nil and the message", lamina.build,
        {machine = "lpbf-cli", layer_width = 0.5, max_output = 1000, parts = {{model = cube, scale = 4}}})

-- ---- in a sandbox ----------------------------------------------------------------------------
local code = [[
local cube, w = ...
return lamina.build{machine = "lpbf-cli", layer_width = w, plate = {width = 100, depth = 100, margin = 5},
                    support_type = "none", parts = {{model = cube, scale = 4, copies = 4}}}]]
local ok, none, msg = lamina.sandbox{code = code, args = {cube, 0.5}, allow = "."}
T.ok(ok and none == nil and tostring(msg):find("outside the sandbox's readable directories", 1, true),
     "sandboxed: a model outside the readable directories is refused", msg)
local ok2, text = lamina.sandbox{code = code .. ":text()", args = {cube, 0.5}, allow = M, memory = 64 * 2^20}
T.ok(ok2 and text == p:text(), "sandboxed with a memory limit: the same program as outside")
local none3, err3 = lamina.sandbox{code = code, args = {cube, 0.0005}, allow = M, time = 0.2}
T.ok(none3 == nil and tostring(err3):find("time limit exceeded", 1, true), "the sandbox's time stops a big build", err3)
local none4, err4 = lamina.sandbox{code = code, args = {cube, 0.002}, allow = M, memory = 4e6}
T.ok(none4 == nil and tostring(err4):find("memory limit exceeded: lamina.build", 1, true),
     "the sandbox's memory stops a big build", err4)
-- 2000 copies of a cube: their models and slicers are counted (each copy
-- more than 1 kB: over 2 MB in all)
local none5, err5 = lamina.sandbox{code = [[
  return lamina.build{machine = "lpbf-cli", layer_width = 0.5, plate = {width = 1000, depth = 1000},
                      lasers = {{field = {0, 0, 1000, 1000}}}, parts = {{model = ..., copies = 2000}}}]],
                      args = {cube}, allow = M, memory = 2e6}
T.ok(none5 == nil and tostring(err5):find("memory limit exceeded: lamina.build: the plate's 2000 parts", 1, true),
     "the sandbox's memory counts the plate's models and slicers", err5)

-- ---- supports: a lifted cube stands on them ------------------------------------
-- the 4 mm cube 1 above the plate (units cm, scale 0.2, z 1), 0.25 layers:
-- lpbf-cli's block supports fill its whole footprint from the plate up, so
-- its run starts at plate layer 1; the 4 layers under it are support alone,
-- of its 16 mm2 footprint less nothing (the layer below holds none of it)
local sb = assert(lamina.build{machine = "lpbf-cli", layer_width = 0.25, support_teeth = {height = 0},
                               parts = {{model = cube, units = "cm", scale = 0.2, z = 1}}})
T.ok(sb.parts[1].layers[1] == 1 and sb.parts[1].layers[2] == 20, "supports: the lifted cube's run is plate layers 1 to 20",
     sb.parts[1].layers[1] .. ".." .. sb.parts[1].layers[2])
local kinds, under = {}, true
for i = 1, 4 do
  for _, v in ipairs(sb:layer(i).vectors) do
    kinds[v.kind] = true
    under = under and v.kind == "support" or v.kind == "jump"
  end
end
T.ok(kinds.support and under, "supports: layers 1 to 4 hold support walls only")
local st = table.concat(sb.styles, ",")
T.is(st, "contour,core,upskin,downskin,support", "supports: the support's style numbered last")
local nb = assert(lamina.build{machine = "lpbf-cli", layer_width = 0.25, support_type = "none",
                               parts = {{model = cube, units = "cm", scale = 0.2, z = 1}}})
T.ok(sb.time.total > nb.time.total, "supports: the build's time holds them",
     ("%g s with, %g s without"):format(sb.time.total, nb.time.total))

T.done()
