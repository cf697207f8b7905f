-- model:validate{...} and model:check(machine): lamina validate's and
-- lamina check's tests from Lua, as tables. The expected figures come from
-- the models' own geometry (their .ug files say what they are).
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M

-- thesis_cube_hole: a 2 x 2 square with a 1 x 1 hole, z 0 .. 2
local holed = assert(lamina.load(M .. "thesis_cube_hole.ug"))
local r = holed:validate{width = 1, cut = "floor"}
T.ok(r.ok and #r == 2, "two layers, all agree")
T.is(r.checked .. "/" .. r.confirmed .. "/" .. r.disagreeing, "4/4/0", "4 contours checked and confirmed")
T.is(r.areas_compared, 2, "net area compared in both layers")
local l1 = r[1]
T.ok(l1.index == 1 and l1.z == 0 and l1.ok, "layer 1 at z 0")
T.is(l1.net_area, 4 - 1, "net area: the square less the hole")
T.is(l1.section_area, 3, "the model's section agrees")
T.ok(#l1 == 2 and l1[1].kind == "solid" and l1[2].kind == "hole", "per contour: solid, then hole")
T.ok(l1[2].status == "confirmed" and l1[2].ok and l1[2].edges > 0 and next(l1[2].problems) == nil,
     "the hole is confirmed, with edges tested and no problem")
T.ok(l1[2].depth_found == 1 and l1[2].parent_found == 1 and l1[1].parent_found == nil,
     "nesting found: the hole inside contour 1")
T.is(l1[2].area, -1, "the hole's signed area")
-- the layers of a slicing run, given
local layers = holed:slice{width = 0.5}
local some = holed:validate{layers = {layers[2], layers[4]}}
T.ok(#some == 2 and some[1].index == 2 and some[2].index == 4 and some.ok, "validate{layers = ...}: just those")
T.raises("layers[1] is a layer of another model", "layers of another model are refused",
         holed.validate, holed, {layers = {lamina.load(M .. "thesis_cube.ug"):slice{width = 1}[1]}})
T.raises("cut must be floor, middle or ceiling, got 'top'", "slice options checked as slice's",
         holed.validate, holed, {cut = "top"})
T.raises("unknown", "layers with slice options is refused", holed.validate, holed, {layers = layers, width = 1})
T.raises("layers[1] must be a lamina.layer", "a list of something else is refused", holed.validate, holed,
         {layers = {1}})

-- two overlapping cubes [0,2]^3 and [1,3]^3, layers of 0.5: the overlap
-- 1 < z < 2 is layers 3 and 4 (z 1.25, 1.75)
local ov = assert(lamina.load(M .. "validate/overlap_cubes.ug"))
local eo = ov:validate{width = 0.5}
local bad = {}
for _, l in ipairs(eo) do
  if not l.ok then bad[#bad + 1] = l.index end
end
T.ok(not eo.ok and eo.disagreeing == 2, "even-odd: two disagreements")
T.is(table.concat(bad, ","), "3,4", "in the layers of the overlap")
local wrong
for _, c in ipairs(eo[3]) do if c.status == "disagrees" then wrong = c end end
T.ok(wrong and wrong.kind == "hole" and wrong.problems.material and not wrong.ok,
     "the overlap labelled a hole disagrees with the material")
-- the label claims material outside the hole and void inside, where the
-- winding is 0 (outside both cubes) or 2 (in both): either contradicts it
T.ok(wrong and (wrong.winding == 0 or wrong.winding == 2) and wrong.position[3] == 1.25,
     "the test point that contradicts it: winding 0 or 2, at the cut height")
local nz = ov:validate{width = 0.5, fill = "nonzero"}
T.ok(nz.ok and nz.disagreeing == 0, "non-zero fill: all agree")
T.is(nz[3].net_area, 4 + 4 - 1, "the merged outline's area: two squares less their overlap")
T.is(nz[1].net_area, 4, "below the overlap: one square")

-- design rules: creol-ladrp (bead 0.08) with max_overhang_deg 45
local p45 = assert(lamina.machine(M .. "drc/ladrp45.yaml"))
local thin = assert(lamina.load(M .. "drc/plate_thin.ug")):check(p45)   -- 10 x 10 x 0.05
T.ok(not thin.ok and #thin >= 1, "a plate 0.05 thick fails")
T.ok(thin[1].rule == "min_wall" and math.abs(thin[1].value - 0.05) < 1e-6 and thin[1].limit == 0.08,
     "its wall: 0.05 against the bead 0.08")
T.like(thin[1].source, "plate_thin%.ug:%d+", "the source face is named")
T.ok(thin.machine == "ladrp45" and thin.min_wall == 0.08 and thin.max_overhang_deg == 45 and thin.samples > 0,
     "the rules checked are given")
local thick = assert(lamina.load(M .. "drc/plate_thick.ug")):check(p45)
T.ok(thick.ok and #thick == 0, "the plate 0.5 thick passes")
local shelf = assert(lamina.load(M .. "drc/shelf.ug"))
local s = shelf:check(p45)
T.is(#s, 1, "the shelf: one violation")
T.ok(s[1].rule == "max_overhang" and s[1].value == 90 and s[1].limit == 45, "its flat underside: 90 degrees, limit 45")
T.is(s[1].area, 3 * 2, "over the underside, 3 x 2")
T.is(s[1].position[3], 3, "at the underside's height")
-- built along x the underside is a wall, and the face at x = 0 rests on the plate
T.ok(shelf:check(p45, {axis = "x"}).ok, "built along x: no overhang")
T.ok(shelf:check(lamina.machine("creol-ladrp")).ok, "without max_overhang_deg the rule is off")
T.raises("unknown", "check's options are checked", shelf.check, shelf, p45, {up = "x"})
T.raises("lamina.machine expected", "check wants a machine", shelf.check, shelf, "creol-ladrp")

-- objects finalized by hand (or by options' metamethods) raise, never crash
do
  local m = assert(lamina.load(M .. "thesis_cube_hole.ug"))
  local evil = setmetatable({}, {__index = function() getmetatable(m).__gc(m) end})
  local ok, err = pcall(m.validate, m, evil)
  T.ok(not ok and tostring(err):find("collected", 1, true), "validate: options that finalize the model",
       tostring(err))
  local m2 = assert(lamina.load(M .. "drc/shelf.ug"))
  local p = lamina.machine("creol-ladrp")
  local evil2 = setmetatable({}, {__index = function() getmetatable(p).__gc(p); getmetatable(m2).__gc(m2) end})
  ok, err = pcall(m2.check, m2, p, evil2)
  T.ok(not ok and tostring(err):find("collected", 1, true), "check: options that finalize the machine and model",
       tostring(err))
  local m3 = assert(lamina.load(M .. "thesis_cube_hole.ug"))
  local ls = m3:slice{width = 1}
  getmetatable(ls[1]).__gc(ls[1])
  ok, err = pcall(m3.validate, m3, {layers = ls})
  T.ok(not ok and tostring(err):find("collected", 1, true), "validate: a finalized layer", tostring(err))
  T.is(tostring(ls), "2 layers", "the list of a finalized layer still prints")
  local ls2 = m3:slice{width = 1}
  getmetatable(m3).__gc(m3)
  T.is(tostring(ls2), "2 layers, z 0 .. 2", "and the list of a finalized model, without its name")
end

T.done()
