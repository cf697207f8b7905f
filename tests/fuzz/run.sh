#!/usr/bin/env bash
# make fuzz: every target its full time, whatever the others find.
#   run.sh FUZZER OUT SECONDS TARGET...
# FUZZER is the libFuzzer build of fuzz_inputs.c; OUT (build-fuzz) holds
# models/ (the copy of tests/models each run starts in: recipes write
# there), corpus/TARGET (the working corpus, seeded from
# tests/fuzz/corpus/TARGET) and gets artifacts/TARGET/ (what libFuzzer
# writes: crash-, leak-, timeout-, oom-, slow-unit- files) and
# TARGET.log. A target runs for SECONDS of wall time: libFuzzer stops at
# its first finding, so it is started again for the time left, until the
# time is spent. A run that fails before it has read its whole corpus
# (an input kept from an earlier run, or a seed, fails at once) has that
# input taken out of the working corpus first; when there is none to take
# out, the target stops there. At the end, a line per target (also in
# OUT/summary.txt): executions, starts, what it found this time; exit 1
# when any target found something.
# UBSan reports stop a run (halt_on_error) so that they count as findings.
set -u
fuzzer=$1 out=$2 secs=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
summary=() failed=0
for t in "$@"; do
    corpus=$out/corpus/$t art=$out/artifacts/$t log=$out/$t.log
    mkdir -p "$corpus" "$art"
    cp "$here/corpus/$t"/* "$corpus"/
    stamp=$out/.stamp-$t run=$out/.run-$t
    : >"$stamp"
    : >"$log"
    end=$(($(date +%s) + secs)) execs=0 starts=0 note=
    while :; do
        left=$((end - $(date +%s)))
        [ "$left" -gt 0 ] || break
        starts=$((starts + 1))
        held=$(find "$corpus" -type f | wc -l)
        : >"$run"
        (cd "$out/models" && "$fuzzer" -max_total_time="$left" -timeout=20 -rss_limit_mb=2048 -max_len=65536 \
            -print_final_stats=1 -artifact_prefix="$art/" "$corpus") >"$log.run" 2>&1
        rc=$?
        cat "$log.run" >>"$log"
        # executions: the final statistics, else the last status line
        n=$(sed -n 's/^stat::number_of_executed_units: *\([0-9]*\).*/\1/p' "$log.run" | tail -n 1)
        [ -n "$n" ] || n=$(sed -n 's/^#\([0-9]*\).*/\1/p' "$log.run" | tail -n 1)
        execs=$((execs + ${n:-0}))
        [ "$rc" -eq 0 ] && break
        if [ "${n:-0}" -le "$held" ]; then
            taken=0
            while IFS= read -r -d '' a; do
                for f in "$corpus"/*; do cmp -s "$a" "$f" && rm -f -- "$f" && taken=$((taken + 1)); done
            done < <(find "$art" -type f -newer "$run" -print0)
            if [ "$taken" -eq 0 ]; then
                note=" (stopped: fails reading its corpus)"
                break
            fi
        fi
    done
    rm -f "$log.run" "$run"
    if [ "$execs" -eq 0 ]; then
        failed=1
        note="$note (nothing ran: see the log)"
    fi
    found=$(find "$art" -type f -newer "$stamp" \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' \
        -o -name 'oom-*' \) | sort)
    slow=$(find "$art" -type f -newer "$stamp" -name 'slow-unit-*' | wc -l)
    nfound=$(printf '%s' "$found" | grep -c . || true)
    [ "$nfound" -eq 0 ] || failed=1
    line=$(printf '%-9s %12d executions in %ds, %d start%s, %d finding%s%s' "$t" "$execs" "$secs" "$starts" \
        "$([ "$starts" -eq 1 ] || echo s)" "$nfound" "$([ "$nfound" -eq 1 ] || echo s)" "$note")
    [ "$slow" -eq 0 ] || line="$line, $slow slow unit$([ "$slow" -eq 1 ] || echo s)"
    summary+=("$line")
    # what the sanitizers said, once each with its count; the first inputs
    while IFS= read -r f; do [ -n "$f" ] && summary+=("    $f"); done < <(grep -h '^SUMMARY: ' "$log" | sort | uniq -c)
    while IFS= read -r f; do [ -n "$f" ] && summary+=("    $f"); done < <(printf '%s\n' "$found" | head -n 5)
    [ "$nfound" -le 5 ] || summary+=("    ... and $((nfound - 5)) more in $art")
    echo "fuzz: $line (log: $log)"
done
{
    echo "fuzz: summary ($(date -u '+%Y-%m-%d %H:%M UTC'), ${secs}s a target)"
    printf '  %s\n' "${summary[@]}"
} | tee "$out/summary.txt"
[ "$failed" -eq 0 ] || echo "fuzz: something was found: reproduce with (cd $out/models && $fuzzer ARTIFACT)"
exit "$failed"
