-- Lifetimes: a child keeps its parent alive through its user value; an
-- object whose finalizer ran (reachable again only through another
-- finalizer, or after calling __gc by hand) raises a clear error instead of
-- touching freed memory. Run under ASan this is the use-after-free test.
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M

local function full_gc()
  collectgarbage()
  collectgarbage()
end

-- a contour outlives every other reference to its layer and model
local contour, machine
do
  local m = lamina.load(M .. "thesis_cube_hole.ug")
  contour = m:slice{width = 1, cut = "floor"}[2]:contour(2)
  machine = lamina.machine("creol-ladrp"):override{angle = 90}:override{angle_step = 45}
end
full_gc()
T.is(contour.area, -1, "contour alive after its model and layers were dropped")
T.is(contour.layer.z, 1, "its layer too")
T.is(contour.layer.model.volume, 6, "and the model")
T.is(contour.parent.kind, "solid", "and its parent contour")
T.ok(machine.angle == 90 and machine.angle_step == 45 and machine.name == "creol-ladrp",
     "a derived machine keeps the loaded profile alive")
local layer = contour.layer
contour = nil
full_gc()
T.is(layer:contour(2).area, -1, "a layer recreates a collected contour userdata")

-- an iterator keeps its object alive
local iter, state, ctrl
do
  local m = lamina.load(M .. "thesis_cube.ug")
  iter, state, ctrl = m:triangles()
