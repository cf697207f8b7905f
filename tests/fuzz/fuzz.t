#!/usr/bin/env bash
# Every reader (models, profiles, programs read back) against mutants of every seed input (see fuzz_inputs.c).
: "${BUILD:?}" "${TESTS:?}"
seeds=$(ls "$TESTS"/models/*.ug "$TESTS"/models/*.stl "$TESTS"/models/*.obj "$TESTS"/models/ug/*.ug \
           "$TESTS"/models/machines/*.yaml "$TESTS"/../machines/*.yaml "$TESTS"/models/validate/*.sls \
           "$TESTS"/models/validate/*.cli 2>/dev/null)
cd "$TESTS/models" && exec "$BUILD/tests/fuzz_inputs" $seeds
