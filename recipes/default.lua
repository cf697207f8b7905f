-- default.lua: the default job, programs and a preview of one part.
--
--   lamina run recipes/default.lua [--out DIR] [--sls-width W] [MODEL]
--
-- Slices MODEL (recipes/parts/thesis_cube_hole.ug) along z twice: with the
-- LADRP profile creol-ladrp (its layer width and cut) and with the SLS
-- profile sls-contours (layers --sls-width wide, 0.25, floor cut). Writes
-- into --out (out/, created if missing), named after the model:
--   NAME.ladrp   the LADRP program
--   NAME.sls     the SLS program
--   NAME.svg     a contact sheet of the SLS layers (lamina.preview)
-- and prints the layers, contours, program sizes and paths.
-- Load options (as `lamina slice` takes them; docs/cli.md): --units U (the
-- model's units, converted to each machine's units), --scale F|FX,FY,FZ, --rotate
-- A:D[,A:D...], --translate X,Y,Z, --place plate, --no-repair.
local args = require "lamina.args"

local o, fail, die, need = args.parse(arg, {
  usage = "lamina run recipes/default.lua [--out DIR] [--sls-width W] [MODEL]"
    .. args.LOAD_USAGE,
  options = args.with_load{
              out = "out", sls_width = 0.25,
              model = args.beside(arg, "parts/thesis_cube_hole.ug") },
  positive = { "sls_width" },
  positional = { "model" },
})
local function load(path, machine) return args.load(o, path, machine, fail, die) end
local model = load(o.model)
local name = o.model:match("([^/]+)$"):gsub("%.[^.]*$", "")
need(lamina.mkdir(o.out))

print(("%s: %d triangles, %d shells, volume %.6g"):format(
  o.model, #model, model.shells, model.volume))
local function job(profile, slicing, ext)
  local machine = need(lamina.machine(profile))
  slicing.machine = machine
  -- --units converts into each machine's units (creol-ladrp's are cm)
  local m = o.units ~= "" and load(o.model, machine) or model
  local layers = need(m:slice(slicing))
  local plan = need(machine:plan(layers))
  local path = ("%s/%s.%s"):format(o.out, name, ext)
  need(plan:write(path))
  local contours = 0
  for _, l in ipairs(layers) do contours = contours + #l end
  print(("%-12s %4d layers  %5d contours  %7d lines  %8d bytes  %s"):format(
    profile, #layers, contours, plan.lines, plan.bytes, path))
  return layers
end
job("creol-ladrp", {}, "ladrp")
local sls = job("sls-contours", { width = o.sls_width, cut = "floor" }, "sls")
local sheet = ("%s/%s.svg"):format(o.out, name)
need(lamina.preview(sls, sheet, "lamina: " .. o.model))
print(("%-12s %4d layers  %s"):format("preview", #sls, sheet))
