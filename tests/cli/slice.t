#!/usr/bin/env bash
# lamina slice: the thesis's SLS sample, options, errors, atomic output,
# determinism, and an SVG contact sheet checked by a real renderer.
. "$(dirname "$0")/lib.sh"

# The thesis's SLS sample (SPEC 9): two layers at z = 0 and z = 1, each an
# outer CCW square of side 2 from (-1,-1) and an inner CW square of side 1
# from (-0.5,-0.5). Blocks of a layer: solid first, then its hole.
expected() {
    for z in 0 1; do
        [ "$z" = 1 ] && echo
        printf 'contour %s.000000\nloop 4\n' "$z"
        printf -- '-1.000000 -1.000000 %s.000000\n1.000000 -1.000000 %s.000000\n' "$z" "$z"
        printf '1.000000 1.000000 %s.000000\n-1.000000 1.000000 %s.000000\nendloop\nendcontour\n\n' "$z" "$z"
        printf 'contour %s.000000\nloop 4\n' "$z"
        printf -- '-0.500000 -0.500000 %s.000000\n-0.500000 0.500000 %s.000000\n' "$z" "$z"
        printf '0.500000 0.500000 %s.000000\n0.500000 -0.500000 %s.000000\nendloop\nendcontour\n' "$z" "$z"
    done
}
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -a z -w 1 --cut floor
is "$RC" 0 "thesis sample: exit 0"
is "$OUT" "$(expected)" "thesis sample reproduced exactly"

run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 1 --cut floor -o "$TMP/a.sls"
is "$RC" 0 "-o: exit 0"
is "$(cat "$TMP/a.sls")" "$(expected)" "-o writes the same program"
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 1 --cut floor -o "$TMP/b.sls"
cmp -s "$TMP/a.sls" "$TMP/b.sls"; ok $? "two runs give byte-identical output"
is "$(ls "$TMP" | grep -c tmp-)" 0 "no temporary files left behind"

# The STL of the same part (one shell from openscad) slices the same.
run "$LAMINA" slice "$M/cube_hole.stl" -w 1 --cut floor
is "$(grep -c '^contour' <<<"$OUT")" 4 "cube_hole.stl: 4 contours in 2 layers"

# Frame with an island: three contours per layer, solid, hole, solid.
run "$LAMINA" slice "$M/frame_island.ug" -w 5
is "$(grep -c '^contour' <<<"$OUT")" 12 "frame with island: 3 contours x 4 layers"

# Along x the layer frame is (y, z, x): output is still model coordinates
# with x the cut height.
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -a x -w 0.5 --cut floor
is "$RC" 0 "axis x: exit 0"
like "$OUT" $'contour -1\\.000000\nloop 4\n-1\\.000000 -1\\.000000 0\\.000000' "axis x: first contour at x=-1 starts at (y,z)=(-1,0)"
is "$(grep -c '^contour' <<<"$OUT")" 6 "axis x: layers at -1 (1 contour), -0.5 and 0 (outer and hole), 0.5 (1)"

# Defaults: axis z, width 1/100 of the extent (2 -> 0.02), middle cut.
run "$LAMINA" slice "$M/thesis_cube.ug"
is "$(grep -c '^contour' <<<"$OUT")" 100 "default width: 100 layers"
like "$OUT" '^contour -0\.990000' "default cut: middle of the first layer"

# Usage errors: exit 2, nothing written.
usage() { run "$LAMINA" slice "$M/thesis_cube.ug" "$@" -o "$TMP/u.sls"; is "$RC" 2 "usage error: $*"; }
usage -a w
usage -a 0,0,0
usage -w 0
usage -w -1
usage --widths 0.5,0.5
usage --planes 0,1,0.5
usage --cut top
usage --bogus
ok "$([ ! -e "$TMP/u.sls" ]; echo $?)" "usage errors write no output file"

