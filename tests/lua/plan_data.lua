-- plan:layer(i): the plan as data. Every figure is checked against the
-- test's own arithmetic on squares (where each hatch line, deposit and
-- jump is known by reasoning), not against lamina's own geometry code.
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M

local function len(x0, y0, x1, y1) return math.sqrt((x1 - x0) ^ 2 + (y1 - y0) ^ 2) end

-- every operation of a layer in order: contours and vectors, by `order`
local function ops(layer)
  local all = {}
  for _, c in ipairs(layer.contours) do all[c.order] = { c[1], c[2], c[1], c[2], contour = c } end
  for _, v in ipairs(layer.vectors) do all[v.order] = v end
  return all
end

-- the jumps of an SLS layer by the test's own walk: from each path's end
-- (a closed contour ends where it starts) to the next one's start
local function jumps(layer)
  local all, total, prev = ops(layer), 0, nil
  for i = 1, #all do
    local o = all[i]
    if prev then total = total + len(prev[3], prev[4], o[1], o[2]) end
    prev = o
  end
  return total, #all
end

local cube = assert(lamina.load(M .. "thesis_cube.ug"))      -- [-1, 1]^3
local cli = lamina.machine("cli-ascii")
local function sls(order, extra)
  local o = { hatch_strategy = "lines", hatch_distance = 0.25, hatch_angle = 0, hatch_order = order,
              layer_angle_increment = 0, speed = 2, jump_speed = 10 }
  for k, v in pairs(extra or {}) do o[k] = v end
  return cli:plan(cube:slice{width = 2}, o)
end

