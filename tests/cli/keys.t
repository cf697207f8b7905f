#!/usr/bin/env bash
# Profile keys that would do nothing are refused, and the words of the
# powder bed work (issue 22, items 2, 3 and 11): a key the profile's planner
# does not read is an error naming the key that planner reads (exit 2 on the
# command line, file:line:column in the profile file given), layer_thickness
# is layer_width, `check` says spot for sls, `units` is a unit name, a bad
# value in a profile file is exit 1 at its position, and -m NAME says how to
# use a NAME.yaml of the current directory.
. "$(dirname "$0")/lib.sh"
CUBE="$M/thesis_cube.ug"
cd "$TMP" || exit 1

# ---- the issue's cases ----------------------------------------------------------
run "$LAMINA" slice "$CUBE" -m cli-ascii -s hatch_strategy=lines --angle 45 -o a.cli
like "$RC $ERR" "^2 lamina slice: --angle 45: raster\\.angle is read by the ladrp planner only, and cli-ascii is an sls profile: set hatch_angle instead" \
    "--angle on an sls profile: exit 2, names hatch_angle"
[ ! -e a.cli ]; ok $? "... and writes nothing"
run "$LAMINA" slice "$CUBE" -m lpbf-cli --islands -o a.cli
like "$RC $ERR" "^2 lamina slice: --islands: raster\\.islands .*lpbf-cli is an sls profile: set hatch_strategy=islands instead" \
    "--islands on lpbf-cli: exit 2, names hatch_strategy=islands"
run "$LAMINA" slice "$CUBE" -m lpbf-cli --angle-step 30 -o a.cli
like "$RC $ERR" "^2 .*set layer_angle_increment instead" "--angle-step on lpbf-cli: names layer_angle_increment"
run "$LAMINA" slice "$CUBE" -m cli-ascii -s raster.angle=45 -o a.cli
like "$RC $ERR" "^2 lamina slice: -s raster\\.angle=45: .*set hatch_angle instead" "-s raster.angle: the same rule"
run "$LAMINA" slice "$CUBE" -w 1 --angle 45 -o a.sls
like "$RC $ERR" "^2 .*sls-contours is an sls profile" "the built-in profile is sls too"
run "$LAMINA" slice "$CUBE" -m creol-ladrp -s hatch_angle=30 -o a.ladrp
like "$RC $ERR" "^2 lamina slice: -s hatch_angle=30: hatch_angle is read by the sls planner only, and creol-ladrp is a ladrp profile: set raster\\.angle instead \\(--angle\\)" \
    "an sls key on a ladrp profile: names raster.angle and its option"
run "$LAMINA" check "$CUBE" -m lpbf-cli -s bead_width=0.5
like "$RC $ERR" "^2 .*set spot_width instead" "check: bead_width on an sls profile names spot_width"
run "$LAMINA" machines --show creol-ladrp -s upskin.power=3
like "$RC $ERR" "^2 .*upskin\\.power is read by the sls planner only.*no key does the same" "machines --show: the same rule"
# the process the values leave is the one that counts
run "$LAMINA" machines --show creol-ladrp -s process=sls -s spot_width=0.1 -s hatch_angle=30
like "$RC $OUT" $'^0 [\\s\\S]*\nhatch_angle: 30\n' "-s process=sls, then sls keys: accepted"
# the right planner's keys do something: the program changes
"$LAMINA" slice "$CUBE" -m cli-ascii -w 1 -s hatch_strategy=lines -o h0.cli 2>/dev/null
"$LAMINA" slice "$CUBE" -m cli-ascii -w 1 -s hatch_strategy=lines -s hatch_angle=45 -o h45.cli 2>/dev/null
! cmp -s h0.cli h45.cli; ok $? "hatch_angle=45 on cli-ascii changes the program"

# --help marks the options of one planner
run "$LAMINA" slice --help
like "$OUT" '^ +--angle X +--set raster\.angle=X \(ladrp profiles\)$' "--help: --angle is for ladrp profiles"
like "$OUT" '^ +--beam-offset +--set beam_offset=true \(sls profiles\)$' "--help: --beam-offset for sls profiles"
like "$OUT" '^ +--gap X +--set gap=X$' "--help: --gap for both"