# An open mesh: a cube without its x=+1 side. Repaired on load (the
# default), the side is filled and the cube slices as the closed one does.
# With --no-repair: the default gap fails (exit 1, no output file); a
# larger gap closes it and says so; --allow-open drops it.
awk 'BEGIN{skip=0} /facet normal 1 0 0/{skip=7} skip>0{skip--; next} {print}' "$M/thesis_cube_ascii.stl" >"$TMP/open.stl"
run "$LAMINA" info --json --no-repair "$TMP/open.stl"
is "$(jq .boundary_edges <<<"$OUT")" 4 "the open cube has 4 boundary edges"
run "$LAMINA" slice "$TMP/open.stl" -w 0.5 -o "$TMP/open.sls"
is "$RC" 0 "repaired on load: exit 0"
like "$ERR" 'repaired: filled 1 hole \(4 boundary edges\)' "... and says what it filled"
"$LAMINA" slice "$M/thesis_cube_ascii.stl" -w 0.5 -o "$TMP/closed.sls" 2>/dev/null
cmp -s "$TMP/open.sls" "$TMP/closed.sls"
ok $? "... into the closed cube's program"
rm -f "$TMP/open.sls"
run "$LAMINA" slice --no-repair "$TMP/open.stl" -w 0.5 -o "$TMP/open.sls"
is "$RC" 1 "open outlines: exit 1"
like "$ERR" 'layer 1 .*open outline from \(1, 1\) to \(1, -1\)' "open outline reported with layer and position"
# the default gap is 1/2000 of the diagonal of the 2 x 2 x 2 box: 0.00173205
like "$ERR" 'stayed open \(gap tolerance 0.00173205\)' "the automatic gap tolerance is reported"
ok "$([ ! -e "$TMP/open.sls" ]; echo $?)" "failed run leaves no output file"
run "$LAMINA" slice --no-repair "$TMP/open.stl" -w 0.5 --gap 2.5 -o "$TMP/open.sls"
is "$RC" 0 "--gap 2.5 closes the gap"
like "$ERR" 'layer 1 .*closed 1 gap, largest 2 \(gap tolerance 2.5\)' "gap closing reported per layer, with the tolerance"
run "$LAMINA" slice --no-repair "$TMP/open.stl" -w 0.5 --gap auto -o "$TMP/open.sls"
is "$RC" 1 "--gap auto: still open"
like "$ERR" 'stayed open \(gap tolerance 0.00173205\)' "--gap auto: the default tolerance"
usage --gap -1
usage --gap big
is "$(grep -c '^loop 4' "$TMP/open.sls")" 4 "closed outlines are 4-point squares"
run "$LAMINA" slice --no-repair "$TMP/open.stl" -w 0.5 --allow-open -o "$TMP/open2.sls"
is "$RC" 0 "--allow-open: exit 0"
like "$ERR" 'dropped' "--allow-open says what it dropped"

# Twin loops: a torus (tube radius 2 around radius 6, 24 x 12 facets) has a
# ring of vertices at its bottom, z = -2. A floor cut there is taken just
# above it: a band of no width, whose two outlines are the same points in
# opposite directions. They cancel (reported); the layer has no contour.
python3 - "$TMP/torus.stl" <<'PY'
import math, sys
R, r, n, m = 6.0, 2.0, 24, 12
P = [[((R + r * math.cos(2 * math.pi * j / m - math.pi / 2)) * math.cos(2 * math.pi * i / n),
       (R + r * math.cos(2 * math.pi * j / m - math.pi / 2)) * math.sin(2 * math.pi * i / n),
       r * math.sin(2 * math.pi * j / m - math.pi / 2)) for j in range(m)] for i in range(n)]
with open(sys.argv[1], "w") as f:
    f.write("solid torus\n")
    for i in range(n):
        for j in range(m):
            a, b = P[i][j], P[(i + 1) % n][j]
            c, d = P[(i + 1) % n][(j + 1) % m], P[i][(j + 1) % m]
            for t in ((a, b, c), (a, c, d)):
                f.write("facet normal 0 0 0\nouter loop\n")
                for p in t:
                    f.write("vertex %.17g %.17g %.17g\n" % p)
                f.write("endloop\nendfacet\n")
    f.write("endsolid torus\n")
PY
run "$LAMINA" slice "$TMP/torus.stl" -w 0.5 --cut floor -o "$TMP/torus.sls"
is "$RC" 0 "torus, floor cut on its bottom ring: exit 0"
like "$ERR" 'layer 1 \(h=-2\): cancelled 2 coincident loops' "the two coincident loops cancel, reported"
is "$(grep -c '^contour -2.000000' "$TMP/torus.sls")" 0 "no contour at the bottom ring"
is "$(head -1 "$TMP/torus.sls")" "contour -1.500000" "the program starts with the next layer"

# SVG contact sheet, rendered by rsvg-convert and checked pixel by pixel
# (solids tinted: the sheet of a run also draws its scan paths).
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 1 --cut floor --svg "$TMP/sheet.svg" -o "$TMP/s.sls"
is "$RC" 0 "--svg: exit 0"
like "$(cat "$TMP/sheet.svg")" '2 layers' "title says how many layers"
rsvg-convert -f png -o "$TMP/sheet.png" "$TMP/sheet.svg"; ok $? "rsvg-convert renders the sheet"
# Panel 0 sits at (10, 34), its drawing at +10 px with scale 180/2 per unit:
# the hole centre (0,0) maps to (110, 134), material at (-0.75, 0) to
# (42.5, 134), outside the part to (15, 38).
px=$(python3 "$TESTS/cli/pixel.py" "$TMP/sheet.png" 110,134 42,134 15,38)
is "$px" "background tint background" "hole is background, material filled, outside background"

