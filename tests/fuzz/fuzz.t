#!/usr/bin/env bash
# Every reader, planner and the Lua API against mutants of every input of
# the fuzz corpus (tests/fuzz/corpus: models, profiles, recipes, programs,
# part files; see fuzz_inputs.c). Files a recipe writes land in a scratch
# copy of tests/models.
: "${BUILD:?}" "${TESTS:?}"
seeds=("$TESTS"/fuzz/corpus/*/*)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cp -r "$TESTS"/models/. "$scratch"/
cd "$scratch" && "$BUILD/tests/fuzz_inputs" "${seeds[@]}"
