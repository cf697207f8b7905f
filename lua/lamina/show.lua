-- lamina.show: a Lua value as a readable, bounded summary (what `lamina
-- repl` prints for a table).
--
--   local show = require "lamina.show"
--   print(show.value(plan.time))
--   print(show.value(plan:layer(5), {depth = 3, lines = 100}))
--
-- show.value(v [, limits]) -> string
--   A table as `{1, 2, key = value, ...}`: the array part (1, 2, ... up to
--   the first nil) first and in order, then the other keys sorted (numbers,
--   then strings, then booleans, then any other key in the order `next`
--   gives); a key that is a short name is bare, any other `[key]`. Tables are read raw: no metamethod of theirs runs, except that
--   a table or userdata whose metatable has `__tostring` or `__name` is
--   shown as `tostring` makes it (a layer list: "12 layers of ..."). A
--   table nested deeper than `depth` is `{...N}`, N its number of entries
--   (`{...1000+}` past 1000); a table inside itself is `<cycle>`. Past
--   `items` array entries "... (K more)" stands for the rest, past `keys`
--   other keys "... (K more keys)". A string is quoted with escapes and
--   cut after `string` bytes ("..." (N bytes)). A number reads as an
--   integer when it is one (2.0 is 2), else with 6 significant digits.
--   What fits in `width` columns is one line; a longer table has one entry
--   (or a run of short ones) per line, indented. The whole is at most
--   `lines` lines and `bytes` bytes: a last line "... (K more lines)" says
--   what was left out. A value that is not a table is shown the same way
--   (a string quoted).
--
-- show.limits: the defaults, {depth = 2, items = 20, keys = 30, string =
-- 60, width = 78, lines = 40, bytes = 4096}; `limits` overrides some (each
-- a number >= 1; math.huge for none). Unknown keys are an error.
local show = {}

show.limits = { depth = 2, items = 20, keys = 30, string = 60, width = 78, lines = 40, bytes = 4096 }

-- captured now: the raw metatable even behind __metatable, whatever a
-- script later does to the debug library
local getmeta = (debug and debug.getmetatable) or getmetatable
local COUNT_MAX = 1000 -- {...N}: counted up to this many entries
local SORT_MAX = 10000 -- more other keys than this are shown unsorted

local reserved = {}
for w in ([[and break do else elseif end false for function goto if in
  local nil not or repeat return then true until while]]):gmatch("%a+") do reserved[w] = true end

local function has_text(v)
    local mt = getmeta(v)
    return type(mt) == "table" and (rawget(mt, "__tostring") ~= nil or rawget(mt, "__name") ~= nil)
end

-- the first n bytes of s, not ending inside a UTF-8 sequence
local function cut_utf8(s, n)
    if #s <= n then return s end
    local k = n
    while k > 0 and k > n - 3 and (s:byte(k + 1) or 0) >= 0x80 and (s:byte(k + 1) or 0) < 0xC0 do k = k - 1 end
    return s:sub(1, k)
end

local escapes = { ["\\"] = "\\\\", ['"'] = '\\"', ["\n"] = "\\n", ["\r"] = "\\r", ["\t"] = "\\t" }

local function quote(s, limit)
    local part = cut_utf8(s, limit)
    -- control bytes escaped; bytes >= 128 too unless s is UTF-8 text
    local pattern = utf8.len(s) and '[%c"\\]' or '[%c"\\\128-\255]'
    local q = part:gsub(pattern, function(c) return escapes[c] or ("\\%03d"):format(c:byte()) end)
    if #part < #s then return ('"%s"... (%d bytes)'):format(q, #s) end
    return '"' .. q .. '"'
end

local function number(x)
    if math.type(x) == "integer" then return ("%d"):format(x) end
    if x ~= x then return "nan" end
    if x == math.huge then return "inf" end
    if x == -math.huge then return "-inf" end
    local i = math.tointeger(x)
    if i and math.abs(x) < 2 ^ 53 then return ("%d"):format(i) end
    return ("%.6g"):format(x)
end

-- tostring that never raises, cut to a bounded length
local function text_of(v, limit)
    local ok, s = pcall(tostring, v)
    if not ok then return "<tostring failed: " .. cut_utf8(tostring(s), limit) .. ">" end
    if #s > 2 * limit then return cut_utf8(s, 2 * limit) .. "..." end
    return s
end

local function count(t)
    local n = 0
    for _ in next, t do
        n = n + 1
        if n >= COUNT_MAX then return COUNT_MAX .. "+" end
    end
    return tostring(n)
end

local function atom(v, o)
    local ty = type(v)
    if ty == "string" then return quote(v, o.string) end
    if ty == "number" then return number(v) end
    if ty == "table" and not has_text(v) then return next(v) == nil and "{}" or "{..." .. count(v) .. "}" end
    return text_of(v, o.string)
end

local function key_text(k, o)
    if type(k) == "string" and #k <= o.string and k:match("^[%a_][%w_]*$") and not reserved[k] then return k end
    return "[" .. atom(k, o) .. "]"
end

local rank = { number = 1, string = 2, boolean = 3 }

