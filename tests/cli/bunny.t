#!/usr/bin/env bash
# The Stanford bunny as a user has it (issue 24): a public scan, 69,451
# triangles open at the bottom (223 boundary edges), drawn in metres,
# sliced with `--units m` into 0.5 mm layers with repair (the default).
# Every layer exits with material and no open outline, the layer count is
# the bunny's height over the width, and each layer's net area is the
# section (openmesh.py's, not lamina's) of the mesh `lamina repair` writes;
# and `lamina validate` of the same run agrees along every axis.
. "$(dirname "$0")/lib.sh"

OM=(python3 "$TESTS/cli/openmesh.py")
B="$TMP/bun zipper.obj"
gunzip -c "$M/bunny/bun_zipper.obj.gz" >"$B"

# ---- the file is the scan the issue describes
run "${OM[@]}" edges "$B"
is "$(jq -c '[.facets, .vertices, .boundary_edges, .boundary_loops, .nonmanifold_edges]' <<<"$OUT")" \
    "[69451,34834,223,5,0]" "bun_zipper: 69,451 triangles, 34,834 vertices used, 223 boundary edges in 5 loops, manifold"
loops=$(jq .boundary_loops <<<"$OUT")
run "$LAMINA" info --json "$B"
is "$(jq -c '.repair | [.holes, .hole_edges, .holes_left, .boundary_edges, .nonmanifold_edges, .welded, .duplicates, .degenerate]' <<<"$OUT")" \
    "[$loops,223,0,0,0,0,0,0]" "info: each of the $loops loops filled, closing the 223 boundary edges; nothing else to do"

# ---- the repaired mesh, in the file's units (metres), for the reference sections
R="$TMP/bunny repaired.stl"
run "$LAMINA" repair "$B" -o "$R"
is "$RC" 0 "lamina repair: exit 0"
like "$ERR" "filled $loops holes \\(223 boundary edges\\)" "lamina repair: every loop filled, its 223 edges said"
run "${OM[@]}" edges "$R"
is "$(jq -c '[.boundary_edges, .nonmanifold_edges]' <<<"$OUT")" "[0,0]" "the repaired bunny is closed and manifold (counted here)"

# ---- sliced as a user would: --units m, 0.5 mm layers, along z (the
# default), y (the bunny's up: the open bottom first) and two oblique axes
axes=(z y 1,1,1 0.3,-0.5,0.8)
# the bunny's extent along each axis in metres, from the file itself (one read of it)
declare -A spans
i=0
while IFS= read -r line; do spans[${axes[i]}]=$line; i=$((i + 1)); done < <("${OM[@]}" extent "$B" "${axes[@]}")
for ax in "${axes[@]}"; do
    run "$LAMINA" slice "$B" --units m -w 0.5 -a "$ax" --json "$TMP/b.json" -o "$TMP/b.sls"
    is "$RC" 0 "bunny --units m -w 0.5 along $ax: exit 0"
    [ "$RC" = 0 ] || echo "$ERR" | head -3 | sed 's/^/# /'
    ok "$(grep -Eq 'stayed open|could not be closed' <<<"$ERR"; [ $? -ne 0 ]; echo $?)" "... no outline stayed open"
    like "$ERR" "repaired: filled $loops holes \\(223 boundary edges\\)" "... stderr says the repair"
    # the bunny's extent along the axis in millimetres, from the file itself
    span=${spans[$ax]}
    ext=$(jq .extent <<<"$span") lo=$(jq '.min * 1000' <<<"$span") hi=$(jq '.max * 1000' <<<"$span")
    layers=$(jq -n "$ext * 1000 / 0.5 - 1e-9 | ceil")
    # one read of the run's 30 MB: per layer its index, cut, contours, area
    jq -c '{units: .job.units, width: .layers[0].width,
            layers: [.layers[] | {index, z, n: (.contours | length), area: .stats.area}]}' "$TMP/b.json" >"$TMP/b.sum"
    is "$(jq '.layers | length' "$TMP/b.sum")" "$layers" "... $layers layers: the bunny's $ext m along $ax over 0.5 mm"
    # a last slab thinner than the width has its middle cut above the top
    # (120.67 mm along z: 0.17 mm in the last layer, cut at 0.25); every
    # layer cut within the bunny must have material
    is "$(jq --argjson lo "$lo" --argjson hi "$hi" '[.layers[] | select(.z > $lo and .z < $hi)
            | select(.n == 0 or .area <= 0) | .index] | join(",")' -r "$TMP/b.sum")" "" \
        "... every layer cut within the bunny has material"
    is "$(jq --argjson lo "$lo" --argjson hi "$hi" '[.layers[] | select(.z <= $lo or .z >= $hi) | .index] | join(",")' -r "$TMP/b.sum")" \
        "$(jq -rn "if ($layers - 0.5) * 0.5 > $ext * 1000 then $layers else \"\" end")" \
        "... only a last layer thinner than half the width is cut outside it"
    is "$(jq -c '[.units, .width]' "$TMP/b.sum")" '["mm",0.5]' "... in millimetres"
    run "${OM[@]}" check "$R" "$TMP/b.json" --scale 1000
    is "$RC" 0 "... every layer's net area = the repaired mesh's section within 1%"
    echo "$OUT" | sed 's/^\([^#]\)/# \1/' | tail -6
    # lamina's own check of the same run agrees: every label, every layer's area
    run "$LAMINA" validate "$B" --units m -w 0.5 -a "$ax" --json
    is "$RC $(jq -c '[.disagreeing, .areas_compared, .areas_differing]' <<<"$OUT")" "0 [0,$layers,0]" \
        "... validate: every label confirmed, the net area of all $layers layers against the section, none differ"
done
done_testing
