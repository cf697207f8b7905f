#!/usr/bin/env bash
# lamina repl on a real terminal: tmux runs it in a pseudo-terminal, the
# test types into it and reads the screen. Checks the banner, =expr and
# bare expressions, continued statements, line editing and history
# (readline), Ctrl-C interrupting a Lua loop and a long slice and
# abandoning a line, errors, Ctrl-D, and plain `lamina` on a terminal;
# help(x) (also checked through a pipe against lua/API.md itself), Tab
# completion, and a layer list's summary; table results printed as data
# (lamina.show: fields sorted, depth, length and size bounds, cycles) and
# errors that list the valid keys listing every one of them.
#
# Independent of the checkout's path and of line wrapping: every program
# runs in the test's own folder, where `models` is a link to the test
# models, so what it prints holds a short relative path whatever the
# checkout's path; the pane is 200 columns wide; and the screen is read
# with `capture-pane -J`, which joins lines the terminal wrapped, so a
# long line still matches as one. tests/cli/long_path.t runs this file
# from a checkout path of over 150 characters.
. "$(dirname "$0")/lib.sh"

if ! command -v tmux >/dev/null; then
    echo "1..0 # SKIP tmux is not installed"
    exit 0
fi

SOCK="lamina-repl-test-$$"
tm() { tmux -L "$SOCK" "$@"; }
trap 'tm kill-server 2>/dev/null; sleep 0.2; rm -rf "$TMP"' EXIT
mkdir -p "$TMP/home"
ln -s "$TESTS/models" "$TMP/models"

# start NAME CMD...: a 200x50 terminal running CMD in $TMP; the pane stays
# after exit, and CMD's exit status goes to $TMP/NAME.status (from the
# shell: tmux does not always reap a sanitizer build's exit in time to
# show it). Every word is quoted for the pane's shell (%q), so paths with
# spaces or shell characters pass through.
start() {
    local name=$1; shift
    local cmd
    cmd=$(printf '%q ' env HOME="$TMP/home" LAMINA_HISTORY="$TMP/history" "$@")
    tm -f /dev/null new-session -d -s "$name" -x 200 -y 50 -c "$TMP" \
        "$cmd; echo \$? >$(printf '%q' "$TMP/$name.status")" \; \
        set-option -t "$name" remain-on-exit on
}
# the screen and its scroll-back, wrapped lines joined (-J keeps trailing
# blanks, which are cut here: a fresh prompt "> " reads ">")
screen() { tm capture-pane -p -J -t "$1" -S -200 | sed 's/[[:space:]]*$//'; }
dead() { [ "$(tm display-message -p -t "$1" '#{pane_dead}')" = 1 ]; }
# wait_for NAME REGEX [SECONDS]: until the screen matches; 0 if it did
# (gives up at once when the program has exited)
wait_for() {
    local t=0 limit=$(( ${3:-10} * 10 ))
    while [ $t -lt $limit ]; do
        screen "$1" | grep -Eq -- "$2" && return 0
        dead "$1" && return 1
        sleep 0.1
        t=$((t + 1))
    done
    return 1
}
# the last non-empty line of the screen
last_line() { screen "$1" | sed '/^[[:space:]]*$/d' | tail -1; }
prompt() { # prompt NAME: wait for a fresh "> " prompt
    local t=0
    while [ $t -lt 100 ]; do
        [ "$(last_line "$1")" = ">" ] && return 0
        dead "$1" && return 1
        sleep 0.1
        t=$((t + 1))
    done
    return 1
}
type_line() { tm send-keys -t "$1" -l "$2"; tm send-keys -t "$1" Enter; }
show_on_failure() { [ "$1" -eq 0 ] || screen "$2" | sed '/^[[:space:]]*$/d; s/^/#   | /' | tail -25; }

start r "$LAMINA" repl
wait_for r 'the lamina module is loaded' 20
rc=$?; ok $rc "banner"
if [ $rc -ne 0 ]; then # nothing else can work
    show_on_failure 1 r
    done_testing
    exit 1
fi
prompt r
ok $? "first prompt '> '"
editing=1
screen r | grep -q 'no line editing' && editing=0

type_line r '=1 + 1'
wait_for r '^2$'
ok $? "=expr prints its value"
prompt r
type_line r 'lamina.version'
wait_for r '^[0-9]+\.[0-9]+\.[0-9]+$'
ok $? "a bare expression prints its value"
prompt r

