#!/usr/bin/env bash
# lamina repair MODEL -o OUT: the repaired mesh written as binary STL (or
# OBJ by extension), checked by this test's own STL reader and by admesh (an
# independent tool: its counts of disconnected edges, reversed facets and
# parts); OBJ reloaded with the same volume; the output never over the
# input, nothing left behind by a failure; the --json report's fields and
# numbers; exit codes. Paths with spaces throughout.
. "$(dirname "$0")/lib.sh"

D="$TMP/with space"
mkdir -p "$D"
j() { jq -r "$1" <<<"$OUT"; }
qm() { printf '%s' "$1" | perl -pe 's/(\W)/\\$1/g'; } # a path as a regex that matches it alone

# cube.py OUT [skip FACE] [flip N]: a 10 mm cube as ASCII STL, 12 facets
# wound outward; face FACE (0..5: -z +z -y +y -x +x) left out, the first N
# facets wound inward
cat >"$TMP/cube.py" <<'EOF'
import sys
out, args = sys.argv[1], sys.argv[2:]
skip = int(args[args.index("skip") + 1]) if "skip" in args else -1
flip = int(args[args.index("flip") + 1]) if "flip" in args else 0
V = [(x, y, z) for z in (0, 10) for y in (0, 10) for x in (0, 10)]
Q = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
T = []
for f, (a, b, c, d) in enumerate(Q):
    if f != skip:
        T += [(a, b, c), (a, c, d)]
T = [(t[0], t[2], t[1]) if i < flip else t for i, t in enumerate(T)]
with open(out, "w") as f:
    f.write("solid cube\n")
    for t in T:
        f.write("facet normal 0 0 0\nouter loop\n")
        for i in t:
            f.write("vertex %g %g %g\n" % V[i])
        f.write("endloop\nendfacet\n")
    f.write("endsolid cube\n")
EOF

# stlcheck.py FILE: this test's own reading of a binary STL: "COUNT BAD"
# where BAD counts the facets whose normal is not of unit length, not along
# the right-hand cross product of its corners, or not pointing away from
# the cube's centre (5,5,5), and corners off the cube's; the size must be
# 84 + 50 COUNT
cat >"$TMP/stlcheck.py" <<'EOF'
import math, struct, sys
b = open(sys.argv[1], "rb").read()
n = struct.unpack_from("<I", b, 80)[0]
if len(b) != 84 + 50 * n:
    print("size %d for %d facets" % (len(b), n)); sys.exit()
bad = 0
for i in range(n):
    v = struct.unpack_from("<12fH", b, 84 + 50 * i)
    nn, c = v[0:3], [v[3:6], v[6:9], v[9:12]]
    u = [c[1][k] - c[0][k] for k in range(3)]
    w = [c[2][k] - c[0][k] for k in range(3)]
    x = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    xl = math.sqrt(sum(t * t for t in x))
    nl = math.sqrt(sum(t * t for t in nn))
    cen = [sum(p[k] for p in c) / 3 - 5 for k in range(3)]
    if abs(nl - 1) > 1e-6 or xl == 0 or sum(nn[k] * x[k] for k in range(3)) / xl < 0.9999 \
            or sum(nn[k] * cen[k] for k in range(3)) <= 0 or v[12] != 0 \
            or any(t not in (0.0, 10.0) for p in c for t in p):
        bad += 1
print(n, bad)
EOF

# admesh_report FILE: admesh's counts of the file as read (its "Original"
# column, before admesh fixes anything), one "name=value" a line
admesh_report() {
    admesh "$1" 2>&1 | perl -ne '
        print "facets=$1\n" if /^Number of facets\s*:\s*(\d+)/;
        print "open1=$1\n" if /^Facets with 1 disconnected edge\s*:\s*(\d+)/;
        print "open2=$1\n" if /^Facets with 2 disconnected edges\s*:\s*(\d+)/;
        print "open3=$1\n" if /^Facets with 3 disconnected edges\s*:\s*(\d+)/;
        print "parts=$1\n" if /^Number of parts\s*:\s*(\d+)/;
        print "reversed=$1\n" if /^Facets reversed\s*:\s*(\d+)/;
        print "backwards=$1\n" if /^Backwards edges\s*:\s*(\d+)/;
        print "added=$1\n" if /^Facets added\s*:\s*(\d+)/;
        printf "volume=%.3f\n", $1 if /Volume\s*:\s*([-\d.]+)/'
}
closed_admesh="facets=12 open1=0 open2=0 open3=0 parts=1 volume=1000.000 added=0 reversed=0 backwards=0"

