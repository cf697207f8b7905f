#!/usr/bin/env bash
# Every reader against mutants of every seed input (see fuzz_inputs.c).
: "${BUILD:?}" "${TESTS:?}"
seeds=$(ls "$TESTS"/models/*.ug "$TESTS"/models/*.stl "$TESTS"/models/*.obj "$TESTS"/models/ug/*.ug \
           "$TESTS"/models/machines/*.yaml "$TESTS"/../machines/*.yaml 2>/dev/null)
cd "$TESTS/models" && exec "$BUILD/tests/fuzz_inputs" $seeds
