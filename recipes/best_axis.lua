-- best_axis.lua: choose the build direction.
--
--   lamina run recipes/best_axis.lua [--width W] [--more] [--overhang-deg D]
--        [--w-layers A] [--w-stair B] [--w-overhang C] [MODEL]
--
-- Scores the candidate build directions z, x, y (with --more also -z, -x, -y,
-- i.e. upside down, and the four body diagonals) of MODEL
-- (recipes/parts/thesis_cube_hole.ug) by three costs, each as lamina.axes
-- measures it:
--   layers    the build height over --width (0.1), rounded up: build time
--   stair     stair-step error volume, sum of area * |n.axis| * width / 2
--             over the sloped triangles
--   overhang  area of the triangles facing down within --overhang-deg (45)
--             of straight down, other than those on the build plate
-- Each cost is divided by its largest value over the candidates (0 when
-- all are 0); the score is A * layers + B * stair + C * overhang with the
-- weights --w-layers, --w-stair, --w-overhang (1, 1, 1), and the lowest
-- score wins (on a tie, the candidate listed first). Prints the table and
-- the choice.
-- Load options (as `lamina slice` takes them; docs/cli.md): --units U (the
-- model's units, converted to mm), --scale F|FX,FY,FZ, --rotate
-- A:D[,A:D...], --translate X,Y,Z, --place plate, --no-repair.
local args = require "lamina.args"
local axes = require "lamina.axes"

local o, fail, die = args.parse(arg, {
  usage = "lamina run recipes/best_axis.lua [--width W] [--more] [--overhang-deg D]"
    .. " [--w-layers A] [--w-stair B] [--w-overhang C] [MODEL]"
    .. args.LOAD_USAGE,
  options = args.with_load{
              width = 0.1, more = false, overhang_deg = 45,
              w_layers = 1, w_stair = 1, w_overhang = 1,
              model = args.beside(arg, "parts/thesis_cube_hole.ug") },
  positive = { "width" },
  positional = { "model" },
})
local function load(path, machine) return args.load(o, path, machine, fail, die) end
for _, k in ipairs{ "w_layers", "w_stair", "w_overhang" } do
  if o[k] < 0 then fail("--%s must be 0 or more, got %g", k:gsub("_", "-"), o[k]) end
end
if o.overhang_deg < 0 or o.overhang_deg > 90 then
  fail("--overhang-deg must be between 0 and 90, got %g", o.overhang_deg)
end
local model = load(o.model)

local rows, top = {}, { layers = 0, stair = 0, overhang = 0 }
for i, axis in ipairs(axes.candidates(o.more)) do
  local m = axes.measures(axes.facets(model, axis), o.width, o.overhang_deg)
  m.axis = axis
  rows[i] = m
  for k in pairs(top) do top[k] = math.max(top[k], m[k]) end
end
local function part(m, k) return top[k] > 0 and m[k] / top[k] or 0 end
local best
for _, m in ipairs(rows) do
  m.score = o.w_layers * part(m, "layers") + o.w_stair * part(m, "stair")
          + o.w_overhang * part(m, "overhang")
  if not best or m.score < best.score - 1e-12 then best = m end
end

print(("model: %s, width %g, weights layers %g stair %g overhang %g"):format(
  o.model, o.width, o.w_layers, o.w_stair, o.w_overhang))
print(("%-8s %10s %7s %12s %12s %7s"):format(
  "axis", "height", "layers", "stair", "overhang", "score"))
for _, m in ipairs(rows) do
  print(("%-8s %10.6g %7d %12.6g %12.6g %7.3f"):format(
    m.axis.name, m.height, m.layers, m.stair, m.overhang, m.score))
end
print("best: " .. best.axis.name)
