-- lamina.axes: build directions and the facets of a model seen along one.
--
--   local axes = require "lamina.axes"
--   local axis = assert(axes.parse("z"))      -- also "-x", "1,1,1"
--   m:slice{axis = axis.slice, width = 0.1}
--   local f = axes.facets(m, axis)
--   print(f.lo, f.hi, #f, f[1].k)
--
-- axes.parse(text) -> axis | nil, message
--   text is x, y, z, -x, -y, -z or a direction "dx,dy,dz". An axis is
--   { name = text, dir = unit {x, y, z}, slice = what model:slice takes as
--   `axis` ("x", "y", "z" for the named axes, so that layers use the
--   documented frames, else the direction) }.
--
-- axes.candidates(more) -> { axis, ... }
--   z, x, y; with `more` also -z, -x, -y (the part upside down) and the
--   four body diagonals.
--
-- axes.facets(model, axis) -> facets
--   One entry per triangle: { lo, hi, k, d, area, a, b, c } where lo..hi is
--   the triangle's span along the axis, d = n.axis for the unit outward
--   normal n (-1 faces straight down, 1 straight up), k = |d|, area its area
--   and a, b, c its vertices. A degenerate triangle has area 0 and d = 0.
--   The list also has fields lo, hi: the model's span along the axis.
--
-- axes.measures(facets, width [, overhang_deg]) -> { height, layers, stair, overhang }
--   What building along the axis costs: the height and the number of layers
--   of `width`; the stair-step error, the volume between the surface and
--   its layers, sum of area * |n.axis| * width / 2 over the sloped triangles
--   (walls have none; faces across the axis are taken to sit on a boundary,
--   as recipes/aligned.lua puts them); and the overhang, the area of the
--   triangles facing down more steeply than overhang_deg (45) from the
--   build plate (n.axis < -cos(overhang_deg)) other than those on the plate.
local axes = {}

local FLAT = 1e-9

local named = {
  x = { 1, 0, 0 }, y = { 0, 1, 0 }, z = { 0, 0, 1 },
}

function axes.parse(text)
  text = tostring(text)
  local sign, letter = text:match("^([+-]?)([xyz])$")
  if letter then
    local d = named[letter]
    if sign ~= "-" then return { name = letter, dir = d, slice = letter } end
    local dir = { -d[1], -d[2], -d[3] }
    return { name = text, dir = dir, slice = dir }
  end
  local x, y, z = text:match("^%s*([^,]+),([^,]+),([^,]+)%s*$")
  x, y, z = tonumber(x), tonumber(y), tonumber(z)
  if not (x and y and z) then
    return nil, ("axis must be x, y, z, -x, -y, -z or dx,dy,dz, got '%s'"):format(text)
  end
  local len = math.sqrt(x * x + y * y + z * z)
  if not (len > 0 and len < math.huge) then
    return nil, ("axis direction must be finite and not zero, got '%s'"):format(text)
  end
  local dir = { x / len, y / len, z / len }
  return { name = text, dir = dir, slice = dir }
end

function axes.candidates(more)
  local list = {}
  local names = { "z", "x", "y" }
  if more then
    for _, n in ipairs{ "-z", "-x", "-y", "1,1,1", "-1,1,1", "1,-1,1", "1,1,-1" } do
      names[#names + 1] = n
    end
  end
  for i, n in ipairs(names) do list[i] = assert(axes.parse(n)) end
  return list
end

function axes.facets(model, axis)
  local ax, ay, az = axis.dir[1], axis.dir[2], axis.dir[3]
  local list, lo, hi = {}, math.huge, -math.huge
  for _, a, b, c in model:triangles() do
    local ha = a[1] * ax + a[2] * ay + a[3] * az
    local hb = b[1] * ax + b[2] * ay + b[3] * az
    local hc = c[1] * ax + c[2] * ay + c[3] * az
    local ux, uy, uz = b[1] - a[1], b[2] - a[2], b[3] - a[3]
    local vx, vy, vz = c[1] - a[1], c[2] - a[2], c[3] - a[3]
    local nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    local len = math.sqrt(nx * nx + ny * ny + nz * nz)
    local d = len > 0 and (nx * ax + ny * ay + nz * az) / len or 0
    local f = {
      lo = math.min(ha, hb, hc), hi = math.max(ha, hb, hc),
      d = d, k = math.abs(d), area = len / 2, a = a, b = b, c = c,
    }
    list[#list + 1] = f
    if f.lo < lo then lo = f.lo end
    if f.hi > hi then hi = f.hi end
  end
  list.lo, list.hi = lo, hi
  return list
end

function axes.measures(facets, width, overhang_deg)
  local cos = math.cos(math.rad(overhang_deg or 45))
  local height = facets.hi - facets.lo
  local plate = facets.lo + 1e-9 * math.max(1, height)
  local m = { height = height, layers = math.max(1, math.ceil(height / width - 1e-9)),
              stair = 0, overhang = 0 }
  for _, f in ipairs(facets) do
    if f.k < 1 - FLAT then m.stair = m.stair + f.area * f.k * width / 2 end
    if f.d < -cos and f.hi > plate then m.overhang = m.overhang + f.area end
  end
  return m
end

return axes