# ---- a closed cube -----------------------------------------------------------
python3 "$TMP/cube.py" "$D/cube.stl"
cp "$D/cube.stl" "$TMP/cube.orig"
run "$LAMINA" repair "$D/cube.stl" -o "$D/out.stl"
is "$RC" 0 "closed cube: exit 0"
is "$ERR" "lamina: $D/cube.stl: nothing to repair" "one line: nothing to repair"
is "$OUT" "" "nothing on standard output"
is "$(python3 "$TMP/stlcheck.py" "$D/out.stl")" "12 0" "12 facets, unit outward normals, the cube's corners"
is "$(head -c 6 "$D/out.stl")" "lamina" "the header names lamina (not 'solid')"
is "$(admesh_report "$D/out.stl" | tr '\n' ' ' | sed 's/ $//')" "$closed_admesh" \
    "admesh: 12 facets, no disconnected edge, one part, volume 1000, nothing to fix"
run "$LAMINA" info --json "$D/out.stl"
is "$(j .format) $(j .closed) $(j .volume) $(j .triangles)" "stl-binary true 1000 12" "lamina reads it back: closed, volume 1000"

# -v: the counts; -q: no summary
run "$LAMINA" repair -v "$D/cube.stl" --output="$D/out2.stl"
like "$ERR" 'before: 12 triangles, 8 vertices, 0 open edges; after: 12 triangles, 8 vertices, 0 open edges' "-v: counts before and after"
cmp -s "$D/out.stl" "$D/out2.stl"; ok $? "--output=FILE: the same bytes"
rm -f "$D/out2.stl"
run "$LAMINA" repair --output "$D/out2.stl" -q "$D/cube.stl"
cmp -s "$D/out.stl" "$D/out2.stl"; ok $? "--output FILE before the model: the same bytes"
run "$LAMINA" repair -q "$D/cube.stl" -o"$D/out2.stl"
is "$RC $ERR" "0 " "-q: no summary line"

# ---- OBJ by extension ----------------------------------------------------------
run "$LAMINA" repair "$D/cube.stl" -o "$D/out.OBJ"
is "$RC" 0 "OBJ: exit 0"
like "$(cat "$D/out.OBJ")" '\A# lamina' "OBJ: text, a comment naming lamina first"
is "$(grep -c '^v ' "$D/out.OBJ") $(grep -c '^f ' "$D/out.OBJ")" "8 12" "OBJ: 8 v lines, 12 f lines"
run "$LAMINA" info --json "$D/out.OBJ"
is "$(j .format) $(j .closed) $(j .volume) $(j .triangles) $(j .vertices)" "obj true 1000 12 8" \
    "OBJ reloads in lamina: closed, the same volume"
ref=$("$LAMINA" info --json "$D/cube.stl" | jq -c '{volume, area, bbox, shells}')
is "$(jq -c '{volume, area, bbox, shells}' <<<"$OUT")" "$ref" "OBJ: the same volume, area and bounding box as the input"

# ---- the model options: the mesh the other commands would slice ------------------------
run "$LAMINA" repair "$D/cube.stl" --units cm --place plate -o "$D/placed.obj"
is "$RC" 0 "--units cm --place plate: exit 0"
run "$LAMINA" info --json "$D/placed.obj"
is "$(jq -c '[.bbox.min, .bbox.max, .volume]' <<<"$OUT")" '[[-50,-50,0],[50,50,100],1000000]' \
    "--units cm --place plate: written in millimetres, on the plate, centred"