type_line r 'for i = 1, 3 do'
wait_for r '^>> $|^>>$'
ok $? "an unfinished statement continues at '>>'"
type_line r 'print("row", i * 10)'
type_line r 'end'
wait_for r '^row +30$'
rc=$?; ok $rc "the continued statement runs"; show_on_failure $rc r
prompt r

type_line r 'm = lamina.load("models/thesis_cube_hole.ug")'
prompt r
type_line r 'm'
wait_for r '^lamina\.model \(models/thesis_cube_hole\.ug: 24 triangles, 2 shells\)$'
ok $? "objects print through __tostring"
prompt r

type_line r 'lamina.load(nil)'
wait_for r "bad argument #1 to 'load' \(string expected, got nil\)"
ok $? "an error is shown"
prompt r
ok $? "and the prompt comes back"

# Ctrl-C: a Lua loop
# (each long statement prints a line first: the interrupt is sent once it runs)
type_line r 'print("spinning") while true do end'
wait_for r '^spinning$'
tm send-keys -t r C-c
wait_for r 'interrupted'
rc=$?; ok $rc "Ctrl-C interrupts a Lua loop"; show_on_failure $rc r
prompt r
ok $? "prompt after the interrupt"
tm send-keys -t r C-l 2>/dev/null; tm clear-history -t r

# Ctrl-C: a long slice (the binding stops between layers)
type_line r 'c = lamina.load("models/thesis_cube.ug")'
prompt r
type_line r 'print("slicing") for i = 1, 1000 do layers = c:slice{width = 2e-5} end'
wait_for r '^slicing$' 20
tm send-keys -t r C-c
wait_for r 'interrupted' 20
rc=$?; ok $rc "Ctrl-C interrupts a long slice"; show_on_failure $rc r
prompt r
type_line r '=2 * 21'
wait_for r '^42$'
ok $? "the session goes on after the interrupt"
prompt r

# Ctrl-C at the prompt abandons the line, and an unfinished statement
tm send-keys -t r -l 'abandoned_call('
tm send-keys -t r C-c
prompt r
rc=$?; ok $rc "Ctrl-C abandons the line being typed"; show_on_failure $rc r
type_line r 'x = {'
wait_for r '^>>'
tm send-keys -t r C-c
prompt r
ok $? "Ctrl-C abandons an unfinished statement"
type_line r '=x'
wait_for r '^nil$'
ok $? "the abandoned statement did not run"
prompt r

# help(x): the API.md entry of a function, found by identity
type_line r 'help(lamina.load)'
wait_for r '^lamina\.load\(path \[, options\]\) → model \| nil, message$' && wait_for r '^Load a model: Unigrafix'
rc=$?; ok $rc "help(lamina.load) prints its entry of lua/API.md"; show_on_failure $rc r
prompt r
type_line r 'help(m)'
wait_for r '^Methods \(help "name" for one\): model:bbox, .*model:slice'
rc=$?; ok $rc "help(object): the type's entry and its methods"; show_on_failure $rc r
prompt r
type_line r 'help(12)'
wait_for r '^help: no help for this number'
ok $? "help(value without docs) says so"
prompt r

# a list of layers prints as a summary: 2 units tall, 12 layers of 1/6
type_line r 'layers = m:slice{width = 1/6}'
prompt r
type_line r 'layers'
wait_for r '^12 layers of thesis_cube_hole\.ug, z 0 \.\. 2$'
rc=$?; ok $rc "a layer list prints as a summary"; show_on_failure $rc r
prompt r
type_line r '=#layers, layers[12].index'
wait_for r '^12[[:space:]]+12$'
ok $? "and is still a list"
prompt r

# a table result prints its fields (lua/API.md's plan.time example: one
# layer, 8 hatch lines of 2 at speed 2, contour 8 at speed 4, 5 s recoat)
type_line r 'p = lamina.machine("cli-ascii"):plan(c:slice{width = 2}, {hatch_strategy = "lines", hatch_distance = 0.25, hatch_angle = 0, speed = 2, ["contour.speed"] = 4, jump_speed = 10, jump_delay = 0.01, recoat_time = 5})'
prompt r
type_line r 'p.time'
wait_for r 'total = 15\.2675' && wait_for r 'vectors = 8' && ! screen r | grep -q 'table: 0x'
rc=$?; ok $rc "a table result (p.time) prints its fields on the terminal"; show_on_failure $rc r
prompt r