-- lines at 0 degrees, 0.25 apart: v = -0.875 + 0.25 k, k = 0..7, each across
-- the whole square from u = -1 to 1
local p = sls("meander")
local l = p:layer(1)
T.is(p:layer(2), nil, "a plan of one layer has no layer 2")
T.is(p:layer(0), nil, "nor a layer 0")
T.raises("number expected", "layer(i) wants a number", p.layer, p, "one")
T.is(l.index, 1, "index: the layer's number in its run")
T.is(#l.contours, 1, "one contour pass")
T.is(#l.vectors, 8, "eight hatch vectors")
local c = l.contours[1]
T.ok(c.kind == "solid" and c.depth == 0 and c.order == 1 and #c == 8, "the contour: solid, depth 0, first, 4 points")
local area = 0
for i = 1, #c, 2 do
  local j = i + 2 > #c and 1 or i + 2
  area = area + c[i] * c[j + 1] - c[j] * c[i + 1]
end
T.is(area / 2, 4, "the contour's points enclose the 2 x 2 square, counter-clockwise")
local lines_ok, dep = true, 0
for k, v in ipairs(l.vectors) do
  local want_v = -0.875 + 0.25 * (k - 1)
  lines_ok = lines_ok and v.kind == "core" and v.order == k + 1 and v[2] == want_v and v[4] == want_v
             and math.abs(v[3] - v[1]) == 2 and math.abs(v[1]) == 1
  dep = dep + len(v[1], v[2], v[3], v[4])
end
T.ok(lines_ok, "each hatch line at its own height, across the square, in order after the contour")
T.ok(l.vectors[1][1] == -1 and l.vectors[2][1] == 1, "meander: the second line runs back")
T.is(dep, 16, "hatch length: 8 lines of 2")
T.is(l.deposit, 16 + 8, "layer.deposit: the hatches and the contour's perimeter")
T.is(p.time.hatched, 16, "the plan's hatched length agrees")

-- jumps: contour start (-1, -1) to the first line 0.125 up, then 7 steps of 0.25
local meander_jumps = jumps(l)
T.near(meander_jumps, 0.125 + 7 * 0.25, "meander jumps by the test's walk")
T.near(l.travel, meander_jumps, "layer.travel is the same length")
T.near(l.time, 24 / 2 + meander_jumps / 10, "layer.time: exposure at 2, jumps at 10", 1e-12)
-- unidirectional: every line from u = -1, so each jump goes back across: hypot(2, 0.25)
local u = sls("unidirectional"):layer(1)
local uni_ok = true
for _, v in ipairs(u.vectors) do uni_ok = uni_ok and v[1] == -1 and v[3] == 1 end
T.ok(uni_ok, "unidirectional: every line left to right")
T.near(jumps(u), 0.125 + 7 * math.sqrt(4 + 0.0625), "unidirectional jumps by the test's walk")
T.near(u.travel, jumps(u), "layer.travel agrees")
-- a recipe comparing strategies: total jump length per strategy
local per = {}
for _, strategy in ipairs{"lines", "stripes", "islands"} do
  local plan = cli:plan(cube:slice{width = 0.5}, { hatch_strategy = strategy, hatch_distance = 0.1,
    stripe_width = 0.5, island_size = 0.5 })
  local walk, reported = 0, 0
  for i = 1, plan.layers do
    local ly = plan:layer(i)
    walk = walk + jumps(ly)
    reported = reported + ly.travel
  end
  per[strategy] = walk
  T.near(reported, walk, strategy .. ": the layers' travel is the walk over their vectors", 1e-9)
  T.near(plan.time.jumped, walk, strategy .. ": and the plan's jumped length", 1e-9)
end
T.ok(per.islands > per.lines and per.stripes > per.lines,
     ("stripes (%g) and islands (%g) jump more than plain lines (%g)"):format(per.stripes, per.islands, per.lines))

-- a hole: contours with their kind, holes clockwise
local holed = assert(lamina.load(M .. "thesis_cube_hole.ug"))
local hp = lamina.machine("sls-contours"):plan(holed:slice{width = 1, cut = "floor"})
T.is(hp:layer(1).z, 0, "layer.z: the cut height")
local kinds, areas = {}, {}
for _, cc in ipairs(hp:layer(1).contours) do
  local a = 0
  for i = 1, #cc, 2 do
    local j = i + 2 > #cc and 1 or i + 2
    a = a + cc[i] * cc[j + 1] - cc[j] * cc[i + 1]
  end
  kinds[#kinds + 1] = cc.kind .. cc.depth
  areas[#areas + 1] = a / 2
end
T.is(table.concat(kinds, " "), "solid0 hole1", "solid and hole with their depths")
T.is(table.concat(areas, " "), "4.0 -1.0", "the hole is clockwise (negative shoelace area)")
T.is(#hp:layer(1).vectors, 0, "contours only: no vectors")

-- LADRP: the thesis raster of the cube, bead 0.08 from the top edge down
local ladrp = lamina.machine("creol-ladrp")
local lp = ladrp:plan(cube:slice{machine = ladrp, width = 2})
local ll = lp:layer(1)
local deposits, dlen, tlen, raster_ok, prev_dir = 0, 0, 0, true, nil
local pos
for i, v in ipairs(ll.vectors) do
  raster_ok = raster_ok and v.order == i and (not pos or (v[1] == pos[1] and v[2] == pos[2]))
  pos = { v[3], v[4] }
  if v.kind == "deposit" then
    deposits = deposits + 1
    local want = 1 - 0.08 * (deposits - 1)
    raster_ok = raster_ok and v[2] == v[4] and math.abs(v[2] - want) < 1e-12 and math.abs(v[3] - v[1]) == 2
    local dir = v[3] > v[1]
    raster_ok = raster_ok and dir ~= prev_dir
    prev_dir = dir
    dlen = dlen + len(v[1], v[2], v[3], v[4])
  else
    raster_ok = raster_ok and v.kind == "travel"
    tlen = tlen + len(v[1], v[2], v[3], v[4])
  end
end
T.is(deposits, 25, "LADRP: 25 deposits (v = 1 down to -0.92)")
T.ok(raster_ok, "each move starts where the last ended; deposits across the square, one bead apart, alternating")
T.near(dlen, 50, "deposit length 25 x 2")
T.near(ll.deposit, 50, "layer.deposit")
-- travel: from the origin to one bead above the top left corner, down a bead,
-- then 24 steps of a bead
T.near(tlen, math.sqrt(1 + 1.08 ^ 2) + 0.08 + 24 * 0.08, "travel by the test's arithmetic")
T.near(ll.travel, tlen, "layer.travel")
T.near(lp.travel, tlen, "the plan's travel")
T.is(ll.time, 0, "LADRP: no time estimate")

-- along x, in the model frame: moves come back in the layer frame
local xp = ladrp:plan(cube:slice{machine = ladrp, axis = "x", width = 2})
local inside = true
for _, v in ipairs(xp:layer(1).vectors) do
  if v.kind == "deposit" then
    for q = 1, 4 do inside = inside and v[q] >= -1 - 1e-12 and v[q] <= 1 + 1e-12 end
  end
end
T.ok(inside, "slicing along x: deposits in the layer frame, within the square")
local mp = ladrp:plan(cube:slice{machine = ladrp, axis = "x", width = 2}, { frame = "machine" })
local same = #mp:layer(1).vectors == #xp:layer(1).vectors
for i, v in ipairs(mp:layer(1).vectors) do
  local w = xp:layer(1).vectors[i]
  same = same and v.kind == w.kind and v[1] == w[1] and v[2] == w[2] and v[3] == w[3] and v[4] == w[4]
end
T.ok(same, "the machine frame gives the same layer-frame vectors")

-- a subset of layers: layer.index is the run's
local run = cube:slice{width = 0.5}
local sub = cli:plan({ run[2], run[4] })
T.is(sub:layer(1).index .. "," .. sub:layer(2).index, "2,4", "a subset keeps the run's layer numbers")

-- the tables are copies: they outlive the plan
local kept = sub:layer(2)
sub = nil
collectgarbage(); collectgarbage()
T.is(#kept.contours, 1, "a layer's data outlives its plan")

-- a plan finalized by hand: plan:layer raises
local gone = cli:plan(run)
getmetatable(gone).__gc(gone)
T.raises("attempt to use a collected lamina.plan", "plan:layer on a finalized plan", gone.layer, gone, 1)

T.done()