run "$LAMINA" repair "$D/cube.stl" --units furlong -o "$D/placed.stl"
is "$RC" 2 "an unknown unit: usage error"
[ ! -e "$D/placed.stl" ]; ok $? "and nothing written"

# ---- standard streams -------------------------------------------------------------
"$LAMINA" repair "$D/cube.stl" -o - 2>/dev/null | cat >"$D/piped.stl"
cmp -s "$D/out.stl" "$D/piped.stl"; ok $? "-o - to a pipe: the same bytes as the file"
run "$LAMINA" repair - -o "$D/stdin.stl" <"$D/cube.stl"
is "$RC $ERR" "0 lamina: <stdin>: nothing to repair" "MODEL -: standard input, named <stdin>"
is "$(head -c 80 "$D/stdin.stl" | tr -d '\0')" "lamina 0.1.0 binary STL of <stdin>" "from stdin: the header names <stdin>"
is "$(python3 "$TMP/stlcheck.py" "$D/stdin.stl")" "12 0" "from stdin: the same facets"
run "$LAMINA" repair "$D/cube.stl" -o - --json
is "$RC" 2 "-o - with --json: usage error (both on standard output)"
like "$ERR" 'both write to standard output' "and says why"
if script -qec true /dev/null >/dev/null 2>&1; then
    script -qec "\"$LAMINA\" repair \"$D/cube.stl\" -o -; echo \"rc=\$?\"" /dev/null >"$TMP/tty" 2>&1
    like "$(tr -d '\r' <"$TMP/tty")" 'not written to a terminal(.|\n)*rc=2' "-o - on a terminal: usage error, no binary on the screen"
else
    ok 0 "# skip no script(1) for a terminal"
fi

# ---- never over the input -----------------------------------------------------------
ls_before=$(ls -a "$D")
run "$LAMINA" repair "$D/cube.stl" -o "$D/cube.stl"
is "$RC" 2 "-o the input: usage error"
like "$ERR" 'is an input of this command.*refusing to overwrite it' "and says so"
unlike=$(grep -c "nothing to repair" <<<"$ERR")
is "$unlike" 0 "before any summary"
cmp -s "$D/cube.stl" "$TMP/cube.orig"; ok $? "the input is untouched"
ln "$D/cube.stl" "$D/hard link.stl"
ln -s "cube.stl" "$D/sym link.stl"
for o in "$D/hard link.stl" "$D/sym link.stl" "$D/./cube.stl"; do
    run "$LAMINA" repair "$D/cube.stl" -o "$o"
    is "$RC" 2 "-o ${o#"$D/"} (the input by another name): refused"
done
run "$LAMINA" repair "$D/sym link.stl" -o "$D/cube.stl"
is "$RC" 2 "the input through a link, -o its target: refused"
cmp -s "$D/cube.stl" "$TMP/cube.orig"; ok $? "the input is still untouched"
rm -f "$D/hard link.stl" "$D/sym link.stl"
is "$(ls -a "$D")" "$ls_before" "no temporary left beside it"

# ---- usage errors ---------------------------------------------------------------------
run "$LAMINA" repair "$D/cube.stl"
is "$RC" 2 "no -o: usage error"
like "$ERR" 'give the output: -o FILE' "and says what to give"
run "$LAMINA" repair "$D/cube.stl" -o
is "$RC" 2 "-o without a value: usage error"
run "$LAMINA" repair "$D/cube.stl" -o ""
is "$RC" 2 "-o '': usage error"
run "$LAMINA" repair -o "$D/x.stl"
is "$RC" 2 "no model: usage error"
run "$LAMINA" repair "$D/cube.stl" -o "$D/x.stl" --bogus
is "$RC" 2 "an unknown option: usage error"
[ ! -e "$D/x.stl" ]; ok $? "no output after a usage error"
run "$LAMINA" repair -- "$D/cube.stl" -o "$D/x.stl"
is "$RC" 2 "after --, -o is a second model: usage error"
run "$LAMINA" repair --help
is "$RC" 0 "--help: exit 0"
like "$OUT" '^usage: lamina repair MODEL -o FILE' "--help: the usage"

