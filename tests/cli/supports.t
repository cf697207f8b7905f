#!/usr/bin/env bash
# Powder-bed supports (issue 27, core/plan/support.h): lpbf-cli runs of
# small models (tests/cli/supportgen.py: a T, an arch, a sphere, a bracket
# with a horizontal hole, a slab floating over a low box, a cube) along z
# and along an oblique axis, checked by tests/cli/supportcheck.py (its own
# even-odd point in polygon and distances, on the JSON's contours in the
# layer frame): every point of part-plus-support stands within the reach
# w tan(angle) of the layer below, support vectors stay out of the part
# (but for teeth), the xy and z gaps, and the checker failing where it must.
. "$TESTS/cli/lib.sh"
GEN() { python3 "$TESTS/cli/supportgen.py" "$@"; }
CHECK() { python3 "$TESTS/cli/supportcheck.py" "$@"; } # functions: the paths may hold spaces
for m in tee arch sphere bracket float cube; do GEN $m "$TMP/$m.stl" || echo "# supportgen $m failed"; done
OBL=1,0.3,2 # the oblique axis

# slh MODEL JSON SLICE-OPTIONS...: lpbf-cli, the layer frame; sets SLRC.
# sl: the same without hatching (the supports do not depend on it; the
# JSON a fifth as long, the checks the faster)
NOHATCH=(--set hatch_strategy=none --set upskin.hatch_strategy=none --set downskin.hatch_strategy=none)
sl() { slh "$@" "${NOHATCH[@]}"; }
slh() {
    local model=$1 json=$2
    shift 2
    rm -f "$json"
    # lpbf-cli's own teeth (0.09 deep) off unless a test sets them
    "$LAMINA" slice "$TMP/$model.stl" -m lpbf-cli --set frame=machine --set support_teeth.height=0 --json "$json" \
        -o "$TMP/p.cli" "$@" 2>"$TMP/sl.err"
    SLRC=$?
    [ $SLRC -eq 0 ] || sed 's/^/#   lamina: /' "$TMP/sl.err" | head -5
}
# expect pass|fail DESCRIPTION CHECK-ARGUMENTS...: the checker's verdict
# (after a slice that succeeded), its summary in the description
expect() {
    local want=$1 desc=$2 out rc
    shift 2
    out=$(CHECK "$@" 2>&1)
    rc=$?
    if [ "$want" = pass ]; then [ $SLRC -eq 0 ] && [ $rc -eq 0 ]; else [ $SLRC -eq 0 ] && [ $rc -eq 1 ]; fi
    local r=$?
    ok $r "$desc (${out##*# })"
    if [ $r -ne 0 ]; then
        echo "#   expected the check to $want, exit $rc; supportcheck $*:"
        printf '%s\n' "$out" | head -8 | sed 's/^/#   /'
    fi
}

# ---- every model, z and oblique: part and support stand ------------------
for m in tee arch sphere bracket float cube; do
    for ax in 0,0,1 $OBL; do
        slh $m "$TMP/$m.json" -a $ax -w 0.5 --set support_type=block
        expect pass "$m, axis $ax, block: every point stands within the reach of the layer below" stands "$TMP/$m.json"
        expect pass "$m, axis $ax: the overhang contours are the part beyond the reach of the part below" \
            overhang "$TMP/$m.json"
        if [ $m = cube ] && [ $ax = 0,0,1 ]; then continue; fi
        expect pass "$m, axis $ax, block: support vectors in the support region, none in the part" vectors "$TMP/$m.json"
    done
done
# the checker can fail: without supports these do not stand
for m in tee arch sphere float bracket; do
    ax=0,0,1
    [ $m = bracket ] && ax=$OBL
    sl $m "$TMP/$m.json" -a $ax -w 0.5 --set support_type=none
    expect fail "$m, axis $ax, support_type=none: the overhangs do not stand" stands "$TMP/$m.json"
    expect fail "$m, axis $ax, support_type=none: no overhang contours (the analysis comes with supports)" \
        overhang "$TMP/$m.json"
