-- Every machine-profile key, walked from the key table (lamina.machine_keys):
-- a value given in YAML loads into the machine, `machine:yaml()` (what
-- `lamina machines --show` prints) loads again as the same profile, and the
-- same value through `lamina machines --show --set KEY=VALUE` and through
-- machine:override gives the same YAML; a bad value gets the same message
-- from the YAML loader and from --set. Needs $LAMINA (the executable).
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina = T.lamina
local LAMINA = assert(os.getenv("LAMINA"), "LAMINA must name the executable")
-- quoted for the shell: the checkout's path may hold spaces
local LAMINA_SH = "'" .. LAMINA:gsub("'", "'\\''") .. "'"

local function write(path, text)
  local f = assert(io.open(path, "w"))
  f:write(text)
  f:close()
end

local function sh(cmd)
  local p = assert(io.popen(cmd .. " 2>&1"))
  local out = p:read("a")
  local ok = p:close()
  return out, ok
end

local function strip(yaml) return (yaml:gsub("#[^\n]*\n", "")) end

local function fmt(v)
  if math.type(v) == "float" then return ("%.17g"):format(v) end
  return tostring(v)
end

-- A list key's value as YAML flow text and as Lua sees it.
local LISTS = {
  numbers = function(k)
    local t, v = {}, {}
    for i = 1, k.count do t[i], v[i] = "12.5", 12.5 end
    return v, "[" .. table.concat(t, ", ") .. "]"
  end,
  lasers = function() return { { field = { 0, 0, 12.5, 12.5 } } }, "[{field: [0, 0, 12.5, 12.5]}]" end,
}

-- Two values the same, tables by their contents.
local function same(a, b)
  if type(a) ~= "table" or type(b) ~= "table" then return a == b end
  for key, x in pairs(a) do if not same(x, b[key]) then return false end end
  for key in pairs(b) do if a[key] == nil then return false end end
  return true
end

-- A value of the key's type, in its range and not its default.
local function sample(k)
  if LISTS[k.type] then return LISTS[k.type](k) end
  if k.type == "number" then
    if k.min == -math.huge then return 12.5 end
    if k.max == math.huge then return k.min + 0.375 end
    return (k.min + k.max) / 2 + 0.25
  elseif k.type == "integer" then
    return math.tointeger(k.min + 7)
  elseif k.type == "boolean" then
    return k.default ~= "true"
  elseif k.type == "choice" or k.choices then -- a choice, or text that is one of some names (units)
    return k.choices[#k.choices] ~= k.default and k.choices[#k.choices] or k.choices[1]
  else
    return (k.type == "template" and "T-" or "s-") .. k.lua:gsub("^.*%.", "")
  end
end

-- key: value in YAML, in its section
local function yaml_line(k, text)
  local section, short = k.name:match("^(.-)%.(.*)$")
  if k.type == "string" or k.type == "template" then text = ('"%s"'):format(text) end
  if section then return ("%s:\n  %s: %s\n"):format(section, short, text) end
  return ("%s: %s\n"):format(k.name, text)
end

-- A key of one planner (its text starts "ladrp:" or "sls") is given to a
-- profile of that planner's process: the other's refuses it (keys.t).
local function planner(k)
  return k.doc and (k.doc:match("^ladrp:") and "ladrp" or k.doc:match("^sls[:,]") and "sls") or "ladrp"
end
local BASES = { ladrp = "inherits: creol-ladrp\n", sls = "inherits: cli-ascii\n" }
-- a plate's width and depth go together: the other of the two
local PARTNER = { ["plate.width"] = "depth", ["plate.depth"] = "width" }
local function base_with(k, line)
  -- process: sls on the ladrp base needs a spot width
  if PARTNER[k.name] then line = line .. "  " .. PARTNER[k.name] .. ": 1\n" end
  return BASES[planner(k)] .. (k.name == "process" and "spot_width: 0.2\n" or "") .. line
end
-- what --set needs besides the key (after it: the values are checked together)
local function set_extra(k)
  if PARTNER[k.name] then return " --set plate." .. PARTNER[k.name] .. "=1" end
  return k.name == "process" and " --set spot_width=0.2" or ""
end
-- what override needs besides the key
local function override_with(k, v)
  local t = { [k.lua] = v }
  if PARTNER[k.name] then t["plate." .. PARTNER[k.name]] = 1 end
  return t
end
write("base-ladrp.yaml", BASES.ladrp)
write("base-sls.yaml", BASES.sls)
local bases = { ladrp = assert(lamina.machine("base-ladrp.yaml")), sls = assert(lamina.machine("base-sls.yaml")) }

local keys = lamina.machine_keys()
T.ok(#keys >= 20, "machine_keys lists the table", #keys)
local walked = 0
for _, k in ipairs(keys) do
  if not k.loader then
    walked = walked + 1
    local v, listed = sample(k)
    local base, bfile = bases[planner(k)], "base-" .. planner(k) .. ".yaml"
    local text = listed or fmt(v)
    local file = k.name .. ".yaml"
    write(file, base_with(k, yaml_line(k, text)))
    local m, err = lamina.machine(file)
    if not T.ok(m, k.name .. ": YAML loads", err) then goto next end
    T.ok(same(m[k.lua], v), k.name .. ": YAML -> machine." .. k.lua, m[k.lua])
    local dump = m:yaml()
    write("dump-" .. file, dump)
    local again = lamina.machine("dump-" .. file)
    T.ok(again and same(again[k.lua], v) and strip(again:yaml()) == strip(dump),
         k.name .. ": the dump (machines --show) loads again as the same profile")
    local shown = sh(("%s machines --show %s --set '%s=%s'%s"):format(LAMINA_SH, bfile, k.name, text, set_extra(k)))
    T.is(strip(shown), strip(dump), k.name .. ": --set gives the same profile as YAML")
    if k.fixed or listed then -- a list is given in the profile or with --set
      T.raises("cannot be changed here", k.name .. ": override refuses it", base.override, base, {[k.lua] = v})
    else
      local ok, o = pcall(base.override, base, override_with(k, v))
      T.ok(ok and strip(o:yaml()) == strip(dump), k.name .. ": override gives the same profile as YAML", o)
      -- machine:plan reads its options before it refuses an empty layer list
      local _, perr = pcall(base.plan, base, {}, {[k.lua] = v})
      T.like(perr, k.plan and "no layers to plan" or "not a planning option",
             k.name .. (k.plan and ": an option of machine:plan" or ": not an option of machine:plan"))
    end
    -- a bad value: the same message from YAML and from --set
    if k.type ~= "string" then
      local bad = k.type == "template" and "{bogus}" or "abc"
      write("bad-" .. file, base_with(k, yaml_line(k, bad)))
      local _, yerr = lamina.machine("bad-" .. file)
      local ymsg = yerr and yerr:match("%.yaml:%d+:%d+: (.*)$")
      local out, ok = sh(("%s machines --show %s --set '%s=%s'"):format(LAMINA_SH, bfile, k.name, bad))
      local smsg = out:match(": %-%-set [^\n]-=[^\n]-: ([^\n]*)")
      T.ok(not ok and ymsg and smsg and smsg:sub(1, #ymsg) == ymsg,
           k.name .. ": a bad value, the same message from YAML and --set", ("%s | %s"):format(yerr, out))
    end
    ::next::
  end
end
T.ok(walked == #keys - 1, "every key but inherits walked", walked)
local out, ok = sh(LAMINA_SH .. " machines --show base-ladrp.yaml --set inherits=x")
T.ok(not ok and out:find("inherits is only read while a profile loads", 1, true), "--set inherits is refused", out)
T.done()
