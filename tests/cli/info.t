#!/usr/bin/env bash
# lamina info: the model report, JSON, and a clear error for every bad input.
. "$(dirname "$0")/lib.sh"

j() { jq -r "$1" <<<"$OUT"; }

run "$LAMINA" info --json "$M/thesis_cube_hole.ug"
is "$RC" 0 "thesis cube with hole: exit 0"
jq -e . >/dev/null <<<"$OUT"; ok $? "--json prints valid JSON"
is "$(j .shells)" 2 "two shells"
is "$(j .cavities)" 1 "one cavity (the through hole)"
is "$(j .volume)" 6 "volume exactly 6, not 10"
is "$(j .boundary_edges)" 0 "no boundary edges"
is "$(j .triangles)" 24 "12 quads, 24 triangles"
is "$(j .vertices)" 16 "16 vertices"
is "$(j '.bbox.min|join(" ")') $(j '.bbox.max|join(" ")')" "-1 -1 0 1 1 2" "bounding box"
is "$(j .format)" unigrafix "format named"

run "$LAMINA" info --json "$M/frame_island.ug"
is "$(j .volume)" 16000 "frame with island: volume 16000"
is "$(j .shells) $(j .cavities)" "2 0" "two shells, the island is not a cavity"

# The same cube in four formats gives the same report.
ref=""
for f in thesis_cube.ug thesis_cube_ascii.stl thesis_cube_binary.stl thesis_cube.obj; do
    run "$LAMINA" info --json "$M/$f"
    is "$RC" 0 "$f loads"
    # (memory differs: formats keep face records and names or not)
    got=$(jq -c 'del(.model, .format, .memory)' <<<"$OUT")
    if [ -z "$ref" ]; then ref=$got; else is "$got" "$ref" "$f: same report as thesis_cube.ug"; fi
done
like "$ref" '"triangles":12,"vertices":8,"edges":18' "12 triangles, 8 vertices, 18 edges"
like "$ref" '"area":24,"volume":8' "area 24, volume 8"
run "$LAMINA" info --json "$M/thesis_cube_binary.stl"
is "$(j .format)" stl-binary "a binary STL whose header starts with 'solid' is read as binary"

run "$LAMINA" info "$M/thesis_cube.ug"
like "$OUT" 'volume +8' "text report shows the volume"
like "$OUT" 'shells +1 \(0 cavities\)' "text report shows shells and cavities"

# Bad input: exit 1, a message with the position, no crash.
bad() { # bad FILE REGEX DESCRIPTION
    run "$LAMINA" info "$M/bad/$1"
    is "$RC" 1 "$3: exit 1"
    like "$ERR" "$2" "$3: message"
}
bad empty.stl 'empty\.stl: empty file' "empty file"
bad truncated.stl 'truncated\.stl: byte [0-9]+: .*12 triangles' "truncated binary STL"
bad wrong_count.stl 'wrong_count\.stl: byte 80: .*13 triangles' "triangle count disagreeing with the size"
bad nan.stl 'nan\.stl:5:[0-9]+: .*finite' "NaN coordinate"
bad inf.obj 'inf\.obj:2:[0-9]+: .*finite' "infinite coordinate"
bad two_vertices.stl 'two_vertices\.stl:6:[0-9]+: .*2 vertices' "facet with 2 vertices"
bad four_vertices.stl 'four_vertices\.stl:7:[0-9]+: .*more than 3' "facet with 4 vertices"
bad undefined_vertex.ug "undefined_vertex\.ug:4:[0-9]+: .*'q'.*'tri'|undefined_vertex\.ug:4:[0-9]+: .*'tri'.*'q'" "face naming an undefined vertex"
bad unterminated_comment.ug 'unterminated_comment\.ug:2:1: .*comment' "unterminated { comment"
bad unterminated_c_comment.ug 'unterminated_c_comment\.ug:2:1: .*comment' "unterminated /* comment"
bad cycle_a.ug 'cycle_[ab]\.ug:[0-9]+:[0-9]+: .*cycle' "include cycle"
bad self_instance.ug 'self_instance\.ug:[0-9]+:[0-9]+: .*loop' "definition that instantiates itself"
bad missing_include.ug 'missing_include\.ug:2:[0-9]+: .*no_such_file' "missing include file"
bad index_out_of_range.obj 'index_out_of_range\.obj:5:[0-9]+: .*7' "OBJ index out of range"
bad missing_semicolon.ug "missing_semicolon\.ug:2:1: .*';'" "missing ';'"

run "$LAMINA" info "$TMP/does-not-exist.stl"
is "$RC" 1 "missing file: exit 1"
like "$ERR" 'does-not-exist\.stl: cannot open' "missing file: message"

printf 'this is not a model\n' >"$TMP/junk.xyz"
run "$LAMINA" info "$TMP/junk.xyz"
is "$RC" 1 "unknown format: exit 1"
like "$ERR" 'unknown model format' "unknown format: message"

# Usage errors exit 2.
run "$LAMINA" info
is "$RC" 2 "no model: usage error"
run "$LAMINA" info --bogus "$M/thesis_cube.ug"
is "$RC" 2 "unknown option: usage error"
run "$LAMINA" frobnicate
is "$RC" 2 "unknown command: usage error"

# An open mesh is a warning, not an error (--no-repair: as the file has it).
head -n 71 "$M/thesis_cube_ascii.stl" >"$TMP/open.stl"; echo "endsolid" >>"$TMP/open.stl"
run "$LAMINA" info --json --no-repair "$TMP/open.stl"
is "$RC" 0 "open mesh: exit 0"
like "$ERR" 'warning: .*open' "open mesh: warning on stderr"
is "$(j .closed)" false "open mesh: closed is false"
is "$(j .repair.ran)" false "open mesh: repair off"
# Repaired (the default): the 10 facets of the file (12 less 2, a face of
# the cube) are closed by one hole of 4 edges filled with 2 triangles.
run "$LAMINA" info --json "$TMP/open.stl"
is "$RC" 0 "repaired: exit 0"
like "$ERR" 'repaired: filled 1 hole \(4 boundary edges\)' "repaired: said on stderr"
is "$(j .closed)" true "repaired: closed"
is "$(j '.repair.holes, .repair.hole_edges, .repair.fill_triangles, .triangles')" "$(printf '1\n4\n2\n12')" \
    "repaired: the counts in the JSON"
is "$(j .volume)" 8 "repaired: the cube's volume"
run "$LAMINA" info "$TMP/open.stl"
like "$OUT" '^repair +filled 1 hole \(4 boundary edges\)$' "repaired: the text report's line"
done_testing