done
# ... nor with one layer's support contours taken out of the JSON
sl tee "$TMP/t.json" -w 0.5 --set support_type=block
jq '.layers[5].contours |= map(select(.region != "support"))' "$TMP/t.json" >"$TMP/cut.json"
expect fail "tee: the JSON without layer 6's support contours does not stand" stands "$TMP/cut.json"
expect fail "tee: support vectors of layer 6 outside its (removed) support region" vectors "$TMP/cut.json"

# ---- support types (-w 1) and angles (-w 0.75) ----------------------------
# (block along both axes above; grid oblique, lines along z: the walls
# run along the layer frame's u and v either way)
for t in grid lines; do
    ax=$OBL
    [ $t = lines ] && ax=0,0,1
    for m in tee arch sphere bracket float; do
        sl $m "$TMP/$m.json" -a $ax -w 1 --set support_type=$t
        expect pass "$m, axis $ax, $t: stands" stands "$TMP/$m.json"
        expect pass "$m, axis $ax, $t: support vectors in the support region" vectors "$TMP/$m.json"
    done
done
for ang in 30 60; do
    for m in tee sphere bracket; do
        sl $m "$TMP/$m.json" -a $OBL -w 0.75 --set support_type=block --set support_angle=$ang
        expect pass "$m, axis $OBL, support_angle=$ang: stands at $ang degrees" stands "$TMP/$m.json" --angle $ang
    done
done
# supports for 60 degrees do not hold at 30 (the angle is read)
sl sphere "$TMP/s.json" -w 0.5 --set support_type=block --set support_angle=60
expect fail "sphere, support_angle=60: does not stand at 30 degrees" stands "$TMP/s.json" --angle 30

# layers of different widths: each layer's reach from its own width
W=$(perl -e 'print join ",", map { (0.5, 1.5, 0.25, 0.75, 1)[$_ % 5] } 0 .. 39')
for m in tee sphere bracket; do
    sl $m "$TMP/$m.json" -a $OBL --widths $W --set support_type=block
    expect pass "$m, axis $OBL, --widths 0.5,1.5,0.25,0.75,1,...: stands, r_k = w_k tan 45" stands "$TMP/$m.json"
done

# ---- where the support is: the models' known places (u = x, v = y along z)
probe() { # probe JSON LAYER U V EXPECTED DESCRIPTION
    is "$(CHECK at "$1" "$2" "$3" "$4" 2>&1)" "$5" "$6"
}
sl tee "$TMP/t.json" -w 1 --set support_type=block
probe "$TMP/t.json" 5 8 0 support "tee: under the bar's wing (8, 0) layer 5 is support"
probe "$TMP/t.json" 5 0 0 part "tee: (0, 0) on layer 5 is the stem"
sl arch "$TMP/a.json" -w 1 --set support_type=block
probe "$TMP/a.json" 2 0 0 support "arch: the opening under the crown is support from the plate (layer 2, (0, 0))"
probe "$TMP/a.json" 2 8 0 part "arch: (8, 0) on layer 2 is the leg"
# the sphere (radius 8) along z, -w 1: layer 1 (z = -7.5) has radius 2.78,
# layer 2 (z = -6.5) 4.66: at 4 on layer 1 (beyond the reach 1) support
sl sphere "$TMP/s.json" -w 1 --set support_type=block
probe "$TMP/s.json" 1 4 0 support "sphere: (4, 0) on layer 1 is support under layer 2's overhang"
probe "$TMP/s.json" 1 0 0 part "sphere: (0, 0) on layer 1 is the part"
# the bracket: the hole (radius 4 about z = 8) from z = 4 to 12
sl bracket "$TMP/b.json" -w 1 --set support_type=block
probe "$TMP/b.json" 7 0 0 support "bracket: inside the hole (layer 7, (0, 0)) support stands on the hole's floor"
probe "$TMP/b.json" 3 0 0 part "bracket: below the hole (layer 3) the part"
# the floating slab (z 9..11, x -3..12) over the box (z 0..6, x -5..5)
sl float "$TMP/f.json" -w 1 --set support_type=block
probe "$TMP/f.json" 1 8.5 0 support "float: beside the box the slab's support reaches the plate (layer 1, (8.5, 0))"
probe "$TMP/f.json" 1 0 0 part "float: (0, 0) on layer 1 is the box"
probe "$TMP/f.json" 7 0 0 support "float: above the box (layer 7, (0, 0)) support stands on the box"
probe "$TMP/f.json" 1 5.5 0 nothing "float: no support within the reach of the box's wall (layer 1, (5.5, 0))"
expect pass "float: no support vector inside the box" vectors "$TMP/f.json"

