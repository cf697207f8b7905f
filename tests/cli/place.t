#!/usr/bin/env bash
# Units and placement on load (core/mesh/xform.h; docs/cli.md, "Units and
# placement on load"): --units, --scale, --rotate, --place and --translate
# on every command that loads a model, and lamina.load's options. The
# models are boxes written here as ASCII STL; every expected bounding box
# is computed here from the box's corners (python, no lamina).
. "$(dirname "$0")/lib.sh"

# box X0 Y0 Z0 X1 Y1 Z1 FILE: an ASCII STL box (12 facets, wound outward)
box() {
    python3 - "$@" <<'PY'
import sys
x0, y0, z0, x1, y1, z1 = map(float, sys.argv[1:7])
c = [(x1 if i & 1 else x0, y1 if i & 2 else y0, z1 if i & 4 else z0) for i in range(8)]
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
with open(sys.argv[7], "w") as f:
    f.write("solid box\n")
    for a, b, cc, d in quads:
        for t in ((a, b, cc), (a, cc, d)):
            f.write("facet normal 0 0 0\nouter loop\n")
            for v in t:
                f.write("vertex %r %r %r\n" % c[v])
            f.write("endloop\nendfacet\n")
    f.write("endsolid box\n")
PY
}
# ref_bbox X0 Y0 Z0 X1 Y1 Z1 STEP...: the box's corners through the steps
# (scale:F,F,F  rot:AXIS:DEG  plate  move:X,Y,Z), as "xmin ymin zmin xmax ymax zmax"
ref_bbox() {
    python3 - "$@" <<'PY'
import math, sys
a = list(map(float, sys.argv[1:7]))
pts = [[a[3] if i & 1 else a[0], a[4] if i & 2 else a[1], a[5] if i & 4 else a[2]] for i in range(8)]
def bb(p):
    return [min(q[k] for q in p) for k in range(3)] + [max(q[k] for q in p) for k in range(3)]
for step in sys.argv[7:]:
    kind, _, arg = step.partition(":")
    if kind == "scale":
        f = list(map(float, arg.split(",")))
        pts = [[q[k] * f[k] for k in range(3)] for q in pts]
    elif kind == "rot":
        ax, deg = arg.split(":")
        r = math.radians(float(deg))
        c, s = round(math.cos(r), 12), round(math.sin(r), 12)
        u, v = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[ax]
        for q in pts:
            q[u], q[v] = c * q[u] - s * q[v], s * q[u] + c * q[v]
    elif kind == "plate":
        b = bb(pts)
        d = [-(b[0] + b[3]) / 2, -(b[1] + b[4]) / 2, -b[2]]
        pts = [[q[k] + d[k] for k in range(3)] for q in pts]
    elif kind == "move":
        t = list(map(float, arg.split(",")))
        pts = [[q[k] + t[k] for k in range(3)] for q in pts]
print(" ".join("%.9g" % (x + 0.0) for x in bb(pts)))
PY
}
# json_bbox: the bbox of `lamina info --json` on standard input, as ref_bbox prints it
json_bbox() {
    python3 -c 'import json, sys
b = json.load(sys.stdin)["bbox"]
print(" ".join("%.9g" % (x + 0.0) for x in b["min"] + b["max"]))'
}

B="$TMP/a box.stl" # a space in the path
box 1 -2 -20 3 5 -12 "$B"
run "$LAMINA" info --json "$B"
is "$RC" 0 "info reads the box"
is "$(printf '%s' "$OUT" | json_bbox)" "1 -2 -20 3 5 -12" "as drawn: [1,3] x [-2,5] x [-20,-12]"

# ---- --place plate: the lowest point on z = 0, the footprint on the origin ----
run "$LAMINA" info --json --place plate "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "$(ref_bbox 1 -2 -20 3 5 -12 plate)" "--place plate: info's bbox"
is "$(printf '%s' "$OUT" | json_bbox)" "-1 -3.5 0 1 3.5 8" "... [-1,1] x [-3.5,3.5] x [0,8]"
run "$LAMINA" info --json --place none "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "1 -2 -20 3 5 -12" "--place none: as drawn"

