#!/usr/bin/env bash
# The progress line (lua/cli/progress.h) on a real terminal: tmux runs
# lamina in a pseudo-terminal and logs every byte it draws (pipe-pane),
# so the redraws are checked however fast the run was; the screen at the
# end shows what a person is left with. No line when standard error is
# not a terminal or with -q; -v says how long the stages took.
#
# Each run waits for `read` before it starts, so the log is in place
# before lamina writes its first byte; a marker printed after it says the
# log is complete (tmux hands the pane's output on in order).
. "$(dirname "$0")/lib.sh"

if ! command -v tmux >/dev/null; then
    echo "1..0 # SKIP tmux is not installed"
    exit 0
fi

SOCK="lamina-progress-test-$$"
tm() { tmux -L "$SOCK" "$@"; }
trap 'tm kill-server 2>/dev/null; rm -rf "$TMP"' EXIT
ln -s "$TESTS/models" "$TMP/models"

# start NAME CMD...: CMD in $TMP on a 120x40 terminal (COLS columns if
# set), its output logged
# raw to $TMP/NAME.raw; its exit status goes to $TMP/NAME.status
start() {
    local name=$1; shift
    local cmd
    cmd=$(printf '%q ' "$@")
    tm -f /dev/null new-session -d -s "$name" -x "${COLS:-120}" -y 40 -c "$TMP" \
        "read go; $cmd; echo \$? >$(printf '%q' "$TMP/$name.status"); echo ==END==; read done" \; \
        set-option -t "$name" remain-on-exit on
    tm pipe-pane -t "$name" -o "cat >>$(printf '%q' "$TMP/$name.raw")"
    date +%s.%N >"$TMP/$name.t0"
    tm send-keys -t "$name" Enter
}
# finish NAME: wait (up to 120 s) until the run is over and logged; sets
# SCREEN (what the terminal shows, trailing blanks cut), RAW (every byte
# drawn), STATUS, ELAPSED (seconds from the start, at least the run's own)
finish() {
    local t=0
    while [ $t -lt 1200 ]; do
        grep -aq '==END==' "$TMP/$1.raw" 2>/dev/null && [ -s "$TMP/$1.status" ] && break
        sleep 0.1
        t=$((t + 1))
    done
    ELAPSED=$(echo "$(date +%s.%N) - $(cat "$TMP/$1.t0")" | bc)
    SCREEN=$(tm capture-pane -p -J -t "$1" -S -200 | sed 's/[[:space:]]*$//')
    RAW=$(tr '\r' '\n' <"$TMP/$1.raw")
    STATUS=$(cat "$TMP/$1.status" 2>/dev/null)
}
# the redraws in the log of a run of N layers: "layer K of N (" each
draws() { grep -ao "layer [0-9]* of $2 (" "$TMP/$1.raw" | wc -l; }

# 1. a terminal, every layer drawn (LAMINA_PROGRESS_INTERVAL=0): 2000
# layers of 0.001 through the 2-unit cube with its hole
start term env LAMINA_PROGRESS_INTERVAL=0 "$LAMINA" slice models/thesis_cube_hole.ug -w 0.001 -o term.sls
finish term
is "$STATUS" 0 "terminal: the slice succeeds"
is "$(grep -ao 'layer [0-9]* of 2000 (' "$TMP/term.raw" | sort -u | wc -l)" 2000 \
    "terminal: the line was drawn for each of the 2000 layers"
like "$RAW" '^lamina: slicing thesis_cube_hole\.ug: layer 1 of 2000 \(0%\)' "... starting at layer 1 of 2000, 0%"
like "$RAW" '^lamina: slicing thesis_cube_hole\.ug: layer 1000 of 2000 \(50%\), [0-9.e+]+ layers/s, ([0-9]+ s|<1 s|[0-9]+ min [0-9]+ s) left' \
    "... halfway: 50%, the rate and the time left"
