-- aligned.lua: layer boundaries on every flat face ("areas of significance").
--
--   lamina run recipes/aligned.lua [--min W] [--max W] [--axis A] [MODEL]
--
-- A layer must not hold two heights of the model's top or bottom faces (the
-- thesis, section 7.4), so every face across the axis (|n.axis| = 1 up to
-- 1e-9) gets a layer boundary. Between two such heights the layers are
-- equal and as few as keep them at most --max (0.5) wide; an interval
-- shorter than --min (0.1) is one layer, and the recipe says so. MODEL
-- defaults to recipes/parts/terrace.ug; --axis is x, y, z (default),
-- -z, ... or dx,dy,dz. Prints the flat heights and the planes, and slices
-- with them to check that every flat height is a layer floor or ceiling.
-- Load options (as `lamina slice` takes them; docs/cli.md): --units U (the
-- model's units, converted to mm), --scale F|FX,FY,FZ, --rotate
-- A:D[,A:D...], --translate X,Y,Z, --place plate, --no-repair.
local args = require "lamina.args"
local axes = require "lamina.axes"
local adaptive = require "lamina.adaptive"

local o, fail, die, need = args.parse(arg, {
  usage = "lamina run recipes/aligned.lua [--min W] [--max W] [--axis A] [MODEL]"
    .. args.LOAD_USAGE,
  options = args.with_load{
              min = 0.1, max = 0.5, axis = "z",
              model = args.beside(arg, "parts/terrace.ug") },
  positive = { "min", "max" },
  positional = { "model" },
})
local function load(path, machine) return args.load(o, path, machine, fail, die) end
if o.min > o.max then fail("--min (%g) is greater than --max (%g)", o.min, o.max) end
local axis, why = axes.parse(o.axis)
if not axis then fail("--axis: %s", why) end
local model = load(o.model)

local facets = axes.facets(model, axis)
local flats = adaptive.flat_heights(facets)
local planes, short = adaptive.aligned_planes(facets, o.min, o.max)
local layers = need(model:slice{axis = axis.slice, planes = planes})

local function list(t)
  local s = {}
  for i, h in ipairs(t) do s[i] = ("%.6g"):format(h) end
  return table.concat(s, " ")
end
print(("model: %s (%d triangles), axis %s"):format(o.model, #model, axis.name))
print(("flat heights: %d: %s"):format(#flats, list(flats)))
print(("planes: %d: %s"):format(#planes, list(planes)))
for _, s in ipairs(short) do
  print(("note: %.6g .. %.6g is narrower than --min %g: one layer"):format(s[1], s[2], o.min))
end

-- every flat height must be a boundary of the sliced layers
local tol = 1e-9 * math.max(1, facets.hi - facets.lo)
local missing = 0
for _, h in ipairs(flats) do
  local found = false
  for _, l in ipairs(layers) do
    found = found or math.abs(l.floor - h) <= tol or math.abs(l.ceiling - h) <= tol
  end
  if not found then
    missing = missing + 1
    print(("flat height %.6g is inside a layer"):format(h))
  end
end
print(("layers: %d, every flat height on a boundary: %s"):format(
  #layers, missing == 0 and "yes" or "no"))
if missing > 0 then os.exit(1) end