# ---- the support's area by hand (the checker's own shoelace) --------------
# The T along z, -w 1: the stem [-2.5, 2.5] x [-4, 4] up to z = 10, the bar
# [-10, 10] x [-4, 4] above. Under each wing of the bar the support is the
# bar's footprint less the stem grown by the reach 1 (the stem spans the
# whole depth: no rounded corner inside the bar): [3.5, 10] x [-4, 4], 52;
# both wings 104 on layers 1-10 (z 0.5 .. 9.5), none in the bar (11-14).
rep() { local i out=; for ((i = 0; i < $2; i++)); do out+="$1 "; done; printf '%s' "$out"; }
area() { CHECK area "$@" 2>&1; }
sl tee "$TMP/t.json" -w 1 --set support_type=block
is "$(area "$TMP/t.json")" "$(rep 104.00 10)$(rep 0.00 3)0.00" "tee: the support's area, 2 x 6.5 x 8 under the wings on layers 1-10"
# support_gap_xy=2: from the stem grown by 2, [4.5, 10]: 2 x 5.5 x 8 = 88
sl tee "$TMP/t.json" -w 1 --set support_type=block --set support_gap_xy=2
is "$(area "$TMP/t.json")" "$(rep 88.00 10)$(rep 0.00 3)0.00" "tee, support_gap_xy=2: 2 x 5.5 x 8 on layers 1-10"
# support_gap_z=2 -w 1: layers 9 and 10 have the bar within 2 layers above
sl tee "$TMP/t.json" -w 1 --set support_type=block --set support_gap_z=2
is "$(area "$TMP/t.json")" "$(rep 104.00 8)$(rep 0.00 5)0.00" "tee, support_gap_z=2: layers 9 and 10 cleared"
# support_min_area: each wing's region is 52 on every layer
sl tee "$TMP/t.json" -w 1 --set support_type=block --set support_min_area=60
is "$(area "$TMP/t.json")" "$(rep 0.00 13)0.00" "tee, support_min_area=60: the wings' regions of 52 dropped"
sl tee "$TMP/t.json" -w 1 --set support_type=block --set support_min_area=50
is "$(area "$TMP/t.json")" "$(rep 104.00 10)$(rep 0.00 3)0.00" "tee, support_min_area=50: kept"
# the floating slab [-3, 12] x [-4, 4] at z 9..11 over the box [-5, 5]^2 x
# [0, 6]: beside the box (x from 5 + 1 to 12) 6 x 8 = 48 on layers 1-6,
# the whole footprint 15 x 8 = 120 on layers 7-9 (standing on the box's
# top), none in the slab (10, 11)
sl float "$TMP/f.json" -w 1 --set support_type=block
is "$(area "$TMP/f.json")" "$(rep 48.00 6)$(rep 120.00 3)0.00 0.00" "float: 48 beside the box on layers 1-6, 120 over it on 7-9"
# the sphere with support_min_area=5: no support piece below 5
sl sphere "$TMP/s.json" -w 0.5 --set support_type=block --set support_min_area=5
CHECK area "$TMP/s.json" --min 5 >/dev/null
ok $? "sphere, support_min_area=5: every support piece (solid less its holes) at least 5"
CHECK area "$TMP/s.json" --min 20 >/dev/null
ok $((!$?)) "... (the check can fail: some are below 20)"

