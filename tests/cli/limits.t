#!/usr/bin/env bash
# Whole-job limits: layers (--max-layers) and the output's estimated size
# (--max-output), refused before the work starts with the numbers and the
# option that raises the limit; and the output held to the limit as it is
# written.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
cd "$TMP" || exit 1
# a 100 mm cube (Unigrafix), 0..100 on every axis
cat >cube100.ug <<'UG'
v a 0 0 0; v b 100 0 0; v c 100 100 0; v d 0 100 0;
v e 0 0 100; v f 100 0 100; v g 100 100 100; v h 0 100 100;
f bottom (a d c b); f top (e f g h); f front (a b f e);
f right (b c g f); f back (c d h g); f left (d a e h);
UG

# ---- layers ---------------------------------------------------------------------
run "$LAMINA" slice cube100.ug -w 1e-6 -o out.sls
like "$RC $ERR" "^1 lamina: width 1e-06 makes 100000000 layers, more than the limit of 1000000
lamina: raise the limit with --max-layers N$" "-w 1e-6 on a 100 mm cube: 10^8 layers refused, with the numbers and the option"
ok $(ls | grep -q 'out\.sls' && echo 1 || echo 0) "no output file, not even a temporary"
run "$LAMINA" slice cube100.ug -w 0.1 --max-layers 999 -o out.sls
like "$RC $ERR" "^1 lamina: width 0\.1 makes 1000 layers, more than the limit of 999" "--max-layers lowers the limit"
run "$LAMINA" slice cube100.ug -w 0.1 --max-layers 1000 -o out.sls
is "$RC $(grep -c '^contour ' out.sls)" "0 1000" "a run of exactly --max-layers layers is made (1000 contour blocks)"
run "$LAMINA" slice cube100.ug --planes 0,50,100 --max-layers 1
like "$RC $ERR" "^1 lamina: the list of planes makes 2 layers, more than the limit of 1" "--planes counts too"
run "$LAMINA" validate cube100.ug -w 1e-5
like "$RC $ERR" "^1 lamina: width 1e-05 makes 10000000 layers, more than the limit of 1000000
lamina: raise the limit with --max-layers N" "validate: 10^7 layers refused"
for bad in 0 -1 1.5 x; do
    run "$LAMINA" slice cube100.ug --max-layers "$bad"
    like "$RC $ERR" "^2 lamina slice: --max-layers takes a whole number of layers >= 1 \(got '$bad'\)" "--max-layers $bad is a usage error"
done

# ---- output -------------------------------------------------------------------
cat >tiny.yaml <<'Y'
inherits: creol-ladrp
bead_width: 1e-5
Y
run "$LAMINA" slice cube100.ug -m ./tiny.yaml -w 10 -o out.ladrp
# 10 layers of 100 / 1e-5 + 1 lines, each at least a travel and a deposit
# ("0.00000 -0.00001 0.00000 uline", 31 bytes each): over 6 GB
like "$RC $ERR" "^1 lamina: the job would write about ([6-9]\.[0-9]+|[1-9][0-9]\.[0-9]+) GB \(10 layers, 1e\+08 scan lines of bead 1e-05\), more than the limit of 4 GB
lamina: raise the limit with --max-output SIZE" "bead_width 1e-5: 10^7 scan lines a layer refused before planning"
ok $(ls | grep -q 'out\.ladrp' && echo 1 || echo 0) "no output file, not even a temporary"
run "$LAMINA" slice cube100.ug -m ./tiny.yaml -w 10 --angle 90 --angle-step 45 -o out.ladrp
# 0, 90 (1e7 + 1 lines each) and 45 degrees (100 sqrt 2 / 1e-5 lines) alternate: still far over
like "$RC $ERR" "^1 lamina: the job would write about [0-9.]+ GB \(10 layers, 1\.2[0-9]*e\+08 scan lines" \
    "changing raster angles are counted layer by layer"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp -w 1 --max-output 1k -o out.ladrp
# 2 layers of 2 / 0.08 + 1 = 26 lines, each a travel, the laser on (and its
# feed) and off, a deposit: about 90 bytes, so 4 to 5 kB
like "$RC $ERR" "^1 lamina: the job would write about [45]\.[0-9]+ kB \(2 layers, 52 scan lines of bead 0\.08\), more than the limit of 1 kB" \
    "--max-output lowers the limit (k = 1024)"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp -w 1 --max-output 1M -o out.ladrp
is "$RC" 0 "--max-output 1M: the same job runs"
# The writer holds the limit too, for what the estimate misses: it slices
# 32 layers spread over the run (the middles of 32 equal runs of layers),
# and a plate 1 thick at height 49 of a run of 1000 layers of 0.1 (layers
# 490-499) lies between the samples at layers 484 and 515: the estimate
# sees only the 0.2-wide pin beside it, which has no room for hatches.
cat >pinplate.ug <<'UG'
v a 0 0 0; v b 0.2 0 0; v c 0.2 0.2 0; v d 0 0.2 0;
v e 0 0 100; v f 0.2 0 100; v g 0.2 0.2 100; v h 0 0.2 100;
f bottom (a d c b); f top (e f g h); f front (a b f e);
f right (b c g f); f back (c d h g); f left (d a e h);
v A 10 0 49; v B 110 0 49; v C 110 100 49; v D 10 100 49;
v E 10 0 50; v F 110 0 50; v G 110 100 50; v H 10 100 50;
f pbottom (A D C B); f ptop (E F G H); f pfront (A B F E);
f pright (B C G F); f pback (C D H G); f pleft (D A E H);
UG
run "$LAMINA" slice pinplate.ug -m lpbf-cli -w 0.1 -o pp.cli
is "$RC" 0 "the pin and plate are sliced"
size=$(wc -c <pp.cli)
run "$LAMINA" slice pinplate.ug -m lpbf-cli -w 0.1 --max-output $((size - 1)) -o pp2.cli
like "$RC $ERR" "^1 lamina: pp2\.cli: cannot write output: output exceeds the limit of $((size - 1)) bytes
lamina: raise the limit with --max-output" "a program one byte over the limit is stopped as it is written"
ok $(ls | grep -q 'pp2\.cli' && echo 1 || echo 0) "and leaves no file"
run "$LAMINA" slice pinplate.ug -m lpbf-cli -w 0.1 --max-output "$size" -o pp3.cli
is "$RC" 0 "a program of exactly the limit is written"
cmp -s pp.cli pp3.cli
ok $? "the same program"
run "$LAMINA" slice "$M/thesis_cube.ug" -m creol-ladrp -w 1 --max-output 100
like "$RC $ERR" "more than the limit of 100 bytes" "the limit holds for standard output too"
for bad in 0 -5 1X 1.5k; do
    run "$LAMINA" slice cube100.ug --max-output "$bad"
    like "$RC $ERR" "^2 lamina slice: --max-output takes a size in bytes" "--max-output $bad is a usage error"
done
run "$LAMINA" validate cube100.ug --max-output 1M
like "$RC $ERR" "^2 lamina validate: option --max-output does not apply to 'validate'" "validate writes no program: no --max-output"

done_testing
