#!/usr/bin/env bash
# lamina slice --json FILE: the layer interchange. Runs validated against
# the shipped schema by python3-jsonschema and checked by jsoncheck.py's own
# arithmetic (shoelace areas, planes, orders, sums); contours point for
# point against the SLS program of the same run; read back by validate;
# streamed (peak memory of a 10,000-layer run).
. "$(dirname "$0")/lib.sh"

SCHEMA="$TESTS/../schema/lamina-run-1.schema.json"
CHECK=(python3 "$TESTS/cli/jsoncheck.py" "$SCHEMA")
python3 "$TESTS/cli/meshgen.py" torus "$TMP/torus.stl"

# ---- four runs: SLS with holes, LADRP, hatched lpbf-cli, an oblique axis ----
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.25 --json "$TMP/a.json" -o "$TMP/a.sls"
is "$RC" 0 "SLS with holes: exit 0"
run "${CHECK[@]}" "$TMP/a.json" --sls "$TMP/a.sls"
is "$RC $OUT" "0 " "SLS with holes: valid, contours = the program's loops point for point, areas = shoelace"
is "$(jq -c '[.job.layers, [.layers[0].contours[] | [.solid, .depth, .parent, .area]], .layers[0].stats.area]' "$TMP/a.json")" \
    '[8,[[true,0,null,4],[false,1,1,-1]],3]' "the thesis cube: 2 x 2 solid, 1 x 1 hole inside it, net area 3"

run "$LAMINA" slice "$M/frame_island.ug" -m creol-ladrp -w 2 --json "$TMP/b.json" -o "$TMP/b.ladrp"
is "$RC" 0 "LADRP: exit 0"
run "${CHECK[@]}" "$TMP/b.json" --inside
is "$RC $OUT" "0 " "LADRP: valid, every deposit inside the section"
is "$(jq -c '[.job.process, ([.layers[].vectors[].kind] | unique), (.layers[0].contours | length)]' "$TMP/b.json")" \
    '["ladrp",["deposit","travel"],3]' "LADRP: deposits and travels; frame, hole and island"

run "$LAMINA" slice "$TMP/torus.stl" -m lpbf-cli -w 0.25 --json "$TMP/c.json" -o "$TMP/c.cli"
is "$RC" 0 "hatched lpbf-cli: exit 0"
run "${CHECK[@]}" "$TMP/c.json" --cli "$TMP/c.cli"
is "$RC $OUT" "0 " "lpbf-cli: valid, as many hatch vectors as the CLI program's \$\$HATCHES"
is "$(jq -c '[.layers[].vectors[].kind] | unique' "$TMP/c.json")" '["contour","core","downskin","jump","support","upskin"]' \
    "lpbf-cli: contour passes, core and skin hatches, jumps, and supports under the torus's lower half"
like "$(jq -c '[.totals.time.total > 0, .layers[0].stats.time > 0]' "$TMP/c.json")" '^\[true,true\]$' "lpbf-cli: the time estimate"

run "$LAMINA" slice "$TMP/torus.stl" -a 1,2,3 -w 0.5 --json "$TMP/d.json" -o "$TMP/d.sls"
is "$RC" 0 "oblique axis: exit 0"
run "${CHECK[@]}" "$TMP/d.json" --sls "$TMP/d.sls"
is "$RC $OUT" "0 " "oblique axis: valid, points on their planes, = the program's loops"
is "$(jq -c '.job.axis | map(. * 14 * . | . * 1e9 | round)' "$TMP/d.json")" '[1000000000,4000000000,9000000000]' \
    "oblique axis: (1, 2, 3) / sqrt(14)"
run "$LAMINA" slice "$TMP/torus.stl" -a x -w 0.5 --frame machine --json "$TMP/e.json" -o "$TMP/e.sls"
run "${CHECK[@]}" "$TMP/e.json" --sls "$TMP/e.sls"
is "$RC $OUT $(jq -r .job.frame "$TMP/e.json")" "0  machine" "machine frame: valid, = the program's loops"