like "$RAW" 'layer 2000 of 2000 \(100%\)' "... ending at layer 2000 of 2000, 100%"
# drawn in place: \r before every redraw, never a newline inside the run
is "$(grep -ac 'layer [0-9]* of 2000' "$TMP/term.raw")" 1 "... all redraws on one terminal line (\\r, no newline)"
ok "$(printf '%s\n' "$SCREEN" | grep -q ' of 2000'; [ $? = 1 ]; echo $?)" "... and erased at the end: the screen shows no progress"
"$LAMINA" slice "$M/thesis_cube_hole.ug" -w 0.001 -o "$TMP/plain.sls" 2>/dev/null
ok "$(cmp -s "$TMP/plain.sls" "$TMP/term.sls"; echo $?)" "... and the program is the same as without a terminal"

# ... cut to the terminal's width: a line that wrapped could not be
# redrawn with \r
COLS=40 start narrow env LAMINA_PROGRESS_INTERVAL=0 "$LAMINA" slice models/thesis_cube_hole.ug -w 0.01 -o narrow.sls
finish narrow
is "$(draws narrow 200)" 0 "a 40-column terminal: the counts do not fit ..."
is "$(grep -ac 'lamina: slicing thesis_cube_hole' "$TMP/narrow.raw")" 1 "... but the line is drawn"
is "$(printf '%s\n' "$RAW" | grep -a '^lamina: slicing' | awk 'length($0) > 39' | wc -l)" 0 \
    "... never longer than 39 characters"

# 2. standard error not a terminal: no line, in the log or the file
start pipe env LAMINA_PROGRESS_INTERVAL=0 sh -c '"$0" slice models/thesis_cube_hole.ug -w 0.001 -o pipe.sls 2>&1 | cat >pipe.err' "$LAMINA"
finish pipe
is "$STATUS" 0 "through a pipe: the slice succeeds"
is "$(draws pipe 2000)" 0 "... and no progress line on the terminal"
is "$(grep -c 'of 2000' "$TMP/pipe.err")" 0 "... nor in the pipe"

# 3. -q on the terminal: no line
start quiet env LAMINA_PROGRESS_INTERVAL=0 "$LAMINA" slice models/thesis_cube_hole.ug -w 0.001 -o quiet.sls -q
finish quiet
is "$STATUS" 0 "-q: the slice succeeds"
is "$(draws quiet 2000)" 0 "-q: no progress line on a terminal"

# ... nor when the data goes to standard output on the terminal: the line
# would land in the middle of it
start tout env LAMINA_PROGRESS_INTERVAL=0 "$LAMINA" slice models/thesis_cube_hole.ug -w 0.01
finish tout
is "$STATUS" 0 "the program to the terminal: the slice succeeds"
like "$SCREEN" '^contour 1\.995000$' "... the program is on the screen"
is "$(draws tout 200)" 0 "... and no progress line in it"
start vjson env LAMINA_PROGRESS_INTERVAL=0 "$LAMINA" validate models/thesis_cube_hole.ug -w 0.01 --json
finish vjson
is "$(draws vjson 200)" 0 "validate --json to the terminal: no progress line"

# 4. redraws throttled by the monotonic clock: at most one per interval
# after the first (which waits one interval too), however fast the layers
# come; ELAPSED is at least the run's own time
start slow env LAMINA_PROGRESS_INTERVAL=0.05 "$LAMINA" slice models/thesis_cube_hole.ug -w 0.0001 -o slow.sls
finish slow
n=$(draws slow 20000)
is "$STATUS" 0 "interval 0.05: the slice of 20000 layers succeeds"
ok "$(echo "$n <= $ELAPSED / 0.05 + 1" | bc | grep -qx 1; echo $?)" \
    "... redrawn $n times in $ELAPSED s: at most one per 0.05 s"
start dflt "$LAMINA" slice models/thesis_cube_hole.ug -w 0.0001 -o dflt.sls
finish dflt
n=$(draws dflt 20000)
ok "$(echo "$n <= ($ELAPSED - 0.5) / 0.2 + 1 || $n == 0" | bc | grep -qx 1; echo $?)" \
    "default: redrawn $n times in $ELAPSED s: none in the first 0.5 s, then at most five a second"

