#!/bin/sh
# Builds MeshLOD (installing the Debian packages it needs if missing) and runs the whole test
# suite with CTest. Arguments are passed to ctest (e.g. -R Hierarchy, -V).
# Each test is stopped after 10 minutes (the longest takes under a minute): a test that crashes
# can hang instead of exiting (VTK's crash handler deadlocks when the crash is inside malloc),
# and the default limit of 25 minutes per test would stall a CI run. A later --timeout wins.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${MESHLOD_BUILD_DIR:-"$repo/build"}
"$repo/.ci/bootstrap.sh"
ctest --test-dir "$build" --output-on-failure --parallel "${MESHLOD_JOBS:-$(nproc)}" \
  --timeout 600 "$@"