# ---- bad models: an error with a position, nothing written ----------------------------
printf 'solid bad\nfacet normal 0 0 0\nouter loop\nvertex 1 2\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid bad\n' >"$D/bad.stl"
ls_before=$(ls -a "$D")
run "$LAMINA" repair "$D/bad.stl" -o "$D/bad-out.stl"
is "$RC" 1 "a malformed STL: exit 1"
like "$ERR" "^lamina: $(qm "$D/bad.stl"):\\d+:\\d+: expected the vertex z coordinate" "the error names file:line:column and what is wrong"
is "$(ls -a "$D")" "$ls_before" "no output file, no temporary"
run "$LAMINA" repair "$D/missing.stl" -o "$D/bad-out.stl"
is "$RC" 1 "a missing model: exit 1"
[ ! -e "$D/bad-out.stl" ]; ok $? "no output"
run "$LAMINA" repair "$D/cube.stl" -o "$D/no such dir/out.stl"
is "$RC" 1 "an output in a missing directory: exit 1"
like "$ERR" 'no such dir' "and names it"
if [ -w /dev/full ]; then
    run "$LAMINA" repair "$D/cube.stl" -o /dev/full
    is "$RC" 1 "-o /dev/full: exit 1"
    like "$ERR" '/dev/full: cannot write output: No space left on device' "the write error, with the reason"
fi

# ---- a cube missing its top face: the JSON report ----------------------------------------
python3 "$TMP/cube.py" "$D/open.stl" skip 1
run "$LAMINA" repair "$D/open.stl" -o "$D/open-out.stl" --json
jq -e . >/dev/null <<<"$OUT"; ok $? "--json: one valid JSON object"
is "$(jq -r 'keys_unsorted | join(" ")' <<<"$OUT")" "model format output output_format repair closed summary before after" \
    "--json: the model, the output, the repair report, the counts before and after"
is "$(jq -r '.repair | keys_unsorted | join(" ")' <<<"$OUT")" \
    "ran welded degenerate duplicates flipped holes hole_edges fill_triangles crossing_loops holes_left boundary_edges nonmanifold_edges crossing_edges weld_tolerance fill_area largest_hole crossings_unknown" \
    "repair: every field of the repair report (as info --json and the run's JSON have it)"
is "$(jq -r '.before | keys_unsorted | join(" ")' <<<"$OUT")" "triangles vertices shells boundary_edges nonmanifold_edges area volume" \
    "before: the mesh's counts"
is "$(j .model) $(j .output) $(j .output_format) $(j .format) $(j .repair.ran)" "$D/open.stl $D/open-out.stl stl-binary stl-ascii true" \
    "the model, the output and their formats"
is "$(j .before.triangles) $(j .before.vertices) $(j .before.boundary_edges) $(j .before.volume)" "10 8 4 666.6666666666666" \
    "before: 10 triangles, 8 vertices, 4 open edges"
is "$(j .repair.holes) $(j .repair.hole_edges) $(j .repair.fill_triangles) $(j .repair.holes_left) $(j .repair.crossing_loops)" \
    "1 4 2 0 0" "one hole of 4 edges filled with 2 triangles"
is "$(j .repair.fill_area) $(j .repair.largest_hole)" "100 100" "the fill covers the missing face: 100 mm2"
python3 -c 'import math, sys; sys.exit(abs(float(sys.argv[1]) - 1e-6 * math.sqrt(300)) > 1e-15)' "$(j .repair.weld_tolerance)"
ok $? "weld tolerance 1e-6 of the diagonal, 10 sqrt(3) ($(j .repair.weld_tolerance))"
is "$(j .repair.boundary_edges) $(j .repair.nonmanifold_edges) $(j .repair.crossing_edges) $(j .closed)" "0 0 0 true" \
    "nothing open or crossing remains"
