-- A sandbox's memory limit counts lamina's own objects (issue 22, item 10):
-- models, slicings and plans share it with Lua's memory; what they hold is
-- given back when they are collected; the error is a clear, catchable Lua
-- error; and what fits is planned exactly as outside the sandbox.
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M
local cube = M .. "thesis_cube.ug" -- 2 x 2 x 2

-- the same program inside a sandbox with a limit (one thread there) as
-- outside on four
local outside = lamina.machine("sls-contours"):plan(lamina.load(cube):slice{width = 0.01}, {threads = 4}):text()
local ok, inside = lamina.sandbox{code = [[
  local m = lamina.load(...)
  return lamina.machine("sls-contours"):plan(m:slice{width = 0.01}, {threads = 4}):text()]],
  args = {cube}, allow = M, memory = 64 * 2^20}
T.ok(ok and inside == outside, "a plan in a sandbox with a memory limit is the program planned outside it")

-- slicing again and again: the slicings let go are collected in time
-- (each is 200 layers of one square: far less than the limit, far more
-- than the limit over 400 of them)
local ok2, n = lamina.sandbox{code = [[
  local m = lamina.load(...)
  local n = 0
  for i = 1, 400 do n = n + #m:slice{width = 0.01} end
  return n]], args = {cube}, allow = M, memory = 4 * 2^20}
T.is(ok2 and n, 400 * 200, "400 slicings let go one after the other fit in 4 MB", n)

-- the error: caught, it names what did not fit; the recipe goes on
local ok3, caught, msg, after = lamina.sandbox{code = [[
  local m = lamina.load(...)
  local keep = {}
  local ok, err = pcall(function() for i = 1, 1e6 do keep[i] = m:slice{width = 0.001} end end)
  local kept = #keep
  keep = nil
  return ok, err, kept > 0 and #m:slice{width = 0.001}]], args = {cube}, allow = M, memory = 8 * 2^20}
T.ok(ok3 and caught == false, "the memory error is a Lua error pcall catches", msg)
-- (whichever allocation passes the limit first: a layer, or Lua's own for
-- the layer's userdata or the list, which says what Lua says)
T.ok(msg == "not enough memory" or msg:find("memory limit exceeded: model:slice of .*thesis_cube%.ug: layer %d+ of " ..
                                            "2000 does not fit %(the recipe's limit is 8388608 bytes"),
     "it says which object did not fit, and the limit", msg)
T.is(after, 2000, "once the slicings are let go, slicing goes on")

-- a slicing whose layers cannot fit even at their least is refused before
-- its schedule is made; without a limit, the layer limit of every slicing
local ok4, err4 = lamina.sandbox{code = [[return #lamina.load(...):slice{width = 2e-5}]], args = {cube}, allow = M,
                                 memory = 2 * 2^20}
T.ok(ok4 == nil, "100,000 layers do not fit in 2 MB")
T.like(err4, "memory limit exceeded: model:slice of .*thesis_cube%.ug would make more than the %d+ layers that fit",
       "refused for its number of layers", err4)
local ok5, n5 = lamina.sandbox{code = [[return #lamina.load(...):slice{width = 1e-6}]], args = {cube}, allow = M,
                               memory = 0}
T.ok(ok5 == nil and n5:find("more than the limit of 1000000", 1, true),
     "(with memory = 0 the usual layer limit speaks)", n5)

-- with the objects gone, their memory is Lua's again: slicings kept until
-- the limit, let go, then a string that needs twice its size while made
local ok6, len = lamina.sandbox{code = [[
  local m = lamina.load(...)
  local keep = {}
  assert(not pcall(function() for i = 1, 1e6 do keep[i] = m:slice{width = 0.001} end end))
  assert(not pcall(string.rep, "x", 3 * 2^20), "no room while the slicings are kept")
  keep = nil
  collectgarbage() -- the finalizers give the layers' memory back
  collectgarbage() -- and their userdata go
  return #("x"):rep(3 * 2^20)]], args = {cube}, allow = M, memory = 16 * 2^20}
T.is(ok6 and len, 3 * 2^20, "the memory of collected objects goes back to Lua (a 3 MB string after 16 MB of slicings)",
     len)

-- a plan's per-layer options from the recipe's `layer` function are held
-- in C for every layer (a couple of kB each) while the plan is made
local function layered(memory)
  return lamina.sandbox{code = [[
    local ls = lamina.load(...):slice{width = 0.001}
    return lamina.machine("sls-contours"):plan(ls, {layer = function() return {} end}).layers]],
    args = {cube}, allow = M, memory = memory}
end
local ok7, err7 = layered(4 * 2^20)
T.ok(ok7 == nil, "per-layer options of 2000 layers do not fit in 4 MB")
T.like(err7, "memory limit exceeded: machine:plan: the layers' hatching options needs %d+ bytes", "and say so", err7)
local ok8, n8 = layered(0)
T.is(ok8 and n8, 2000, "(with memory = 0 they are planned)")

T.done()
