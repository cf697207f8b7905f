#!/usr/bin/env bash
# The Lua binding and the Lua command line: the Lua test scripts in
# tests/lua (through `lamina run`, and api.lua again through a stock lua5.4
# loading the C module lamina.so), `lamina run` and its arguments,
# `lamina -e`, `lamina repl` without a terminal, exit codes, Ctrl-C.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
BUILD=${BUILD:-$(dirname "$LAMINA")}
export TESTS

# Run a TAP-printing Lua test and pass its results on as ours.
lua_tap() { # lua_tap LABEL CMD...
    local label=$1; shift
    mkdir -p "$TMP/scratch"
    (cd "$TMP/scratch" && "$@") >"$TMP/tap" 2>"$TMP/tap.err"
    local rc=$? plan=0
    while IFS= read -r line; do
        case "$line" in
            "ok "*) ok 0 "$label: ${line#* - }" ;;
            "not ok "*) ok 1 "$label: ${line#* - }" ;;
            "#"*) echo "$line" ;;
            1..*) plan=${line#1..} ;;
        esac
    done <"$TMP/tap"
    ok $([ "$rc" -eq 0 ] && [ "$plan" -gt 0 ] && echo 0 || echo 1) "$label: ran to the end (exit $rc, $plan tests)"
    [ "$rc" -eq 0 ] || sed 's/^/#   /' "$TMP/tap.err" | head -20
    rm -rf "$TMP/scratch"
}