if [ $editing -eq 1 ]; then
    # Tab completes globals' fields, and methods of a userdata after ':'
    tm send-keys -t r -l 'lamina.lo'
    tm send-keys -t r Tab
    wait_for r '^> lamina\.load$'
    rc=$?; ok $rc "Tab completes lamina.lo to lamina.load"; show_on_failure $rc r
    tm send-keys -t r -l '("models/thesis_cube.ug").volume'
    tm send-keys -t r Enter
    wait_for r '^8\.0$'
    ok $? "the completed line runs"
    prompt r
    tm send-keys -t r -l 'm:sli'
    tm send-keys -t r Tab
    wait_for r '^> m:slice$'
    rc=$?; ok $rc "Tab completes a method of a userdata"; show_on_failure $rc r
    tm send-keys -t r C-u
    prompt r
    tm send-keys -t r -l 'lamina.m'
    tm send-keys -t r Tab Tab
    wait_for r 'lamina\.machine_keys +lamina\.machines +lamina\.mkdir'
    rc=$?; ok $rc "Tab Tab lists the choices"; show_on_failure $rc r
    tm send-keys -t r C-u
    prompt r
fi

if [ $editing -eq 1 ]; then
    # line editing: backspace, beginning of line
    tm send-keys -t r -l '=6*8'
    tm send-keys -t r BSpace
    tm send-keys -t r -l '7'
    tm send-keys -t r Enter
    wait_for r '^42$'
    ok $? "line editing: backspace"
    prompt r
    tm send-keys -t r -l '+1'
    tm send-keys -t r C-a
    tm send-keys -t r -l '=100'
    tm send-keys -t r Enter
    wait_for r '^101$'
    ok $? "line editing: Ctrl-A to the start of the line"
    prompt r
    # history: Up recalls the last statement
    tm send-keys -t r Up
    wait_for r '^> =100\+1$'
    ok $? "history: Up recalls the last line"
    tm send-keys -t r C-u
else
    echo "# no line editor found: skipping the editing and history checks"
fi

# Ctrl-D quits with exit code 0 and saves the history
tm send-keys -t r C-d
t=0
while [ ! -s "$TMP/r.status" ] && [ $t -lt 100 ]; do sleep 0.1; t=$((t + 1)); done
is "$(cat "$TMP/r.status" 2>/dev/null)" "0" "Ctrl-D quits, exit 0"
if [ $editing -eq 1 ]; then
    grep -qx '=100+1' "$TMP/history"
    ok $? "history file written"
    grep -q 'abandoned_call' "$TMP/history"
    ok $((! $?)) "abandoned lines are not in the history"
    # the history is there in the next session
    start h "$LAMINA" repl
    prompt h
    tm send-keys -t h Up
    wait_for h '^> =100\+1$'
    ok $? "history comes back in a new session"
    tm send-keys -t h C-u C-d
fi

# plain `lamina` on a terminal is the prompt
start p "$LAMINA"
wait_for p 'the lamina module is loaded' 20
ok $? "plain lamina on a terminal starts the prompt"
prompt p
type_line p '=#lamina.load("models/thesis_cube.ug")'
wait_for p '^12$'
ok $? "with lamina loaded"
prompt p
tm send-keys -t p C-d
t=0
while [ ! -s "$TMP/p.status" ] && [ $t -lt 100 ]; do sleep 0.1; t=$((t + 1)); done
is "$(cat "$TMP/p.status" 2>/dev/null)" "0" "plain lamina: Ctrl-D quits, exit 0"

