#!/usr/bin/env bash
# The man pages (make man: $BUILD/man, generated from the commands' --help)
# against the executable: a page per command `lamina --help` lists, each
# page's OPTIONS exactly the options its command's --help shows (read here
# on their own: the usage lines and the option table's entries), the short
# and long spellings of one option together; the exit codes, environment and
# files sections; the generator reports no option without a text.
. "$(dirname "$0")/lib.sh"

ROOT=$(cd "$TESTS/.." && pwd)
MANDIR="$BUILD/man"

# help_opts TEXT: the options a help text shows -- every option on its usage
# lines (the first line and the indented lines right after it) and the
# names leading each option-table entry ("  -m, --machine ...", "  --safe ...")
help_opts() {
    printf '%s\n' "$1" | perl -ne '
        BEGIN { $syn = 1 }
        if ($. > 1 && $syn && !/^ {4,}[^ -]/) { $syn = 0 }
        if ($syn) { print "$1\n" while /(?<![\w-])(--?[A-Za-z][\w-]*)/g; next }
        if (/^\s+(-[A-Za-z0-9]),\s+(--[\w-]+)/) { print "$1\n$2\n"; next }
        print "$1\n" if /^\s+(--?[A-Za-z][\w-]*)/' | sort -u
}
# page_opts FILE: the options heading the entries of a page's OPTIONS section
page_opts() {
    perl -ne '
        $in = 1 if /^\.SH OPTIONS/; $in = 0 if /^\.SH (?!OPTIONS)/;
        if ($in && $tp) { s/\\-/-/g; print "$1\n" while /\\fB(--?[A-Za-z][\w-]*)\\fR/g }
        $tp = /^\.TP/' "$1" | sort -u
}

[ -f "$MANDIR/lamina.1" ]; ok $? "make man wrote lamina.1"
cmds=$("$LAMINA" --help | sed -n 's/^  lamina \([a-z][a-z0-9-]*\) .*/\1/p')
[ -n "$cmds" ]; ok $? "lamina --help lists commands"
is "$(cd "$MANDIR" && ls *.1 | sort | tr '\n' ' ')" \
    "$(for c in $cmds; do echo "lamina-$c.1"; done | sort | tr '\n' ' ')lamina.1 " "one page per command and lamina(1)"

# short/long pairs from every help ("-m, --machine" entries, "-s/--set" in prose)
pairs=$( (for c in $cmds; do "$LAMINA" "$c" --help; done) |
    perl -ne 'print "$1 $2\n" if /^\s+(-[A-Za-z0-9]),\s+(--[\w-]+)/; print "$1 $2\n" while /(?<![\w-])(-[A-Za-z0-9])\/(--[\w-]+)/g' | sort -u)
# with_pairs: a list of options and the other spelling of each
with_pairs() {
    local o
    for o in $1; do
        echo "$o"
        printf '%s\n' "$pairs" | awk -v o="$o" '$1 == o { print $2 } $2 == o { print $1 }'
    done | sort -u
}

top=$("$LAMINA" --help | grep '^  lamina -' | sed 's/^  lamina //' | tr '\n' ' ')
is "$(page_opts "$MANDIR/lamina.1" | tr '\n' ' ')" "$(help_opts "usage: $top" | tr '\n' ' ')" \
    "lamina(1): the options of lamina --help"
for c in $cmds; do
    h=$("$LAMINA" "$c" --help)
    want=$(help_opts "$h")
    got=$(page_opts "$MANDIR/lamina-$c.1")
    missing=$(comm -23 <(printf '%s\n' "$want") <(printf '%s\n' "$got") | grep . | tr '\n' ' ')
    extra=$(comm -13 <(with_pairs "$want") <(printf '%s\n' "$got") | grep . | tr '\n' ' ')
    is "$missing" "" "lamina-$c(1) has every option of 'lamina $c --help'"
    is "$extra" "" "lamina-$c(1) has no option that 'lamina $c --help' lacks"
    p=$(cat "$MANDIR/lamina-$c.1")
    like "$p" '^\.SH "EXIT STATUS"\n(.*\n)*\.B 2\n' "lamina-$c(1): exit status"
    like "$p" '^\.B LAMINA_MACHINES$' "lamina-$c(1): LAMINA_MACHINES"
    like "$p" '^\.B LAMINA_PLUGINS$' "lamina-$c(1): LAMINA_PLUGINS"
    like "$p" '^\.SH FILES$' "lamina-$c(1): files"
    like "$p" '^\.SH EXAMPLES$' "lamina-$c(1): examples"
