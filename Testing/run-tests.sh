#!/bin/sh
# Builds MeshLOD (installing the Debian packages it needs if missing) and runs the whole test
# suite with CTest. Arguments are passed to ctest (e.g. -R Hierarchy, -V).
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${MESHLOD_BUILD_DIR:-"$repo/build"}
"$repo/.ci/bootstrap.sh"
ctest --test-dir "$build" --output-on-failure --parallel "${MESHLOD_JOBS:-$(nproc)}" "$@"