# the CLI program: without --place its layers are below the plate; with it, none is
run "$LAMINA" slice "$B" -m lpbf-cli -w 0.5 -o "$TMP/low.cli"
is "$RC" 0 "slice as drawn (lpbf-cli)"
low=$(grep -c '^\$\$LAYER/-' "$TMP/low.cli")
ok $([ "$low" -gt 0 ] && echo 0 || echo 1) "as drawn, $low \$\$LAYER values are negative"
run "$LAMINA" slice "$B" -m lpbf-cli -w 0.5 --place plate -o "$TMP/plate.cli"
is "$RC" 0 "slice --place plate"
layers=$(grep -o '^\$\$LAYER/[^ ]*' "$TMP/plate.cli" | sed 's/^\$\$LAYER\///')
is "$(printf '%s\n' "$layers" | wc -l | tr -d ' ')" 16 "16 layers of 0.5 over 8"
is "$(printf '%s\n' "$layers" | awk '$1 + 0 < 0' | wc -l | tr -d ' ')" 0 "every \$\$LAYER value is non-negative"
is "$(printf '%s\n' "$layers" | awk 'NR == 1 || $1 + 0 < m { m = $1 + 0 } NR == 1 || $1 + 0 > x { x = $1 + 0 } END { print m, x }')" \
    "0.25 7.75" "the layers' cuts run from 0.25 to 7.75 (lpbf-cli cuts mid-layer; the plate is z = 0)"
# validate and check take the same options and see the same part
run "$LAMINA" validate "$B" -w 0.5 --place plate --json
is "$RC" 0 "validate --place plate"
run "$LAMINA" check "$B" -m ded-gcode --place plate --rotate x:90 --json
ok $([ "$RC" -eq 0 ] || [ "$RC" -eq 3 ]; echo $?) "check takes them too (exit $RC)"

# ---- --units: the model's unit to the machine's --------------------------------
S="$TMP/small.stl" # 0.02 across: a part drawn in metres
box 0 0 0 0.02 0.01 0.005 "$S"
run "$LAMINA" info --json --units m "$S"
is "$(printf '%s' "$OUT" | json_bbox)" "0 0 0 20 10 5" "--units m: 0.02 m is 20 mm (info: mm)"
run "$LAMINA" info --json --units in "$S"
is "$(printf '%s' "$OUT" | json_bbox)" "$(ref_bbox 0 0 0 0.02 0.01 0.005 scale:25.4,25.4,25.4)" "--units in: x 25.4"
run "$LAMINA" slice "$S" -m lpbf-cli -o "$TMP/small.cli"
like "$ERR" "^lamina: warning: .*small\.stl: the model is 0\.02 across .*smaller than 0\.5 mm; was it drawn in another unit\? If it was drawn in metres, --units m makes it 20 mm$" \
    "in mm without --units: a warning naming --units m, on one line"
run "$LAMINA" slice "$S" -m lpbf-cli -w 0.5 --units m -o "$TMP/small.cli"
is "$RC" 0 "--units m: slices"
unlike_warning=$(printf '%s\n' "$ERR" | grep -c warning)
is "$unlike_warning" 0 "... with no warning"
is "$(grep -c '^\$\$LAYER/' "$TMP/small.cli")" 10 "... 10 layers of 0.5 mm over 5 mm"
is "$(grep '^\$\$DIMENSION/' "$TMP/small.cli")" '$$DIMENSION/0.00000,0.00000,0.00000,20.00000,10.00000,5.00000' \
    "... the header's dimension in mm: 20 x 10 x 5"
# a machine in cm: 0.02 m is 2 cm
run "$LAMINA" slice "$S" -m creol-ladrp --units m -o "$TMP/small.ladrp"
is "$RC" 0 "creol-ladrp (cm) --units m"
run "$LAMINA" info --json --units mm -m creol-ladrp "$S"
is "$RC" 0 "info -m creol-ladrp --units mm runs"
# the warning follows --units: the 8 mm box said to be in m is 8 m; in cm
# it would be 80 mm (nearer 100 mm than 8 mm in mm)
run "$LAMINA" slice "$B" -m lpbf-cli -w 1 --units m -o "$TMP/big.cli"
like "$ERR" "8000 mm, larger than 2000 mm; was it drawn in another unit\? If it was drawn in centimetres, --units cm makes it 80 mm$" \
    "--units m on a part in mm: the warning names the unit that replaces it"
