-- scan_orders.lua: LADRP raster orders compared by stage travel.
--
--   lamina run recipes/scan_orders.lua [--machine NAME] [--width W] [MODEL]
--
-- Plans MODEL (recipes/parts/pillars.ug: four pillars, four islands per
-- layer) on an LADRP machine (--machine, creol-ladrp) with layers --width
-- wide (0, the default: the machine's layer width) in six ways: the raster at 0 degrees in
-- every layer, alternating 0/90, and turning 67.5 degrees per layer; each
-- with whole scan lines across the layer (boustrophedon) and with the
-- islands rastered one after another, the nearest next (islands = true).
-- Prints the travel (moves with the laser off), the deposit length and
-- moves, and the travel against the plain boustrophedon (0 degrees, whole
-- lines).
-- Load options (as `lamina slice` takes them; docs/cli.md): --units U (the
-- model's units, converted to the machine's units), --scale F|FX,FY,FZ, --rotate
-- A:D[,A:D...], --translate X,Y,Z, --place plate, --no-repair.
local args = require "lamina.args"

local o, fail, die, need = args.parse(arg, {
  usage = "lamina run recipes/scan_orders.lua [--machine NAME] [--width W] [MODEL]"
    .. args.LOAD_USAGE,
  options = args.with_load{
              machine = "creol-ladrp", width = 0, model = args.beside(arg, "parts/pillars.ug") },
  positional = { "model" },
})
local function load(path, machine) return args.load(o, path, machine, fail, die) end
local machine, err = lamina.machine(o.machine)
if not machine then die("%s", err) end
if machine.process ~= "ladrp" then
  fail("%s is an %s machine, not ladrp", o.machine, machine.process)
end
if o.width < 0 then fail("--width must be 0 (the machine's) or more, got %g", o.width) end
local model = load(o.model, machine)
local layers = need(model:slice{machine = machine, width = o.width > 0 and o.width or nil})

-- raster angles: the first layer's is 0, each next one turns by the step
local orders = { { "0", 0 }, { "0/90", 90 }, { "+67.5", 67.5 } }
local solids = 0
for _, l in ipairs(layers) do
  for _, c in ipairs(l:contours()) do
    if c.solid then solids = solids + 1 end
  end
end
print(("model: %s, %d layers, %d solid contours, machine %s (bead %g)"):format(
  o.model, #layers, solids, machine.name, machine.bead_width))
print(("%-8s %-14s %12s %12s %8s %9s"):format(
  "angles", "order", "travel", "deposit", "moves", "travel %"))
local plain
for _, order in ipairs(orders) do
  for _, by_island in ipairs{ false, true } do
    local plan = need(machine:plan(layers, {
      angle = 0, angle_step = order[2], alternate = true, islands = by_island }))
    plain = plain or plan.travel
    print(("%-8s %-14s %12.4f %12.4f %8d %8.1f%%"):format(order[1],
      by_island and "islands" or "boustrophedon", plan.travel, plan.deposit,
      plan.deposits, 100 * plan.travel / plain))
  end
end
