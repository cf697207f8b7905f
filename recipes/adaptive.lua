-- adaptive.lua: adaptive layer widths by cusp height (Dolenc and Makela).
--
--   lamina run recipes/adaptive.lua [--cusp H] [--min W] [--max W]
--                                   [--axis A] [--list] [--allow-open] [MODEL]
--
-- A layer of width w leaves a stair step ("cusp") of height w * |n.axis| on
-- a triangle with unit normal n that it crosses. Each layer is made as wide
-- as it can be, at most --max (0.5), while no triangle it crosses gets a cusp
-- above --cusp (0.05), and never narrower than --min (0.02). The recipe
-- slices MODEL (recipes/parts/sphere.obj) with those widths and compares the
-- layer count with the widest uniform slicing whose measured worst cusp is
-- no worse than adaptive's (flat faces that miss the uniform grid count: a
-- face across the axis inside a layer leaves a cusp of the layer's width).
-- --axis: x, y, z (default), -z, ... or a direction dx,dy,dz. --list prints
-- every layer: index, floor, ceiling, width. --allow-open slices a mesh that
-- is not closed, dropping the outlines that stay open (counted and said);
-- without it such a mesh (one that repair on load did not close: model.closed
-- false) stops the recipe with a message and exit 1: the slicer's when an
-- outline stays open, else the count of open edges.
-- Load options (as `lamina slice` takes them; docs/cli.md): --units U (the
-- model's units, converted to mm), --scale F|FX,FY,FZ, --rotate
-- A:D[,A:D...], --translate X,Y,Z, --place plate, --no-repair.
local args = require "lamina.args"
local axes = require "lamina.axes"
local adaptive = require "lamina.adaptive"

local o, fail, die, need = args.parse(arg, {
  usage = "lamina run recipes/adaptive.lua [--cusp H] [--min W] [--max W] [--axis A]"
    .. " [--list] [--allow-open] [MODEL]"
    .. args.LOAD_USAGE,
  options = args.with_load{
              cusp = 0.05, min = 0.02, max = 0.5, axis = "z", list = false, allow_open = false,
              model = args.beside(arg, "parts/sphere.obj") },
  positive = { "cusp", "min", "max" },
  positional = { "model" },
})
local function load(path, machine) return args.load(o, path, machine, fail, die) end
if o.min > o.max then fail("--min (%g) is greater than --max (%g)", o.min, o.max) end
local axis, why = axes.parse(o.axis)
if not axis then fail("--axis: %s", why) end
local model = load(o.model)

local facets = axes.facets(model, axis)
if #model == 0 or not (facets.hi > facets.lo) then
  die("%s has no extent along %s (%d triangles): no layer to make", o.model, axis.name, #model)
end
local widths = adaptive.cusp_widths(facets, o)
local planes = adaptive.planes(facets.lo, widths)
local worst = adaptive.worst_cusp(facets, planes)
-- an open mesh (one that repair on load did not close, or --no-repair):
-- the slicer's message when a layer's outline stays open, else this one;
-- either way a message and exit 1, not a run on a part that is not solid
local open_mesh = ("the mesh is not closed (%d boundary edges%s); --allow-open slices it, dropping the"
  .. " outlines that stay open"):format(model.boundary_edges, o.no_repair and ", --no-repair" or "")
local layers, serr = model:slice{axis = axis.slice, widths = widths, allow_open = o.allow_open}
if not layers then die("%s%s", serr, model.closed and "" or "; " .. open_mesh) end
if not model.closed and not o.allow_open then die("%s: %s", o.model, open_mesh) end
if #layers ~= #widths then die("%s: %d layers for %d widths", o.model, #layers, #widths) end
local open, open_layers = 0, 0
for _, l in ipairs(layers) do
  open = open + (l.open or 0)
  if (l.open or 0) > 0 then open_layers = open_layers + 1 end
end

local uniform, why = adaptive.uniform(facets, worst, o.max)

local wlo, whi = math.huge, 0
for _, w in ipairs(widths) do wlo, whi = math.min(wlo, w), math.max(whi, w) end
print(("model: %s (%d triangles), axis %s, span %.6g .. %.6g"):format(
  o.model, #model, axis.name, facets.lo, facets.hi))
print(("cusp %g, widths in [%g, %g]"):format(o.cusp, o.min, o.max))
if open > 0 then
  print(("open mesh: %d outlines stayed open in %d layers and were dropped (--allow-open)"):format(
    open, open_layers))
end
print(("adaptive: %d layers, worst cusp %.6g, widths %.6g .. %.6g"):format(
  #widths, worst, wlo, whi))
if uniform then
  print(("uniform: %d layers of %.6g, worst cusp %.6g"):format(
    uniform.layers, uniform.width, uniform.worst))
  local st = uniform.steepest
  if st.width ~= uniform.width then
    print(("  (at the width the sloped facets allow, %.6g, uniform takes %d layers but leaves a cusp of %.6g"
      .. " at flat faces off its grid: not the same worst cusp)"):format(st.width, st.layers, st.worst))
  end
  print(("adaptive uses %.1f%% fewer layers than uniform at the same worst cusp"):format(
    100 * (1 - #widths / uniform.layers)))
else
  print(("uniform: none with worst cusp %.6g (%s)"):format(worst, why))
end
if worst > o.cusp * (1 + 1e-9) then
  print(("note: --min %g breaks the cusp limit where the surface is nearly flat"):format(o.min))
end
if o.list then
  for i, l in ipairs(layers) do
    print(("layer %d %.9g %.9g %.9g"):format(i, l.floor, l.ceiling, l.width))
  end
end
