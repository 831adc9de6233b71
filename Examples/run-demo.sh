#!/bin/sh
# Builds MeshLOD (installing the Debian packages it needs if missing) and runs the demo.
# Usage: Examples/run-demo.sh [output-directory] [demo options, see Examples/MeshLODDemo.cxx]
# The output directory defaults to demo-output/ in the repository.
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${MESHLOD_BUILD_DIR:-"$repo/build"}
"$repo/.ci/bootstrap.sh"

output="$repo/demo-output"
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then
  output=$1
  shift
fi
# Debian's VTK renders through X only: give the demo an X server in memory for its picture.
exec xvfb-run -a "$build/bin/MeshLODDemo" "$output" "$@"