# nothing fits a unit: a --scale
box 0 0 0 1e-9 1e-9 1e-9 "$TMP/dust.stl"
run "$LAMINA" slice "$TMP/dust.stl" -m lpbf-cli -w 1e-10 --max-layers 100 -o "$TMP/dust.cli"
like "$ERR" "was it drawn in another unit\? --scale 100000000000 makes it 100 mm$" "too small for any unit: a --scale"

# ---- --rotate: in the order given ------------------------------------------------
xz=$(ref_bbox 1 -2 -20 3 5 -12 rot:x:90 rot:z:90)
zx=$(ref_bbox 1 -2 -20 3 5 -12 rot:z:90 rot:x:90)
ok $([ "$xz" != "$zx" ] && echo 0 || echo 1) "x:90 then z:90 and the reverse differ ($xz / $zx)"
run "$LAMINA" info --json --rotate x:90 --rotate z:90 "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "$xz" "--rotate x:90 --rotate z:90"
run "$LAMINA" info --json --rotate z:90 --rotate x:90 "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "$zx" "--rotate z:90 --rotate x:90"
run "$LAMINA" info --json --rotate x:90,z:90 "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "$xz" "--rotate x:90,z:90 is the first"
run "$LAMINA" info --json --rotate y:-90 "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "$(ref_bbox 1 -2 -20 3 5 -12 rot:y:-90)" "--rotate y:-90"

# ---- the order of the steps: scale, rotations, place, translate ------------------
# given in another order on the command line, applied in this one
run "$LAMINA" info --json --translate 10,20,30 --place plate --rotate x:90 --scale 2,1,0.5 "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "$(ref_bbox 1 -2 -20 3 5 -12 scale:2,1,0.5 rot:x:90 plate move:10,20,30)" \
    "scale, then rotate, then place, then translate, whatever the order given"
run "$LAMINA" info --json --units cm --scale 2 "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "$(ref_bbox 1 -2 -20 3 5 -12 scale:20,20,20)" "--units cm --scale 2: x 20"
run "$LAMINA" info --json --translate 1,0,0 --translate 0,2,0 "$B"
is "$(printf '%s' "$OUT" | json_bbox)" "2 0 -20 4 7 -12" "two --translate add up"
# a quarter turn stays exact: the STL's integers stay integers
run "$LAMINA" info --json --rotate x:90 --rotate y:270 --rotate z:-180 "$B"
like "$(printf '%s' "$OUT" | json_bbox)" '^-?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+ -?[0-9]+$' "quarter turns: integer coordinates"
# slicing sees the transformed part: a 2 x 7 x 8 box turned x:90 is 7 tall
run "$LAMINA" slice "$B" -m lpbf-cli -w 0.5 --rotate x:90 --place plate -o "$TMP/turned.cli"
is "$(grep -c '^\$\$LAYER/' "$TMP/turned.cli")" 14 "turned x:90 and placed: 14 layers of 0.5 (7 tall)"
# the default is as drawn, bit for bit
"$LAMINA" slice "$B" -m lpbf-cli -w 0.5 -o "$TMP/plain.cli" 2>/dev/null
"$LAMINA" slice "$B" -m lpbf-cli -w 0.5 --place none --scale 1 --rotate z:360 --translate 0,0,0 -o "$TMP/ident.cli" 2>/dev/null
cmp -s "$TMP/plain.cli" "$TMP/ident.cli"
ok $? "identity options write the same bytes as none"