-- the keys of t other than its array part 1..n, sorted; and their number
local function other_keys(t, n)
    local keys, order, total = {}, {}, 0
    for k in next, t do
        if not (math.type(k) == "integer" and k >= 1 and k <= n) then
            total = total + 1
            if total <= SORT_MAX then
                keys[total] = k
                order[k] = total
            end
        end
    end
    if total <= SORT_MAX then
        table.sort(keys, function(a, b)
            local ra, rb = rank[type(a)] or 4, rank[type(b)] or 4
            if ra ~= rb then return ra < rb end
            if ra == 3 then return not a and b end
            if ra == 4 then return order[a] < order[b] end
            return a < b
        end)
    end
    return keys, total
end

-- The tree of what is shown: {prefix, atom} or {prefix, items}.
local function node_of(v, level, path, o, prefix)
    if type(v) ~= "table" or has_text(v) or next(v) == nil then return { prefix = prefix, atom = atom(v, o) } end
    if path[v] then return { prefix = prefix, atom = "<cycle>" } end
    if level > o.depth then return { prefix = prefix, atom = atom(v, o) } end
    path[v] = true
    local items, n = {}, 0
    while rawget(v, n + 1) ~= nil do n = n + 1 end
    for i = 1, math.min(n, o.items) do items[#items + 1] = node_of(rawget(v, i), level + 1, path, o) end
    if n > o.items then items[#items + 1] = { atom = ("... (%d more)"):format(n - o.items), note = true } end
    local keys, total = other_keys(v, n)
    for j = 1, math.min(#keys, o.keys) do
        local k = keys[j]
        items[#items + 1] = node_of(rawget(v, k), level + 1, path, o, key_text(k, o) .. " = ")
    end
    if total > o.keys then
        local unsorted = total > SORT_MAX and ", unsorted" or ""
        items[#items + 1] = { atom = ("... (%d more keys%s)"):format(total - o.keys, unsorted), note = true }
    end
    path[v] = nil
    return { prefix = prefix, items = items }
end

-- the node on one line, or nil when that is longer than budget
local function flat(node, budget)
    local head = node.prefix or ""
    if node.atom then return head .. node.atom end
    local parts, len = {}, #head + 2
    for i, it in ipairs(node.items) do
        local s = flat(it, budget - len)
        if not s then return nil end
        len = len + #s + (i > 1 and 2 or 0)
        if len > budget then return nil end
        parts[i] = s
    end
    return head .. "{" .. table.concat(parts, ", ") .. "}"
end

local function layout(node, indent, width, out)
    local s = flat(node, width - #indent)
    if s and #indent + #s <= width or node.atom then
        out[#out + 1] = indent .. (s or (node.prefix or "") .. node.atom)
        return
    end
    out[#out + 1] = indent .. (node.prefix or "") .. "{"
    local inner, line = indent .. "  ", nil
    for _, it in ipairs(node.items) do
        -- an entry that fits on a line joins a run of them
        local one = flat(it, width - #inner - 1)
        local piece = one and #inner + #one < width and one .. (it.note and "" or ",")
        if piece and line and #line + 1 + #piece <= width then
            line = line .. " " .. piece
        else
            if line then out[#out + 1] = line end
            line = piece and inner .. piece
            if not piece then
                layout(it, inner, width, out)
                out[#out] = out[#out] .. ","
            end
        end
    end
    if line then out[#out + 1] = line end
    out[#out + 1] = indent .. "}"
end

local function limits_of(given)
    local o = {}
    for k, v in pairs(show.limits) do o[k] = v end
    if given == nil then return o end
    if type(given) ~= "table" then error(("bad argument #2 to 'value' (table expected, got %s)"):format(type(given)), 3) end
    for k, v in next, given do
        if o[k] == nil then
            local names = {}
            for name in pairs(show.limits) do names[#names + 1] = name end
            table.sort(names)
            error(("bad argument #2 to 'value' (unknown limit %s (limits: %s))"):format(
                type(k) == "string" and "'" .. k .. "'" or type(k), table.concat(names, ", ")), 3)
        end
        if type(v) ~= "number" or not (v >= 1) then
            error(("bad argument #2 to 'value' (%s must be a number >= 1)"):format(k), 3)
        end
        o[k] = v
    end
    return o
end

function show.value(v, limits)
    local o = limits_of(limits)
    local out = {}
    layout(node_of(v, 1, {}, o), "", o.width, out)
    local total = 0
    for _, line in ipairs(out) do total = total + #line + 1 end
    if #out > o.lines or total > o.bytes then
        -- the longest head that leaves room for the note, within both bounds
        local keep, bytes = 0, 0
        while keep < o.lines - 1 and keep < #out and bytes + #out[keep + 1] + 1 + 32 <= o.bytes do
            keep = keep + 1
            bytes = bytes + #out[keep] + 1
        end
        local left = #out - keep
        for i = #out, keep + 1, -1 do out[i] = nil end
        out[#out + 1] = ("... (%d more lines)"):format(left)
    end
    return table.concat(out, "\n")
end

return show
