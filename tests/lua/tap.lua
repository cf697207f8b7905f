-- A small TAP producer for the Lua tests: ok, is, like, raises, fails, done.
-- Loaded with dofile(TESTS .. "/lua/tap.lua"); tests/cli/lua.t runs the
-- test scripts and passes their results on.
local T = { n = 0, failed = 0 }

local function report(pass, desc, diag)
  T.n = T.n + 1
  print((pass and "ok " or "not ok ") .. T.n .. " - " .. desc)
  if not pass then
    T.failed = T.failed + 1
    if diag then print("#   " .. tostring(diag):gsub("\n", "\n#   ")) end
  end
  return pass
end

function T.ok(cond, desc, diag) return report(not not cond, desc, diag) end

function T.is(got, want, desc)
  return report(got == want, desc, ("got %s, expected %s"):format(tostring(got), tostring(want)))
end

function T.near(got, want, desc, eps)
  eps = eps or 1e-9
  return report(type(got) == "number" and math.abs(got - want) <= eps, desc,
                ("got %s, expected %s"):format(tostring(got), tostring(want)))
end

function T.like(s, pattern, desc)
  return report(type(s) == "string" and s:find(pattern) ~= nil, desc,
                ("%s does not match /%s/"):format(tostring(s), pattern))
end

-- f(...) must raise an error whose message contains `plain` (plain text).
function T.raises(plain, desc, f, ...)
  local ok, err = pcall(f, ...)
  return report(not ok and type(err) == "string" and err:find(plain, 1, true) ~= nil, desc,
                ok and "no error" or ("error: %s (expected '%s')"):format(tostring(err), plain))
end

-- f(...) must return nil and a message matching pattern.
function T.fails(pattern, desc, f, ...)
  local a, b = f(...)
  return report(a == nil and type(b) == "string" and b:find(pattern) ~= nil, desc,
                ("returned %s, %s"):format(tostring(a), tostring(b)))
end

function T.done()
  print("1.." .. T.n)
  os.exit(T.failed == 0 and 0 or 1)
end

-- The module: the global in the executable, require in a stock lua5.4.
T.lamina = rawget(_G, "lamina") or require("lamina")
T.TESTS = assert(os.getenv("TESTS"), "TESTS must name the tests directory")
T.M = T.TESTS .. "/models/"
T.ROOT = T.TESTS .. "/.."

return T