is "$(j .after.triangles) $(j .after.vertices) $(j .after.boundary_edges) $(j .after.area) $(j .after.volume)" "12 8 0 600 1000" \
    "after: 12 triangles, closed, area 600, volume 1000"
is "$(j .repair.welded) $(j .repair.degenerate) $(j .repair.duplicates) $(j .repair.flipped)" "0 0 0 0" \
    "nothing welded, removed or flipped"
is "$(j .summary)" "filled 1 hole (4 boundary edges)" "the summary"
is "$RC" 0 "a hole repair filled: exit 0"
is "$ERR" "lamina: $D/open.stl: repaired: filled 1 hole (4 boundary edges)" "stderr: what was repaired, nothing else"
is "$(python3 "$TMP/stlcheck.py" "$D/open-out.stl")" "12 0" "the output: 12 facets, unit outward normals"
is "$(admesh_report "$D/open-out.stl" | tr '\n' ' ' | sed 's/ $//')" "$closed_admesh" "admesh: no open edges, one part, volume 1000"

# facets wound inward: flipped, counted, written outward
python3 "$TMP/cube.py" "$D/flipped.stl" flip 3
run "$LAMINA" repair "$D/flipped.stl" -o "$D/flipped-out.stl" --json
is "$RC $(j .repair.flipped) $(j .closed)" "0 3 true" "3 facets wound inward: flipped (3), closed"
is "$ERR" "lamina: $D/flipped.stl: repaired: 3 facets flipped" "stderr: the flips"
is "$(python3 "$TMP/stlcheck.py" "$D/flipped-out.stl")" "12 0" "written outward"
is "$(admesh_report "$D/flipped-out.stl" | tr '\n' ' ' | sed 's/ $//')" "$closed_admesh" "admesh: nothing reversed"

# a lone facet: repair leaves its loop open (filled, it would be a sliver
# of no volume): the file is written all the same, exit 3
printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' >"$D/lone.stl"
run "$LAMINA" repair "$D/lone.stl" -o "$D/lone-out.stl" --json
is "$RC" 3 "a lone facet: exit 3 (still open)"
is "$(j .repair.holes_left) $(j .repair.boundary_edges) $(j .closed) $(j .after.triangles)" "1 3 false 1" \
    "one loop left open, 3 open edges"
like "$ERR" 'warning: .*3 open edges' "a warning says what remains open"
[ "$(wc -c <"$D/lone-out.stl")" -eq 134 ]; ok $? "the file is written: one facet, 134 bytes"
# (admesh takes a file of under 284 bytes for empty: the count is read here)
is "$(python3 -c 'import struct, sys; print(struct.unpack_from("<I", open(sys.argv[1], "rb").read(), 80)[0])' "$D/lone-out.stl")" 1 \
    "its count says one facet"

# --no-repair: written as read, still open: exit 3 with the file written
run "$LAMINA" repair "$D/open.stl" -o "$D/open-raw.stl" --no-repair --json
is "$RC" 3 "--no-repair on an open cube: exit 3"
is "$(j .repair.ran) $(j .repair.holes) $(j .after.boundary_edges) $(j .closed)" "false 0 4 false" \
    "--no-repair: nothing done, 4 open edges"
like "$ERR" 'not repaired \(--no-repair\)' "stderr: not repaired"
like "$ERR" 'warning: .*4 open edges' "a warning says what remains open"
is "$(python3 "$TMP/stlcheck.py" "$D/open-raw.stl" 2>&1 | cut -d' ' -f1)" "10" "the file is written all the same: 10 facets"
is "$(admesh_report "$D/open-raw.stl" | grep -E '^(open1|facets)=' | tr '\n' ' ')" "facets=10 open1=4 " \
    "admesh sees the 4 facets with an open edge"
run "$LAMINA" repair -q "$D/open.stl" -o "$D/open-raw.stl" --no-repair
is "$RC" 3 "-q: the same exit"
like "$ERR" '\A[^\n]*warning: [^\n]*4 open edges[^\n]*\n?\z' "-q: only the warning"

done_testing
