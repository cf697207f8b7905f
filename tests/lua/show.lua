-- lamina.show.value (lua/lamina/show.lua, what `lamina repl` prints for a
-- table): key order, quoting, numbers, metatables, limits and bounds. The
-- expected texts follow lua/API.md's rules, written out by hand.
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local show = require "lamina.show"
local v = show.value

-- order: the array part, then numbers, strings (byte order), booleans
T.is(v({"a", "b", [5] = 0, [-1] = 0, zeta = 1, Alpha = 2, [true] = 3, [false] = 4, _x = 5}, {width = 200}),
     '{"a", "b", [-1] = 0, [5] = 0, Alpha = 2, _x = 5, zeta = 1, [false] = 4, [true] = 3}',
     "array part first, then numbers, strings, booleans, sorted")
T.is(v({[1] = 1, [3] = 3}), "{1, [3] = 3}", "the array part stops at the first nil")
T.is(v({["end"] = 1, ["1x"] = 2, ["a.b"] = 3}), '{["1x"] = 2, ["a.b"] = 3, ["end"] = 1}',
     "keys that are not names (a keyword too) are bracketed")
T.is(v({}), "{}", "an empty table")
T.is(v({{}}, {depth = 1}), "{{}}", "an empty table is {} even past the depth")

-- numbers
T.is(v({1, 2.0, -3.0, 0.1, 1 / 3, 1e20, 2 ^ 53, 1 / 0, -1 / 0, 0 / 0}),
     "{1, 2, -3, 0.1, 0.333333, 1e+20, 9.0072e+15, inf, -inf, nan}",
     "integers as integers, others %.6g, inf and nan")
T.is(v(math.mininteger), tostring(math.mininteger), "the smallest integer")

-- strings
T.is(v("a\"b\\c\n\t\0\127"), '"a\\"b\\\\c\\n\\t\\000\\127"', "escapes in a string")
T.is(v("\255x"), '"\\255x"', "a byte of no UTF-8 character is escaped")
T.is(v("é"), '"é"', "UTF-8 text stays as it is")
T.is(v(("é"):rep(10), {string = 5}), '"éé"... (20 bytes)', "a string is cut at a whole character")
T.is(v({["k" .. ("y"):rep(100)] = 1}, {string = 4}), '{["kyyy"... (101 bytes)] = 1}', "a long key is cut too")

-- metatables
local named = setmetatable({1}, {__name = "thing"})
T.like(v(named), "^thing: ", "a table with __name is what tostring makes of it")
T.is(v({setmetatable({}, {__tostring = function() return "T!" end})}), "{T!}", "__tostring inside a table")
T.like(v({setmetatable({}, {__tostring = function() error("boom", 0) end})}), "^{<tostring failed: boom>}$",
       "a failing __tostring does not raise")
local hidden = setmetatable({x = 1}, {__metatable = false, __index = function() error("ran") end,
                                     __pairs = function() error("ran") end})
T.is(v(hidden), "{x = 1}", "read raw: no __index, no __pairs")
local layers = T.lamina.load(T.M .. "thesis_cube.ug"):slice{width = 1}
T.like(v({layers}), "^{2 layers of thesis_cube%.ug, z %-1 %.%. 1}$", "a layer list inside a table: its summary")
T.like(v(T.lamina.load(T.M .. "thesis_cube.ug")), "^lamina%.model ", "a userdata: its __tostring")

-- depth, items, keys, cycles
T.is(v({a = {b = {1, 2, 3}}}), "{a = {b = {...3}}}", "depth 2: the third level is {...N}")
T.is(v({a = {b = {1, 2, 3}}}, {depth = 3}), "{a = {b = {1, 2, 3}}}", "depth 3 shows it")
local big = {}
for i = 1, 2000 do big[i] = i end
T.is(v({big}, {depth = 1}), "{{...1000+}}", "the count of {...N} stops at 1000")
T.is(v({1, 2, 3, a = 1, b = 2, c = 3}, {items = 2, keys = 1}), "{1, 2, ... (1 more), a = 1, ... (2 more keys)}",
     "items and keys limits, with the counts of the rest")
local a, b = {}, {}
a.b, b.a = b, a
T.is(v(a, {depth = 5}), "{b = {a = <cycle>}}", "a cycle of two tables")
local shared = {1}
T.is(v({shared, shared}), "{{1}, {1}}", "a table met twice but not inside itself is shown twice")

-- layout and bounds
local row = {}
for i = 1, 30 do row[i] = i end
local text = v(row, {items = 30, width = 20})
for line in text:gmatch("[^\n]+") do
  T.ok(#line <= 20, "width 20: '" .. line .. "'")
end
T.is(text:gsub("%s+", " "), "{ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, }",
     "and every item once, in order")
local many = {}
for i = 1, 100 do many[i] = ("%03d"):format(i) .. ("x"):rep(70) end
text = v(many, {items = 100, bytes = 1000})
T.ok(#text <= 1000, "at most `bytes` bytes (" .. #text .. ")")
T.like(text, "\n%.%.%. %(%d+ more lines%)$", "and says what was left out")
local _, nl = v(many, {items = 100, lines = 10}):gsub("\n", "")
T.is(nl + 1, 10, "at most `lines` lines")

-- limits
T.raises("unknown limit 'deep'", "an unknown limit is an error", v, {}, {deep = 1})
T.raises("depth must be a number >= 1", "a limit below 1 is an error", v, {}, {depth = 0})
T.raises("table expected, got string", "limits must be a table", v, {}, "x")
T.is(show.limits.depth, 2, "show.limits holds the defaults")

T.done()
