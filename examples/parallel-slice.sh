#!/usr/bin/env bash
# parallel-slice.sh: slice one job in N parts at once with GNU parallel, on
# this machine or on many (its --sshlogin mode), and join the parts into
# the program the whole run writes (byte for byte the same).
#
# usage: parallel-slice.sh [-n PARTS] [-j JOBS] [-S LOGINS] MODEL PROGRAM [SLICE OPTIONS...]
#   -n PARTS   parts to cut the run into (default: 4; at most the run's layers)
#   -j JOBS    parts run at once on each host (default: GNU parallel's, one
#              per core)
#   -S LOGINS  run the parts on these hosts, GNU parallel's --sshlogin list
#              ("host1,4/user@host2,:"; ':' is this machine). The model is
#              copied to each host (--transferfile), each part copied back
#              (--return) and the remote copies removed (--cleanup). lamina
#              must be installed there (LAMINA names it, same path
#              everywhere), and -m must name a profile the hosts have (a
#              shipped name, or a file at the same path); ssh must log in
#              without a password (ssh-agent or keys).
#   SLICE OPTIONS are lamina slice's (-m MACHINE, -w WIDTH, -s KEY=VALUE ...);
#   not -o, --svg, --json or --layers (the script sets --layers and -o).
# Environment: LAMINA (default: lamina on PATH).
# A part that fails stops the others (--halt now,fail=1); nothing is
# written then, and the parts are removed either way.
#
# Example: parallel-slice.sh -n 8 -S server1,server2,: part.stl part.cli -m lpbf-cli
set -euo pipefail
LAMINA=${LAMINA:-lamina}
parts=4 jobs="" logins=""
usage() { sed -n 's/^# \{0,1\}//; 5,6p' "$0" >&2; exit 2; }
while getopts "n:j:S:h" o; do
    case $o in
    n) parts=$OPTARG ;;
    j) jobs=$OPTARG ;;
    S) logins=$OPTARG ;;
    *) usage ;;
    esac
done
shift $((OPTIND - 1))
[ $# -ge 2 ] || usage
model=$1 program=$2
shift 2
case $parts in '' | *[!0-9]* | 0) echo "parallel-slice.sh: -n takes a number of parts >= 1" >&2; exit 2 ;; esac
[ -r "$model" ] || { echo "parallel-slice.sh: cannot read the model $model" >&2; exit 1; }
command -v parallel >/dev/null || { echo "parallel-slice.sh: needs GNU parallel (Debian: apt install parallel)" >&2; exit 1; }

# the parts next to the program (same file system); removed at the end
work=$(mktemp -d "$(dirname -- "$program")/.lamina-parts.XXXXXX")
trap 'rm -rf "$work"' EXIT
opts=(--halt now,fail=1 -q)
[ -n "$jobs" ] && opts+=(-j "$jobs")
if [ -z "$logins" ]; then
    parallel "${opts[@]}" "$LAMINA" slice "$model" --layers "{}/$parts" -o "$work/part.{}" "$@" \
        ::: $(seq 1 "$parts")
else
    # Remote: from the work directory, with the model under its own name
    # (the program's part label comes from it): GNU parallel copies paths
    # relative to it into the login directory of each host (':', this
    # machine, runs in the work directory itself) and the parts back. The
    # parts are named after the work directory, so that two jobs on one
    # host do not meet.
    model_abs=$(cd "$(dirname -- "$model")" && pwd)/$(basename -- "$model")
    name=$(basename -- "$model") tag=part-${work##*.}
    ln -s "$model_abs" "$work/$name"
    (cd "$work" && parallel "${opts[@]}" -S "$logins" --workdir . --transferfile "$name" \
        --return "$tag.{}" --cleanup "$LAMINA" slice "$name" --layers "{}/$parts" -o "$tag.{}" "$@" \
        ::: $(seq 1 "$parts"))
    rm "$work/$name"
fi
"$LAMINA" join "$work"/*.[0-9]* -o "$program"
