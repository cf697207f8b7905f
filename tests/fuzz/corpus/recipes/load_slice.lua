local m = assert(lamina.load("thesis_cube_hole.ug"))
local layers = assert(m:slice{width = 0.5})
for _, L in ipairs(layers) do
  for _, c in ipairs(L:contours()) do
    for u, v in c:points() do local x, y, z = L:to_model(u, v) end
    c:contains(0, 0); c:bbox(); c:children()
  end
  L:bbox(); L:open_ends(); L:frame()
end
print(#layers, m:bbox())