# help() without a terminal (the loop reads a pipe): what it prints is
# API.md's entry, line for line (perl cuts the section out of the file here)
ROOT=$(cd "$TESTS/.." && pwd)
section() { # section HEADING-PREFIX: API.md from that heading to the next
    H="$1" perl -ne 'if (/^#/) { $in = index($_, $ENV{H}) == 0 } print if $in' "$ROOT/lua/API.md" |
        sed -e '1s/^#* //' -e '1s/`//g' | sed -e :a -e '/^\n*$/{$d;N;ba' -e '}'
}
printf 'help(lamina.load)\n' | (cd "$ROOT" && "$LAMINA" repl) >"$TMP/help.out" 2>&1
section '### `lamina.load(' >"$TMP/help.want"
diff "$TMP/help.want" "$TMP/help.out" >"$TMP/help.diff"
rc=$?; ok $rc "help(lamina.load) is API.md's entry, line for line"
[ $rc -eq 0 ] || sed 's/^/#   /' "$TMP/help.diff" | head -10
printf 'axes = require "lamina.axes"\nhelp(axes.measures)\n' | "$LAMINA" repl >"$TMP/help.out" 2>&1
section '### `axes.measures(' >"$TMP/help.want"
diff "$TMP/help.want" "$TMP/help.out" >/dev/null
ok $? "help(a function of a lamina Lua module) is its entry"
printf 'help(lamina.machine("creol-ladrp").plan)\n' | "$LAMINA" repl >"$TMP/help.out" 2>&1
like "$(head -1 "$TMP/help.out")" '^machine:plan\(layers \[, opts\]\) → plan \| nil, message$' "help(a method taken from an object)"
printf 'help "bbox"\nhelp "conventions"\nhelp "nothing_like_it"\nhelp()\n' | "$LAMINA" repl >"$TMP/help.out" 2>&1
like "$(cat "$TMP/help.out")" '^help: .bbox. is in model:bbox, layer:bbox, contour:bbox$' "help of a short name lists its entries"
like "$(cat "$TMP/help.out")" '^Conventions$' "help of a topic"
like "$(cat "$TMP/help.out")" "^help: no help for 'nothing_like_it'" "help of nothing known says so"
like "$(cat "$TMP/help.out")" '^  .*plan:layer' "help() lists the topics"

# ---- tables print as data (lamina.show), through a pipe ------------------
# Each case prints "== NAME" first; section NAME is what came after it.
cat >"$TMP/show.in" <<'EOF'
c = lamina.load("models/thesis_cube.ug")
p = lamina.machine("cli-ascii"):plan(c:slice{width = 2}, {hatch_strategy = "lines", hatch_distance = 0.25, hatch_angle = 0, speed = 2, ["contour.speed"] = 4, jump_speed = 10, jump_delay = 0.01, recoat_time = 5})
print("== time")
p.time
q = lamina.machine("cli-ascii"):plan(c:slice{width = 0.25}, {hatch_strategy = "lines", hatch_distance = 0.5, hatch_angle = 0, layer_angle_increment = 0, hatch_order = "unidirectional"})
print("== layer")
q:layer(5)
print("== nested")
{a = {b = {c = {d = 1}}}}
print("== long")
(function() local t = {} for i = 1, 100 do t[i] = i end return t end)()
print("== cycle")
t = {name = "loop"} t.self = t t.list = {t}
t
print("== huge")
h = {} for i = 1, 5000 do h["k" .. i] = {} for j = 1, 20 do h["k" .. i][j] = ("w"):rep(30) .. j end end
h
print("== huge_all")
#require("lamina.show").value(h, {lines = math.huge, bytes = math.huge}):gsub("[^\n]", "") + 1
print("== several")
=p.time.vectors, {1, 2}, "plain"
print("== named")
setmetatable({}, {__name = "thing"})
print("== end")
EOF
(cd "$TMP" && "$LAMINA" repl <"$TMP/show.in" >"$TMP/show.out" 2>"$TMP/show.err")
is "$?" 0 "the table cases run through a pipe"
[ -s "$TMP/show.err" ] && sed 's/^/#   err: /' "$TMP/show.err" | head -5
case_out() { awk -v want="== $1" '/^== /{on = ($0 == want); next} on' "$TMP/show.out"; }
# one line: the summary with its line breaks and indentation taken out
flat() { tr '\n' ' ' | tr -s ' ' | sed 's/{ /{/g; s/ }/}/g; s/ $//'; }

out=$(case_out time)
# the values of API.md's example: jumps 0.125 + 7 x 0.25 at 10/s plus 8 x 0.01 s
for kv in 'contours = 1' 'exposed = 24' 'exposure = 10' 'hatched = 16' 'jumped = 1.875' 'jumps = 0.2675' \
          'layers = {15.2675}' 'recoat = 5' 'total = 15.2675' 'vectors = 8'; do
    printf '%s' "$out" | grep -qF -- "$kv" || { echo "# p.time lacks '$kv'"; false; } || break
done
ok $? "p.time prints its fields and values"
keys=$(printf '%s' "$out" | grep -oE '[a-z_]+ =' | tr -d ' =' | tr '\n' ' ')
is "$keys" "contours exposed exposure hatched jumped jumps layers recoat total vectors " "p.time's keys are sorted"
like "$out" '\A\{' "p.time: a table's summary, not table: 0x..."

