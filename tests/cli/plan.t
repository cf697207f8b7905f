#!/usr/bin/env bash
# lamina slice -m MACHINE: the thesis's LADRP sample through creol-ladrp,
# the SLS profile against the built-in dialect, CLI ASCII and binary, DED
# G-code, command-line overrides and profile errors.
. "$(dirname "$0")/lib.sh"

# The thesis's LADRP sample (section 2.1), first commands of the first layer.
thesis='start_plot
3 set_dimension
0.15 feedrate
0 penup
-1.00000 1.08000 0.0 uline
0.0 -0.08 0.0 uline
0 pendown
0.15 feedrate
2.00000 0.0 0.0 uline
0 penup
0.0 -0.08 0.0 uline
0 pendown
0.15 feedrate
-2.00000 0.0 0.0 uline
0 penup
0.0 -0.08 0.0 uline
0 pendown
0.15 feedrate
2.00000 0.0 0.0 uline
0 penup
0.0 -0.08 0.0 uline
0 pendown
0.15 feedrate
-2.00000 0.0 0.0 uline
0 penup'
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp -o "$TMP/cube.ladrp"
is "$RC" 0 "creol-ladrp: exit 0"
# compare word by word: words equal, or numbers equal to 1e-9
cmp_numeric() {
    awk 'NR == FNR { a[NR] = $0; n = NR; next }
         FNR <= n { na = split(a[FNR], x); nb = split($0, y);
                    if (na != nb) { print "line " FNR ": " a[FNR] " vs " $0; bad = 1; next }
                    for (i = 1; i <= na; i++) {
                        if (x[i] == y[i]) continue
                        if (x[i] ~ /^-?[0-9.]+$/ && y[i] ~ /^-?[0-9.]+$/ && (x[i] - y[i])^2 < 1e-18) continue
                        print "line " FNR ": " a[FNR] " vs " $0; bad = 1 } }
         END { if (FNR < n) { print "output too short"; bad = 1 }; exit bad }' "$1" "$2"
}
printf '%s\n' "$thesis" >"$TMP/thesis.ladrp"
msg=$(cmp_numeric "$TMP/thesis.ladrp" "$TMP/cube.ladrp"); ok $? "the thesis's LADRP sample, command by command ($msg)"
# the first layer: 25 deposit lines of length 2; 25 layers of 0.08
is "$(grep -c '^2.00000 0.00000 0.00000 uline$\|^-2.00000 0.00000 0.00000 uline$' "$TMP/cube.ladrp")" 625 "25 lines of 2 units in each of 25 layers"
is "$(grep -c ' 0.08000 uline$' "$TMP/cube.ladrp")" 24 "24 layer changes lift the stage by 0.08"

# The SLS profile is byte for byte the built-in dialect.
for args in "thesis_cube_hole.ug -w 1 --cut floor" "frame_island.ug -w 3 -a x" "cube_hole.stl -w 0.3 -a 1,1,1"; do
    set -- $args
    model=$1; shift
    "$LAMINA" slice "$M/$model" "$@" -o "$TMP/a.sls"
    "$LAMINA" slice "$M/$model" "$@" -m sls-contours -o "$TMP/b.sls"
    cmp -s "$TMP/a.sls" "$TMP/b.sls"; ok $? "sls-contours equals the built-in output: $model $*"
done

# CLI ASCII, and CLI binary decoded independently: the same job.
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -m cli-ascii -w 1 --cut floor -o "$TMP/a.cli"
is "$RC" 0 "cli-ascii: exit 0"
is "$(sed -n 5,7p "$TMP/a.cli")" '$$DIMENSION/-1.00000,-1.00000,0.00000,1.00000,1.00000,2.00000
$$LAYERS/2
$$LABEL/1,thesis_cube_hole' "header: the bounding box (the 2-unit cube from z 0 to 2), 2 layers, the part's label"
is "$(grep -c '^\$\$POLYLINE/' "$TMP/a.cli")" 4 "four polylines"
is "$(grep '^\$\$POLYLINE/' "$TMP/a.cli" | cut -d/ -f2 | cut -d, -f1 | sort -u)" 1 "one part id for the model's every contour"
like "$(cat "$TMP/a.cli")" '\$\$POLYLINE/1,1,5,-1.00000,-1.00000,1.00000,-1.00000,1.00000,1.00000,-1.00000,1.00000,-1.00000,-1.00000' "solid: dir 1, closed, counter-clockwise"
like "$(cat "$TMP/a.cli")" '\$\$POLYLINE/1,0,5,-0.50000,-0.50000,-0.50000,0.50000,' "hole: dir 0, clockwise, the same part id"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -m cli-binary -w 1 --cut floor -o "$TMP/b.cli"
is "$RC" 0 "cli-binary (plugin): exit 0"
python3 "$TESTS/cli/clidecode.py" "$TMP/b.cli" >"$TMP/b.txt"; ok $? "the binary file decodes"
cmp -s "$TMP/a.cli" "$TMP/b.txt"; ok $? "binary CLI decodes to the ASCII CLI of the same job"
run "$LAMINA" slice "$M/frame_island.ug" -m cli-binary -w 2.5 -o "$TMP/c.cli"
"$LAMINA" slice "$M/frame_island.ug" -m cli-ascii -w 2.5 -o "$TMP/c.txt"
python3 "$TESTS/cli/clidecode.py" "$TMP/c.cli" | cmp -s - "$TMP/c.txt"; ok $? "frame with island: binary and ASCII agree over 8 layers"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -m cli-ascii -w 1 --cut floor --beam-offset -o "$TMP/d.cli"
like "$(cat "$TMP/d.cli")" '\$\$POLYLINE/1,1,5,-0.95000,-0.95000,' "--beam-offset: solids inset by half the spot (0.05)"
like "$(cat "$TMP/d.cli")" '\$\$POLYLINE/1,0,5,-0.55000,-0.55000,' "--beam-offset: holes grow by half the spot"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp --perimeters 1 -o "$TMP/p.ladrp"
is "$RC" 0 "--perimeters 1: exit 0"
is "$(sed -n 5p "$TMP/p.ladrp")" "-0.96000 -0.96000 0.00000 uline" "--perimeters: the first move goes to the inset square's corner (d/2 in)"
run "$LAMINA" slice "$M/thesis_cube.ug" -m cli-binary -o "$TMP/e.cli" --frame machine
is "$RC" 0 "binary CLI in the machine frame"

