#!/usr/bin/env bash
# Hostile inputs (issue 11): huge shell counts, huge coordinates, files that
# are not files, oversized and deeply nested inputs, and messages that must
# not echo a file that is not a model or a profile. Large inputs are made
# here, small: Unigrafix instances double a shape.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
j() { jq -r "$1" <<<"$OUT"; }

# --- many shells -------------------------------------------------------
# 2^18 one-triangle shells, each tilted over an eighth of the stack: the old
# grid listed each in 32768 cells, 2^33 entries, past its 32-bit counts.
{
    echo "def L0; v a 0 0 0; v b 1 0 0; v c 0 1 32768; f (a b c); end;"
    for k in $(seq 1 18); do echo "def L$k; i (L$((k - 1))); i (L$((k - 1)) -tz $((1 << (k - 1)))); end;"; done
    echo "i (L18);"
} > stack.ug
run "$LAMINA" info --json stack.ug
is "$RC" 0 "2^18 stacked triangles from an instancing file of $(wc -c < stack.ug) bytes: exit 0"
is "$(j .triangles) $(j .shells) $(j .cavities)" "262144 262144 0" "all 2^18 triangles, each its own shell, no cavity"

# 4096 closed tetrahedra in a row inside one box: each is a cavity of it.
# Volume by hand: box 4 x 4 x 4100 minus 4096 tetrahedra of 1/6.
{
    echo "v a 0 0 0; v b 4 0 0; v c 4 4 0; v d 0 4 0; v e 0 0 4100; v f 4 0 4100; v g 4 4 4100; v h 0 4 4100;"
    echo "f (a d c b); f (e f g h); f (a b f e); f (b c g f); f (c d h g); f (d a e h);"
    echo "def T0; v p 1 1 1; v q 2 1 1; v r 1 2 1; v s 1 1 2; f (p r q); f (p q s); f (q r s); f (r p s); end;"
    for k in $(seq 1 12); do echo "def T$k; i (T$((k - 1))); i (T$((k - 1)) -tz $((1 << (k - 1)))); end;"; done
    echo "i (T12);"
} > row.ug
run "$LAMINA" info --json row.ug
is "$RC" 0 "4096 tetrahedra in a box: exit 0"
is "$(j .shells) $(j .cavities)" "4097 4096" "every tetrahedron is a cavity of the box"
is "$(jq -r '.volume - (4 * 4 * 4100 - 4096 / 6) | fabs < 1e-6' <<<"$OUT")" true "volume: the box less 4096 tetrahedra"

# --- huge coordinates ---------------------------------------------------
printf 'v a 0 0 0; v b 1 0 0; v c 0 1 0;\nv d 0 0 1.5e308;\nf (a c b); f (a b d); f (b c d); f (c a d);\n' > huge.ug
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1.5e308\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n' > huge.obj
{
    echo "solid h"
    for t in "0 0 0|0 1 0|1 0 0" "0 0 0|1 0 0|0 0 1.5e308" "1 0 0|0 1 0|0 0 1.5e308" "0 1 0|0 0 0|0 0 1.5e308"; do
        IFS='|' read -r p q r <<<"$t"
        printf 'facet normal 0 0 0\nouter loop\nvertex %s\nvertex %s\nvertex %s\nendloop\nendfacet\n' "$p" "$q" "$r"
    done
    echo "endsolid h"
} > huge.stl
for cmd in info validate "slice -o out.sls" "check -m ded-gcode"; do
    run "$LAMINA" $cmd huge.ug
    like "$RC $ERR" '^1 lamina: huge\.ug:2:9: .*more than a double can measure' "$cmd, vertex at 1.5e308 (.ug): refused at the number"
    run "$LAMINA" $cmd huge.obj
    like "$RC $ERR" '^1 lamina: huge\.obj:4:7: .*more than a double can measure' "$cmd, vertex at 1.5e308 (OBJ)"
    run "$LAMINA" $cmd huge.stl
    like "$RC $ERR" '^1 lamina: huge\.stl:13:12: .*more than a double can measure' "$cmd, vertex at 1.5e308 (STL)"
