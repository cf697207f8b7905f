#!/usr/bin/env bash
# lamina info's sizes: the model's arrays counted from its own counts (a
# closed triangle mesh: 24 bytes a vertex, 12 a triangle; an edge its two
# ends, an offset and its two triangles; three edges a triangle; a shell
# index and a shell-order entry a triangle), the run's layer count as
# lamina slice makes it, and the command's peak memory.
. "$(dirname "$0")/lib.sh"

cube=$M/thesis_cube_binary.stl
run "$LAMINA" info --json "$cube"
is "$RC" 0 "info --json: exit 0"
read -r V T E S mesh edges shells model peak <<<"$(jq -r '[.vertices, .triangles, .edges, .shells,
    .memory.mesh, .memory.edges, .memory.shells, .memory.model, .memory.peak] | @tsv' <<<"$OUT")"
is "$mesh" $((V * 24 + T * 12)) "mesh bytes: 24 a vertex, 12 a triangle ($V, $T)"
is "$edges" $((E * 8 + (E + 1) * 4 + 3 * T * 4 + 2 * E * 4)) "edge bytes: ends, offsets, 3 a triangle, 2 triangles an edge"
ok $(( !(shells >= T * 8 + (S + 1) * 4 && shells < T * 8 + (S + 1) * 4 + S * 256) )) "shell bytes: 2 indices a triangle, offsets, a record a shell"
is "$model" $((mesh + edges + shells)) "model bytes: the sum"
ok $(( !(peak > 1000000 && peak < 200000000) )) "peak memory: a plausible resident set ($peak bytes)"

# the run: layers as slice makes them, for -m and slice options
for opts in "" "-m lpbf-cli -w 0.05" "-m creol-ladrp" "-a x -w 0.25"; do
    # shellcheck disable=SC2086
    want=$("$LAMINA" slice "$cube" $opts -o /dev/null --json - 2>/dev/null | jq '.layers | length')
    # shellcheck disable=SC2086
    got=$("$LAMINA" info --json "$cube" $opts | jq .run.layers)
    is "$got" "$want" "info ${opts:-(defaults)}: the run's layers = slice's"
done
run "$LAMINA" info "$cube" -m lpbf-cli
like "$OUT" "^run +[0-9]+ layers \(lpbf-cli\), about [0-9.]+ kB of program$" "text: the run line"
like "$OUT" "^model memory +[0-9.]+ kB \(mesh" "text: the model memory line"
like "$OUT" "^peak memory +[0-9.]+ MB \(this command\)$" "text: the peak line"
run "$LAMINA" info "$cube" -m no-such-machine
is "$RC" 1 "info -m with an unknown machine fails"
run "$LAMINA" info "$cube" -w -1
is "$RC" 2 "info -w -1: usage error"

done_testing
