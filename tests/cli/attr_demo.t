#!/usr/bin/env bash
# Adding one attribute to every vector touches three files outside tests
# (issue 23): tests/shape/attr_demo.sh builds a copy of the source with a
# test-only attribute and finds it in the JSON, the viewer's data, Lua's
# plan data and part files.
: "${LAMINA:?}" "${TESTS:?}"
exec bash "$TESTS/shape/attr_demo.sh" "$TESTS/.." "$LAMINA"