for t in "$TESTS"/lua/*.lua; do
    name=$(basename "$t" .lua)
    [ "$name" = tap ] && continue
    lua_tap "$name.lua" "$LAMINA" run "$t"
done

# The same API through a stock lua5.4 and package.cpath (the C module).
if command -v lua5.4 >/dev/null && [ -f "$BUILD/lamina.so" ]; then
    preload=""
    if ldd "$BUILD/lamina.so" 2>/dev/null | grep -q libasan; then
        # a sanitizer build: the ASan runtime must come first in a plain lua5.4
        preload="$(cc -print-file-name=libasan.so):$(cc -print-file-name=libubsan.so)"
    fi
    LD_PRELOAD=$preload ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} \
    LAMINA_MACHINES="$ROOT/machines" LAMINA_PLUGINS="$BUILD/plugins:$ROOT/plugins" \
    LUA_CPATH="$BUILD/?.so;;" lua_tap "lua5.4 + lamina.so" lua5.4 "$TESTS/lua/api.lua"
    run env LUA_CPATH="$BUILD/?.so;;" LD_PRELOAD=$preload lua5.4 -e \
        'package.cpath = os.getenv("LUA_CPATH"); local l = require "lamina"; print(l.version, package.loaded.lamina == l)'
    like "$OUT" '^[0-9]+\.[0-9]+\.[0-9]+	true$' 'lua5.4: require "lamina" via package.cpath'
else
    echo "# skipped: lua5.4 or $BUILD/lamina.so missing"
fi

# ---- lamina run ----------------------------------------------------------
cat >"$TMP/args.lua" <<'EOF'
local n = select("#", ...)
print(arg[0], #arg, arg[1], arg[2], n, (...))
print(arg[-1], arg[-2])
EOF
run "$LAMINA" run "$TMP/args.lua" first "second arg"
is "$RC" 0 "run: exit 0"
is "$OUT" "$TMP/args.lua	2	first	second arg	2	first
run	lamina" "run: arguments in arg and ..."
run "$LAMINA" run - a b <"$TMP/args.lua"
is "$(head -1 <<<"$OUT")" "-	2	a	b	2	a" "run -: the recipe from standard input"

cat >"$TMP/recipe.lua" <<'EOF'
local m = assert(lamina.load(arg[1]))
local sls = assert(lamina.machine("sls-contours"))
assert(sls:plan(m:slice{width = 1, cut = "floor"}):write(arg[2]))
print(("%s: %d layers written"):format(m.path, #m:slice{width = 1}))
EOF
run "$LAMINA" run "$TMP/recipe.lua" "$M/thesis_cube_hole.ug" "$TMP/out.sls"
is "$RC" 0 "a recipe that writes a program"
is "$(grep -c '^contour' "$TMP/out.sls")" 4 "the program has the thesis's 4 contours"
run "$LAMINA" slice "$M/thesis_cube_hole.ug" -w 1 --cut floor
is "$(cat "$TMP/out.sls")" "$OUT" "the recipe's SLS program equals lamina slice's"

# machine:plan writes what `lamina slice -m MACHINE` writes
cat >"$TMP/plan.lua" <<'EOF'
local model, machine, axis, width = ...
local m, mc = assert(lamina.load(model)), assert(lamina.machine(machine))
io.write(mc:plan(m:slice{machine = mc, axis = axis, width = tonumber(width)}):text())
EOF
for case in "creol-ladrp z 2" "cli-ascii x 1" "sls-contours y 0.5"; do
    set -- $case
    "$LAMINA" slice "$M/frame_island.ug" -m "$1" -a "$2" -w "$3" >"$TMP/cli.out" 2>/dev/null
    "$LAMINA" run "$TMP/plan.lua" "$M/frame_island.ug" "$1" "$2" "$3" >"$TMP/lua.out"
    cmp -s "$TMP/cli.out" "$TMP/lua.out" && [ -s "$TMP/lua.out" ]
    ok $? "machine:plan = lamina slice -m $1 -a $2 -w $3"
done

echo 'local t = require "lamina"; assert(t == lamina); print(type(t.load))' >"$TMP/req.lua"
run "$LAMINA" run "$TMP/req.lua"
is "$OUT" "function" 'run: require "lamina" is the global'

run "$LAMINA" run "$TMP/nonexistent.lua"
is "$RC" 1 "run: missing recipe exits 1"
like "$ERR" '^lamina: cannot open .*nonexistent\.lua' "run: missing recipe message"
echo 'x = = 1' >"$TMP/syntax.lua"
run "$LAMINA" run "$TMP/syntax.lua"
is "$RC" 1 "run: syntax error exits 1"
like "$ERR" 'syntax\.lua:1:' "run: syntax error names file and line"
printf 'local function f()\n  lamina.load(nil)\nend\nf()\n' >"$TMP/err.lua"
run "$LAMINA" run "$TMP/err.lua"
is "$RC" 1 "run: a runtime error exits 1"
like "$ERR" "^lamina: .*err\.lua:2: bad argument #1 to 'load' \(string expected, got nil\)" "run: error message"
like "$ERR" 'stack traceback:' "run: with a traceback"
echo 'os.exit(3)' >"$TMP/exit3.lua"
run "$LAMINA" run "$TMP/exit3.lua"
is "$RC" 3 "run: os.exit(3) is the exit code"
echo 'error({})' >"$TMP/errobj.lua"
run "$LAMINA" run "$TMP/errobj.lua"
like "$ERR" 'error object is a table value' "run: a non-string error"
run "$LAMINA" run
is "$RC" 2 "run without a recipe: usage error"
run "$LAMINA" run --help
is "$RC" 0 "run --help"
like "$OUT" 'usage: lamina run \[--safe .*\n +\[-j N\] RECIPE\.lua \[ARGS\.\.\.\]' "run --help text"

# ---- lamina -e -------------------------------------------------------------
run "$LAMINA" -e "print(lamina.load('$M/thesis_cube_hole.ug').volume)"
is "$OUT" "6.0" "-e: code runs with lamina loaded"
run "$LAMINA" -e 'x = 21' -e 'print(x * 2)'
is "$OUT" "42" "-e twice"
run "$LAMINA" -e 'error("boom")'
is "$RC" 1 "-e: error exits 1"
like "$ERR" '^lamina: \(command line\):1: boom' "-e: error message"
run "$LAMINA" -e
is "$RC" 2 "-e without code: usage error"
run "$LAMINA" -e 'x=1' stray
is "$RC" 2 "-e with a stray argument: usage error"

# ---- lamina repl without a terminal --------------------------------------
run "$LAMINA" repl <<'EOF'
=1 + 1
m = lamina.load(os.getenv("TESTS") .. "/models/thesis_cube_hole.ug")
m.volume
for i = 1,
  2 do
  print("line", i)
end
#m:slice{width = 1}
lamina.load(nil)
return "after", "error"
local s = [[two
lines]] print(s)
EOF
is "$RC" 0 "repl from a pipe: exit 0"
is "$OUT" "2
6.0
line	1
line	2
2
after	error
two
lines" "repl: =expr, bare expressions, continued statements"
like "$ERR" "^stdin:1: bad argument #1 to 'load' \(string expected, got nil\)" "repl: errors go to stderr and it goes on"
run "$LAMINA" repl <<<'for i = 1, 2 do'
like "$ERR" "'end' expected.*near <eof>" "repl: an unfinished statement at end of input is reported"
run "$LAMINA" repl extra
is "$RC" 2 "repl with an argument: usage error"
run "$LAMINA" repl --help
like "$OUT" "usage: lamina repl" "repl --help"
run "$LAMINA" </dev/null
is "$RC" 2 "plain lamina without a terminal: usage error"

# ---- help ------------------------------------------------------------------
run "$LAMINA" --help
for c in info slice validate check machines run repl -e; do
    like "$OUT" "lamina $c" "--help lists '$c'"
done

# ---- Ctrl-C ----------------------------------------------------------------
# SIGINT interrupts a running recipe: in Lua code (the hook) and inside a
# long slice (the binding polls between layers): the error "interrupted"
# (raised again after a pcall that catches it: the recipe ends), then
# lamina ends by SIGINT as every command does (status 130).
interrupt() { # interrupt LABEL LUA-CODE
    printf '%s\n' "$2" >"$TMP/long.lua"
    : >"$TMP/out" # emptied here: the wait below must not see the last run's line
    # a background job of a script starts with SIGINT ignored (and an
    # ignored SIGINT stays ignored): perl gives it its default
    perl -e '$SIG{INT} = "DEFAULT"; exec @ARGV' "$LAMINA" run "$TMP/long.lua" >"$TMP/out" 2>"$TMP/err" &
    local pid=$! t=0
    # wait until it has started (it prints a line), then interrupt it
    while [ ! -s "$TMP/out" ] && kill -0 $pid 2>/dev/null && [ $t -lt 1200 ]; do sleep 0.1; t=$((t + 1)); done
    kill -INT $pid 2>/dev/null
    { wait $pid; } 2>/dev/null
    local rc=$?
    is "$rc" 130 "Ctrl-C: $1: ends by SIGINT (130)"
    like "$(cat "$TMP/err")" 'interrupted' "Ctrl-C: $1: 'interrupted'"
}
interrupt "Lua loop" 'print("go") io.stdout:flush() while true do end'
interrupt "slicing" 'local m = lamina.load(os.getenv("TESTS") .. "/models/thesis_cube.ug")
print("go") io.stdout:flush()
for i = 1, 1000000 do m:slice{width = 2e-5} end'
like "$(cat "$TMP/err")" "in method 'slice'" "Ctrl-C: the slice itself was interrupted"
# planning on worker threads: the calling thread stops them between
# layers, then raises the error
interrupt "planning on 4 threads" 'local m = lamina.load(os.getenv("TESTS") .. "/models/thesis_cube.ug")
local ladrp = lamina.machine("creol-ladrp")
local layers = m:slice{machine = ladrp, width = 0.01}
print("go") io.stdout:flush()
for i = 1, 1000000 do ladrp:plan(layers, {threads = 4, bead_width = 0.002}) end'
like "$(cat "$TMP/err")" "in method 'plan'" "Ctrl-C: the threaded plan itself was interrupted"
# a recipe that catches the error still ends, by SIGINT; so does lamina -e
interrupt "caught by pcall" 'print("go") io.stdout:flush()
local ok, e = pcall(function() while true do end end)
print("caught", e)'
is "$(cat "$TMP/out")" "go" "Ctrl-C: the recipe caught it and went on no further"

: >"$TMP/out"
perl -e '$SIG{INT} = "DEFAULT"; exec @ARGV' "$LAMINA" -e 'print("go") io.stdout:flush() while true do end' >"$TMP/out" 2>"$TMP/err" &
pid=$! t=0
while [ ! -s "$TMP/out" ] && kill -0 $pid 2>/dev/null && [ $t -lt 1200 ]; do sleep 0.1; t=$((t + 1)); done
kill -INT $pid 2>/dev/null
{ wait $pid; } 2>/dev/null
is "$?" 130 "Ctrl-C: lamina -e ends by SIGINT (130)"
# an ignored SIGINT (nohup) stays ignored: the recipe runs to its end
printf 'print("go") io.stdout:flush()\nwhile not io.open(arg[1]) do end\nprint("done")\n' >"$TMP/wait.lua"
: >"$TMP/out"
(trap '' INT; exec "$LAMINA" run "$TMP/wait.lua" "$TMP/flag") >"$TMP/out" 2>"$TMP/err" &
pid=$! t=0
while [ ! -s "$TMP/out" ] && kill -0 $pid 2>/dev/null && [ $t -lt 1200 ]; do sleep 0.1; t=$((t + 1)); done
kill -INT $pid 2>/dev/null
: >"$TMP/flag"
{ wait $pid; } 2>/dev/null
is "$? $(tail -n 1 "$TMP/out")" "0 done" "SIGINT ignored when lamina started: the recipe runs to its end"

done_testing