# ---- perforation: windows cut out of the walls ------------------------------
slen() { jq '[.layers[].vectors[] | select(.kind == "support") | ((.to[0] - .from[0]) * (.to[0] - .from[0]) + (.to[1] - .from[1]) * (.to[1] - .from[1]) | sqrt)] | add // 0' "$1"; }
sl tee "$TMP/t.json" -w 0.5 --set support_type=grid
l0=$(slen "$TMP/t.json")
sl tee "$TMP/t.json" -w 0.5 --set support_type=grid --set support_perforation.width=0.5 --set support_perforation.spacing=1.5
l1=$(slen "$TMP/t.json")
# windows 0.5 square every 1.5 along a wall and upwards (one layer of 0.5
# in three): about (0.5 / 1.5)^2 = 1/9 of the walls' length goes
perl -e "my \$f = 1 - $l1 / $l0; exit !(\$f > 0.08 && \$f < 0.14)"
ok $? "tee, grid, perforation 0.5 every 1.5: about 1/9 of the walls cut out ($l1 of $l0)"
expect pass "tee, perforated: support vectors in the support region" vectors "$TMP/t.json"
expect pass "tee, perforated: stands (the region is not perforated)" stands "$TMP/t.json"

# ---- teeth: the walls reach ceil(height / w) layers into the part ---------
for m in tee arch float; do
    for ax in 0,0,1 $OBL; do
        sl $m "$TMP/$m.json" -a $ax -w 0.5 --set support_type=block --set support_teeth.height=1 \
            --set support_teeth.width=0.5 --set support_teeth.spacing=1
        expect pass "$m, axis $ax, teeth 1 high (2 layers of 0.5): support vectors in the part only over 2 layers" \
            vectors "$TMP/$m.json" --teeth-layers 2
        expect fail "$m, axis $ax, teeth 1 high: they do reach the second layer (--teeth-layers 1 fails)" \
            vectors "$TMP/$m.json" --teeth-layers 1
        expect pass "$m, axis $ax, teeth: stands" stands "$TMP/$m.json"
    done
done
sl tee "$TMP/t.json" -w 0.5 --set support_type=block --set support_teeth.height=1
expect fail "tee, teeth on: the teeth-off check fails (the checker sees them)" vectors "$TMP/t.json"

# ---- support_gap_xy: support at least 2 from the part's walls -------------
# (Not checked: stands. The gap is taken from every layer's support, so a
# slope's support beside the part below goes too: with support_gap_xy=2 the
# arch along z has no support at all, its crown overhangs unsupported; the
# rule as support.h gives it.)
# (tol 0.01: the part grown by a polygonal circle, its chords inside it)
for m in tee float; do
    for ax in 0,0,1 $OBL; do
        sl $m "$TMP/$m.json" -a $ax -w 0.5 --set support_type=block --set support_gap_xy=2
        expect pass "$m, axis $ax, support_gap_xy=2: every support point 2 from the part" \
            vectors "$TMP/$m.json" --gap-xy 2 --tol 0.01
    done
done
sl tee "$TMP/t.json" -w 0.5 --set support_type=block --set support_gap_xy=2
expect fail "tee, support_gap_xy=2: a gap of 2.5 is not kept (the checker can fail)" vectors "$TMP/t.json" --gap-xy 2.5 --tol 0.01
sl tee "$TMP/t.json" -w 0.5 --set support_type=block
expect fail "tee, no gap asked: the gap of 2 is not kept" vectors "$TMP/t.json" --gap-xy 2 --tol 0.01

# ---- support_gap_z: ceil(2 / 1) = 2 layers clear under the part ------------
for m in tee arch bracket float; do
    for ax in 0,0,1 $OBL; do
        sl $m "$TMP/$m.json" -a $ax -w 1 --set support_type=block --set support_gap_z=2
        expect pass "$m, axis $ax, support_gap_z=2 -w 1: no support with part within 2 layers above" \
            gapz "$TMP/$m.json" --layers 2
    done