# 5. validate: the per-layer report lines on standard output (the same
# terminal) are never mixed with the progress line
start val env LAMINA_PROGRESS_INTERVAL=0 "$LAMINA" validate models/thesis_cube_hole.ug -w 0.01
finish val
is "$STATUS" 0 "validate on a terminal succeeds"
like "$RAW" '^lamina: validating thesis_cube_hole\.ug: layer 200 of 200 \(100%\)' "... with its progress line"
is "$(printf '%s\n' "$SCREEN" | grep -Ec '^layer [0-9]+ \(h=[0-9.]+\): 2 contours, 2 confirmed, 0 disagreeing$')" 200 \
    "... all 200 report lines on the screen whole, no progress text on them"
like "$SCREEN" '^layer 200 \(h=1\.995\): 2 contours, 2 confirmed, 0 disagreeing$' "... the last layer is layer 200 (1-based), at h=1.995"
ok "$(printf '%s\n' "$SCREEN" | grep -q ' of 200 '; [ $? = 1 ]; echo $?)" "... and no progress left on the screen"
start valq env LAMINA_PROGRESS_INTERVAL=0 "$LAMINA" validate models/thesis_cube_hole.ug -w 0.01 -q
finish valq
is "$(draws valq 200)" 0 "validate -q: no progress line"
like "$SCREEN" '^models/thesis_cube_hole\.ug: 200 layers, 400 contours checked, 400 confirmed, 0 disagreeing' "... the summary"
ok "$(printf '%s\n' "$SCREEN" | grep -q '^layer '; [ $? = 1 ]; echo $?)" "... and no per-layer lines (nothing disagrees)"

# 6. -v: the stages and the layers' time, after the line is erased
start verb "$LAMINA" slice models/thesis_cube_hole.ug -w 0.01 -o verb.sls -v
finish verb
like "$SCREEN" '^lamina: reading the model and preparing the layers: [0-9]+\.[0-9]{3} s$' "-v: the time of the first stage"
like "$SCREEN" '^lamina: slicing thesis_cube_hole\.ug: 200 layers in [0-9]+\.[0-9]{3} s( \([0-9.e+]+ layers/s\))?$' \
    "-v: the layers and their time"
like "$SCREEN" '^lamina: writing the outputs: [0-9]+\.[0-9]{3} s$' "-v: the time of writing"

# 7. a message during the run starts on a line of its own: an outline
# left open in every layer is reported while the line is drawn
python3 - "$TMP/open.stl" <<'PY'
import sys
# a square tube without its top and bottom, one side missing: every layer
# cuts an open outline of three sides
q = [((0,0,0),(2,0,0),(2,0,2),(0,0,2)), ((2,0,0),(2,2,0),(2,2,2),(2,0,2)), ((2,2,0),(0,2,0),(0,2,2),(2,2,2))]
with open(sys.argv[1], "w") as f:
    f.write("solid t\n")
    for a, b, c, d in q:
        for t in ((a, b, c), (a, c, d)):
            f.write("facet normal 0 0 0\nouter loop\n" + "".join("vertex %g %g %g\n" % p for p in t) + "endloop\nendfacet\n")
    f.write("endsolid t\n")
PY
start open env LAMINA_PROGRESS_INTERVAL=0 "$LAMINA" slice open.stl -w 0.1 -o open.sls --allow-open --no-repair
finish open
is "$STATUS" 0 "open outlines with --allow-open: succeeds"
is "$(printf '%s\n' "$SCREEN" | grep -c 'could not be closed')" 20 "... the first 20 open outlines reported"
is "$(printf '%s\n' "$SCREEN" | grep -Ec '^lamina: open\.stl: layer [0-9]+ \(h=[0-9.]+\): open outline from \([^)]*\) to \([^)]*\) could not be closed$')" 20 \
    "... each on a line of its own, no progress text before or after it"
like "$SCREEN" '^lamina: open\.stl: layer 1 \(h=0\.05\): open outline' "... the first is layer 1 (h=0.05)"
ok "$(printf '%s\n' "$SCREEN" | grep -q ' of 20 ('; [ $? = 1 ]; echo $?)" "... and no progress left on the screen"

done_testing
