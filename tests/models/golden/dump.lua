-- Every field of a plan and of each plan:layer(i), keys sorted, numbers
-- with 17 digits: the golden corpus's view of Lua's plan data.
--   lamina run dump.lua MACHINE THREADS MODEL [STRATEGY]
local machine, threads, model, strategy = arg[1], tonumber(arg[2]), arg[3], arg[4]
local m = lamina.machine(machine)
local opts = {threads = threads}
if m.process == "sls" then
  opts.hatch_strategy = strategy or "lines"
  opts.skin_layers = 2
  opts.island_size = 0.8
  opts.speed, opts.jump_speed, opts.recoat_time = 800, 3000, 4
end
local layers = lamina.load(model):slice{machine = m, width = 0.25}
local plan = assert(m:plan(layers, opts))
local out = {}
local function put(v, indent)
  local t = type(v)
  if t == "number" then
    out[#out + 1] = math.type(v) == "integer" and tostring(v) or string.format("%.17g", v)
  elseif t ~= "table" then
    out[#out + 1] = string.format("%q", tostring(v))
  else
    local keys = {}
    for k in pairs(v) do keys[#keys + 1] = k end
    table.sort(keys, function(a, b)
      if type(a) == type(b) then return a < b end
      return type(a) == "number"
    end)
    out[#out + 1] = "{\n"
    for _, k in ipairs(keys) do
      out[#out + 1] = indent .. "  " .. tostring(k) .. " = "
      put(v[k], indent .. "  ")
      out[#out + 1] = "\n"
    end
    out[#out + 1] = indent .. "}"
  end
end
local fields = {}
for _, k in ipairs{"lines", "bytes", "layers", "machine", "process", "binary",
                   "travel", "deposit", "deposits", "time"} do
  fields[k] = plan[k]
end
put(fields, "")
out[#out + 1] = "\n"
for i = 1, plan.layers do
  put(plan:layer(i), "")
  out[#out + 1] = "\n"
end
io.write(table.concat(out))