# the checker itself finds what it is there to find
perl -pe 's/"area": 4,/"area": 4.5,/ if $. < 20' "$TMP/a.json" >"$TMP/bad.json"
run "${CHECK[@]}" "$TMP/bad.json"
like "$RC $OUT" '^1 .*area 4.5, the shoelace sum says 4' "checker: a wrong area fails"
perl -pe 's/\[1, -1, 0.125\]/[1, -1.5, 0.125]/' "$TMP/a.json" >"$TMP/bad.json"
run "${CHECK[@]}" "$TMP/bad.json" --sls "$TMP/a.sls"
like "$RC $OUT" '^1 (?s:.*)the program has' "checker: a point moved fails against the program"

# ---- the schema rejects a broken run ---------------------------------------
perl -pe 's/"solid": true/"solid": "yes"/' "$TMP/a.json" >"$TMP/bad.json"
run "${CHECK[@]}" "$TMP/bad.json"
like "$RC $OUT" "^1 jsoncheck: schema: 'yes' is not of type 'boolean'" "schema: solid \"yes\" fails"
jq -c 'del(.totals)' "$TMP/a.json" >"$TMP/bad.json"
run "${CHECK[@]}" "$TMP/bad.json"
like "$RC $OUT" "^1 jsoncheck: schema: 'totals' is a required property" "schema: no totals fails"
jq -c '.layers[0].vectors[0].kind = "laser"' "$TMP/a.json" >"$TMP/bad.json"
run "${CHECK[@]}" "$TMP/bad.json"
like "$RC $OUT" "^1 jsoncheck: schema: 'laser' is not one of" "schema: an unknown vector kind fails"

# ---- the estimate (hatch.t's hand-computed layer) ---------------------------
cube="$M/thesis_cube.ug"
t=(-s speed=2 -s contour.speed=4 -s jump_speed=10 -s jump_delay=0.01 -s recoat_time=5)
run "$LAMINA" slice "$cube" -m cli-ascii -w 1 -s hatch_distance=0.25 -s hatch_angle=0 -s hatch_strategy=lines "${t[@]}" \
    -o "$TMP/j.cli" --json "$TMP/j.json"
is "$(jq -c '[.totals.layers, .layers[0].stats.time, .totals.time.recoat, (.totals.time.total - ([.layers[].stats.time] | add) | fabs < 1e-9)]' "$TMP/j.json")" \
    '[2,15.2675,10,true]' "--json: the first layer's 15.2675 s, recoating 2 x 5 s, the total is the layers' sum"
run "${CHECK[@]}" "$TMP/j.json" --cli "$TMP/j.cli"
is "$RC $OUT" "0 " "the estimated run: valid"
is "$(jq -c '.totals.time' "$TMP/a.json")" null "no speeds: no estimate (null)"

# ---- streams, determinism, failures ------------------------------------------
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.25 --json - -o "$TMP/s.sls" >"$TMP/s.json"
cmp -s "$TMP/s.json" "$TMP/a.json"; ok $? "--json - writes the same JSON to standard output"
cmp -s "$TMP/s.sls" "$TMP/a.sls"; ok $? "... and the program is the same as without --json"
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.25 -o "$TMP/n.sls"
cmp -s "$TMP/n.sls" "$TMP/a.sls"; ok $? "the program is byte-identical with and without --json"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.25 --json -
like "$RC $ERR" "^2 .*the program \(without -o\) and --json - both write to standard output" "--json - without -o: usage error"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.25 --json "$TMP/nodir/x.json" -o "$TMP/x.sls"
like "$RC $ERR" "(?s)^1 lamina: .*nodir/x.json" "--json into a missing directory: exit 1"
[ ! -e "$TMP/x.sls" ]; ok $? "... and no program is left"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.25 --json "$M/thesis_cube_hole.ug"
like "$RC $ERR" "^2 lamina slice: --json .* is an input of this command" "--json onto the model: refused"

# ---- read back: validate --program run.json -----------------------------------
run "$LAMINA" validate "$TMP/torus.stl" --program "$TMP/d.json"
like "$RC $OUT" '^0 (?s:.*)d.json: lamina-run program, [0-9]+ layers' "validate reads the oblique run back: exit 0"
like "$OUT" '0 disagreeing; net area against the section in [0-9]+ layers, 0 differ' "... every contour and area confirmed"
run "$LAMINA" validate "$TMP/torus.stl" --program "$TMP/e.json"
is "$RC" 0 "validate reads the machine-frame run back (its own frame): exit 0"
# a hole marked solid: the line of that contour
line=$(grep -n '"solid": false' "$TMP/a.json" | head -1 | cut -d: -f1)
perl -pe 's/"solid": false/"solid": true/ if $. == '"$line" "$TMP/a.json" >"$TMP/flip.json"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" --program "$TMP/flip.json"
like "$RC $OUT" "^3 (?s:.*)contour 2 \(solid, $TMP/flip.json:$line:5\) direction: written clockwise but labelled solid" \
    "a flipped solid: exit 3, the contour and its file:line:col"
