-- The Lua-side library modules the recipes share (lua/lamina/*.lua):
-- lamina.args, lamina.axes, lamina.adaptive and lamina.preview, on hand-made
-- facets whose answers follow by reasoning and on small models.
local T = dofile(os.getenv("TESTS") .. "/lua/tap.lua")
local lamina, M = T.lamina, T.M
local args = require "lamina.args"
local axes = require "lamina.axes"
local adaptive = require "lamina.adaptive"

-- lamina.args ------------------------------------------------------------------
local spec = {
  usage = "r.lua [--cusp H] [--list] [MODEL]",
  options = { cusp = 0.05, list = false, axis = "z", w_stair = 1, model = "m.ug" },
  positive = { "cusp" },
  positional = { "model" },
}
local o = args.parse({ [0] = "some/dir/r.lua", "--cusp", "0.1", "--list", "--w-stair=2", "a.stl" }, spec)
T.ok(o.cusp == 0.1 and o.list == true and o.w_stair == 2 and o.model == "a.stl" and o.axis == "z",
     "args: values, a flag, --name=value, a dash as underscore, a positional")
o = args.parse({ [0] = "r.lua" }, spec)
T.ok(o.cusp == 0.05 and o.list == false and o.model == "m.ug", "args: defaults")
o = args.parse({ [0] = "r.lua", "--", "--odd-name.stl" }, spec)
T.is(o.model, "--odd-name.stl", "args: -- ends the options")
-- Option errors are objects: they print as the message (no traceback from
-- `lamina run` or a stock lua) and carry the exit code.
local function raises_object(msg, exit, desc, f, ...)
  local ok, err = pcall(f, ...)
  T.ok(not ok and type(err) == "table" and tostring(err):find(msg, 1, true) ~= nil and err.exit == exit, desc,
       ok and "no error" or ("error: %s, exit %s (expected '%s', exit %d)"):format(tostring(err),
         tostring(type(err) == "table" and err.exit), msg, exit))
end
local function bad(argv, msg, desc)
  argv[0] = "dir/r.lua"
  raises_object(msg, 2, "args: " .. desc, args.parse, argv, spec)
end
bad({ "--bogus" }, "r.lua: unknown option --bogus\nusage: r.lua [--cusp H]", "unknown option, with the usage")
bad({ "-x" }, "r.lua: unknown option -x", "unknown short option")
bad({ "--cusp" }, "r.lua: --cusp needs a value", "missing value")
bad({ "--cusp", "abc" }, "r.lua: --cusp expects a number, got 'abc'", "not a number")
bad({ "--cusp", "nan" }, "--cusp expects a number, got 'nan'", "nan is not a number")
bad({ "--cusp", "-1" }, "r.lua: --cusp must be greater than 0, got -1", "positive")
bad({ "--list=maybe" }, "--list is a flag (true or false), got 'maybe'", "flag value")
bad({ "a", "b" }, "r.lua: unexpected argument 'b'", "too many positionals")
local _, fail, die = args.parse({ [0] = "r.lua" }, spec)
raises_object("r.lua: min 2 > max 1\nusage: r.lua", 2, "args: fail() for the recipe's own checks, exit 2", fail,
              "min %g > max %g", 2, 1)
raises_object("r.lua: m.ug: cannot open", 1, "args: die() for an input that does not load, exit 1", die,
              "%s: cannot open", "m.ug")
local _, derr = pcall(die, "gone")
T.ok(not tostring(derr):find("usage", 1, true), "args: die() leaves the usage out")
T.is(args.beside({ [0] = "recipes/x.lua" }, "parts/a.ug"), "recipes/parts/a.ug", "args.beside")
T.is(args.beside({ [0] = "x.lua" }, "parts/a.ug"), "parts/a.ug", "args.beside in the current directory")

-- lamina.axes ------------------------------------------------------------------
local z = axes.parse("z")
T.ok(z.slice == "z" and z.dir[3] == 1, "axes.parse z slices along the named axis")
local nz = axes.parse("-z")
T.ok(type(nz.slice) == "table" and nz.dir[3] == -1, "axes.parse -z is the direction (0, 0, -1)")
local d = axes.parse("1,1,1")
T.near(d.dir[1], 1 / math.sqrt(3), "axes.parse 1,1,1 is a unit vector")
T.fails("axis must be x, y, z", "axes.parse rejects a word", axes.parse, "up")
T.fails("not zero", "axes.parse rejects the zero direction", axes.parse, "0,0,0")
T.is(#axes.candidates(false), 3, "three candidates")
T.is(#axes.candidates(true), 10, "ten with more")

local cube = assert(lamina.load(M .. "thesis_cube_hole.ug"))
local f = axes.facets(cube, z)
T.ok(#f == 24 and f.lo == 0 and f.hi == 2, "facets: one per triangle, the span along the axis")
local flat, wall = 0, 0
for _, t in ipairs(f) do
  if t.k == 1 then flat = flat + 1 elseif t.k == 0 then wall = wall + 1 end
end
T.ok(flat == 8 and wall == 16, "facets: |n.z| is 1 on the tops and bottoms, 0 on the walls")

local plate = assert(lamina.load(M .. "recipes/plate.ug"))
local mz = axes.measures(axes.facets(plate, z), 0.1)
local mx = axes.measures(axes.facets(plate, axes.parse("x")), 0.1)
T.ok(mz.height == 1 and mz.layers == 10 and mz.stair == 0 and mz.overhang == 0,
     "measures: the plate along z is 1 high, 10 layers, no stairs, no overhang")
T.ok(mx.height == 10 and mx.layers == 100 and mx.overhang == 0, "measures: along x 10 high, 100 layers")
local tee = assert(lamina.load(M .. "recipes/tee.ug"))
T.near(axes.measures(axes.facets(tee, z), 0.1).overhang, 96, "measures: the T's underside overhangs along z")
T.near(axes.measures(axes.facets(tee, axes.parse("x")), 0.1).overhang, 16, "measures: the stem's side along x")
T.near(axes.measures(axes.facets(tee, nz), 0.1).overhang, 0, "measures: nothing upside down")
-- a 45-degree roof: sloped facets count in the stair error, area * k * w / 2
local function facet(lo, hi, k, area) return { lo = lo, hi = hi, k = k, d = k, area = area or 1 } end
local roof = { facet(0, 1, math.sqrt(0.5), 2), lo = 0, hi = 1 }
T.near(axes.measures(roof, 0.2).stair, 2 * math.sqrt(0.5) * 0.1, "measures: stair error of a slope")

-- lamina.adaptive ----------------------------------------------------------------
local function near_all(got, want, desc)
  local same = #got == #want
  for i = 1, #want do same = same and math.abs(got[i] - want[i]) < 1e-9 end
  T.ok(same, desc, table.concat(got, " "))
end
local ws = adaptive.cusp_widths({ facet(0, 10, 0.5), lo = 0, hi = 10 }, { cusp = 0.1, min = 0.01, max = 1 })
local all = #ws == 50
for _, w in ipairs(ws) do all = all and math.abs(w - 0.2) < 1e-9 end
T.ok(all, "cusp_widths: a slope with |n.a| = 0.5 and cusp 0.1 gets 50 layers of 0.2")

-- a gentle slope (limit 1) with a steep band 2.5..3 (limit 0.1): the layer
-- below stops under the band instead of crossing it
local fs = { facet(0, 10, 0.1), facet(2.5, 3, 1), lo = 0, hi = 10 }
ws = adaptive.cusp_widths(fs, { cusp = 0.1, min = 0.01, max = 1 })
near_all(ws, { 1, 1, 0.5, 0.1, 0.1, 0.1, 0.1, 0.1, 1, 1, 1, 1, 1, 1, 1 },
         "cusp_widths: stops under a steeper band, narrow across it, wide again above")
local planes = adaptive.planes(0, ws)
T.ok(#planes == 16 and planes[1] == 0 and math.abs(planes[16] - 10) < 1e-9, "planes: from the floor to the top")
T.near(adaptive.worst_cusp(fs, planes), 0.1, "worst_cusp: the cusp limit holds")
local uniform = {}
for i = 0, 10 do uniform[i + 1] = i end
local worst, at = adaptive.worst_cusp(fs, uniform)
T.ok(math.abs(worst - 1) < 1e-9 and at == fs[2], "worst_cusp: a unit layer across the steep band")
T.is(adaptive.worst_cusp({ facet(1, 1, 1), lo = 0, hi = 2 }, { 0, 1, 2 }), 0,
     "worst_cusp: a flat face on a boundary crosses no layer")
T.near(adaptive.worst_cusp({ facet(1, 1, 1), lo = 0, hi = 2 }, { 0, 0.5, 1.5, 2 }), 1,
       "worst_cusp: a flat face inside a layer of 1")
ws = adaptive.cusp_widths({ facet(0, 1, 1), lo = 0, hi = 1 }, { cusp = 0.001, min = 0.1, max = 0.5 })
T.ok(#ws == 10 and math.abs(ws[1] - 0.1) < 1e-12, "cusp_widths: never narrower than min")
ws = adaptive.cusp_widths({ facet(0, 1, 0), lo = 0, hi = 1.2 }, { cusp = 0.1, min = 0.5, max = 1 })
T.ok(#ws == 2 and ws[1] == 1 and ws[2] == 0.5, "cusp_widths: walls do not limit; the last layer is min wide")

local u = adaptive.uniform({ facet(0, 10, 0.5), facet(2, 3, 0.8), lo = 0, hi = 10 }, 0.08, 1)
T.ok(math.abs(u.width - 0.1) < 1e-12 and u.layers == 100 and math.abs(u.worst - 0.08) < 1e-9,
     "uniform: the width that gives the steepest facet the cusp")
u = adaptive.uniform({ facet(0, 0, 1), facet(0, 2, 0), lo = 0, hi = 2 }, 0, 0.5)
T.ok(u.width == 0.5 and u.layers == 4 and u.worst == 0, "uniform: max wide without sloped facets")

-- the issue's case: a 45-degree slope (k = sqrt(1/2)) and a flat face at
-- 3.3. cusp / k = 0.0707 puts 3.3 at 46.67 layers: the face would sit inside
-- a layer and leave a cusp of 0.0707 > 0.05. The widest width that puts it
-- on a boundary is 3.3 / 47 (0.0702, cusp 0.0496 on the slope): 143 layers.
local k45 = math.sqrt(0.5)
u = adaptive.uniform({ facet(0, 10, k45), facet(3.3, 3.3, 1), lo = 0, hi = 10 }, 0.05, 1)
T.ok(math.abs(u.width - 3.3 / 47) < 1e-12 and u.layers == 143 and u.worst <= 0.05
     and math.abs(u.worst - 3.3 / 47 * k45) < 1e-9,
     "uniform: at the same worst cusp, the flat face on a boundary (3.3 / 47)",
     ("width %.17g, %d layers, worst %.17g"):format(u.width, u.layers, u.worst))
T.ok(math.abs(u.steepest.width - 0.05 / k45) < 1e-12 and math.abs(u.steepest.worst - 0.05 / k45) < 1e-9,
     "uniform.steepest: cusp / k wide, the flat face inside a layer leaves 0.0707",
     ("width %.17g, worst %.17g"):format(u.steepest.width, u.steepest.worst))
-- two flat faces 0.0301 apart: no width over the cusp puts both on the
-- grid, so the cusp itself is the width (a flat face inside leaves 0.05)
u = adaptive.uniform({ facet(0, 10, k45), facet(3.3, 3.3, 1), facet(3.3301, 3.3301, 1), lo = 0, hi = 10 }, 0.05, 1)
T.ok(math.abs(u.width - 0.05) < 1e-12 and u.layers == 200 and math.abs(u.worst - 0.05) < 1e-9,
     "uniform: flat faces no grid wider than the cusp aligns: the cusp's width",
     ("width %.17g, %d layers, worst %.17g"):format(u.width, u.layers, u.worst))
local none, why = adaptive.uniform({ facet(0, 10, k45), lo = 0, hi = 10 }, 0, 1)
T.ok(none == nil and why:find("sloped", 1, true), "uniform: no width reaches a zero cusp on a slope")

local terrace = { facet(0, 0, 1), facet(1, 1, 1), facet(1.05, 1.05, 1), facet(2.5, 2.5, 1),
                  facet(0, 1, 0), lo = 0, hi = 2.5 }
near_all(adaptive.flat_heights(terrace), { 0, 1, 1.05, 2.5 }, "flat_heights")
local ap, short = adaptive.aligned_planes(terrace, 0.1, 0.5)
near_all(ap, { 0, 0.5, 1, 1.05, 1.05 + 1.45 / 3, 1.05 + 2.9 / 3, 2.5 },
         "aligned_planes: flat heights kept, equal layers of at most max between")
T.ok(#short == 1 and short[1][1] == 1 and short[1][2] == 1.05, "aligned_planes: names the interval under min")

-- lamina.preview (the C contact sheet) -------------------------------------------
local layers = cube:slice{ width = 0.5 }
local path = os.tmpname()
T.ok(lamina.preview(layers, path), "preview: written")
local f = io.open(path, "rb")
local text = f:read("a")
f:close()
os.remove(path)
local _, paths = text:gsub('<path class="section"', "")
T.ok(text:match("^<%?xml") and paths == 4 and text:find('fill-rule="evenodd"', 1, true),
     "preview: one evenodd path per layer")
T.fails("no/such/dir", "preview: an unwritable path is nil, message", lamina.preview, layers, "/no/such/dir/x.svg")

T.done()
