#!/usr/bin/env bash
# join checks the values a part holds, not only its hashes: a part whose
# hashes match but which holds a number that is not finite, a point
# outside the job's box (by more than the two beads' tolerance), a layer
# height that is no height, a negative exposure or a hatch kind the
# planner does not write is refused (exit 1) naming the file, the byte
# and the layer, and nothing is written. The parts are crafted from real
# ones by partcraft.py, which reads the format on its own and makes both
# hashes right again.
. "$(dirname "$0")/lib.sh"
craft() { python3 "$TESTS/cli/partcraft.py" "$@"; }
cube=$M/thesis_cube_hole.ug   # -1..1 x -1..1 x 0..2: 4 layers of 0.5
for m in sls-contours creol-ladrp lpbf-cli; do
    "$LAMINA" slice "$cube" -m "$m" -w 0.5 -o "$TMP/$m.whole" 2>/dev/null &&
        "$LAMINA" slice "$cube" -m "$m" -w 0.5 --layers 1:2 -o "$TMP/$m.a" &&
        "$LAMINA" slice "$cube" -m "$m" -w 0.5 --layers 3:4 -o "$TMP/$m.b"
    ok $? "$m: the whole run and its parts 1:2 and 3:4"
    craft "$TMP/$m.b" "$TMP/$m.same" - - 0
    cmp -s "$TMP/$m.b" "$TMP/$m.same"
    ok $? "$m: the crafting script reads the part and its hashes as lamina writes them"
done

echo keep >"$TMP/prog"
# refused M FIELD-SPEC DESCRIPTION REGEX: part b of machine M changed by
# partcraft.py (TAG FIELD VALUE), joined with part a
refused() {
    local m=$1 tag=$2 field=$3 value=$4 d=$5 re=$6 where layer at
    where=$(craft "$TMP/$m.b" "$TMP/bad" "$tag" "$field" "$value") || { ok 1 "$d: crafted"; return; }
    read -r layer at <<<"$where"
    run "$LAMINA" join "$TMP/$m.a" "$TMP/bad" -o "$TMP/prog"
    is "$RC" 1 "$d: refused"
    if [ "$layer" = - ]; then
        like "$ERR" "bad: byte $at: corrupt part file: $re" "$d: says where and why"
    else
        like "$ERR" "bad: byte $at: corrupt part file: layer $layer: $re" "$d: says where (layer $layer) and why"
    fi
    is "$(cat "$TMP/prog")" keep "$d: the output is untouched"
}
refused sls-contours C x nan "a contour point's x NaN" "contour point 1 is not finite \(nan, "
refused sls-contours C y inf "a contour point's y infinite" "contour point 1 is not finite \([^,]*, inf, "
refused sls-contours C x hi+3 "a contour point 3 beads beyond the box" "contour point 1 \(1\.[0-9]+, .*\) is outside the job's box"
refused sls-contours C z 1e300 "a contour point far above the box" "contour point 1 \(.*, 1e\+300\) is outside the job's box"
refused sls-contours C power -1 "a negative laser power" "a contour with a power of -1"
refused sls-contours L z inf "an infinite layer height" "height inf, width 0\.5"
refused sls-contours L z 1e9 "a layer far above the box" "height 1e\+09 .* is outside the job's box"
refused sls-contours J zmax nan "the header's box NaN" "the job's box .*nan.* is not finite"
refused creol-ladrp M z nan "a LADRP move NaN" "a move to is not finite"
refused creol-ladrp M y lo-3 "a LADRP move 3 beads below the box" "a move to \(.*\) is outside the job's box"
refused lpbf-cli H x hi+3 "a hatch vector 3 beads beyond the box" "hatch end 1 \(.*\) is outside the job's box"
refused lpbf-cli H y nan "a hatch vector NaN" "hatch end 1 is not finite"
refused lpbf-cli H kind - "a hatch kind the planner does not write" "hatches of kind 9 \\(not a hatch region\\)"

# within the tolerance (a bead beyond the box: LADRP's approach move is
# one bead above its first line): joined, the point as changed
craft "$TMP/sls-contours.b" "$TMP/near" C x hi+1 >/dev/null
run "$LAMINA" join "$TMP/sls-contours.a" "$TMP/near" -o "$TMP/near.out"
is "$RC" 0 "a contour point one bead beyond the box joins"
cmp -s "$TMP/near.out" "$TMP/sls-contours.whole"
ok $((!$?)) "... and the program holds the changed point"

# to standard output: nothing, not the layers before the bad one
craft "$TMP/sls-contours.b" "$TMP/nan" C x nan >/dev/null
run "$LAMINA" join "$TMP/sls-contours.a" "$TMP/nan"
is "$RC" 1 "a NaN part joined to standard output: refused"
is "$OUT" "" "... with nothing written"
run "$LAMINA" join "$TMP/sls-contours.a" "$TMP/nan" -o "$TMP/new.out"
[ ! -e "$TMP/new.out" ]
ok $? "... and no file made by -o"
# the parts as sliced still join into the whole run
for m in sls-contours creol-ladrp lpbf-cli; do
    "$LAMINA" join "$TMP/$m.b" "$TMP/$m.a" -o "$TMP/$m.joined" 2>/dev/null
    cmp -s "$TMP/$m.joined" "$TMP/$m.whole"
    ok $? "$m: the parts as sliced join into the whole run"
done

done_testing