# More than 100 layers: 100 panels, evenly chosen, said in the title.
run "$LAMINA" slice "$M/thesis_cube.ug" -w 0.01 --svg "$TMP/many.svg" -o "$TMP/many.sls"
like "$(cat "$TMP/many.svg")" '100 of 200 layers shown' "at most 100 panels"
is "$(grep -c '<path class="section"' "$TMP/many.svg")" 100 "100 panels drawn"
# Targets that are not plain files. The atomic rename must not replace a
# device or a pipe with a plain file (it once turned -o /dev/null into a
# plain file; a FIFO stands in for devices here, so that a regression
# cannot break the machine's /dev/null), nor a symbolic link with a file.
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 1 --cut floor -o "$TMP/plain.sls"
mkfifo "$TMP/fifo"
timeout 20 cat "$TMP/fifo" >"$TMP/from-fifo" &  # a bounded wait, should the FIFO be replaced
reader=$!
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 1 --cut floor -o "$TMP/fifo"
wait "$reader"
is "$RC" 0 "-o FIFO: exit 0"
ok "$([ -p "$TMP/fifo" ]; echo $?)" "the FIFO is still a FIFO"
ok "$(cmp -s "$TMP/plain.sls" "$TMP/from-fifo"; echo $?)" "the program came out of the FIFO whole"
echo old >"$TMP/real.sls"
ln -s real.sls "$TMP/link.sls"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 1 --cut floor -o "$TMP/link.sls"
is "$RC" 0 "-o SYMLINK: exit 0"
ok "$([ -L "$TMP/link.sls" ]; echo $?)" "the link is still a link"
ok "$(cmp -s "$TMP/plain.sls" "$TMP/real.sls"; echo $?)" "the file it names holds the program"
mkdir "$TMP/adir"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 1 --cut floor -o "$TMP/adir"
like "$RC $ERR" "(?s)^1 .*adir: cannot write output: is a directory" "-o DIRECTORY: exit 1, said so"

# Every profile key from the command line (--set), the options as its
# aliases, GNU conventions.
run "$LAMINA" slice "$M/thesis_cube.ug" -m sls-contours --set spot_width=0.3 --set layer_width=0.05 -o "$TMP/s.sls"
is "$RC" 0 "--set spot_width --set layer_width: exit 0"
is "$(grep -c '^contour' "$TMP/s.sls")" 40 "--set layer_width=0.05: a 2-unit cube in 40 layers"
run "$LAMINA" slice "$M/thesis_cube.ug" -m sls-contours -s spot_width=0.3 --set beam_offset=true -w 1 -o "$TMP/b.sls"
is "$(sed -n 3p "$TMP/b.sls")" "-0.850000 -0.850000 -0.500000" "--set spot_width=0.3 with beam_offset: the contour inset by 0.15"
run "$LAMINA" slice "$M/thesis_cube.ug" -w 1 --beam-offset --set spot_width=0.3 -o "$TMP/b2.sls"
cmp -s "$TMP/b.sls" "$TMP/b2.sls"
ok $? "--beam-offset is --set beam_offset=true"
run "$LAMINA" slice "$M/thesis_cube.ug" --width=1 --cut=floor -o "$TMP/eq.sls"
run "$LAMINA" slice "$M/thesis_cube.ug" --width 1 --cut floor -o "$TMP/sp.sls"
cmp -s "$TMP/eq.sls" "$TMP/sp.sls"
ok $? "--name=value and --name value are the same"
run "$LAMINA" slice "$M/thesis_cube.ug" -w1 --set cut=floor -o "$TMP/att.sls"
cmp -s "$TMP/eq.sls" "$TMP/att.sls"
ok $? "-w1 (attached value) and --set cut=floor"
cp "$M/thesis_cube.ug" "$TMP/-cube.ug"
(cd "$TMP" && "$LAMINA" slice -w 1 -o dash.sls -- -cube.ug)
ok $? "-- ends the options: a model named -cube.ug"
run "$LAMINA" slice "$M/thesis_cube.ug" --set bead_width=abc
like "$RC $ERR" "^2 lamina slice: --set bead_width=abc: bead_width must be a number, got 'abc'" "--set: a bad value, exit 2, the YAML loader's message"
run "$LAMINA" slice "$M/thesis_cube.ug" -w 0
like "$RC $ERR" "^2 lamina slice: -w 0: layer_width must be greater than 0, got '0'" "-w is layer_width: its message"
run "$LAMINA" slice "$M/thesis_cube.ug" --angel 5
like "$RC $ERR" "^2 lamina slice: unknown option '--angel' \\(did you mean '--angle'\\?\\)" "an unknown option: did you mean"
like "$ERR" "try 'lamina slice --help'" "the hint names the command"
run "$LAMINA" slice "$M/thesis_cube.ug" --bead-width 0.3
like "$RC $ERR" "^2 .*unknown option '--bead-width' \\(did you mean '--set bead_width=...'\\?\\)" "a profile key spelt as an option: --set"
run "$LAMINA" slice "$M/thesis_cube.ug" --islands=yes
like "$RC $ERR" "^2 .*option --islands takes no value" "a flag with a value"
run "$LAMINA" slice "$M/thesis_cube.ug" -w 1 --widths 1,1
is "$RC" 2 "-w with --widths: usage error"
run "$LAMINA" slice --help
like "$OUT" '--islands +--set raster.islands=true' "--help lists the profile options with the key they set"
ok "$([ ! -e "$TMP/u2.sls" ]; echo $?)" "usage errors write nothing"
done_testing