# ---- bad values: exit 2 with the message, nothing written ------------------------
bad() { # bad CMD OPTION VALUE MESSAGE-REGEX
    run "$LAMINA" "$1" "$B" "$2" "$3" -o "$TMP/bad.out"
    [ "$1" = slice ] || run "$LAMINA" "$1" "$B" "$2" "$3"
    like "$RC $ERR" "^2 lamina $1: $4" "$1 $2 $3: exit 2 with the message"
}
rm -f "$TMP/bad.out"
bad slice --rotate q:90 "--rotate q:90: the axis must be x, y or z$"
bad slice --rotate x:abc "--rotate x:abc: the angle must be a finite number of degrees$"
bad info --scale 0 "--scale 0: a factor of 0 flattens the model$"
bad validate --scale 1,2 "--scale 1,2: expected a factor F or three FX,FY,FZ"
bad check --translate 1,2 "--translate 1,2: expected X,Y,Z"
bad slice --place floor "--place floor: expected plate or none$"
bad info --units furlong "--units furlong: the units lamina knows are mm, cm, m"
ok $([ ! -e "$TMP/bad.out" ]; echo $?) "no output written"
run "$LAMINA" slice "$B" --rotate
like "$RC $ERR" "^2 lamina slice: option --rotate needs a value" "--rotate without a value"
run "$LAMINA" machines --place plate
like "$RC $ERR" "^2 lamina machines: option --place does not apply to 'machines'" "machines loads no model: refused"
# a coordinate pushed out of range: exit 1 naming the step
run "$LAMINA" info "$B" --scale 1e300 --units m
like "$RC $ERR" "^1 lamina: .*after scaling \(units and --scale\).*is beyond 1e50" "out of range after scaling: exit 1, the step named"

# ---- the Lua form: the same bboxes -----------------------------------------------
lua_bbox() { # lua_bbox PATH LUA-TABLE
    "$LAMINA" run - "$1" <<LUA
local m = assert(lamina.load(arg[1], $2))
local b = {m:bbox()}
for i = 1, 6 do b[i] = ("%.9g"):format(b[i] + 0.0) end
print(table.concat(b, " "))
LUA
}
is "$(lua_bbox "$B" '{place = "plate"}')" "$(ref_bbox 1 -2 -20 3 5 -12 plate)" "Lua place = \"plate\""
is "$(lua_bbox "$B" '{rotate = {"x:90", "z:90"}}')" "$xz" "Lua rotate = {\"x:90\", \"z:90\"}"
is "$(lua_bbox "$B" '{rotate = "z:90,x:90"}')" "$zx" "Lua rotate = \"z:90,x:90\""
run "$LAMINA" info --json --units in --scale 1,2,3 --rotate y:30 --place plate --translate 1,1,1 "$B"
is "$(lua_bbox "$B" '{units = "in", scale = {1, 2, 3}, rotate = "y:30", place = "plate", translate = {1, 1, 1}}')" \
    "$(printf '%s' "$OUT" | json_bbox)" "Lua: every option at once, as the CLI has it"
is "$(lua_bbox "$S" '{units = "m", machine = "creol-ladrp"}')" "0 0 0 2 1 0.5" "Lua units = \"m\" for a machine in cm: 2 cm"
is "$(lua_bbox "$S" '{units = "m", machine = lamina.machine("lpbf-cli")}')" "0 0 0 20 10 5" "... a machine object in mm: 20 mm"
is "$(lua_bbox "$S" '{scale = 100, repair = false}')" "0 0 0 2 1 0.5" "Lua scale = 100"
run "$LAMINA" run - "$B" <<'LUA'
for _, o in ipairs{{rotate = "q:90"}, {units = "furlong"}, {scale = 0}, {translate = {1, 2}}, {place = "floor"},
                   {rotat = "x:90"}, {machine = "no-such-machine", units = "m"}, {repair = "no"}} do
  local ok, err = pcall(lamina.load, arg[1], o)
  print(ok, err)
end
LUA
is "$RC" 0 "Lua: bad options are errors (pcall), not crashes"
like "$OUT" "^false\tbad argument #2 to 'lamina\.load' \(rotate 'q:90': the axis must be x, y or z\)$" "rotate q:90"
like "$OUT" "^false\t.*units must be mm, cm, m, um, in or ft, got 'furlong'" "units furlong"
like "$OUT" "^false\t.*scale '0': a factor of 0 flattens the model" "scale 0"
like "$OUT" "^false\t.*translate must be a list of 3 numbers, got 2" "translate {1, 2}"
like "$OUT" "^false\t.*place 'floor': expected plate or none" "place floor"
like "$OUT" "^false\t.*unknown option 'rotat' \(did you mean 'rotate'\? options: units, scale, rotate, translate, place, repair, machine\)" \
    "an unknown key lists the valid ones"