done
[ ! -e out.sls ]; ok $? "no output file"
# the largest coordinates allowed: every quantity finite, Embree happy
printf 'v a -1e50 -1e50 -1e50; v b 1e50 -1e50 -1e50; v c -1e50 1e50 -1e50;\nv d -1e50 -1e50 1e50;\nf (a c b); f (a b d); f (b c d); f (c a d);\n' > big.ug
run "$LAMINA" info big.ug
is "$RC" 0 "coordinates of 1e50: info works"
if printf '%s' "$OUT" | grep -qi 'inf\b\|nan'; then ok 1 "info prints no inf or nan"; else ok 0 "info prints no inf or nan"; fi
run "$LAMINA" check big.ug -m ded-gcode
ok "$([ "$RC" -eq 0 ] || [ "$RC" -eq 3 ]; echo $?)" "check of a 2e50 part runs (exit $RC, no abort in Embree)"
run "$LAMINA" validate big.ug
like "$RC $OUT" '^0 .*0 disagreeing' "validate of a 2e50 part: all labels confirmed"

# --- files that are not files, and sizes --------------------------------
cp "$M/thesis_cube.ug" cube.ug
run timeout 60 "$LAMINA" info /dev/zero
like "$RC $ERR" '^1 lamina: /dev/zero: .*not a regular file' "/dev/zero as a model: refused before reading"
mkfifo pipe.ug pipe.yaml
run timeout 60 "$LAMINA" info pipe.ug
like "$RC $ERR" '^1 lamina: pipe\.ug: .*not a regular file' "a FIFO as a model: refused, not waited on"
printf 'include /dev/urandom;\n' > inc_dev.ug
run timeout 60 "$LAMINA" info inc_dev.ug
like "$RC $ERR" '^1 lamina: inc_dev\.ug:1:1: cannot include .*not a regular file' "include /dev/urandom: refused"
printf 'include pipe.ug;\n' > inc_pipe.ug
run timeout 60 "$LAMINA" info inc_pipe.ug
like "$RC $ERR" '^1 lamina: inc_pipe\.ug:1:1: cannot include .*not a regular file' "include of a FIFO: refused"
run timeout 60 "$LAMINA" slice cube.ug -m ./pipe.yaml -o out.sls
like "$RC $ERR" '^1 lamina: \./pipe\.yaml: .*not a regular file' "a FIFO as a profile: refused"
run env LAMINA_MAX_INPUT=1K "$LAMINA" info "$M/thesis_cube_binary.stl"
is "$RC" 0 "LAMINA_MAX_INPUT=1K: a 684-byte STL fits"
run env LAMINA_MAX_INPUT=500 "$LAMINA" info "$M/thesis_cube_binary.stl"
like "$RC $ERR" '^1 lamina: .*thesis_cube_binary\.stl: too large for a model: 684 bytes, the limit is 500; set LAMINA_MAX_INPUT' "LAMINA_MAX_INPUT=500: refused, saying how to raise it"
for bad in 12Q -5 abc 0; do
    run env LAMINA_MAX_INPUT=$bad "$LAMINA" info "$M/thesis_cube_binary.stl"
    like "$RC $ERR" '^1 lamina: .*thesis_cube_binary\.stl: cannot read: LAMINA_MAX_INPUT is not a size' \
        "LAMINA_MAX_INPUT=$bad: refused, not the default quietly"
