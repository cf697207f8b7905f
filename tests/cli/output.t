#!/usr/bin/env bash
# Output that cannot be written is an error, and an interrupted run leaves
# no temporary file: standard output checked at exit for every command,
# a full disk named with its reason, a replaced file's mode kept, -o onto
# the model refused, SIGINT/SIGTERM/SIGHUP/SIGPIPE during a slice, stale
# temporaries after SIGKILL. Long runs are waited for by condition (a file
# appears, the process exits), never by a fixed sleep.
. "$(dirname "$0")/lib.sh"

cd "$TMP" || exit 1
cp "$M/thesis_cube.ug" model.ug # a model repair has nothing to say about: the messages are the outputs'

# ---- standard output that cannot be written ------------------------------------------
if [ -w /dev/full ]; then
    for cmd in "validate model.ug --json" "validate model.ug" "info model.ug" "info model.ug --json" \
               "check model.ug -m creol-ladrp" "check model.ug -m creol-ladrp --json" "machines" \
               "machines --show creol-ladrp" "slice model.ug" "-e print(1)" "--help" "--version" "slice --help"; do
        # shellcheck disable=SC2086
        "$LAMINA" $cmd >/dev/full 2>"$TMP/err"
        rc=$?
        like "$rc $(cat "$TMP/err")" "^1 lamina.*: (cannot write to standard output|\(?stdout\)?: cannot write output)(: No space left on device)?$" \
            "lamina $cmd > /dev/full: exit 1 with a message"
    done
    # the same commands succeed when standard output can take it
    run "$LAMINA" validate model.ug --json
    is "$RC" 0 "(validate --json to a file: exit 0)"
    run "$LAMINA" slice model.ug -o /dev/full
    like "$RC $ERR" "^1 lamina: /dev/full: cannot write output: No space left on device$" \
        "slice -o /dev/full: the path and the reason"
    run "$LAMINA" slice model.ug -m creol-ladrp -o /dev/full
    like "$RC $ERR" "^1 lamina: /dev/full: cannot write output: No space left on device$" "the same through an LADRP profile"
    run "$LAMINA" -e 'print(lamina.machine("sls-contours"):plan(lamina.load("model.ug"):slice{width = 1}):write("/dev/full"))'
    like "$OUT" "^nil	/dev/full: cannot write output: No space left on device$" "plan:write to /dev/full: the path and the reason"
else
    echo "# /dev/full is not writable here: skipped"
fi
# a closed standard output with SIGPIPE ignored: EPIPE is a write error
# (the pipe's reader is closed before lamina starts: with `| true` the
# reader may still be there when lamina writes, and the run passes)
perl -e '$SIG{PIPE} = "IGNORE"; pipe(my $r, my $w) or die; close $r; open(STDOUT, ">&", $w) or die; exec @ARGV' \
    "$LAMINA" info model.ug --json 2>"$TMP/err"
echo "$?" >"$TMP/rc"
like "$(cat "$TMP/rc") $(cat "$TMP/err")" "^1 lamina: cannot write to standard output(: Broken pipe)?$" \
    "a reader that went away (SIGPIPE ignored): exit 1 with a message"

# ---- replacing files ---------------------------------------------------------------------
echo old >kept.sls
chmod 600 kept.sls
"$LAMINA" slice model.ug -o kept.sls
is "$(stat -c %a kept.sls) $(head -c 7 kept.sls)" "600 contour" "a replaced file keeps its mode 600"
chmod 640 kept.sls
"$LAMINA" slice model.ug -o kept.sls --svg kept.svg
is "$(stat -c %a kept.sls)" 640 "and 640"
rm -f new.sls
(umask 027; "$LAMINA" slice model.ug -o new.sls)
is "$(stat -c %a new.sls)" 640 "a new file gets 0666 less the umask"
sum=$(cksum <model.ug)
for target in model.ug ./model.ug "$TMP/model.ug" ../"$(basename "$TMP")"/model.ug; do
    run "$LAMINA" slice model.ug -o "$target"
    like "$RC $ERR" "^2 lamina slice: -o .*model\.ug is an input of this command \(read as model\.ug\): refusing to overwrite it$" "-o $target: refused"