out=$(case_out layer | flat)
# layer 5 of 8 (2 tall, width 0.25): a 2 x 2 square, one contour of 4
# points (8 numbers and kind, depth, order: 11 entries) and 4 hatch lines
# 0.5 apart ({u0, v0, u1, v1, kind, order}: 6; the angle 0 on every
# layer), deposit 8 + 4 x 2
like "$out" 'index = 5[,}]' "p:layer(5) prints its index"
like "$out" 'deposit = 16[,}]' "and its deposit"
like "$out" 'contours = \{\{\.\.\.11\}\}' "its contours, deeper than two levels, as {...N}"
like "$out" 'vectors = \{\{\.\.\.6\}, \{\.\.\.6\}, \{\.\.\.6\}, \{\.\.\.6\}\}' "its vectors the same way"
is "$(case_out nested)" "{a = {b = {...1}}}" "a nested table is cut at depth 2, with the count"
is "$(case_out long | flat)" "{$(seq -s ', ' 1 20), ... (80 more)}" "a long array: 20 items and the count of the rest"
is "$(case_out cycle)" '{list = {<cycle>}, name = "loop", self = <cycle>}' "a cyclic table prints, cycles marked"
out=$(case_out huge)
n=$(printf '%s\n' "$out" | wc -l)
bytes=$(printf '%s\n' "$out" | wc -c)
[ "$n" -le 40 ] && [ "$bytes" -le 4096 ]
ok $? "a huge table prints at most 40 lines and 4 KB ($n lines, $bytes bytes)"
left=$(printf '%s\n' "$out" | tail -1 | sed -n 's/^\.\.\. (\([0-9]*\) more lines)$/\1/p')
all=$(case_out huge_all)
is "$((n - 1 + ${left:-0}))" "$all" "and its last line counts the lines left out"
like "$(printf '%s\n' "$out" | sed -n 2p)" '^  k1 = \{$' "the huge table's keys come sorted"
is "$(case_out several)" "8	{1, 2}	plain" "several results: a table as data, the others as print shows them"
like "$(case_out named)" '^thing: 0x' "a table with __name prints as tostring makes it"

# ---- errors that list the valid keys list all of them -------------------
# override's keys: those lamina.machine_keys() documents as not fixed and
# not loader-only, but lists (gas_flow, lasers), which override refuses
want=$("$LAMINA" -e 'for _, k in ipairs(lamina.machine_keys()) do
  if not k.fixed and not k.loader and k.type ~= "numbers" and k.type ~= "lasers" then print(k.lua) end end' | sort)
printf 'lamina.machine("cli-ascii"):override{speeeed = 1}\n' | "$LAMINA" repl >"$TMP/keys.out" 2>&1
msg=$(head -1 "$TMP/keys.out")
like "$msg" "options: [a-z_.]+(, [a-z_.]+)*\)\)$" "override's unknown-key error ends after its last key"
got=$(printf '%s' "$msg" | sed -n 's/.*options: \(.*\)))$/\1/p' | tr -d ' ' | tr ',' '\n' | sort)
is "$got" "$want" "and lists every key override takes, each whole ($(printf '%s\n' "$want" | wc -l) keys)"
# a profile's unknown key: the top-level keys of lamina machines --keys's
# table (its first table; a dotted key's section once) and the alias it names
want=$("$LAMINA" machines --keys | awk '/^$/ {exit} {print}' | sed -n 's/^| `\([^`]*\)`.*/\1/p' | sed 's/\..*//' |
       awk '!s[$0]++'; "$LAMINA" machines --keys | awk '/^$/ {exit} {print}' | sed -n 's/.*Also `\([a-z_]*\)`.*/\1/p')
printf 'name: x\nprocess: sls\nspot_width: 0.1\nnot_a_key: 1\n' >"$TMP/bad.yaml"
msg=$("$LAMINA" -e "print(select(2, lamina.machine('$TMP/bad.yaml')))" 2>&1)
got=$(printf '%s' "$msg" | sed -n 's/.*allowed: \(.*\))$/\1/p' | tr -d ' ' | tr ',' '\n' | sort)
is "$got" "$(printf '%s\n' "$want" | sort)" "a profile's unknown-key error lists every top-level key"

done_testing
