#!/usr/bin/env bash
# The bash completion ($BUILD/completion/lamina, made with the man pages from
# the commands' --help), sourced into a bash and called as bash calls it:
# COMP_WORDS and COMP_CWORD set, _lamina, then COMPREPLY. Commands; each
# command's options exactly as its --help shows them (read here on their
# own); the choices of an option; machine names from the machine
# directories (a profile added through LAMINA_MACHINES shows up); profile
# keys; models by extension, recipes by .lua.
. "$(dirname "$0")/lib.sh"

C="$BUILD/completion/lamina"
[ -f "$C" ]; ok $? "make man wrote the completion"
bash -n "$C"; ok $? "it is valid bash"

W="$TMP/w"
mkdir -p "$W/sub" "$W/machines"
touch "$W/a.ug" "$W/b.STL" "$W/c.obj" "$W/d.txt" "$W/e.lua" "$W/sub/f.stl"
printf "name: my-mill\ninherits: creol-ladrp\n" >"$W/machines/my-mill.yaml"

# comp WORD...: the completions of the last word (sorted, one line)
comp() {
    (cd "$W" && bash -c '. "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _lamina
        printf "%s\n" "${COMPREPLY[@]}"' _ "$C" "$LAMINA" "$@") 2>&1 | grep . | sort | tr '\n' ' ' | sed 's/ $//'
}

cmds=$("$LAMINA" --help | sed -n 's/^  lamina \([a-z][a-z0-9-]*\) .*/\1/p' | sort | tr '\n' ' ' | sed 's/ $//')
is "$(comp "" | tr ' ' '\n' | grep -v '^-' | tr '\n' ' ' | sed 's/ $//')" "$cmds" "every command of lamina --help"
like "$(comp -)" '(^| )--version( |$)' "and the options before a command"
is "$(comp sl)" "slice" "a command from its start"

# each command's options: the usage lines' and the option table's (as man.t
# reads them), with the other spelling of each, and --help
pairs=$(for c in $cmds; do "$LAMINA" "$c" --help; done |
    perl -ne 'print "$1 $2\n" if /^\s+(-[A-Za-z0-9]),\s+(--[\w-]+)/; print "$1 $2\n" while /(?<![\w-])(-[A-Za-z0-9])\/(--[\w-]+)/g' | sort -u)
for c in $cmds; do
    want=$("$LAMINA" "$c" --help | perl -ne '
        BEGIN { $syn = 1 }
        if ($. > 1 && $syn && !/^ {4,}[^ -]/) { $syn = 0 }
        if ($syn) { print "$1\n" while /(?<![\w-])(--?[A-Za-z][\w-]*)/g; next }
        if (/^\s+(-[A-Za-z0-9]),\s+(--[\w-]+)/) { print "$1\n$2\n"; next }
        print "$1\n" if /^\s+(--?[A-Za-z][\w-]*)/')
    want=$( (echo --help; for o in $want; do echo "$o"
        printf '%s\n' "$pairs" | awk -v o="$o" '$1 == o { print $2 } $2 == o { print $1 }'; done) |
        sort -u | tr '\n' ' ' | sed 's/ $//')
    is "$(comp "$c" -)" "$want" "lamina $c -<Tab>: its options"
done

is "$(comp slice --cut "")" "ceiling floor middle" "--cut: its choices"
is "$(comp slice --cut = m)" "middle" "--cut=m (= a word of its own, bash's default)"
is "$(comp slice --cut=m)" "--cut=middle" "--cut=m (one word)"
is "$(comp slice -a "")" "x y z" "-a: the axes"
is "$(comp slice --fill n)" "nonzero" "--fill: its choices"
machines=$("$LAMINA" machines | awk '{print $1}' | sort | tr '\n' ' ' | sed 's/ $//')
[ -n "$machines" ]; ok $? "lamina machines lists profiles"
is "$(comp slice -m "")" "$machines" "-m: the machine names"
is "$(comp check --machine "")" "$machines" "--machine: the same"
is "$(LAMINA_MACHINES="$W/machines" comp slice -m my)" "my-mill" "a profile of LAMINA_MACHINES"
is "$(comp machines --show cli-)" "$(printf '%s\n' $machines | grep '^cli-' | tr '\n' ' ' | sed 's/ $//')" \
    "--show: machine names"
is "$(comp slice -s bead)" "bead_width=" "-s: profile keys"
is "$(comp slice "")" "a.ug b.STL c.obj machines sub" "a model: .ug .stl .obj files and directories"
is "$(comp info sub/)" "sub/f.stl" "in a directory"
is "$(comp run "")" "e.lua machines sub" "a recipe: .lua files"
is "$(comp slice a.ug -o "")" "a.ug b.STL c.obj d.txt e.lua machines sub" "-o: any file"
is "$(comp -e "")" "" "-e CODE: nothing to offer"
is "$(comp repl "")" "" "repl takes no argument"

done_testing