done

# an environment variable is documented when the program reads it
for v in LAMINA_THREADS LAMINA_MAX_INPUT LAMINA_HISTORY; do
    if grep -q "$v" "$LAMINA"; then
        like "$(cat "$MANDIR/lamina.1")" "^\\.B $v\$" "lamina(1) documents $v (lamina reads it)"
    else
        unlike=$(grep -c "^\.B $v\$" "$MANDIR/lamina.1")
        is "$unlike" 0 "lamina(1) leaves out $v (lamina does not read it)"
    fi
done

# the generator itself: no option without a text, no stale text in man/*.in
version=$("$LAMINA" --version | sed 's/^lamina //')
run python3 "$ROOT/man/genman.py" --lamina "$LAMINA" --in "$ROOT/man" --out "$TMP/man" \
    --version "$version" --binary "$LAMINA" --binary "$BUILD/lamina.so"
is "$RC" 0 "genman.py runs"
is "$ERR" "" "genman.py: every option has a text, every hand-written option text an option"
# the pages do not depend on where or when they were built: same input, same bytes
for f in "$MANDIR"/*.1; do
    cmp -s "$f" "$TMP/man/$(basename "$f")"
    ok $? "$(basename "$f"): the same page again"
done

# a hand-written option text for an option --help does not list is reported
mkdir -p "$TMP/in"
cp "$ROOT"/man/*.in "$TMP/in/"
printf '.\\"@option --no-such-option\nText.\n' >>"$TMP/in/lamina-info.1.in"
run python3 "$ROOT/man/genman.py" --lamina "$LAMINA" --in "$TMP/in" --out "$TMP/man2" --version x
like "$ERR" 'lamina-info\.1\.in describes --no-such-option' "a stale option text is reported"
run python3 "$ROOT/man/genman.py" --lamina "$LAMINA" --in "$ROOT/man" --out "$TMP/man3" --version x --expect "info"
is "$RC" 1 "a command list other than lamina --help's fails the build"
like "$ERR" 'lamina --help. lists the commands' "and says why"

# a lamina with one more command and more options (as later versions add
# them): its pages and completion follow from --help alone
cat >"$TMP/newer" <<EOS
#!/usr/bin/env bash
if [ "\$1" = --help ]; then
    "$LAMINA" --help | sed 's/^\(  lamina repl .*\)/  lamina join PART... -o PROGRAM      assemble parts of a split run\n\1/'
elif [ "\$1" = join ]; then
    printf 'usage: lamina join PART... -o PROGRAM [-q | -v]\nJoin the part files.\n  -o, --output     the program\n  -q, --quiet      no progress\n  -v, --verbose    more detail\n'
elif [ "\$1" = slice ]; then
    "$LAMINA" slice --help
    printf '  -j, --jobs N     threads (default: the online cores)\n      --layers A:B plan only layers A..B\n'
else
    exec "$LAMINA" "\$@"
fi
EOS
chmod +x "$TMP/newer"
printf 'print("LAMINA_THREADS")' >"$TMP/reads-threads"
run python3 "$ROOT/man/genman.py" --lamina "$TMP/newer" --in "$ROOT/man" --out "$TMP/newer-man" --version x \
    --binaries "$TMP/reads-threads" --completion-in "$ROOT/completion/lamina.bash.in" --completion-out "$TMP/newer-comp"
is "$RC" 0 "genman.py on a lamina with a new command"
is "$ERR" "" "without warnings"
[ -f "$TMP/newer-man/lamina-join.1" ]; ok $? "the new command has its page"
is "$(page_opts "$TMP/newer-man/lamina-join.1" | tr '\n' ' ')" "--output --quiet --verbose -o -q -v " "with its options"
like "$(cat "$TMP/newer-man/lamina-slice.1")" '^\\fB\\-j\\fR, \\fB\\-\\-jobs\\fR \\fIN\\fR$' "a new option in a page"
like "$(cat "$TMP/newer-man/lamina-slice.1")" '^\\fB\\-\\-layers\\fR \\fIA:B\\fR$' "with its argument A:B"
like "$(cat "$TMP/newer-man/lamina.1")" '^\.B LAMINA_THREADS$' "LAMINA_THREADS documented once a binary reads it"
like "$(cat "$TMP/newer-man/lamina.1")" '\\fBlamina join\\fR PART' "lamina(1) lists the new command"
like "$(cat "$TMP/newer-comp")" "\\[join\\]='-o --output -q --quiet -v --verbose'" "the completion offers its options"

done_testing