# DED G-code: absolute moves, laser on/off as M-codes, layer comments.
run "$LAMINA" slice "$M/thesis_cube.ug" -m ded-gcode -w 0.5 -o "$TMP/cube.gcode"
is "$RC" 0 "ded-gcode: exit 0"
like "$(head -5 "$TMP/cube.gcode")" 'G21' "preamble sets millimetres"
is "$(grep -c '^; layer ' "$TMP/cube.gcode")" 4 "four layer comments"
ok "$(awk '/^M3/ && !on { on = NR } /^G1 / { if (!on || on > NR) bad = 1; exit } END { exit bad + 0 }' "$TMP/cube.gcode"; echo $?)" "laser on before the first deposit"
# the laser's state along the program: on (M3) only when off, off (M5)
# only when on or not yet known (the first), every deposit with it on, and
# off at the end; M9 (powder off) with each M5: each said once
ok "$(awk '/^M3( |$)/ { if (st == "on") bad = 1; st = "on" } /^M5( |$)/ { if (st == "off") bad = 1; st = "off"; m5++ }
    /^M9( |$)/ { m9++ } /^G1 / && st != "on" { bad = 1 } END { exit bad || st != "off" || m5 != m9 }' "$TMP/cube.gcode"; echo $?)" \
    "ded-gcode: laser and powder switched on and off once each time, off at the end"
like "$(head -1 "$TMP/cube.gcode")" "^; lamina DED program: part thesis_cube on ded-gcode " "ded-gcode: the preamble names the part"
ok "$(grep '^G1 ' "$TMP/cube.gcode" | awk '{ for (i = 2; i <= NF; i++) if ($i ~ /^[XY]/) { v = substr($i, 2) + 0; if (v < -1.0000001 || v > 1.0000001) bad = 1 } } END { exit bad }'; echo $?)" "every deposit stays inside the part"

# Command-line options override the profile.
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp --angle 90 -o "$TMP/r90.ladrp"
is "$(grep -m1 -A2 pendown "$TMP/r90.ladrp" | tail -1)" "0.00000 2.00000 0.00000 uline" "--angle 90: deposits run along y (the scan frame turned counter-clockwise)"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp --first-line center -o "$TMP/c.ladrp"
is "$(sed -n 5p "$TMP/c.ladrp")" "-1.00000 1.04000 0.00000 uline" "--first-line center: first line half a bead in"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp -w 1 -o "$TMP/w1.ladrp"
is "$(grep -c ' 1.00000 uline$' "$TMP/w1.ladrp")" 1 "-w overrides the profile's layer width (one layer change of 1)"

# Errors: unknown machine, broken profile, options a writer cannot take.
run "$LAMINA" slice "$M/thesis_cube.ug" -m no-such-machine -o "$TMP/x.out"
is "$RC" 1 "unknown machine: exit 1"
like "$ERR" "unknown machine 'no-such-machine'" "unknown machine: message"
printf 'name: broken\nprocess: ladrp\nbead_width: -1\ndialect: {}\n' >"$TMP/broken.yaml"
run "$LAMINA" slice "$M/thesis_cube.ug" -m "$TMP/broken.yaml" -o "$TMP/x.out"
is "$RC" 1 "broken profile: exit 1"
like "$ERR" 'broken\.yaml:3:13: .*bead_width' "broken profile: file:line:column"
ok "$([ ! -e "$TMP/x.out" ]; echo $?)" "no output file after a failure"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp --angle x
is "$RC" 2 "bad --angle: usage error"
done_testing