done
sl tee "$TMP/t.json" -w 1 --set support_type=block --set support_gap_z=2
expect fail "tee, support_gap_z=2: the third layer above is part (gapz --layers 3 fails)" gapz "$TMP/t.json" --layers 3
sl tee "$TMP/t.json" -w 1 --set support_type=block
expect fail "tee, no gap_z: support right under the part (gapz --layers 1 fails)" gapz "$TMP/t.json" --layers 1
sl tee "$TMP/t.json" -w 1 --set support_type=block --set support_gap_z=2 --set support_teeth.height=2
expect pass "tee, support_gap_z=2 with teeth asked: no teeth then" vectors "$TMP/t.json"
expect pass "... and 2 layers clear" gapz "$TMP/t.json" --layers 2

# ---- no support where none is needed ---------------------------------------
sl tee "$TMP/t.json" -w 0.5 --set support_type=block --set support_angle=90
expect pass "tee, support_angle=90: no support" none "$TMP/t.json"
sl cube "$TMP/c.json" -w 0.5 --set support_type=block
expect pass "cube along z, default angle: no support" none "$TMP/c.json"
sl tee "$TMP/t.json" -w 0.5 --set support_type=block
expect fail "tee, block: the none check fails (the checker can fail)" none "$TMP/t.json"
# the shipped metal powder-bed profiles make block supports by default, the
# others none: lpbf-cli as it is supports the tee and its supports stand
sl tee "$TMP/t.json" -w 0.5
expect fail "tee, lpbf-cli as it is (support_type block by default): supported" none "$TMP/t.json"
expect pass "tee, lpbf-cli as it is: everything stands" stands "$TMP/t.json"
for pr in creol-ladrp sls-contours; do
    is "$("$LAMINA" machines --show $pr 2>/dev/null | sed -n 's/^support_type: //p')" \
       "$( [ $pr = sls-contours ] && echo none)" "$pr: support_type none (polymer SLS stands in its powder; LADRP has no such key)"
done

# ---- determinism: -j 1 and -j 2 byte-identical -----------------------------
for m in tee sphere float; do
    for t in block grid; do
        o=(-m lpbf-cli --set frame=machine -a $OBL -w 0.5 --set support_type=$t --set support_teeth.height=0.5)
        "$LAMINA" slice "$TMP/$m.stl" "${o[@]}" -j 1 -o "$TMP/j1.cli" --json "$TMP/j1.json" 2>/dev/null
        "$LAMINA" slice "$TMP/$m.stl" "${o[@]}" -j 2 -o "$TMP/j2.cli" --json "$TMP/j2.json" 2>/dev/null
        cmp -s "$TMP/j1.cli" "$TMP/j2.cli" && cmp -s "$TMP/j1.json" "$TMP/j2.json" && [ -s "$TMP/j1.cli" ]
        ok $? "$m, $t: program and JSON byte-identical with -j 1 and -j 2"
    done
done

# ---- the build-time estimate counts the supports ---------------------------
secs() { # the seconds of "estimated build time [H h] [M min] S s"
    perl -ne 'if (/estimated build time ((?:[\d.]+ (?:h|min|s) ?)+)/) { my $t = 0; my $s = $1;
        while ($s =~ /([\d.]+) (h|min|s)/g) { $t += $1 * ($2 eq "h" ? 3600 : $2 eq "min" ? 60 : 1) } print $t }'
}
"$LAMINA" slice "$TMP/tee.stl" -m lpbf-cli -w 0.5 --set support_type=block --json "$TMP/ts.json" -o "$TMP/ts.cli" 2>"$TMP/ts.err"
"$LAMINA" slice "$TMP/tee.stl" -m lpbf-cli -w 0.5 --set support_type=none --json "$TMP/tn.json" -o "$TMP/tn.cli" 2>"$TMP/tn.err"
s1=$(secs <"$TMP/ts.err"); s0=$(secs <"$TMP/tn.err")
[ -n "$s1" ] && [ -n "$s0" ] && perl -e "exit !($s1 > $s0)"
ok $? "tee: the printed estimate is longer with supports ($s1 s) than without ($s0 s)"
[ $? -eq 0 ] || { sed 's/^/#   /' "$TMP/ts.err" "$TMP/tn.err"; }
got=$(jq -n --slurpfile a "$TMP/ts.json" --slurpfile b "$TMP/tn.json" \
    '[($a[0].totals.time.total > $b[0].totals.time.total), ($a[0].totals.time.exposure > $b[0].totals.time.exposure), ($a[0].totals.time.recoat == $b[0].totals.time.recoat)]' | tr -d ' \n')
