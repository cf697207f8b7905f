-- lamina.args: the command-line options of a recipe.
--
--   local args = require "lamina.args"
--   local o, fail, die, need = args.parse(arg, {
--     usage = "lamina run recipes/adaptive.lua [--cusp H] [--axis A] [--list] [MODEL]",
--     options = { cusp = 0.05, axis = "z", list = false, model = "recipes/parts/x.ug" },
--     positive = { "cusp" },     -- numbers that must be > 0
--     positional = { "model" },  -- names the words after the options fill, in order
--   })
--   if o.cusp > 1 then fail("--cusp must be at most 1, got %g", o.cusp) end
--
-- An option is `--name VALUE` or `--name=VALUE`; its default gives its type
-- (a number must read as a finite number). An option whose default is a
-- boolean is a flag: `--name` sets it true (`--name=false` clears it).
-- A dash in a name is an underscore in the table (`--w-stair` is
-- `o.w_stair`). Words that do not start with `-` (and everything after
-- `--`) fill the positional names; a positional name is an option too
-- (`--model FILE`). `--help` prints the usage and exits with 0.
--
-- Every mistake raises an error object (a table printing as "RECIPE:
-- MESSAGE" and the usage, with `exit = 2`): `lamina run` prints it without
-- a traceback and exits with 2, as for the command line's own usage
-- errors. `fail` (the second result) raises one for the recipe's own checks
-- of its options; `die` (the third) raises "RECIPE: MESSAGE" without the
-- usage and exits with 1, for inputs that do not load. `need` (the fourth)
-- takes a lamina call's results: the value when there is one, else `die`
-- with the call's message (`local layers = need(model:slice{...})`), in
-- place of `assert`, which would print a traceback. A stock `lua` prints
-- them without a traceback too.
--
-- args.with_load(options) adds the load options (`lamina slice`'s --units,
-- --scale, --rotate, --translate, --place, --no-repair; docs/cli.md) to a
-- spec's options, args.LOAD_USAGE is their usage text, and
-- args.load(o, path, machine, fail, die) loads a model with them: a bad
-- value is `fail` (exit 2), a file that does not load `die` (exit 1).
--
-- args.beside(arg, "parts/x.ug") is a path beside the running recipe
-- ("recipes/parts/x.ug" for `lamina run recipes/y.lua`): default models
-- that work from any directory.
local args = {}

args.LOAD_USAGE = " [--units U] [--scale F] [--rotate A:D] [--translate X,Y,Z] [--place plate] [--no-repair]"

local LOAD_DEFAULTS = { units = "", scale = "", rotate = "", translate = "", place = "", no_repair = false }

function args.with_load(options)
  for k, v in pairs(LOAD_DEFAULTS) do
    if options[k] == nil then options[k] = v end
  end
  return options
end

function args.load(o, path, machine, fail, die)
  local function given(v) if v ~= "" then return v end end
  local ok, model, err = pcall(lamina.load, path, {
    units = given(o.units), scale = given(o.scale), rotate = given(o.rotate), translate = given(o.translate),
    place = given(o.place), repair = not o.no_repair, machine = machine })
  if not ok then fail("%s", tostring(model):match("%((.*)%)$") or tostring(model)) end
  if not model then die("%s", err) end
  return model
end

function args.beside(argv, rel)
  local dir = argv and argv[0] and tostring(argv[0]):match("^(.*)/")
  return dir and dir .. "/" .. rel or rel
end

-- An error object: prints as its message; `lamina run` exits with `exit`.
local Failure = { __tostring = function(e) return e.message end }

local function raise(message, exit)
  error(setmetatable({ message = message, exit = exit }, Failure), 0)
end

local function script_name(argv)
  local s = argv and argv[0] or "recipe"
  return (tostring(s):match("[^/]+$"))
end

function args.parse(argv, spec)
  local name, usage = script_name(argv), spec.usage or ""
  local function message(fmt, ...)
    return name .. ": " .. (select("#", ...) > 0 and fmt:format(...) or fmt)
  end
  local function fail(fmt, ...) raise(message(fmt, ...) .. "\nusage: " .. usage, 2) end
  local function die(fmt, ...) raise(message(fmt, ...), 1) end
  local function need(v, err, ...)
    if v == nil or v == false then die("%s", tostring(err or "failed")) end
    return v, err, ...
  end
  local o = {}
  for k, v in pairs(spec.options or {}) do o[k] = v end
  local function set(key, value, shown)
    local default = spec.options[key]
    if type(default) == "number" then
      local n = tonumber(value)
      if not n or n ~= n or n == math.huge or n == -math.huge then
        fail("%s expects a number, got '%s'", shown, value)
      end
      o[key] = n
    elseif type(default) == "boolean" then
      if value ~= "true" and value ~= "false" then
        fail("%s is a flag (true or false), got '%s'", shown, value)
      end
      o[key] = value == "true"
    else
      o[key] = value
    end
  end

  local words, i, n = {}, 1, #argv
  while i <= n do
    local a = argv[i]
    if a == "--" then
      for j = i + 1, n do words[#words + 1] = argv[j] end
      break
    elseif a == "--help" or a == "-h" then
      print("usage: " .. usage)
      os.exit(0)
    elseif a:sub(1, 2) == "--" then
      local key, value = a:match("^%-%-([^=]+)=(.*)$")
      key = (key or a:sub(3)):gsub("-", "_")
      local shown = "--" .. key:gsub("_", "-")
      if spec.options[key] == nil then fail("unknown option %s", shown) end
      if value then
        set(key, value, shown)
      elseif type(spec.options[key]) == "boolean" then
        o[key] = true
      else
        if i == n then fail("%s needs a value", shown) end
        i = i + 1
        set(key, argv[i], shown)
      end
    elseif a:sub(1, 1) == "-" and a ~= "-" and not tonumber(a) then
      fail("unknown option %s", a)
    else
      words[#words + 1] = a
    end
    i = i + 1
  end

  local positional = spec.positional or {}
  if #words > #positional then
    fail("unexpected argument '%s'", words[#positional + 1])
  end
  for j, w in ipairs(words) do set(positional[j], w, positional[j]:upper()) end
  for _, key in ipairs(spec.positive or {}) do
    if o[key] <= 0 then fail("--%s must be greater than 0, got %g", key:gsub("_", "-"), o[key]) end
  end
  return o, fail, die, need
end

return args