like "$OUT" "^false\t.*machine: unknown machine 'no-such-machine'" "an unknown machine"
like "$OUT" "^false\t.*repair must be true or false" "repair = \"no\""

# ---- the recipes take the load options -------------------------------------------
ROOT=$(cd "$TESTS/.." && pwd)
for r in default adaptive aligned best_axis scan_orders hatching; do
    run "$LAMINA" run "$ROOT/recipes/$r.lua" --rotate q:90 --out "$TMP/r-out"
    [ "$r" = default ] || run "$LAMINA" run "$ROOT/recipes/$r.lua" --rotate q:90
    like "$RC $ERR" "^2 lamina: $r\.lua: rotate 'q:90': the axis must be x, y or z
usage: lamina run recipes/$r\.lua .*--rotate" "$r --rotate q:90: a usage error, exit 2"
    run "$LAMINA" run "$ROOT/recipes/$r.lua" --help
    like "$OUT" "--units U.*--place plate.*--no-repair" "$r --help names the load options"
done
run "$LAMINA" run "$ROOT/recipes/adaptive.lua" --units m --rotate x:90 --place plate "$S"
is "$RC" 0 "adaptive.lua --units m --rotate x:90 --place plate"
like "$OUT" "span 0 \.\. 10$" "... its span along z: the 0.01 m of y, in mm, from the plate"
run "$LAMINA" run "$ROOT/recipes/aligned.lua" --scale 1,1,2 --translate 0,0,1 "$B"
like "$OUT" "^flat heights: 2: -39 -23$" "aligned.lua --scale 1,1,2 --translate 0,0,1: the faces at -39 and -23"
run "$LAMINA" run "$ROOT/recipes/default.lua" --out "$TMP/d-out" "$B"
like "$OUT" "creol-ladrp +100 layers" "default.lua on the 8 mm box: creol-ladrp (cm) takes it as 8 cm, 100 layers of 0.08"
run "$LAMINA" run "$ROOT/recipes/default.lua" --units mm --out "$TMP/d-out" "$B"
like "$OUT" "creol-ladrp +10 layers" "... with --units mm, 0.8 cm: 10 layers"
like "$OUT" "sls-contours +32 layers" "... and sls-contours (mm) 8 mm: 32 layers of 0.25"
# an open mesh: a box without its top, which the slicer closes layer by layer
python3 - "$TMP/cup.stl" <<'PY'
import sys
c = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
with open(sys.argv[1], "w") as f:
    f.write("solid cup\n")
    for a, b, cc, d in [(0, 2, 3, 1), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]:
        for t in ((a, b, cc), (a, cc, d)):
            f.write("facet normal 0 0 0\nouter loop\n" + "".join("vertex %d %d %d\n" % c[v] for v in t) + "endloop\nendfacet\n")
    f.write("endsolid cup\n")
PY
run "$LAMINA" run "$ROOT/recipes/adaptive.lua" --no-repair "$TMP/cup.stl"
like "$RC $ERR" "\A1 lamina: adaptive\.lua: [^\n]*cup\.stl: the mesh is not closed \(4 boundary edges, --no-repair\); --allow-open slices it[^\n]*\z" \
    "adaptive.lua on an open mesh: a message on one line, exit 1"
run "$LAMINA" run "$ROOT/recipes/adaptive.lua" --no-repair --allow-open "$TMP/cup.stl"
is "$RC" 0 "... and with --allow-open it runs"
printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' >"$TMP/flat.stl"
run "$LAMINA" run "$ROOT/recipes/adaptive.lua" --allow-open "$TMP/flat.stl"
like "$RC $ERR" "\A1 lamina: adaptive\.lua: [^\n]*flat\.stl has no extent along z[^\n]*\z" "a flat model: a message, no traceback"

done_testing
