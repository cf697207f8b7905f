-- Nothing a script does can crash the host: drive every function and
-- method of the module (found by introspection, so new ones are covered)
-- with wrong types, nil, huge numbers, NaN and objects of the wrong kind,
-- call the iterators and metamethods directly, and check the messages of
-- misuse name the function and the argument. Run in a scratch directory
-- (some calls are given file names).
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M

local model = assert(lamina.load(M .. "thesis_cube_hole.ug"))
local layers = model:slice{width = 1}
local layer = layers[1]
local contour = layer:contour(2)
local sls = assert(lamina.machine("sls-contours"))
local ladrp = assert(lamina.machine("creol-ladrp"))
local derived = ladrp:override{angle = 30}
local plan = assert(sls:plan(layers))

local function pack(...) return {n = select("#", ...), ...} end
local values = pack(
  nil, false, true, 0, -1, 1, 2, 3, 1e308, -1e308, 1e-308, 0 / 0, math.huge, -math.huge,
  math.maxinteger, math.mininteger, "", "x", "z", "floor", "\0", ("a"):rep(5000), {}, {1, 2, 3},
  {width = 1e-300}, {width = 1e300}, {axis = {1e308, 1e308, 1e308}}, {axis = {1e-308, 0, 0}},
  {planes = {-1e308, 1e308}}, {widths = {1e300}}, {gap = 1e308}, {bead_width = 1e300},
  {bead_width = 1e-300}, {angle = 1e308}, {feed_rate = 1e308}, {min_deposit = 1e308},
  {widths = {0 / 0}}, {planes = {1, 1}}, {axis = "y", cut = "ceiling", fill = "nonzero"},
  {machine = ladrp}, {machine = layer}, {[1e308] = 1}, {[{}] = 1},
  print, coroutine.create(print), io.stdout,
  model, layer, contour, sls, derived, plan, layers
)
local NV = values.n

