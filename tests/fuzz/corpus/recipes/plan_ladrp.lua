local m = assert(lamina.load("thesis_cube_hole.ug"))
local mc = assert(lamina.machine("creol-ladrp"))
local layers = assert(m:slice{width = 0.25, cut = "floor"})
local p = assert(mc:plan(layers, {angle = 30, perimeters = 1}))
local t = p:text()
assert(#t > 0)
local o = mc:override{bead_width = 0.2}
print(o:yaml())