# malformed JSON: file:line:col
printf '{"format": "lamina-run", "version": 1,\n "job": {"frame": "model",, }}\n' >"$TMP/m.json"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" --program "$TMP/m.json"
like "$RC $ERR" "^1 lamina: $TMP/m.json:2:27: expected a string" "malformed JSON: line and column"
# cut inside a number past byte 3000 (wherever the run's text puts it: a cut
# after a comma would say "expected a string" instead)
python3 -c 'import re, sys; t = open(sys.argv[1]).read(); m = re.compile(r"[0-9]").search(t, 3000)
sys.stdout.write(t[:m.end()])' "$TMP/a.json" >"$TMP/m.json"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" --program "$TMP/m.json"
like "$RC $ERR" "^1 lamina: $TMP/m.json:[0-9]+:[0-9]+: unexpected end of file" "truncated JSON: where it ends"
jq -c '.version = 2' "$TMP/a.json" >"$TMP/m.json"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" --program "$TMP/m.json"
like "$RC $ERR" "^1 lamina: .*version 2 of the lamina-run format: this lamina reads version 1" "another version: refused"
line=$(grep -n '"points": \[\[-1, -1, 0.125\]' "$TMP/a.json" | head -1 | cut -d: -f1)
perl -pe 's/"points": \[\[-1, -1, 0.125\]/"points": [[-1, -1]/' "$TMP/a.json" >"$TMP/m.json"
run "$LAMINA" validate "$M/thesis_cube_hole.ug" --program "$TMP/m.json"
like "$RC $ERR" "^1 lamina: $TMP/m.json:$line:[0-9]+: a point must be 3 numbers" "a point of two numbers: its line"

# ---- streamed: a 10,000-layer run's peak memory, with and without --json ------
# 10,000 layers of the cube with a hole: the JSON is some 15 MB, more than a
# tenth of the run's whole memory (4-6 MB; more under ASan), so a sink that
# kept a quarter of it would show. The margin is that quarter of the JSON,
# not a share of the run's memory: the run's peak varies by up to about
# 2 MB from run to run (3.3-5.5 MB measured without --json: one huge page
# of the heap, lua/cli/main.c), more than 10% of the run since Embree and
# GEOS are no longer mapped at start (8 -> 4 MB).
/usr/bin/time -f %M -o "$TMP/m0" "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.0002 -o "$TMP/big.sls"
/usr/bin/time -f %M -o "$TMP/m1" "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.0002 -o "$TMP/big.sls" --json "$TMP/big.json"
m0=$(tail -1 "$TMP/m0") m1=$(tail -1 "$TMP/m1")
size=$(($(stat -c %s "$TMP/big.json") / 1024))
is "$(jq '.totals.layers' "$TMP/big.json")" 10000 "the big run has 10,000 layers"
ok $((size * 10 > m0 ? 0 : 1)) "the JSON (${size} KB) is over 10% of the run's peak memory (${m0} KB): holding it would show"
ok $(((m1 - m0) * 4 <= size ? 0 : 1)) "peak memory with --json ${m1} KB, without ${m0} KB: within a quarter of the JSON"

# An oblique cut through the cube with a hole: in one layer the hole's
# corner lies on the outline (within rounding); hatching used to stop there
# ("TopologyException: ... Self-intersection"). The region is repaired, so
# the run completes and its hatches are the program's.
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -m lpbf-cli -s hatch_strategy=islands -a 1,1,2 -o "$TMP/ob.cli" \
    --json "$TMP/ob.json"
is "$RC" 0 "oblique cut with a hole touching the outline: hatched (exit 0)"
run "${CHECK[@]}" "$TMP/ob.json" --cli "$TMP/ob.cli"
is "$RC $OUT" "0 " "... its JSON passes the schema and matches the CLI program's hatches"

done_testing