# ---- every key: the planner the table says, the planner its text says ----------
# The reference's meaning column starts "ladrp:" or "sls" for a key of one
# planner (written with the key, not derived from the planner column): each
# is refused on a profile of the other process and accepted on its own, and
# every other key is accepted on both.
"$LAMINA" machines --keys | perl -ne '
    next unless /^\| `([\w.]+)` \| ([^|]*(?:\\\|[^|]*)*) \| [^|]* \| (.*) \|$/;
    my ($k, $t, $doc) = ($1, $2, $3);
    next if $k eq "inherits" || $k eq "name" || $k eq "process" || $k =~ /^dialect\./;
    my $v = $t =~ /^`([^`]+)`/ ? $1 : $t =~ /^boolean/ ? "true" : $t =~ /^(?:whole )?number/ ? "1"
          : $t =~ /^list of (\d+) numbers/ ? "[" . join(",", (1) x $1) . "]"
          : $t =~ /^list of .* lasers/ ? "[{\"field\":[0,0,1,1]}]" : "x";
    my $who = $doc =~ /^ladrp:/ ? "ladrp" : $doc =~ /^sls[:,]/ ? "sls" : "both";
    print "$k $v $who\n"' >keys.txt
[ "$(wc -l <keys.txt)" -gt 60 ]; ok $? "the reference lists the keys ($(wc -l <keys.txt))"
bad=""
while read -r k v who; do
    extra=() # a plate's width and depth go together
    case $k in plate.width) extra=(-s plate.depth=1) ;; plate.depth) extra=(-s plate.width=1) ;; esac
    for prof in creol-ladrp:ladrp cli-ascii:sls; do
        "$LAMINA" machines --show "${prof%%:*}" -s "$k=$v" "${extra[@]}" >/dev/null 2>err.txt
        rc=$?
        want=0
        [ "$who" != both ] && [ "$who" != "${prof##*:}" ] && want=2
        [ "$rc" = "$want" ] || bad="$bad $k($prof:$rc)"
        [ "$want" = 2 ] && ! grep -q "is read by the $who planner only" err.txt && bad="$bad $k(message)"
    done
done <keys.txt
is "$bad" "" "every key: refused (exit 2) exactly on the process whose planner does not read it"

# ---- in a profile file -----------------------------------------------------------
printf 'inherits: cli-ascii\nname: r\nraster:\n  angle: 45\n' >r.yaml
run "$LAMINA" slice "$CUBE" -m ./r.yaml -o r.cli
like "$RC $ERR" "^1 lamina: \\./r\\.yaml:4:3: raster\\.angle is read by the ladrp planner only, and this is an sls profile: set hatch_angle instead" \
    "a raster key in an sls profile file: exit 1 at file:line:column"
printf 'inherits: creol-ladrp\nname: r\nskin_layers: 2\n' >s.yaml
run "$LAMINA" machines --show ./s.yaml
like "$RC $ERR" "^1 lamina: \\./s\\.yaml:3:1: skin_layers is read by the sls planner only" "an sls key in a ladrp profile file"
# a base may hold the keys of both processes: only the file given is held to
# its own planner, the keys it inherits are not
printf 'description: both\nspot_width: 0.1\nbead_width: 0.1\nhatch_angle: 30\nraster:\n  angle: 45\ndialect: {}\n' >both.yaml
printf 'inherits: ./both.yaml\nname: s\nprocess: sls\n' >child-sls.yaml
printf 'inherits: ./both.yaml\nname: l\nprocess: ladrp\n' >child-ladrp.yaml
run "$LAMINA" machines --show ./child-sls.yaml
like "$RC $OUT" $'^0 [\\s\\S]*\nhatch_angle: 30\n' "a child of a two-process base: sls loads"
run "$LAMINA" machines --show ./child-ladrp.yaml
like "$RC $OUT" $'^0 [\\s\\S]*\n  angle: 45\n' "... and ladrp loads"
# every shipped profile keeps to its planner
for f in "$TESTS"/../machines/*.yaml; do
    "$LAMINA" machines --show "$f" >/dev/null 2>&1; ok $? "shipped $(basename "$f") loads"
done

# ---- layer_thickness is layer_width -----------------------------------------------
"$LAMINA" slice "$CUBE" -m cli-ascii -s layer_width=0.5 -o w.cli 2>/dev/null
run "$LAMINA" slice "$CUBE" -m cli-ascii -s layer_thickness=0.5 -o t.cli
is "$RC" 0 "-s layer_thickness: accepted"
cmp -s w.cli t.cli; ok $? "-s layer_thickness=0.5 writes what -s layer_width=0.5 writes"
is "$(grep -c '^\$\$LAYER/' t.cli)" 4 "... 4 layers of 0.5 through the 2-high cube"
printf 'inherits: cli-ascii\nname: t\nlayer_thickness: 0.5\n' >t.yaml
run "$LAMINA" machines --show ./t.yaml
like "$RC $OUT" $'^0 [\\s\\S]*\nlayer_width: 0\\.5\n' "layer_thickness in YAML: the profile's layer_width"
printf 'inherits: cli-ascii\nname: t\nlayer_width: 0.5\nlayer_thickness: 0.2\n' >tt.yaml
run "$LAMINA" machines --show ./tt.yaml
like "$RC $ERR" "^1 lamina: \\./tt\\.yaml:4:1: duplicate key 'layer_thickness': layer_thickness is another name of layer_width \\(given at line 3\\)" \
    "both names in one file: a duplicate key"
"$LAMINA" machines --keys | grep -q '^| `layer_width` .*Also `layer_thickness`'; ok $? "--keys names the alias"

# ---- check says spot for a powder bed ---------------------------------------------
run "$LAMINA" check "$M/drc/plate_thin.ug" -m sls-contours
like "$RC $OUT" "^3 min_wall: wall 0\\.05 thick at .*thinner than the spot 0\\.1 " "check on an sls profile: the spot"
! grep -q bead <<<"$OUT"; ok $? "... and no bead"
run "$LAMINA" check "$M/drc/plate_thin.ug" -m creol-ladrp
like "$OUT" "thinner than the bead 0\\.08 " "on a ladrp profile: the bead"

# ---- units is a unit name -------------------------------------------------------------
printf 'inherits: cli-ascii\nname: u\nunits: "<script>console.log(7)</script>"\n' >u.yaml
run "$LAMINA" slice "$CUBE" -m ./u.yaml --svg u.svg -o u.cli
like "$RC $ERR" "^1 lamina: \\./u\\.yaml:3:8: units must be mm, cm, m, um, µm, in, inch or ft, got '<script>" \
    "units: <script>: exit 1 at file:line:column"
[ ! -e u.svg ] && [ ! -e u.cli ]; ok $? "... and nothing written"
run "$LAMINA" slice "$CUBE" -m cli-ascii -s 'units=<svg onload=alert(1)>' --svg u.svg -o u.cli
like "$RC $ERR" "^2 lamina slice: -s units=<svg onload=alert\\(1\\)>: units must be mm, " "-s units=<svg ...>: exit 2"
for u in mm cm m um µm in inch ft; do
    run "$LAMINA" machines --show cli-ascii -s "units=$u"
    like "$RC $OUT" "^0 [\\s\\S]*\nunits: \"$u\"\n" "units $u: accepted"
done

# ---- a bad value in a profile file: exit 1 at its position ---------------------------
printf 'inherits: lpbf-cli\nname: x\nhatch_distance: 1e-9\n' >x.yaml
run "$LAMINA" slice "$CUBE" -m ./x.yaml -o x.cli
like "$RC $ERR" "^1 lamina: \\./x\\.yaml:3:17: hatch_distance must be 1e-06 or more, got '1e-9'" \
    "hatch_distance: 1e-9 in a file: exit 1, file:line:column"
printf 'inherits: lpbf-cli\nname: x\nupskin:\n  island_size: 0\n' >y.yaml
run "$LAMINA" slice "$CUBE" -m ./y.yaml -o x.cli
like "$RC $ERR" "^1 lamina: \\./y\\.yaml:4:16: upskin\\.island_size must be 1e-06 or more" "a section's island size too"
run "$LAMINA" slice "$CUBE" -m lpbf-cli -s hatch_distance=1e-9 -o x.cli
like "$RC $ERR" "^2 lamina slice: -s hatch_distance=1e-9: hatch_distance must be 1e-06 or more" \
    "the same value with -s: a usage error (exit 2), as every -s value"

# ---- -m NAME and a NAME.yaml here ------------------------------------------------------
printf 'inherits: lpbf-cli\nname: my-slm\n' >my-slm.yaml
run "$LAMINA" slice "$CUBE" -m my-slm -o m.cli
like "$RC $ERR" "^1 lamina: unknown machine 'my-slm': no my-slm\\.yaml in .*; my-slm\\.yaml in the current directory is not searched: write \\./my-slm\\.yaml$" \
    "-m my-slm with ./my-slm.yaml here: says to write ./my-slm.yaml"
run "$LAMINA" slice "$CUBE" -m ./my-slm.yaml -w 1 -o m.cli
is "$RC" 0 "-m ./my-slm.yaml: the file"
run "$LAMINA" slice "$CUBE" -m no-such -o m.cli
like "$RC $ERR" "^1 lamina: unknown machine 'no-such': .*lists them\\)$" "no file here: no hint"
mkdir -p sub && printf 'inherits: lpbf-cli\nname: base\n' >sub/base.yaml && printf 'inherits: base\nname: c\n' >sub/c.yaml
run "$LAMINA" machines --show sub/c.yaml
like "$RC $ERR" "^1 lamina: sub/c\\.yaml:1:11: inherits 'base': .*; base\\.yaml beside this profile is not searched: write \\./base\\.yaml$" \
    "inherits NAME with NAME.yaml beside the file: the same hint"

done_testing
