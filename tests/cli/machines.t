#!/usr/bin/env bash
# lamina machines: listing the shipped profiles, --show's resolved YAML
# (which loads again as the same profile), the search path, and errors.
. "$(dirname "$0")/lib.sh"
unset LAMINA_MACHINES
MF="$M/machines"

run "$LAMINA" machines
is "$RC" 0 "machines: exit 0"
is "$(wc -l <<<"$OUT")" 6 "machines: the six shipped profiles"
like "$OUT" '^cli-ascii +sls +Common Layer Interface' "cli-ascii listed: sls, description"
like "$OUT" $'\nlpbf-cli +sls +LPBF machine' "lpbf-cli listed: sls, description"
like "$OUT" $'\ncreol-ladrp +ladrp +LADRP stage of the thesis' "creol-ladrp listed: ladrp, description"
like "$OUT" $'\nded-gcode +ladrp +DED cell' "ded-gcode listed"
like "$OUT" $'\nsls-contours +sls +SLS contours of the thesis' "sls-contours listed"
is "$ERR" "" "machines: nothing on stderr"

# Search path: $LAMINA_MACHINES first; the first directory wins per name.
mkdir -p "$TMP/m"
sed 's/^description: .*/description: my own thesis cell/' "$TESTS/../machines/creol-ladrp.yaml" >"$TMP/m/creol-ladrp.yaml"
cp "$MF/base.yaml" "$TMP/m/zz-base.yaml"
echo "not a profile" >"$TMP/m/notes.txt"
run env LAMINA_MACHINES="$TMP/m" "$LAMINA" machines
is "$RC" 0 "LAMINA_MACHINES: exit 0"
is "$(wc -l <<<"$OUT")" 7 "LAMINA_MACHINES: six shipped plus one, the shadowed one once"
like "$OUT" $'\ncreol-ladrp +ladrp +my own thesis cell' "LAMINA_MACHINES: its creol-ladrp wins"
like "$OUT" $'\nzz-base +ladrp +$' "LAMINA_MACHINES: its own profile listed (no description)"
run env LAMINA_MACHINES="$TMP/m" "$LAMINA" machines --show creol-ladrp
like "$OUT" 'description: "my own thesis cell"' "--show NAME finds the first directory's profile"

# A broken profile in a directory: the others are still listed, exit 1.
cp "$MF/bead_zero.yaml" "$TMP/m/broken.yaml"
run env LAMINA_MACHINES="$TMP/m" "$LAMINA" machines
is "$RC" 1 "a broken profile: exit 1"
like "$ERR" 'broken\.yaml:3:13: bead_width must be greater than 0' "a broken profile: file:line:col on stderr"
is "$(wc -l <<<"$OUT")" 7 "a broken profile: the others are listed"

# --show: valid YAML that loads again as the same profile.
for name in creol-ladrp sls-contours ded-gcode cli-ascii; do
    run "$LAMINA" machines --show "$name"
    is "$RC" 0 "--show $name: exit 0"
    printf '%s\n' "$OUT" >"$TMP/$name.yaml"
    run "$LAMINA" machines --show "$TMP/$name.yaml"
    is "$RC" 0 "--show $name: the dump loads again"
    is "$(grep -v '^#' <<<"$OUT")" "$(grep -v '^#' "$TMP/$name.yaml")" "--show $name: round trip gives the same YAML"
done
run "$LAMINA" machines --show creol-ladrp
like "$OUT" $'name: "creol-ladrp"\n' "--show: name quoted"
like "$OUT" $'\nbead_width: 0\\.08\n' "--show: bead width"
like "$OUT" $'\n  deposit: "\\{dx:%\\.5f\\} \\{dy:%\\.5f\\} \\{dz:%\\.5f\\} uline"' "--show: templates quoted"
like "$OUT" 'preamble: "start_plot\\n\{dimension\} set_dimension\\n\{rate:%\.2f\} feedrate"' "--show: newlines escaped"
if command -v python3 >/dev/null && python3 -c 'import yaml' 2>/dev/null; then
    printf '%s\n' "$OUT" | python3 -c 'import sys, yaml; d = yaml.safe_load(sys.stdin); sys.exit(0 if d["dialect"]["preamble"] == "start_plot\n{dimension} set_dimension\n{rate:%.2f} feedrate" and d["bead_width"] == 0.08 else 1)'
    ok $? "--show: another YAML parser reads the same values"
fi

# A profile inheriting a shipped one by name, found through the machine dirs.
run "$LAMINA" machines --show "$MF/child.yaml"
is "$RC" 0 "--show PATH inheriting creol-ladrp: exit 0"
like "$OUT" $'name: "creol-child"\n' "child: its name"
like "$OUT" $'units: "cm"\n' "child: units from creol-ladrp"
like "$OUT" $'  angle: 90\n' "child: its raster angle"
like "$OUT" '  feed: "\{rate:%\.3f\} feedrate"' "child: its feed command"
ok "$(grep -c laser_off <<<"$OUT")" "child: laser_off removed"
like "$OUT" '  laser_on: "0 pendown"' "child: laser_on inherited"