done
run env LAMINA_MAX_INPUT=500 "$LAMINA" info cube.ug
is "$RC" 0 "the cube's $(wc -c < cube.ug)-byte .ug fits in 500 bytes"
printf 'include cube.ug;\n' > inc_cube.ug
run env LAMINA_MAX_INPUT=100 "$LAMINA" info inc_cube.ug
like "$RC $ERR" '^1 lamina: inc_cube\.ug:1:1: cannot include .*too large for a model' "the limit holds for each include"
# profiles: 4 MiB (4194304 bytes) exactly is fine, one byte more is not
pad() { # pad FILE SIZE: a valid profile padded with a comment to SIZE bytes
    cp "$M/machines/base.yaml" "$1"
    local have; have=$(wc -c < "$1")
    { printf '#'; head -c $(($2 - have - 2)) /dev/zero | tr '\0' 'x'; printf '\n'; } >> "$1"
}
pad p4m.yaml 4194304
run "$LAMINA" slice cube.ug -m ./p4m.yaml -o out.nc
is "$RC $(wc -c < p4m.yaml)" "0 4194304" "a profile of exactly 4 MiB loads"
pad p4m1.yaml 4194305
run "$LAMINA" slice cube.ug -m ./p4m1.yaml -o out.nc
like "$RC $ERR" '^1 lamina: \./p4m1\.yaml: too large for a machine profile: 4194305 bytes, the limit is 4194304' "one byte more is refused"

# --- YAML nesting ---------------------------------------------------------
head -c 100000 /dev/zero | tr '\0' '[' > deep.yaml
run timeout 60 "$LAMINA" slice cube.ug -m ./deep.yaml -o out.nc
like "$RC $ERR" '^1 lamina: \./deep\.yaml:1:33: lists and mappings nested more than 32 deep' "100,000 nested '[': refused at the 33rd"
# the top level and raster are 2 levels, 30 lists make 32: within the limit
{ printf 'name: n\nprocess: ladrp\nbead_width: 0.5\ndialect: {deposit: "D", travel: "T"}\nraster: {angle: '
  printf '[%.0s' $(seq 30); printf 1; printf ']%.0s' $(seq 30); printf '}\n'; } > deep32.yaml
run "$LAMINA" slice cube.ug -m ./deep32.yaml -o out.nc
like "$RC $ERR" '^1 .*deep32\.yaml:5:.*angle must be a number' "32 levels pass the depth check (and meet the schema)"
sed -i 's/\[1\]/[[1]]/' deep32.yaml
run "$LAMINA" slice cube.ug -m ./deep32.yaml -o out.nc
like "$RC $ERR" '^1 .*deep32\.yaml:5:.*nested more than 32 deep' "33 levels do not"

# --- messages quote nothing of a file that is not a model or profile ------
printf 'root:$6$SECRETSALT$0123456789abcdef:19000:0:99999:7:::\nalice:$6$OTHERSALT$fedcba:19000:0:99999:7:::\n' > shadow
chmod 600 shadow
printf 'include shadow;\n' > inc_shadow.ug
run "$LAMINA" info inc_shadow.ug
like "$RC $ERR" "^1 lamina: shadow:1:1: not a Unigrafix file" "include of a non-model: refused as such"
if grep -q 'SECRET\|root' <<<"$ERR"; then ok 1 "include of a non-model: nothing of it quoted"; else ok 0 "include of a non-model: nothing of it quoted"; fi
run "$LAMINA" slice cube.ug -m ./shadow -o out.nc
is "$RC" 1 "a non-profile as a profile: exit 1"
if grep -q 'SECRET\|root' <<<"$ERR"; then ok 1 "a non-profile: nothing of it quoted ($ERR)"; else ok 0 "a non-profile: nothing of it quoted"; fi
cp shadow shadow.yaml
run "$LAMINA" info shadow.yaml
if grep -q 'SECRET\|root' <<<"$ERR"; then ok 1 "a non-model as a model: nothing quoted"; else ok 0 "a non-model as a model: nothing quoted"; fi
printf 'v a 0 0 0;\nthis_is_a_very_long_unknown_statement_name_that_goes_on;\n' > long.ug
run "$LAMINA" info long.ug
like "$ERR" "long\.ug:2:1: unknown statement 'this_is_a_very_long_\.\.\.'$" "a recognised model's token: 20 bytes quoted at most"

done_testing
