-- machine:plan{threads = N} (issue 15): the same program, figures, layer
-- data and errors for every N, through every shipped machine; the recipe's
-- functions called on the calling thread, once per layer, in order;
-- lamina.threads() and `lamina run -j N` / LAMINA_THREADS.
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M

-- A deterministic dump of a value (keys sorted, numbers to the last bit),
-- so plan:layer(i) tables can be compared whole.
local function dump(v, out)
  out = out or {}
  local t = type(v)
  if t == "table" then
    local keys = {}
    for k in pairs(v) do keys[#keys + 1] = k end
    table.sort(keys, function(a, b)
      if type(a) ~= type(b) then return type(a) < type(b) end
      return a < b
    end)
    out[#out + 1] = "{"
    for _, k in ipairs(keys) do
      out[#out + 1] = tostring(k) .. "="
      dump(v[k], out)
      out[#out + 1] = ","
    end
    out[#out + 1] = "}"
  elseif t == "number" then
    out[#out + 1] = math.type(v) == "integer" and tostring(v) or ("%a"):format(v)
  else
    out[#out + 1] = tostring(v)
  end
  return out
end

-- Everything a plan shows: its text, its fields and every layer's data.
local function whole(plan)
  local parts = { plan:text(), plan.bytes, plan.lines, plan.layers, plan.travel, plan.deposit, plan.deposits }
  local s = table.concat(dump(plan.time))
  for i = 1, plan.layers do s = s .. table.concat(dump(plan:layer(i))) end
  for k = 2, #parts do parts[k] = ("%a"):format(parts[k]) end
  return table.concat(parts, "\n") .. s
end

-- A UV sphere of radius 5 as an ASCII STL: layers of every size, round
-- islands at the poles (the test's own mesh, not lamina's).
local function sphere(path, nu, nv)
  local f = assert(io.open(path, "w"))
  f:write("solid s\n")
  local function p(i, j)
    local th, ph = 2 * math.pi * i / nu, math.pi * j / nv
    return 5 * math.sin(ph) * math.cos(th), 5 * math.sin(ph) * math.sin(th), 5 * math.cos(ph)
  end
  local function tri(a, b, c)
    f:write("facet normal 0 0 0\nouter loop\n")
    for _, q in ipairs{a, b, c} do f:write(("vertex %.17g %.17g %.17g\n"):format(q[1], q[2], q[3])) end
    f:write("endloop\nendfacet\n")
  end
  for j = 0, nv - 1 do
    for i = 0, nu - 1 do
      local a, b, c, d = {p(i, j)}, {p(i + 1, j)}, {p(i + 1, j + 1)}, {p(i, j + 1)}
      if j > 0 then tri(a, d, b) end
      if j < nv - 1 then tri(b, d, c) end
    end
  end
  f:write("endsolid s\n")
  f:close()
end

local tmp = os.tmpname()
sphere(tmp .. ".stl", 24, 12)
local models = {
  { "cube-hole", assert(lamina.load(M .. "thesis_cube_hole.ug")), { width = 0.25 } },
  { "frame-islands", assert(lamina.load(M .. "frame_island.stl")), { width = 2 } },
  { "sphere", assert(lamina.load(tmp .. ".stl")), { width = 0.4 } },
}

-- every shipped machine, each model, threads 1, 2, 3, 8 (and 0: the cores)
local names = lamina.machines()
T.is(#names, 6, "six shipped machines")
for _, name in ipairs(names) do
  local mc = assert(lamina.machine(name))
  local ladrp = mc.process == "ladrp"
  for _, md in ipairs(models) do
    local layers = md[2]:slice{machine = mc, width = md[3].width}
    -- options that make a layer's plan hang on more than the layer: the
    -- stage left by the layer before (islands, perimeters, raster angle
    -- per layer) or the layers around (skins)
    local opts = ladrp and { islands = true, perimeters = 1, angle_step = 30 }
                       or { hatch_strategy = "islands", island_size = 3, hatch_distance = 0.6, skin_layers = 2 }
    local every_other = {}
    for i = 1, #layers, 2 do every_other[#every_other + 1] = layers[i] end
    for _, set in ipairs{ { "all layers", layers }, { "every other layer", every_other } } do
      local want
      for _, n in ipairs{1, 2, 3, 8, 0} do
        local o = { threads = n }
        for k, v in pairs(opts) do o[k] = v end
        local plan = assert(mc:plan(set[2], o))
        local got = whole(plan)
        if n == 1 then
          want = got
          T.ok(plan.layers == #set[2] and #plan:text() > 100, ("%s %s, %s: threads = 1 plans %d layers"):format(
            name, md[1], set[1], plan.layers))
        else
          T.ok(got == want, ("%s %s, %s: threads = %d gives the same program, figures and layers"):format(
            name, md[1], set[1], n))
        end
      end
    end
  end
end

-- The recipe's functions: on the calling thread, every layer once, in
-- order, before planning; the same program as with one thread.
local cli = lamina.machine("cli-ascii")
local sph = models[3][2]:slice{width = 0.4}
local function recipe_plan(threads, fail_at, how)
  local calls = {}
  local plan, msg = cli:plan(sph, {
    threads = threads, hatch_strategy = "lines", hatch_distance = 0.5,
    layer = function(layer, i)
      calls[#calls + 1] = "layer " .. i
      if how == "layer" and i == fail_at then error("no parameters for layer " .. i) end
      -- islands so small (the least island_size) that hatching the layer
      -- is refused: by a worker (plan), or before planning, for `order`
      -- (order-hatch)
      if (how == "plan" or how == "order-hatch") and i == fail_at then
        return { hatch_strategy = "islands", island_size = 1e-6 }
      end
      return { hatch_angle = 17 * i }
    end,
    order = how ~= "plan" and function(vectors, layer, params)
      calls[#calls + 1] = "order " .. params.index
      if how == "order" and params.index == fail_at then return { { 0, 0, 1 } } end
      return vectors
    end or nil,
  })
  return plan, msg, calls
end
local p1, _, calls1 = recipe_plan(1)
local p4, _, calls4 = recipe_plan(4)
local seq = {}
for i = 1, #sph do seq[#seq + 1] = "layer " .. i seq[#seq + 1] = "order " .. i end
T.is(table.concat(calls4, ","), table.concat(seq, ","), "threads = 4: layer and order called for layers 1..n once each, in order")
T.is(table.concat(calls1, ","), table.concat(calls4, ","), "the same calls as with threads = 1")
T.ok(p1 and p4 and whole(p1) == whole(p4), "the recipe's plan is the same with 1 and 4 threads")

-- errors: the same message for 1 and 4 threads, and nothing planned after
local k = math.floor(#sph / 2)
for _, how in ipairs{"layer", "order", "plan", "order-hatch"} do
  local ok1, a1, b1 = pcall(recipe_plan, 1, k, how)
  local ok4, a4, b4 = pcall(recipe_plan, 4, k, how)
  local m1, m4 = ok1 and b1 or a1, ok4 and b4 or a4
  T.ok(not (ok1 and a1) and type(m1) == "string", ("%s fails at layer %d with threads = 1: %s"):format(how, k, tostring(m1)))
  T.is(m4, m1, ("%s fails at layer %d: the same message with threads = 4"):format(how, k))
  T.is(ok4, ok1, ("%s: raised or returned alike"):format(how))
  if how == "plan" or how == "order-hatch" then
    T.ok(ok1 and a1 == nil and m1:find(("layer %d: the hatch distance"):format(sph[k].index), 1, true),
         how .. ": nil and the planner's message for that layer", m1)
  end
end
-- an output limit passed half-way while writing: the estimate takes the
-- plan's hatch distance, 0.4; the recipe's layer function makes it 0.05
-- as the layers are planned (8 times the vectors), so it passes the estimate
local fine = function() return { hatch_distance = 0.05 } end
local function lim(threads, max)
  return cli:plan(sph, {threads = threads, hatch_strategy = "lines", hatch_distance = 0.4, layer = fine, max_output = max})
end
local full = #assert(lim(1)):text()
local n1, e1 = lim(1, full // 2)
local n4, e4 = lim(4, full // 2)
T.ok(n1 == nil and n4 == nil and e1 == e4 and e1:find("output exceeds the limit", 1, true),
     "an output limit reached half-way: nil and the same message with 1 and 4 threads", e4)

-- a sandbox's time limit stops a threaded plan between layers (memory = 0:
-- a sandbox with a memory limit plans on one thread)
local none, terr = lamina.sandbox{code = [[
  local m = lamina.load(...)
  local ladrp = lamina.machine("creol-ladrp")
  local layers = m:slice{machine = ladrp, width = 0.01}
  while true do ladrp:plan(layers, {threads = 4, bead_width = 0.01}) end]],
  args = {M .. "thesis_cube.ug"}, allow = M, time = 0.3, memory = 0}
T.ok(none == nil and terr:find("time limit exceeded", 1, true) and terr:find("in method 'plan'", 1, true),
     "a sandbox's time limit stops a plan on 4 threads", terr)

-- threads' own checks
local lad = lamina.machine("creol-ladrp")
for _, bad in ipairs{ 1.5, -1, 257, "2", true } do
  local ok, msg = pcall(lad.plan, lad, sph, { threads = bad })
  T.ok(not ok and msg:find("threads must be a", 1, true) and msg:find("bad argument #3", 1, true),
       ("threads = %s: an error naming the option"):format(tostring(bad)), msg)
end
T.raises("threads must be a finite number", "threads = nan", lad.plan, lad, sph, { threads = 0 / 0 })
T.ok(lad:plan(sph, { threads = 256 }), "threads = 256 is allowed")
T.ok(lad:plan(sph, { threads = 2.0 }), "threads = 2.0 (a float with a whole value) is allowed")

-- lamina.threads(): the default, from the command line that started the script
T.is(lamina.threads(), tonumber(os.getenv("LAMINA_THREADS") or "1") or 1, "lamina.threads(): LAMINA_THREADS or 1")
local lam = os.getenv("LAMINA")
if lam then
  local script = tmp .. ".lua"
  local f = assert(io.open(script, "w"))
  f:write([[
local out = ...
print(lamina.threads())
local m = assert(lamina.load(os.getenv("TESTS") .. "/models/thesis_cube_hole.ug"))
local cli = lamina.machine("cli-ascii")
local plan = assert(cli:plan(m:slice{width = 0.25}, {hatch_strategy = "lines", hatch_distance = 0.5,
  layer = function(layer, i) if i == 5 and os.getenv("FAIL") then error("no layer 5 today") end end}))
assert(plan:write(out))
]])
  f:close()
  local function run(env, j)
    local out = tmp .. ".out"
    os.remove(out)
    local pipe = assert(io.popen(("%s %q run %s %q %q 2>&1; echo \"exit $?\""):format(env, lam, j, script, out)))
    local text = pipe:read("a")
    pipe:close()
    local fo = io.open(out, "rb")
    local prog = fo and fo:read("a")
    if fo then fo:close() end
    os.remove(out)
    return text, prog
  end
  local o1, prog1 = run("env -u LAMINA_THREADS", "")
  local o3, prog3 = run("env -u LAMINA_THREADS", "-j 3")
  local oe, proge = run("env LAMINA_THREADS=2", "")
  local ob = run("env LAMINA_THREADS=2", "--jobs 5")
  T.like(o1, "^1\nexit 0\n$", "lamina run: lamina.threads() is 1 by default")
  T.like(o3, "^3\nexit 0\n$", "lamina run -j 3: 3")
  T.like(oe, "^2\nexit 0\n$", "LAMINA_THREADS=2: 2")
  T.like(ob, "^5\nexit 0\n$", "--jobs 5 wins over LAMINA_THREADS")
  T.ok(prog1 and prog1 == prog3 and prog1 == proge, "the recipe writes the same program with -j 1, 3 and LAMINA_THREADS=2")
  local f1, fp1 = run("env -u LAMINA_THREADS FAIL=1", "-j 1")
  local f4, fp4 = run("env -u LAMINA_THREADS FAIL=1", "-j 4")
  T.like(f4, "no layer 5 today", "a recipe whose layer function fails: its message")
  T.ok(f1:gsub("^%d\n", "") == f4:gsub("^%d\n", "") and f4:find("exit 1\n$"),
       "the same message and exit status with -j 1 and -j 4", f1 .. "\n---\n" .. f4)
  T.ok(fp1 == nil and fp4 == nil, "no output file when the plan fails")
  T.like(run("env LAMINA_THREADS=x", ""), "LAMINA_THREADS must be a number of threads from 1 to 256 %(got 'x'%).*exit 2",
         "a bad LAMINA_THREADS: a usage error")
  T.like(run("env", "-j 0"), "%-j takes a number of threads from 1 to 256 %(got '0'%).*exit 2", "-j 0: a usage error")
  os.remove(script)
end
os.remove(tmp .. ".stl")
os.remove(tmp)
T.done()
