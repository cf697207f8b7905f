#!/usr/bin/env bash
# The man pages' examples (man/*.in, .EX blocks) do what they say: every
# `lamina slice|check|info|machines|validate|join|repair` line runs (exit 0; 3 is
# check's "violations found") on stand-in parts, and in every slice example
# each profile value given (-s KEY=VALUE or an option short for one, as
# `lamina slice --help` lists them) changes the program: an example may not
# show an option that does nothing (issue 22: `-m cli-binary --angle 45`).
. "$(dirname "$0")/lib.sh"
ROOT=$(cd "$TESTS/.." && pwd)
cd "$TMP" || exit 1
cp "$M/thesis_cube_binary.stl" part.stl
cp "$M/thesis_cube.obj" part.obj
cp "$M/thesis_cube_hole.ug" part.ug
cp "$M/thesis_cube_hole.ug" thesis_cube_hole.ug

# the options of `lamina slice --help` that are short for --set
keyopts=" $("$LAMINA" slice --help | sed -n '/^Profile values/,$p' | grep '^  ' | grep -o -- '--[a-z-]*' | grep -v -- '--set' | tr '\n' ' ') -w "
[ "${#keyopts}" -gt 20 ]; ok $? "slice --help lists its profile options:$keyopts"

n=0
for page in "$ROOT"/man/*.in; do
    while IFS= read -r line; do
        # roff to text: \- is -, \(aq is '
        line=${line//\\-/-}
        case "$line" in
            "lamina slice "* | "lamina check "* | "lamina info "* | "lamina machines"* | "lamina validate "* | "lamina join "* | "lamina repair "*) ;;
            *) continue ;;
        esac
        case "$line" in *"|"* | *'$'* | *"\\"*) continue ;; esac
        read -r -a w <<<"$line"
        n=$((n + 1))
        "$LAMINA" "${w[@]:1}" >out.txt 2>err.txt
        rc=$?
        want=0
        [ "${w[1]}" = check ] && [ "$rc" = 3 ] && want=3
        is "$rc" "$want" "$(basename "$page"): '$line' runs$( [ "$rc" = "$want" ] || printf ' (%s)' "$(head -1 err.txt)")"
        [ "${w[1]}" = slice ] || continue
        # each profile value of a slice example changes the program
        out=""
        for ((i = 2; i < ${#w[@]}; i++)); do [ "${w[i]}" = -o ] && out=${w[i + 1]}; done
        [ -n "$out" ] || continue
        for ((i = 2; i < ${#w[@]}; i++)); do
            o=${w[i]}
            [ "$o" = -s ] || [ "$o" = --set ] || [[ "$keyopts" == *" $o "* ]] || continue
            # drop the option and its value (a flag such as --islands has none)
            drop=2
            [[ "$o" == --* ]] && "$LAMINA" slice --help | grep -q -- "^ *$o  " && drop=1
            rest=("${w[@]:1:i-1}" "${w[@]:i+drop}")
            for ((j = 0; j < ${#rest[@]}; j++)); do [ "${rest[j]}" = "$out" ] && rest[j]="without.$out"; done
            "$LAMINA" "${rest[@]}" >/dev/null 2>&1
            ! cmp -s "$out" "without.$out"
            ok $? "$(basename "$page"): '${w[*]:i:drop}' changes the program of '$line'"
        done
    done < <(awk '/^\.EX/ { e = 1; next } /^\.EE/ { e = 0 } e' "$page")
done
[ "$n" -ge 10 ]; ok $? "the pages show at least 10 such examples ($n)"

done_testing