end
full_gc()
local i, a = iter(state, ctrl)
T.ok(i == 1 and #a == 3, "triangles() iterator state keeps the model")

-- resurrection: a finalizer that runs first (it was set last) stores
-- objects that are being finalized in the same cycle
local kept = {}
do
  local m = lamina.load(M .. "thesis_cube_hole.ug")
  local ls = m:slice{width = 1}
  local c = ls[1]:contour(2)
  local mc = lamina.machine("sls-contours")
  local dm = mc:override{spot_width = 0.2}
  local p = mc:plan(ls)
  setmetatable({}, {__gc = function()
    kept.model, kept.layers, kept.contour, kept.machine, kept.derived, kept.plan = m, ls, c, mc, dm, p
  end})
end
full_gc()
T.ok(kept.model and kept.contour and kept.plan, "objects resurrected")
local checks = {
  {"model", function() return kept.model.volume end},
  {"model:slice", function() return kept.model:slice{} end},
  {"model:triangles", function() return kept.model:triangles() end},
  {"layer", function() return kept.layers[1].z end},
  {"layer:contours", function() return kept.layers[1]:contours() end},
  {"contour", function() return kept.contour.area end},
  {"contour:points", function() for _ in kept.contour:points() do end end},
  {"machine", function() return kept.machine.name end},
  {"derived machine", function() return kept.derived.spot_width end},
  {"plan", function() return kept.plan:text() end},
  {"#plan", function() return #kept.plan end},
  {"plan of collected layers", function() return lamina.machine("sls-contours"):plan(kept.layers) end},
  {"override of a collected machine", function() return kept.derived:override{} end},
}
for _, c in ipairs(checks) do T.raises("attempt to use a collected lamina.", c[1] .. " after finalization", c[2]) end
for _, name in ipairs{"model", "contour", "machine", "derived", "plan"} do
  T.like(tostring(kept[name]), "%(collected%)$", "tostring of a finalized " .. name)
end
T.like(tostring(kept.layers[2]), "%(collected%)$", "tostring of a finalized layer")
kept = nil
full_gc()

-- a resurrected model whose own finalizer is still pending, sliced: the
-- finalizer runs during the slice (the slice allocates, the collector
-- steps, ten finalizers per step) and must not free the model under it
do
  local saved
  do
    local m = lamina.load(M .. "thesis_cube_hole.ug")
    local fillers = {}
    for k = 1, 20000 do fillers[k] = setmetatable({}, {__gc = function() end}) end
    setmetatable({}, {__gc = function() saved = m end}) -- finalized first: set last
  end
  local steps = 0
  repeat collectgarbage("step", 0); steps = steps + 1 until saved or steps > 100000
  T.ok(saved and pcall(function() return saved.volume end),
       "the model was resurrected and its finalizer is still pending")
  local ok, layers = pcall(saved.slice, saved, {width = 1e-4})
  T.ok(ok and #layers == 20000, "slicing it while its finalizer runs", not ok and layers or nil)
  local alive, err = pcall(function() return saved.volume end)
  T.ok(not alive and err:find("collected", 1, true), "the finalizer ran during the slice, which freed the model at its end")
  full_gc()
  T.ok(pcall(function() return #layers[1000] end), "the layers stay good")
end

-- options tables whose metamethods finalize the objects being used
do
  local mc = lamina.load(M .. "thesis_cube_hole.ug")
  local ls = mc:slice{width = 1}
  local sls = lamina.machine("sls-contours")
  local evil = setmetatable({}, {__index = function(_, k)
    local gc = getmetatable(sls).__gc
    gc(sls)
    getmetatable(ls[1]).__gc(ls[1])
    return nil
  end})
  local ok, err = pcall(sls.plan, sls, ls, evil)
  T.ok(not ok and err:find("collected", 1, true), "plan: options that finalize the machine and a layer",
       tostring(err))
  local m2 = lamina.load(M .. "thesis_cube_hole.ug")
  local evil2 = setmetatable({}, {__index = function() getmetatable(m2).__gc(m2) end})
  local ok2, res = pcall(m2.slice, m2, evil2)
  T.ok(ok2 and #res == 100, "slice: options that finalize the model being sliced", tostring(res))
  T.raises("attempt to use a collected lamina.model", "and the model is gone afterwards",
           function() return m2.volume end)
  local mc3 = lamina.machine("creol-ladrp")
  local evil3 = setmetatable({}, {__index = function() getmetatable(mc3).__gc(mc3) end})
  local ok3, d = pcall(mc3.override, mc3, evil3)
  T.ok(not ok3, "override: options that finalize the machine", tostring(d))
end

-- __gc called by hand, twice, then the object used
local m = lamina.load(M .. "thesis_cube_hole.ug")
local ls = m:slice{width = 1}
local c = ls[1]:contour(1)
local gc = getmetatable(m).__gc
gc(m)
gc(m)
T.raises("attempt to use a collected lamina.model", "model after __gc", function() return m.volume end)
T.is(ls[1].z, 0.5, "its layers own their data")
T.is(c.area, 4, "and their contours")
T.is(ls[1].model, m, "layer.model is the finalized model")
getmetatable(ls[1]).__gc(ls[1])
T.raises("attempt to use a collected lamina.layer", "layer after __gc", function() return ls[1].z end)
T.raises("attempt to use a collected lamina.contour", "contour of a finalized layer", function() return c.area end)
T.raises("attempt to use a collected lamina.layer", "plan with a finalized layer",
         function() return lamina.machine("sls-contours"):plan(ls) end)
getmetatable(c).__gc(c)
T.raises("attempt to use a collected lamina.contour", "contour after __gc", function() return #c end)
local mc = lamina.machine("creol-ladrp")
local dm = mc:override{angle = 5}
getmetatable(mc).__gc(mc)
T.raises("attempt to use a collected lamina.machine", "derived machine after its owner's __gc",
         function() return dm.angle end)
T.raises("attempt to use a collected lamina.machine", "machine after __gc", function() return mc.angle end)
local p = lamina.machine("sls-contours"):plan(lamina.load(M .. "thesis_cube.ug"):slice{width = 1})
getmetatable(p).__gc(p)
T.raises("attempt to use a collected lamina.plan", "plan after __gc", function() return p:text() end)

-- many runs: memory is given back (checked by the leak detector under SAN)
local cube = lamina.load(M .. "frame_island.ug")
local sls = lamina.machine("sls-contours")
for k = 1, 50 do
  local run = cube:slice{width = 1}
  for _, l in ipairs(run) do l:contours() end
  sls:plan(run)
end
full_gc()
T.ok(collectgarbage("count") < 4096, "Lua heap back under 4 MB after 50 runs")

T.done()