-- every function: module functions, methods, metamethods, iterators
local funcs = {}
for name, f in pairs(lamina) do
  if type(f) == "function" then funcs[#funcs + 1] = {"lamina." .. name, f} end
end
local objects = {model = model, layer = layer, contour = contour, machine = ladrp, plan = plan}
for class, obj in pairs(objects) do
  local mt = getmetatable(obj)
  local _, methods = debug.getupvalue(mt.__index, 1)
  for name, f in pairs(methods) do funcs[#funcs + 1] = {class .. ":" .. name, f, obj} end
  for name, f in pairs(mt) do
    if type(f) == "function" and name ~= "__gc" then funcs[#funcs + 1] = {class .. "." .. name, f, obj} end
  end
end
local tri_next = model:triangles()
local pts_next = contour:points()
local pts_model = contour:points("model")
funcs[#funcs + 1] = {"triangles iterator", tri_next, model}
funcs[#funcs + 1] = {"points iterator", pts_next, contour}
funcs[#funcs + 1] = {"points('model') iterator", pts_model, contour}
table.sort(funcs, function(a, b) return a[1] < b[1] end)

local calls, errors, bad_messages = 0, 0, {}
local function try(name, f, ...)
  calls = calls + 1
  local ok, err = pcall(f, ...)
  if not ok then
    errors = errors + 1
    if type(err) ~= "string" or err == "" then bad_messages[#bad_messages + 1] = name .. ": " .. tostring(err) end
  end
end

for _, entry in ipairs(funcs) do
  local name, f, self = entry[1], entry[2], entry[3]
  local before = calls
  try(name, f)
  for i = 1, NV do
    local v = values[i]
    try(name, f, v)
    try(name, f, v, v)
    try(name, f, v, v, v)
    if self then
      try(name, f, self, v)
      try(name, f, self, v, v)
      try(name, f, self, 1, v)
      try(name, f, self, v, 1)
      try(name, f, self, layers, v)
    end
  end
  T.ok(calls > before, name .. ": survived " .. (calls - before) .. " calls")
  collectgarbage()
end
T.ok(errors > 0 and #bad_messages == 0, ("%d calls, %d errors, every message a string"):format(calls, errors),
     table.concat(bad_messages, "\n"))

-- messages name the function and the argument
T.raises("bad argument #1 to 'slice' (table expected, got nil)", "method: nil", function() return model:slice(nil) end)
T.raises("bad argument #1 to 'slice' (table expected, got number)", "method: number", function() return model:slice(1) end)
T.raises("bad argument #1 to 'slice' (lamina.model expected, got lamina.layer)", "method on a wrong object",
         function() local slice = model.slice; return slice(layer, {}) end)
T.raises("bad argument #1 to 'contains' (number expected, got no value)", "contains()",
         function() return contour:contains() end)
T.raises("bad argument #2 to 'contains' (number expected, got string)", "contains(0, 'x')",
         function() return contour:contains(0, "x") end)
T.raises("bad argument #1 to 'load' (string expected, got nil)", "lamina.load(nil)", function() return lamina.load(nil) end)
T.raises("bad argument #1 to 'machine' (string expected, got table)", "lamina.machine({})",
         function() return lamina.machine({}) end)
T.raises("bad argument #1 to 'override' (table expected, got nil)", "override(nil)",
         function() return ladrp:override(nil) end)
T.raises("bad argument #1 to 'plan' (table expected, got nil)", "plan(nil)", function() return sls:plan(nil) end)
T.raises("bad argument #1 to 'write' (string expected, got nil)", "write(nil)", function() return plan:write(nil) end)
T.raises("number has no integer representation", "triangle(1.5)", function() return model:triangle(1.5) end)
T.raises("bad argument #1 to 'points' (invalid option 'world')", "points('world')",
         function() return contour:points("world") end)
T.raises("lamina.model expected, got lamina.layer", "a layer where a model belongs",
         function() return model.bbox(layer) end)

-- huge and odd values that are valid do something sensible
T.is(#model:slice{width = 1e300}, 1, "width 1e300: one layer")
T.is(#model:slice{planes = {-1e308, 1e308}}, 1, "planes spanning the doubles: one layer")
T.is(layer:contour(math.maxinteger), nil, "contour(maxinteger) is nil")
T.is(layer:contour(math.mininteger), nil, "contour(mininteger) is nil")
T.is(contour:contains(0 / 0, 0 / 0), false, "contains(NaN, NaN) is false")
T.is(contour:contains(1e308, -1e308), false, "contains(huge) is false")
local x, y, z = layer:to_model(1e308, -1e308, 1e308)
T.ok(x == 1e308 and y == -1e308 and z == 1e308, "to_model(huge)")
T.is(tri_next(model, math.maxinteger), nil, "triangle iterator past the end")
T.is(tri_next(model, -5), nil, "triangle iterator before the start")
T.is(pts_next(contour, 4), nil, "points iterator past the end")
T.ok(ladrp:plan(model:slice{machine = ladrp, width = 1}, {bead_width = 1e300}), "bead 1e300: a plan")
T.ok(ladrp:plan(model:slice{machine = ladrp, width = 1}, {angle = 1e308, angle_step = -1e308}), "angle 1e308: a plan")

-- the options table is not modified, and other tables are left alone
local opts = {width = 1, cut = "floor"}
model:slice(opts)
T.ok(opts.width == 1 and opts.cut == "floor" and next(opts, next(opts, next(opts))) == nil, "options untouched")

-- metamethods called directly, twice, and on the wrong object
local mt = getmetatable(plan)
T.ok(pcall(mt.__len, plan), "__len direct")
T.ok(not pcall(mt.__len, model), "__len on a model")
T.ok(not pcall(mt.__gc, model), "__gc of a plan on a model")
T.is(select("#", getmetatable(model).__index(model)), 0, "__index without a key")
T.is(getmetatable(model).__index(model, 42), nil, "__index with a number key")
T.is(model[true], nil, "model[true]")
T.raises("attempt to index", "assigning a field", function() model.volume = 1 end)

-- the debug library swapping user values is survived, not trusted
local c2 = layers[2]:contour(2)
debug.setuservalue(c2, 42, 1)
T.raises("attempt to use a collected lamina.contour", "contour whose layer was replaced", function() return c2.area end)
T.like(tostring(c2), "collected", "tostring of that contour")
local l2 = model:slice{width = 1}[2]
debug.setuservalue(l2, "nope", 1)
T.raises("collected", "layer whose run was replaced", function() return l2:frame() end)
T.is(l2.z, 1.5, "its own data still reads")
local l3 = model:slice{width = 1}[1]
debug.setuservalue(l3, {42, "x"}, 2)
local ok = pcall(l3.contours, l3)
T.ok(ok ~= nil, "layer with a forged contour cache")
local d2 = ladrp:override{angle = 1}
debug.setuservalue(d2, sls, 1)
T.raises("attempt to use a collected lamina.machine", "derived machine whose owner was replaced",
         function() return d2.angle end)

-- ... and so is a userdata given another lamina type's metatable (giving
-- one io's file metatable crashes Lua's own io library: not tried)
local victims = {model, layer, contour, ladrp, plan}
local mts = {}
for _, v in ipairs(victims) do mts[#mts + 1] = debug.getmetatable(v) end
local survived = 0
for _, v in ipairs{lamina.load(M .. "thesis_cube.ug"), model:slice{width = 1}[1], layer:contour(1),
                   lamina.machine("sls-contours"), sls:plan(layers)} do
  local own = debug.getmetatable(v)
  for _, mt2 in ipairs(mts) do
    debug.setmetatable(v, mt2)
    for name, f in pairs(mt2) do
      if type(f) == "function" then pcall(f, v, "z", 1) end
    end
    local idx = mt2.__index
    if type(idx) == "function" then
      for _, key in ipairs{"volume", "z", "area", "name", "text", "contours", "slice", "plan", "close"} do
        local ok, f = pcall(idx, v, key)
        if ok and type(f) == "function" then pcall(f, v, {}) end
      end
    end
    survived = survived + 1
  end
  debug.setmetatable(v, own)
end
T.is(survived, 25, "userdata with another type's metatable are refused")
T.raises("corrupt lamina.model", "a layer with the model metatable", function()
  local l = model:slice{width = 1}[1]
  debug.setmetatable(l, getmetatable(model))
  return l.volume
end)

T.done()
