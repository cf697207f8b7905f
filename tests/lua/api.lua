-- The lamina module's behaviour: models, slicing, layers, contours,
-- machines and plans, against the thesis's samples (SPEC 9, 4.1, 4.2).
-- Runs in `lamina run` and in a stock lua5.4 through the C module.
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M

-- module ---------------------------------------------------------------------
T.like(lamina.version, "^%d+%.%d+%.%d+$", "lamina.version")
for _, f in ipairs{"load", "machine", "machines", "plugin", "writers"} do
  T.is(type(lamina[f]), "function", "lamina." .. f)
end

-- model ----------------------------------------------------------------------
local m = assert(lamina.load(M .. "thesis_cube_hole.ug"))
T.is(m.format, "unigrafix", "format")
T.is(m.path, M .. "thesis_cube_hole.ug", "path")
T.is(#m, 24, "#model = triangles")
T.is(m.ntriangles, 24, "ntriangles")
T.is(m.vertices, 16, "vertices")
T.is(m.edges, 36, "edges")
T.is(m.shells, 2, "shells")
T.is(m.cavities, 1, "cavities")
T.is(m.wires, 0, "wires")
T.is(m.volume, 6, "volume 8 - 2")
T.is(m.area, 34, "surface area: outer box 24, inner box 10")
T.is(m.boundary_edges, 0, "boundary edges")
T.is(m.nonmanifold_edges, 0, "non-manifold edges")
T.is(m.degenerate_triangles, 0, "degenerate triangles")
T.is(m.orientation_conflicts, 0, "orientation conflicts")
T.is(m.closed, true, "closed")
T.is(m.nosuchfield, nil, "unknown field is nil")
T.is(select("#", m:bbox()), 6, "bbox: 6 values")
local bb = {m:bbox()}
T.ok(bb[1] == -1 and bb[2] == -1 and bb[3] == 0 and bb[4] == 1 and bb[5] == 1 and bb[6] == 2, "bbox values")
T.like(tostring(m), "^lamina%.model %(.*thesis_cube_hole%.ug: 24 triangles, 2 shells%)$", "tostring(model)")

local vols = {}
for i = 1, m.shells do vols[#vols + 1] = m:shell(i).volume end
table.sort(vols)
T.ok(vols[1] == -2 and vols[2] == 8, "shell volumes -2 and 8")
T.is(#m:shell(1).bbox, 6, "shell bbox")
T.raises("shell index out of range", "shell(3)", m.shell, m, 3)

local count, shells = 0, {}
for i, a, b, c, s in m:triangles() do
  count = count + 1
  shells[s] = (shells[s] or 0) + 1
  assert(i == count and #a == 3 and #b == 3 and #c == 3)
end
T.is(count, 24, "triangles(): every triangle")
T.ok(shells[1] == 12 and shells[2] == 12, "triangles(): shell of each")
local a1, b1, c1, s1 = m:triangle(24)
T.ok(type(a1[1]) == "number" and s1 == 2, "triangle(24)")
T.raises("triangle index out of range", "triangle(0)", m.triangle, m, 0)
T.raises("triangle index out of range", "triangle(25)", m.triangle, m, 25)

T.fails("cannot open", "load: missing file", lamina.load, M .. "nope.stl")
T.fails("truncated%.stl", "load: a bad file names itself", lamina.load, M .. "bad/truncated.stl")
T.fails("undefined_vertex%.ug:%d+:%d+", "load: position of a Unigrafix error", lamina.load,
        M .. "bad/undefined_vertex.ug")
local stl = assert(lamina.load(M .. "cube_hole.stl"))
T.is(stl.format, "stl-binary", "binary STL")

-- slicing: the thesis sample (SPEC 9) -------------------------------------------
local layers = m:slice{axis = "z", width = 1, cut = "floor"}
T.is(#layers, 2, "two layers")
local function pts(c)
  local t = {}
  for _, u, v in c:points() do t[#t + 1] = ("%g %g"):format(u, v) end
  return table.concat(t, ", ")
end
for i, l in ipairs(layers) do
  T.is(l.index, i, "layer index " .. i)
  T.is(l.z, i - 1, "layer " .. i .. " z")
  T.is(l.floor, i - 1, "floor")
  T.is(l.ceiling, i, "ceiling")
  T.is(l.width, 1, "width")
  T.is(l.cut, "floor", "cut rule")
  T.is(l.layers, 2, "layers in the run")
  T.is(#l, 2, "two contours")
  T.is(l.area, 3, "material area 4 - 1")
  T.is(l.points, 8, "points")
  T.is(l.model, m, "layer.model")
  local outer, inner = l:contour(1), l:contour(2)
  T.is(outer.kind, "solid", "outer solid")
  T.is(outer.depth, 0, "outer depth 0")
  T.is(outer.area, 4, "outer area +4 (CCW)")
  T.is(outer.perimeter, 8, "outer perimeter")
  T.is(pts(outer), "-1 -1, 1 -1, 1 1, -1 1", "outer: CCW from the lowest-leftmost point")
  T.is(inner.kind, "hole", "inner hole")
  T.is(inner.depth, 1, "inner depth 1")
  T.is(inner.area, -1, "inner area -1 (CW)")
  T.is(pts(inner), "-0.5 -0.5, -0.5 0.5, 0.5 0.5, 0.5 -0.5", "inner: CW from the lowest-leftmost point")
  T.is(inner.parent, outer, "inner.parent is the outer contour (same userdata)")
  T.is(outer.parent, nil, "outer has no parent")
  T.is(inner.layer, l, "contour.layer")
  T.is(inner.z, l.z, "contour.z")
  T.is(#inner, 4, "#contour")
  T.is(outer:children()[1], inner, "children")
  T.ok(outer:contains(0.75, 0) and outer:contains(0, 0) and not outer:contains(1.5, 0), "outer:contains")
  T.ok(inner:contains(0, 0) and not inner:contains(0.75, 0), "inner:contains")
  local u0, v0, u1, v1 = inner:bbox()
  T.ok(u0 == -0.5 and v0 == -0.5 and u1 == 0.5 and v1 == 0.5, "contour bbox")
  local u, v = inner:point(3)
  T.ok(u == 0.5 and v == 0.5, "point(3)")
  T.raises("point index out of range", "point(5)", inner.point, inner, 5)
  local zs = {}
  for _, x, y, z in outer:points("model") do zs[#zs + 1] = z end
  T.ok(#zs == 4 and zs[1] == l.z and zs[4] == l.z, "points('model') at the cut height")
end
T.is(layers[1]:contours()[1], layers[1]:contour(1), "contours are cached")
T.is(layers[1]:contour(3), nil, "contour(3) is nil")
T.like(tostring(layers[1]), "^lamina%.layer 1 %(z=0%.0, width 1%.0, 2 contours%)$", "tostring(layer)")
T.like(tostring(layers[1]:contour(2)), "^lamina%.contour 2 of layer 1 %(hole, depth 1, 4 points", "tostring(contour)")

-- other options
local ceil = m:slice{width = 1, cut = "ceiling"}
T.ok(ceil[1].z == 1 and ceil[2].z == 2 and #ceil[2] == 2, "ceiling cut: top face still gives the section")
local mid = m:slice{}
T.is(#mid, 100, "default width: 1/100 of the extent")
T.is(mid[1].cut, "middle", "default cut middle")
T.ok(math.abs(mid[1].gap - 5e-4 * math.sqrt(12)) < 1e-15 and mid[1].slivers == 0 and mid[1].twins == 0,
     "default gap: 1/2000 of the diagonal of the 2 x 2 x 2 box; no degenerate loops")
T.is(m:slice{width = 1, gap = 0.25}[1].gap, 0.25, "gap as given")
local w = m:slice{widths = {0.5, 0.5, 1}}
T.ok(#w == 3 and w[3].floor == 1 and w[3].width == 1, "widths")
local p = m:slice{planes = {0, 0.5, 2}}
T.ok(#p == 2 and p[2].width == 1.5, "planes")
local x = m:slice{axis = "x", width = 0.5, cut = "floor"}
T.is(#x, 4, "axis x: 4 layers")
local fu, fv, fw = x[1]:frame()
T.ok(fu[2] == 1 and fv[3] == 1 and fw[1] == 1, "axis x frame (y, z, x)")
T.ok(#x[1] == 1 and #x[2] == 2, "axis x: the hole appears in the middle layers")
local X, Y, Z = x[1]:to_model(0.25, 1.5)
T.ok(X == -1 and Y == 0.25 and Z == 1.5, "to_model")
local d = m:slice{axis = {0, 0, 2}, width = 1, cut = "floor"}
T.is(pts(d[1]:contour(1)), pts(layers[1]:contour(1)), "axis {0,0,2} is z")
local upper = m:slice{axis = "Z", width = 1}
T.is(#upper, 2, "axis 'Z'")

local fi = assert(lamina.load(M .. "frame_island.ug"))
local fl = fi:slice{width = 5}
T.is(#fl, 4, "frame with island: 4 layers")
local kinds = {}
for _, c in ipairs(fl[1]:contours()) do kinds[#kinds + 1] = c.kind .. c.depth end
T.is(table.concat(kinds, " "), "solid0 hole1 solid2", "frame, hole, island")
T.is(fl[1]:contour(3).parent, fl[1]:contour(2), "island's parent is the hole")

-- slice misuse
T.raises("bad argument #1 to 'slice' (table expected, got nil)", "slice(nil)", function() return m:slice(nil) end)
T.raises("bad argument #1 to 'slice' (cut must be floor, middle or ceiling, got 'top')", "slice{cut='top'}",
         function() return m:slice{cut = "top"} end)
T.raises("unknown option 'widht'", "slice: typo", function() return m:slice{widht = 1} end)
T.raises("give one of width, widths and planes", "slice: width and widths",
         function() return m:slice{width = 1, widths = {1, 1}} end)
T.raises("width must be greater than 0, got -1", "slice: negative width", function() return m:slice{width = -1} end)
T.raises("width must be a number, got 'a'", "slice: width as text", function() return m:slice{width = "a"} end)
T.raises("width must be a finite number", "slice: width NaN", function() return m:slice{width = 0 / 0} end)
T.raises("width 1e-09 makes 2000000000 layers, more than the limit of 1000000 (raise the limit with max_layers)",
         "slice: too many layers", function() return m:slice{width = 1e-9} end)
T.raises("width 0.001 makes 2000 layers, more than the limit of 1999", "slice: max_layers lowers the limit",
         function() return m:slice{width = 1e-3, max_layers = 1999} end)
T.is(#m:slice{width = 1e-3, max_layers = 2000}, 2000, "slice: a run at the limit is made")
T.raises("max_layers must be a whole number >= 1, got 0.5", "slice: max_layers checked",
         function() return m:slice{max_layers = 0.5} end)
T.raises("the widths add up to 1 but the model spans 2", "slice: widths do not cover",
         function() return m:slice{widths = {0.5, 0.5}} end)
T.raises("planes must increase strictly", "slice: planes decreasing", function() return m:slice{planes = {0, 1, 0.5}} end)
T.raises("widths[2] must be a number, got 'x'", "slice: widths entry", function() return m:slice{widths = {1, "x"}} end)
T.raises("axis must be 'x', 'y', 'z'", "slice: axis w", function() return m:slice{axis = "w"} end)
T.raises("axis", "slice: axis 0,0,0", function() return m:slice{axis = {0, 0, 0}} end)
T.raises("gap must be 0 or more", "slice: negative gap", function() return m:slice{gap = -1} end)
T.raises("fill must be evenodd or nonzero", "slice: fill", function() return m:slice{fill = "x"} end)
T.raises("machine must be a lamina.machine", "slice: machine", function() return m:slice{machine = 1} end)
T.raises("allow_open must be true or false", "slice: allow_open", function() return m:slice{allow_open = 1} end)

-- machines -------------------------------------------------------------------
local names = lamina.machines()
local have = {}
for _, n in ipairs(names) do have[n] = true end
T.ok(have["sls-contours"] and have["creol-ladrp"], "machines() lists the shipped profiles")
local sorted = true
for i = 2, #names do sorted = sorted and names[i - 1] < names[i] end
T.ok(sorted, "machines() sorted")

local sls = assert(lamina.machine("sls-contours"))
T.is(sls.name, "sls-contours", "machine name")
T.is(sls.process, "sls", "process")
T.is(sls.spot_width, 0.1, "spot width")
T.is(sls.bead_width, 0.1, "SLS bead width is the spot width")
T.is(sls.writer, "text", "writer")
T.is(sls.layer_width, nil, "no layer width")
T.like(tostring(sls), "^lamina%.machine sls%-contours %(sls, spot 0%.1%)$", "tostring(machine)")
local ladrp = assert(lamina.machine("creol-ladrp"))
T.ok(ladrp.bead_width == 0.08 and ladrp.feed_rate == 0.15 and ladrp.cut == "floor" and ladrp.units == "cm",
     "creol-ladrp values")
T.ok(ladrp.angle == 0 and ladrp.angle_step == 0 and ladrp.alternate and ladrp.first_line == "edge"
     and ladrp.min_deposit == 0 and ladrp.perimeters == 0 and not ladrp.beam_offset and ladrp.frame == "model",
     "raster defaults")
T.is(ladrp.travel_rate, 0.15, "travel rate follows the feed rate")
T.is(ladrp.gap, "auto", "gap: auto unless the profile sets one")
T.fails("unknown machine 'nope'", "machine: unknown name", lamina.machine, "nope")
T.fails("bad_process%.yaml:%d+:%d+", "machine: error with position", lamina.machine, M .. "machines/bad_process.yaml")
local byp = assert(lamina.machine(T.ROOT .. "/machines/sls-contours.yaml"))
T.is(byp.name, "sls-contours", "machine by path")

local o = ladrp:override{bead_width = 0.1, feed_rate = 0.3, angle = 45, angle_step = 90, first_line = "center",
                         alternate = false, min_deposit = 0.2, cut = "middle", frame = "machine", gap = 0.1,
                         layer_width = 0.5, perimeters = 2}
T.ok(o.bead_width == 0.1 and o.feed_rate == 0.3 and o.travel_rate == 0.3 and o.angle == 45 and o.angle_step == 90
     and o.first_line == "center" and not o.alternate and o.min_deposit == 0.2 and o.cut == "middle"
     and o.frame == "machine" and o.gap == 0.1 and o.layer_width == 0.5 and o.perimeters == 2, "override")
T.ok(ladrp.bead_width == 0.08 and ladrp.angle == 0, "override leaves the original alone")
T.like(tostring(o), "overridden", "tostring of a derived machine")
T.is(o:override{angle = 0}.bead_width, 0.1, "override of an override")
T.raises("bead_width is read by the ladrp planner only, and sls-contours is an sls profile: set spot_width instead",
         "SLS: bead_width is refused, naming spot_width", sls.override, sls, {bead_width = 0.2})
T.raises("angle is read by the ladrp planner only, and sls-contours is an sls profile: set hatch_angle instead",
         "override: a raster key on an sls machine", sls.override, sls, {angle = 45})
T.raises("hatch_angle is read by the sls planner only, and creol-ladrp is a ladrp profile: set raster.angle instead",
         "plan: an sls key on a ladrp machine", ladrp.plan, ladrp, {}, {hatch_angle = 45})
T.raises("bead_width must be greater than 0, got -1", "override: bead_width", ladrp.override, ladrp, {bead_width = -1})
T.raises("feed_rate must be 0 or more", "override: feed_rate", ladrp.override, ladrp, {feed_rate = -1})
T.raises("first_line must be edge or center", "override: first_line", ladrp.override, ladrp, {first_line = "top"})
T.raises("alternate must be true or false", "override: alternate", ladrp.override, ladrp, {alternate = "yes"})
T.raises("perimeters must be a whole number from 0 to 1000", "override: perimeters", ladrp.override, ladrp,
         {perimeters = 1.5})
T.raises("max_overhang_deg must be from 0 to 90", "override: overhang", ladrp.override, ladrp, {max_overhang_deg = 91})
T.raises("angle must be a finite number", "override: angle inf", ladrp.override, ladrp, {angle = math.huge})
T.raises("process cannot be changed", "override: process", ladrp.override, ladrp, {process = "sls"})
T.raises("unknown option 'beadwidth'", "override: typo", ladrp.override, ladrp, {beadwidth = 1})
T.like(o:yaml(), "\n  angle: 45\n", "yaml() shows overrides")

-- plans ----------------------------------------------------------------------
local function expected_sls()
  local out = {}
  for z = 0, 1 do
    if z == 1 then out[#out + 1] = "" end
    local sq = {
      {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}},
      {{-0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}, {0.5, -0.5}},
    }
    for k, loop in ipairs(sq) do
      if k == 2 then out[#out + 1] = "" end
      out[#out + 1] = ("contour %.6f"):format(z)
      out[#out + 1] = "loop 4"
      for _, q in ipairs(loop) do out[#out + 1] = ("%.6f %.6f %.6f"):format(q[1], q[2], z) end
      out[#out + 1] = "endloop"
      out[#out + 1] = "endcontour"
    end
  end
  return table.concat(out, "\n") .. "\n"
end
local plan = assert(sls:plan(layers))
T.is(plan:text(), expected_sls(), "SLS plan: the thesis sample (SPEC 9)")
T.is(#plan, 35, "#plan: lines")
T.ok(plan.lines == 35 and plan.bytes == #plan:text() and plan.layers == 2 and plan.machine == "sls-contours"
     and plan.process == "sls" and plan.binary == false, "plan fields")
T.like(tostring(plan), "^lamina%.plan %(sls%-contours, sls, 2 layers, 35 lines%)$", "tostring(plan)")
local one = assert(sls:plan({layers[2]}))
T.is(one.layers, 1, "a subset of the run")
T.like(one:text(), "^contour 1%.000000\n", "subset: the second layer only")
T.raises("comes from another slicing run", "plan: layers of two runs", sls.plan, sls, {layers[1], ceil[2]})
T.raises("layers must be in slicing order", "plan: order", sls.plan, sls, {layers[2], layers[1]})
T.raises("no layers to plan", "plan: empty", sls.plan, sls, {})
T.raises("layers[2] must be a lamina.layer, got a table", "plan: not a layer", sls.plan, sls, {layers[1], {}})
T.raises("cut cannot be changed here", "plan: slicing option", sls.plan, sls, layers, {cut = "floor"})
T.raises("bad argument #2 to 'plan' (angle must be a number, got 'x')", "plan: bad option",
         function() return sls:plan(layers, {angle = "x"}) end)
T.raises("angle is read by the ladrp planner only, and sls-contours is an sls profile: set hatch_angle instead",
         "plan: a layer function's raster key on an sls machine",
         function() return sls:plan(layers, {layer = function() return {angle = 5} end}) end)

local cube = assert(lamina.load(M .. "thesis_cube.ug"))
local cl = cube:slice{machine = ladrp, width = 2}
T.is(#cl, 1, "thesis cube in one layer")
local lp = assert(ladrp:plan(cl))
local lines = {}
for line in lp:text():gmatch("([^\n]*)\n") do lines[#lines + 1] = line end
T.is(table.concat(lines, "\n", 1, 12), table.concat({
  "start_plot", "3 set_dimension", "0.15 feedrate", "0 penup",
  "-1.00000 1.08000 0.00000 uline", "0.00000 -0.08000 0.00000 uline",
  "0 pendown", "0.15 feedrate", "2.00000 0.00000 0.00000 uline",
  "0 penup", "0.00000 -0.08000 0.00000 uline", "0 pendown"}, "\n"),
  "LADRP plan: the thesis sample's moves (SPEC 4.1)")
local deposits = 0
for _, line in ipairs(lines) do if line == "2.00000 0.00000 0.00000 uline" or line == "-2.00000 0.00000 0.00000 uline" then deposits = deposits + 1 end end
T.is(deposits, 25, "25 scan lines of 2 units, 0.08 apart")
local rot = assert(ladrp:plan(cl, {angle = 90}))
T.ok(rot:text():find("0.00000 2.00000 0.00000 uline", 1, true) or rot:text():find("0.00000 -2.00000 0.00000 uline", 1, true),
     "plan opts: raster at 90 degrees")
T.ok(ladrp:plan(cl, {bead_width = 0.5}).lines < lp.lines, "plan opts: wider bead, fewer lines")
T.raises("2e+300 scan lines of bead 1e-300), more than the limit of 4 GB (raise the limit with the option max_output)",
         "plan: bead too small", ladrp.plan, ladrp, cl, {bead_width = 1e-300})
-- one layer of the 2 x 2 cube, bead 0.08: 2 / 0.08 + 1 = 26 scan lines, the
-- first of them on the top edge, so 25 deposits, each after a travel, and
-- the travel down onto the first line; in the dialect's bytes: per travel
-- "0 penup", "X Y Z uline" (31 bytes), "0 pendown", "0.15 feedrate", per
-- deposit a uline (30): over 1.6 kB
T.raises("kB (1 layers, 26 scan lines of bead 0.08), more than the limit of 1 kB",
         "plan: max_output lowers the limit", ladrp.plan, ladrp, {cl[1]}, {max_output = 1024})
-- the estimate takes the plan's bead (0.08: about 2.4 kB, the program's 25
-- lines of penup, travel, pendown, feedrate, deposit); a recipe's layer
-- function that halves it as the layer is planned doubles the lines: the
-- program passes 3000 bytes, the estimate does not, and the limit holds as
-- the program is written
local halve = function() return { bead_width = 0.04 } end
local none, over = ladrp:plan({cl[1]}, {max_output = 3000, layer = halve})
T.ok(none == nil and over:match("output exceeds the limit of 3000 bytes"), "plan: the written program is held to the limit too")
local whole = ladrp:plan({cl[1]}, {layer = halve}).bytes
T.ok(whole > 3000, "plan: the halved bead's program is over 3000 bytes", whole)
T.is(ladrp:plan({cl[1]}, {max_output = whole, layer = halve}).bytes, whole, "plan: a program of exactly the limit is planned")

local out = os.tmpname()
T.ok(plan:write(out), "plan:write")
local f = assert(io.open(out, "rb"))
T.is(f:read("a"), plan:text(), "written file = text()")
f:close()
os.remove(out)
T.fails("cannot create output", "plan:write into a missing directory", plan.write, plan, "/nonexistent/dir/x.sls")

-- a plugin writer: binary output, #plan in bytes
local bin = lamina.machine(M .. "machines/plugin_writer.yaml")
if bin then
  local bp, msg = bin:plan(layers)
  if bp then
    T.ok(bp.binary and #bp == bp.bytes and #bp:text() == bp.bytes, "plugin writer: binary plan, #plan = bytes")
  else
    T.ok(false, "plugin writer plan", msg)
  end
else
  T.ok(false, "plugin_writer.yaml loads")
end

-- a recipe's hatcher names its vectors' region by vocab.h's names: a hatch
-- region is taken, anything else is an error naming the vector and what it got
do
  local cli = lamina.machine("cli-ascii")
  local two = m:slice{width = 1}
  local function with(kind)
    return cli:plan(two, {hatcher = function() return {{-0.5, -0.5, 0.5, 0.5, kind = kind}} end})
  end
  T.ok(with("downskin"):text():find("$$HATCHES/1,1,", 1, true), "hatcher: kind = downskin is planned")
  T.raises("vector 1: kind must be core, upskin or downskin, got 'contour'", "hatcher: kind = contour",
           with, "contour")
  T.raises("vector 1: kind must be core, upskin or downskin, got 3", "hatcher: kind = 3", with, 3)
  T.raises("vector 1: kind must be core, upskin or downskin, got 'cor'", "hatcher: kind = cor", with, "cor")
end

T.done()
