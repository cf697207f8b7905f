-- Write a UV sphere as a Wavefront OBJ: lamina run uv_sphere.lua OUT.obj
-- [RADIUS [SEGMENTS [RINGS]]] (defaults 10, 32, 16). Poles on the z axis,
-- faces counter-clockwise seen from outside; quads split into two triangles.
local path = assert(arg[1], "usage: uv_sphere.lua OUT.obj [RADIUS [SEGMENTS [RINGS]]]")
local r, seg, rings = tonumber(arg[2] or 10), tonumber(arg[3] or 32), tonumber(arg[4] or 16)
local f = assert(io.open(path, "w"))
f:write(("# UV sphere: radius %g, %d segments, %d rings\n"):format(r, seg, rings))
local function v(x, y, z) f:write(("v %.9g %.9g %.9g\n"):format(x, y, z)) end
v(0, 0, -r)                                  -- vertex 1: south pole
for i = 1, rings - 1 do                      -- rings from south to north
  local t = math.pi * i / rings - math.pi / 2
  for j = 0, seg - 1 do
    local p = 2 * math.pi * j / seg
    v(r * math.cos(t) * math.cos(p), r * math.cos(t) * math.sin(p), r * math.sin(t))
  end
end
v(0, 0, r)                                   -- the north pole, last
local north = 2 + (rings - 1) * seg
local function at(i, j) return 2 + (i - 1) * seg + j % seg end
for j = 0, seg - 1 do
  f:write(("f 1 %d %d\n"):format(at(1, j + 1), at(1, j)))
  f:write(("f %d %d %d\n"):format(north, at(rings - 1, j), at(rings - 1, j + 1)))
  for i = 1, rings - 2 do
    local a, b, c, d = at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)
    f:write(("f %d %d %d\nf %d %d %d\n"):format(a, b, c, a, c, d))
  end
end
f:close()
