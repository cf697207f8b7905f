-- hatching.lua: powder-bed scan strategies compared on one part.
--
--   lamina run recipes/hatching.lua [--machine NAME] [--width W] [--distance H] [--skins N] [MODEL]
--
-- Plans MODEL (recipes/parts/frame_island.ug: the thesis's frame with its
-- island) on an SLS machine (--machine, lpbf-cli) with layers --width wide
-- (1; 0: the machine's layer width), hatch distance --distance (0, the
-- default: the machine's) and skins --skins layers deep (-1, the default:
-- the machine's), with each strategy: lines (meander,
-- unidirectional, greedy), stripes and islands (sequential, checker,
-- random), and one recipe-made order (the machine's lines, each layer
-- scanned from its last vector back to its first). Prints per strategy the
-- number of hatch vectors, their total length, the jump length (between
-- vectors and contour passes) and the
-- estimated build time (exposure + jumps + recoating; the machine's speeds).
-- Load options (as `lamina slice` takes them; docs/cli.md): --units U (the
-- model's units, converted to the machine's units), --scale F|FX,FY,FZ, --rotate
-- A:D[,A:D...], --translate X,Y,Z, --place plate, --no-repair.
local args = require "lamina.args"

local o, fail, die, need = args.parse(arg, {
  usage = "lamina run recipes/hatching.lua [--machine NAME] [--width W] [--distance H] [--skins N] [MODEL]"
    .. args.LOAD_USAGE,
  options = args.with_load{
              machine = "lpbf-cli", width = 1, distance = 0, skins = -1,
              model = args.beside(arg, "parts/frame_island.ug") },
  positional = { "model" },
})
local function load(path, machine) return args.load(o, path, machine, fail, die) end
local machine, err = lamina.machine(o.machine)
if not machine then die("%s", err) end
if machine.process ~= "sls" then fail("%s is an %s machine, not sls", o.machine, machine.process) end
if o.width < 0 then fail("--width must be 0 (the machine's) or more, got %g", o.width) end
if o.distance < 0 then fail("--distance must be 0 (the machine's) or more, got %g", o.distance) end
if o.skins < -1 or o.skins ~= math.floor(o.skins) then
  fail("--skins must be -1 (the machine's) or a whole number of layers, got %g", o.skins)
end
local model = load(o.model, machine)
local layers = need(model:slice{machine = machine, width = o.width > 0 and o.width or nil})
local h = o.distance > 0 and o.distance or machine.hatch_distance
local skins = o.skins >= 0 and math.tointeger(o.skins) or machine.skin_layers

local strategies = {
  { "lines", { hatch_strategy = "lines", hatch_order = "meander" } },
  { "lines unidirectional", { hatch_strategy = "lines", hatch_order = "unidirectional" } },
  { "lines greedy", { hatch_strategy = "lines", hatch_order = "greedy" } },
  { "stripes", { hatch_strategy = "stripes" } },
  { "islands sequential", { hatch_strategy = "islands", island_order = "sequential" } },
  { "islands checker", { hatch_strategy = "islands", island_order = "checker" } },
  { "islands random", { hatch_strategy = "islands", island_order = "random" } },
  { "lines, recipe order", { hatch_strategy = "lines",
      order = function(vectors)
        local r = {}
        for i = #vectors, 1, -1 do r[#r + 1] = vectors[i] end
        return r
      end } },
}
print(("model: %s, %d layers, machine %s (hatch distance %g, %s)"):format(
  o.model, #layers, machine.name, h, skins > 0 and "skins " .. skins .. " layers deep" or "no skins"))
print(("%-22s %9s %12s %12s %11s"):format("strategy", "vectors", "length", "jumps", "time s"))
for _, s in ipairs(strategies) do
  local opts = { hatch_distance = h, skin_layers = skins }
  for k, v in pairs(s[2]) do opts[k] = v end
  local plan = need(machine:plan(layers, opts))
  local t = plan.time
  print(("%-22s %9d %12.3f %12.3f %11.3f"):format(s[1], t.vectors, t.hatched, t.jumped, t.total))
end