is "$got" "[true,true,true]" "tee: the JSON's total and exposure times grow with supports, recoating does not"

# the support is exposed at the support's speed: the exposure time grows by
# the walls' length over it, the deposit length by the walls' length (the
# part's own vectors the same either way); the total is the layers' sum
got=$(jq -n --slurpfile a "$TMP/ts.json" --slurpfile b "$TMP/tn.json" '
    ([$a[0].layers[].vectors[] | select(.kind == "support") | [.to[0] - .from[0], .to[1] - .from[1], .to[2] - .from[2]]
      | (.[0] * .[0] + .[1] * .[1] + .[2] * .[2] | sqrt)] | add) as $len
    | ($a[0].job.exposure[] | select(.region == "support") | .speed) as $v
    | [$len > 0,
       (($a[0].totals.time.exposure - $b[0].totals.time.exposure) - $len / $v | fabs < 1e-6),
       (($a[0].totals.deposit_length - $b[0].totals.deposit_length) - $len | fabs < 1e-6),
       ($a[0].totals.time.total - ([$a[0].layers[].stats.time] | add) | fabs < 1e-6)]' | tr -d ' \n')
is "$got" "[true,true,true,true]" "tee: exposure + support length / support speed, deposit + support length, total = the layers' sum"

# ---- the support's exposure ------------------------------------------------
"$LAMINA" slice "$TMP/tee.stl" -m lpbf-cli -w 0.5 --set support_type=block --set support.speed=1234 \
    --set support.power=77 --json "$TMP/e.json" -o "$TMP/e.cli" 2>/dev/null
is "$(jq -c '[.job.exposure[] | select(.region == "support") | .speed, .power]' "$TMP/e.json")" "[1234,77]" \
    "support.speed=1234 support.power=77: the JSON's job.exposure for region support"
n=$(grep -c '^//support power 77 speed 1234//$' "$TMP/e.cli")
ok $((n == 0)) "... and the program's support blocks carry it ($n blocks)"
n=$(jq '[.layers[].vectors[] | select(.kind == "support")] | length' "$TMP/e.json")
ok $((n == 0)) "... the JSON has support vectors ($n)"
# ---- hostile values: refused quickly, nothing written ----------------------
# windows of 5e-10 every 1e-9 along 13 mm walls: 1.3e10 pieces a wall; the
# estimate refuses them at the default limit, and past a raised limit the
# walls are counted before any is cut
rm -f "$TMP/h.cli"
run "$LAMINA" slice "$TMP/tee.stl" -m lpbf-cli -w 1 -s support_perforation.width=5e-10 -s support_perforation.spacing=1e-9 \
    -o "$TMP/h.cli"
like "$RC $ERR" '^1 lamina: the job would write about .*more than the limit of 4 GB' "perforation 1e-9: refused by the estimate"
run "$LAMINA" slice "$TMP/tee.stl" -m lpbf-cli -w 1 -s support_perforation.width=5e-10 -s support_perforation.spacing=1e-9 \
    --max-output 1000T -o "$TMP/h.cli"
like "$RC $ERR" '^2 lamina slice: layer [0-9]+: support_spacing, support_teeth.spacing or support_perforation.spacing is too small' \
    "... past a raised limit: the walls refused, the layer named"
[ ! -e "$TMP/h.cli" ]
ok $? "... and no program written"
done_testing
