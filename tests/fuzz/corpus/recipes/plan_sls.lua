local m = assert(lamina.load("frame_island.ug"))
local mc = assert(lamina.machine("sls-contours"))
local layers = assert(m:slice{axis = {1, 1, 2}, width = 2})
local p = assert(mc:plan(layers))
print(#p:text())
for i = 1, m:triangles() and 3 or 0 do local a, b, c, s = m:triangle(i) end
print(m:shell(1).volume)