done
ln -s model.ug link.ug
ln model.ug hard.ug
run "$LAMINA" slice link.ug -o hard.ug
like "$RC $ERR" "^2 lamina slice: -o hard\.ug is an input of this command \(read as link\.ug\)" "a link and a hard link to the model: the same file, refused"
run "$LAMINA" slice model.ug --svg link.ug
like "$RC $ERR" "^2 lamina slice: --svg link\.ug is an input of this command \(read as model\.ug\)" "--svg onto the model: refused"
is "$(cksum <model.ug)" "$sum" "the model is untouched"

# ---- signals during a slice ------------------------------------------------------------------
# A slice that runs until it is stopped, writing from the start: LADRP
# with a bead of 1e-7, 2 * 10^7 scan lines in each of the 2 layers.
printf 'inherits: creol-ladrp\nbead_width: 1e-7\n' >fine.yaml
LONG=(slice model.ug -m ./fine.yaml -w 1 --max-output 16G) # about 5 GB, stopped long before
# wait_for COND-COMMAND: poll until it holds, at most about 60 s
wait_for() {
    for _ in $(seq 1 6000); do eval "$1" && return 0; sleep 0.01; done
    return 1
}
temps() { ls "$TMP/sig" 2>/dev/null | grep -c 'out\.sls\.tmp-'; }
for sig in INT TERM HUP PIPE; do
    rm -rf "$TMP/sig"
    mkdir "$TMP/sig"
    # a background job of a script starts with SIGINT ignored, and a suite
    # run under nohup starts with SIGHUP ignored (lamina rightly leaves an
    # ignored signal ignored): perl gives each signal tried its default
    perl -e '$SIG{$_} = "DEFAULT" for qw(INT TERM HUP PIPE); exec @ARGV' "$LAMINA" "${LONG[@]}" -o "$TMP/sig/out.sls" 2>"$TMP/err" &
    pid=$!
    wait_for '[ "$(temps)" -gt 0 ]'
    ok $? "SIG$sig: the slice is writing its temporary file"
    kill -s "$sig" "$pid"
    { wait "$pid"; } 2>/dev/null
    rc=$?
    num=$(kill -l "$sig")
    is "$rc" $((128 + num)) "SIG$sig: ends with status 128 + $num"
    is "$(ls "$TMP/sig" | tr '\n' ' ')" "" "SIG$sig: no temporary file, no output left"
done

# ---- SIGKILL: the next run removes the stale temporary ---------------------------------------
rm -rf "$TMP/sig"
mkdir "$TMP/sig"
"$LAMINA" "${LONG[@]}" -o "$TMP/sig/out.sls" &
pid=$!
wait_for '[ "$(temps)" -gt 0 ]'
kill -KILL "$pid"
{ wait "$pid"; } 2>/dev/null
is "$?" 137 "SIGKILL: the process is gone"
is "$(temps)" 1 "SIGKILL leaves its temporary behind (nothing can run)"
stale=$(ls "$TMP/sig")
like "$stale" "^out\.sls\.tmp-$pid-......$" "the temporary's name holds the writer's pid"
# look-alikes that are not provably lamina's stale temporaries
printf 'live\n' >"$TMP/sig/out.sls.tmp-1-abcdef"
printf 'notes\n' >"$TMP/sig/out.sls.tmp-notes"
printf 'other\n' >"$TMP/sig/other.sls.tmp-2-abcdef"
exec 9<"$TMP/sig/out.sls.tmp-1-abcdef"
flock -x 9     # held as a live writer holds its own
"$LAMINA" slice model.ug -o "$TMP/sig/out.sls"
is "$?" 0 "the next slice to the same file runs"
is "$(ls "$TMP/sig" | tr '\n' ' ')" "other.sls.tmp-2-abcdef out.sls out.sls.tmp-1-abcdef out.sls.tmp-notes " \
    "it removed the dead writer's temporary, not a locked one, another name or another target's"
exec 9<&-
"$LAMINA" slice model.ug -o "$TMP/sig/out.sls"
is "$(ls "$TMP/sig" | tr '\n' ' ')" "other.sls.tmp-2-abcdef out.sls out.sls.tmp-notes " \
    "once its lock is released, that one goes too"

done_testing
