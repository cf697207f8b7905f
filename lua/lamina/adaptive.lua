-- lamina.adaptive: layer boundaries that follow the geometry.
--
--   local axes, adaptive = require "lamina.axes", require "lamina.adaptive"
--   local f = axes.facets(model, axes.parse("z"))
--   local widths = adaptive.cusp_widths(f, { cusp = 0.05, min = 0.02, max = 0.5 })
--   local planes = adaptive.planes(f.lo, widths)
--   print(adaptive.worst_cusp(f, planes))
--   local aligned, short = adaptive.aligned_planes(f, 0.02, 0.5)
--
-- The facets are those of lamina.axes.facets: per triangle its span lo..hi
-- along the axis and k = |n.axis|. The cusp height of a layer of width w at
-- a triangle it crosses is w * k (Dolenc and Makela, "Slicing procedures for
-- layered manufacturing techniques", 1994): 0 for a wall, w for a face
-- across the axis.
--
-- adaptive.cusp_widths(facets, {cusp=, min=, max=}) -> { width, ... }
--   Layers from facets.lo up, each as wide as it can be (at most max) while
--   every triangle it crosses keeps w * k <= cusp, but never narrower than
--   min (where min * k > cusp the cusp limit is broken: worst_cusp tells).
--   A layer stops just under a face that would limit it, when that is at
--   least min above its floor, so flat faces tend to land on boundaries.
--   The last layer ends at facets.hi (or is min wide). One sweep over the
--   triangles sorted by lo, with a heap of those still crossing the current
--   height: O(T log T + S) for T triangles and S layers.
--
-- adaptive.planes(from, widths) -> { from, from + w1, ... }
--
-- adaptive.worst_cusp(facets, planes) -> cusp, facet
--   The largest w * k over the triangles and the layers they cross (a face
--   across the axis lying on a boundary crosses none). O(T log S + S log S).
--
-- adaptive.uniform(facets, cusp, max) -> { width, layers, worst, steepest } | nil, why
--   The widest uniform slicing (from facets.lo, at most max wide) whose
--   measured worst cusp is at most `cusp`, so the two are compared at equal
--   worst cusp: the steepest sloped facet's width cusp / k when every face
--   across the axis lands on a layer boundary there; else the widest
--   narrower width that puts them all on boundaries, or cusp itself (a flat
--   face inside a layer of w leaves a cusp of w). `steepest` is the slicing
--   at the steepest sloped facet's width, whatever flat faces it misses
--   ({ width, layers, worst }). nil and why when no width reaches `cusp`
--   (cusp 0 with sloped facets, or flat faces no grid aligns).
--
-- adaptive.flat_heights(facets) -> { h, ... }
--   The heights of the faces across the axis (k = 1 up to 1e-9), sorted,
--   equal ones (up to 1e-9 of the span) once.
--
-- adaptive.aligned_planes(facets, min, max) -> planes, short
--   Boundaries at facets.lo, facets.hi and every flat height; each interval
--   between two of them split into the fewest equal layers of at most max.
--   `short` lists the intervals { from, to } that are narrower than min (one
--   layer each).
local adaptive = {}

adaptive.FLAT = 1e-9

local function tolerance(facets)
  return 1e-9 * math.max(1, facets.hi - facets.lo)
end

-- a binary max-heap of facets by k
local function push(heap, f)
  local i = #heap + 1
  heap[i] = f
  while i > 1 do
    local p = i // 2
    if heap[p].k >= f.k then break end
    heap[i], heap[p] = heap[p], f
    i = p
  end
end

local function pop(heap)
  local n = #heap
  local last = heap[n]
  heap[n] = nil
  n = n - 1
  if n == 0 then return end
  local i = 1
  heap[1] = last
  while true do
    local c = 2 * i
    if c > n then break end
    if c < n and heap[c + 1].k > heap[c].k then c = c + 1 end
    if heap[c].k <= last.k then break end
    heap[i], heap[c] = heap[c], last
    i = c
  end
end

function adaptive.cusp_widths(facets, opts)
  local cusp, wmin, wmax = opts.cusp, opts.min, opts.max
  assert(cusp > 0 and wmin > 0 and wmin <= wmax, "need cusp > 0 and 0 < min <= max")
  local eps = tolerance(facets)
  local sorted = {}
  for _, f in ipairs(facets) do
    if f.k > 0 then sorted[#sorted + 1] = f end -- walls never limit a layer
  end
  table.sort(sorted, function(p, q) return p.lo < q.lo end)

  local widths, heap, h, top, i, n = {}, {}, facets.lo, facets.hi, 1, #sorted
  while top - h > eps do
    -- the triangles that start at or below h cross the layer unless they end there
    while i <= n and sorted[i].lo <= h + eps do push(heap, sorted[i]); i = i + 1 end
    while heap[1] and heap[1].hi <= h + eps do pop(heap) end
    local w = wmax
    if heap[1] then w = math.max(wmin, math.min(w, cusp / heap[1].k)) end
    -- the triangles that start inside the layer: stop under one, or narrow the layer
    for j = i, n do
      local f = sorted[j]
      if f.lo >= h + w - eps then break end
      local limit = cusp / f.k
      if limit < w then
        local under = f.lo - h
        if under >= wmin and under >= limit then w = under; break end
        w = math.max(limit, wmin)
      end
    end
    if h + w >= top - eps then w = math.max(top - h, wmin) end
    widths[#widths + 1] = w
    h = h + w
  end
  return widths
end

function adaptive.planes(from, widths)
  local planes, h = { from }, from
  for i, w in ipairs(widths) do
    h = h + w
    planes[i + 1] = h
  end
  return planes
end

-- first index i with planes[i] > x (#planes + 1 if none)
local function upper(planes, x)
  local lo, hi = 1, #planes + 1
  while lo < hi do
    local mid = (lo + hi) // 2
    if planes[mid] > x then hi = mid else lo = mid + 1 end
  end
  return lo
end

function adaptive.worst_cusp(facets, planes)
  local eps, S = tolerance(facets), #planes - 1
  if S < 1 then return 0 end
  -- sparse table: best[j][i] = widest layer among i .. i + 2^(j-1) - 1
  local best = { {} }
  for i = 1, S do best[1][i] = planes[i + 1] - planes[i] end
  local j, span = 1, 1
  while 2 * span <= S do
    local prev, row = best[j], {}
    for i = 1, S - 2 * span + 1 do row[i] = math.max(prev[i], prev[i + span]) end
    j, span = j + 1, 2 * span
    best[j] = row
  end
  local function widest(a, b)
    local level, len = 1, 1
    while 2 * len <= b - a + 1 do level, len = level + 1, 2 * len end
    return math.max(best[level][a], best[level][b - len + 1])
  end

  local worst, at = 0, nil
  for _, f in ipairs(facets) do
    if f.k > 0 then
      -- layers i with planes[i+1] > lo and planes[i] < hi (open overlap)
      local a = upper(planes, f.lo + eps) - 1 -- the first layer whose ceiling is above lo
      local b = upper(planes, f.hi - eps) - 1 -- the last whose floor is below hi
      if a < 1 then a = 1 end
      if b > S then b = S end
      if a <= b then
        local c = widest(a, b) * f.k
        if c > worst then worst, at = c, f end
      end
    end
  end
  return worst, at
end

-- the offsets from lo of the flat heights above it
local function flat_offsets(facets)
  local eps, out = tolerance(facets), {}
  for _, h in ipairs(adaptive.flat_heights(facets)) do
    if h - facets.lo > eps then out[#out + 1] = h - facets.lo end
  end
  return out
end

-- every flat height on the grid lo + i * w
local function aligned(offsets, w, eps)
  for _, d in ipairs(offsets) do
    local k = math.floor(d / w + 0.5)
    if math.abs(d - k * w) > eps then return false end
  end
  return true
end

local function uniform_at(facets, width)
  local n = math.max(1, math.ceil((facets.hi - facets.lo) / width - 1e-9))
  local planes = {}
  for i = 0, n do planes[i + 1] = facets.lo + i * width end
  return { width = width, layers = n, worst = adaptive.worst_cusp(facets, planes) }
end

adaptive.MAX_GRID_TRIES = 100000

function adaptive.uniform(facets, cusp, wmax)
  local kmax = 0
  for _, f in ipairs(facets) do
    if f.k < 1 - adaptive.FLAT and f.k > kmax then kmax = f.k end
  end
  if kmax > 0 and not (cusp > 0) then
    return nil, "no uniform width leaves no cusp on a sloped facet"
  end
  -- the steepest sloped facet's width: what a flat face off its grid spoils
  local w0 = math.min(kmax > 0 and cusp / kmax or wmax, wmax)
  local steepest = uniform_at(facets, w0)
  local eps, offsets = tolerance(facets), flat_offsets(facets)
  local width = w0
  if not aligned(offsets, w0, eps) and w0 > cusp then
    -- the widest w < w0 that puts every flat face on the grid, as long as
    -- it is wider than cusp (at cusp, a flat face inside a layer leaves
    -- exactly cusp)
    width = nil
    local d1 = offsets[1]
    local m = math.ceil(d1 / w0 - 1e-9)
    for _ = 1, adaptive.MAX_GRID_TRIES do
      local w = d1 / m
      if w <= cusp then break end
      if w < w0 and aligned(offsets, w, eps) then width = w; break end
      m = m + 1
    end
    width = width or (cusp > 0 and cusp or nil)
    if not width then return nil, "no uniform width puts every flat face on a layer boundary" end
  end
  local u = width == w0 and steepest or uniform_at(facets, width)
  u.steepest = steepest
  return u
end

function adaptive.flat_heights(facets)
  local eps, hs = tolerance(facets), {}
  for _, f in ipairs(facets) do
    if f.k >= 1 - adaptive.FLAT then hs[#hs + 1] = (f.lo + f.hi) / 2 end
  end
  table.sort(hs)
  local out = {}
  for _, h in ipairs(hs) do
    if not out[1] or h - out[#out] > eps then out[#out + 1] = h end
  end
  return out
end

function adaptive.aligned_planes(facets, wmin, wmax)
  local eps = tolerance(facets)
  local stops = { facets.lo }
  for _, h in ipairs(adaptive.flat_heights(facets)) do
    if h - stops[#stops] > eps and facets.hi - h > eps then stops[#stops + 1] = h end
  end
  stops[#stops + 1] = facets.hi
  local planes, short = { facets.lo }, {}
  for i = 1, #stops - 1 do
    local from, to = stops[i], stops[i + 1]
    local n = math.max(1, math.ceil((to - from) / wmax - 1e-9))
    if to - from < wmin then short[#short + 1] = { from, to } end
    for k = 1, n - 1 do planes[#planes + 1] = from + (to - from) * k / n end
    planes[#planes + 1] = to
  end
  return planes, short
end

return adaptive