# Errors: bad profiles exit 1 with file:line:col; usage errors exit 2.
run "$LAMINA" machines --show "$MF/bead_zero.yaml"
is "$RC" 1 "bad profile: exit 1"
like "$ERR" '^lamina: .*bead_zero\.yaml:3:13: bead_width must be greater than 0' "bad profile: file:line:col"
is "$OUT" "" "bad profile: nothing on stdout"
run "$LAMINA" machines --show "$MF/unknown_field.yaml"
like "$ERR" 'unknown_field\.yaml:5:33: dialect\.travel: unknown field' "template error: line:col inside the template"
run "$LAMINA" machines --show "$MF/python_tag.yaml"
is "$RC" 1 "a python tag: exit 1"
like "$ERR" "python_tag\\.yaml:3:13: YAML tag '!!python/object/apply:os.system' is not allowed" "a python tag: refused"
ok "$(grep -c pwned <<<"$OUT$ERR")" "a python tag: nothing ran"
run "$LAMINA" machines --show "$MF/cycle_a.yaml"
is "$RC" 1 "inherits cycle: exit 1"
like "$ERR" 'cycle_b\.yaml:3:11: inherits cycle' "inherits cycle: position"
run "$LAMINA" machines --show "$MF/malformed.yaml"
like "$ERR" 'malformed\.yaml:4:10: malformed YAML' "malformed YAML: position"
run "$LAMINA" machines --show no-such-machine
is "$RC" 1 "unknown machine: exit 1"
like "$ERR" "unknown machine 'no-such-machine'" "unknown machine: message"
run "$LAMINA" machines --show "$TMP/missing.yaml"
is "$RC" 1 "missing file: exit 1"

for args in "--bogus" "--show" "extra" "--show creol-ladrp --show sls-contours" "--show="; do
    # shellcheck disable=SC2086
    run "$LAMINA" machines $args
    is "$RC" 2 "usage error: machines $args"
done
run "$LAMINA" machines --help
is "$RC" 0 "--help: exit 0"
like "$OUT" 'LAMINA_MACHINES' "--help: describes the search path"
run "$LAMINA" --help
like "$OUT" 'lamina machines' "lamina --help lists machines"

# --keys: the key reference, which machines/README.md carries verbatim.
run "$LAMINA" machines --keys
is "$RC" 0 "--keys: exit 0"
like "$OUT" $'\n\\| `raster.islands` \\| boolean \\| `false` \\|' "--keys: a row per key with type and default"
readme=$(sed -n '/^<!-- keys: begin/,/^<!-- keys: end/p' "$TESTS/../machines/README.md" | sed '1d;$d')
is "$readme" "$OUT" "machines/README.md's key reference is what --keys prints (regenerate it with lamina machines --keys)"

# --show with --set: the profile a run would use.
run "$LAMINA" machines --show creol-ladrp --set feed_rate=0.3 -s raster.angle=45 --set perimeters=2
is "$RC" 0 "--show --set: exit 0"
like "$OUT" $'\nfeed_rate: 0\\.3\ntravel_rate: 0\\.3\n' "--set feed_rate: the travel rate that followed it follows"
like "$OUT" $'\n  angle: 45\n' "-s raster.angle=45"
like "$OUT" $'\n  perimeters: 2\n' "--set perimeters (a raster key by its own name)"
run "$LAMINA" machines --show creol-ladrp --set 'dialect.layer=; layer {number}'
like "$OUT" $'\n  layer: "; layer \\{number\\}"\n' "--set a dialect template"
run "$LAMINA" machines --show creol-ladrp --set feed_rate=-1
like "$RC $ERR" "^2 lamina machines: --set feed_rate=-1: feed_rate must be 0 or more, got '-1'" "--set: a bad value, exit 2, the loader's message"
like "$ERR" "try 'lamina machines --help'" "the hint names the command"
run "$LAMINA" machines --show creol-ladrp --set feedrate=1
like "$RC $ERR" "^2 .*unknown key 'feedrate' \\(did you mean 'feed_rate'\\?\\)" "--set: an unknown key, did you mean"
run "$LAMINA" machines --show creol-ladrp --set feed_rate
like "$RC $ERR" "^2 .*--set feed_rate: expected KEY=VALUE" "--set without ="
run "$LAMINA" machines --set feed_rate=1
is "$RC" 2 "--set without --show: usage error"
run "$LAMINA" machines --show=creol-ladrp --set=feed_rate=0.5
is "$RC" 0 "--show=NAME --set=KEY=VALUE: exit 0"
like "$OUT" $'\nfeed_rate: 0\\.5\n' "--show=NAME --set=KEY=VALUE"

done_testing
