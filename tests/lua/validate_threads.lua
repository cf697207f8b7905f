-- model:validate{threads = N} (issue 15): the layers are checked on N
-- threads and the report is the one a single thread makes, value for value
-- (every number compared to its last bit through %a), on models with a
-- cavity, an island, an oblique axis, a disagreement (overlapping shells
-- under even-odd), and a list mixing layers of two runs along different
-- axes (each worker's section index follows the frame of the layer it is
-- given).
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M

-- the report as text: keys sorted, numbers exact
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
  elseif math.type(v) == "float" then
    out[#out + 1] = string.format("%a", v)
  else
    out[#out + 1] = tostring(v)
  end
  return out
end
local function text(r) return table.concat(dump(r)) end

local holed = assert(lamina.load(M .. "thesis_cube_hole.ug"))
local frame = assert(lamina.load(M .. "frame_island.ug"))
local ov = assert(lamina.load(M .. "validate/overlap_cubes.ug"))

local cases = {
  { "cube with a cavity", holed, { width = 0.3 } },
  { "frame with an island", frame, { width = 0.5, cut = "floor" } },
  { "frame along an oblique axis", frame, { axis = { 1, 1, 2 }, width = 0.7 } },
  { "overlapping cubes, even-odd", ov, { width = 0.25 } },
}
for _, c in ipairs(cases) do
  local name, m, opts = c[1], c[2], c[3]
  local one = m:validate(opts)
  T.ok(#one >= 4 and one.checked > 0, name .. ": threads = 1 checks layers (" .. #one .. ")")
  local want = text(one)
  for _, n in ipairs({ 2, 3, 8 }) do
    local o = {}
    for k, v in pairs(opts) do o[k] = v end
    o.threads = n
    T.is(text(m:validate(o)), want, name .. ": threads = " .. n .. " reports what threads = 1 does")
  end
end
-- the overlap case is a real failure, so the equality above covers the
-- disagreements too
local eo = ov:validate{ width = 0.25, threads = 2 }
T.ok(not eo.ok and eo.disagreeing > 0, "overlapping cubes: disagreements reported with threads = 2")

-- layers of two runs, z and x, interleaved
local z, x = frame:slice{ width = 0.5 }, frame:slice{ axis = "x", width = 0.5 }
local mixed = {}
for i = 1, math.max(#z, #x) do
  if z[i] then mixed[#mixed + 1] = z[i] end
  if x[i] then mixed[#mixed + 1] = x[i] end
end
local want = text(frame:validate{ layers = mixed })
T.ok(#mixed > 10, "a list of " .. #mixed .. " layers along z and x")
T.is(text(frame:validate{ layers = mixed, threads = 2 }), want, "mixed axes, threads = 2")
T.is(text(frame:validate{ layers = mixed, threads = 8 }), want, "mixed axes, threads = 8")
T.is(#frame:validate{ layers = {}, threads = 4 }, 0, "no layers, four threads: an empty report")

T.is(text(holed:validate{ width = 1, threads = 0 }), text(holed:validate{ width = 1, threads = 1 }),
     "threads = 0 (the online cores): the report of one thread")
T.raises("threads must be a whole number from 0 to 256 (0: the online cores), got -1", "threads = -1 is refused",
         holed.validate, holed, { width = 1, threads = -1 })
T.raises("threads must be a whole number from 0 to 256 (0: the online cores), got 1.5", "threads = 1.5 is refused",
         holed.validate, holed, { layers = {}, threads = 1.5 })
T.raises("threads must be a number", "threads = 'two' is refused", holed.validate, holed, { threads = "two" })
T.raises("unknown option 'thread'", "a misspelt key is still caught", holed.validate, holed, { thread = 2 })
T.done()
