#!/bin/sh
# Builds MeshLOD (installing the Debian packages it needs if missing) and runs the side-by-side
# benchmark; writes Benchmarks/RESULTS.md. Arguments are passed to MeshLODBenchmark (see the
# top of MeshLODBenchmark.cxx), e.g. --meshes gyroid:600000 --targets 0.1.
# Takes about ten minutes on two cores (more when other programs use them).
set -eu
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${MESHLOD_BUILD_DIR:-"$repo/build"}
"$repo/.ci/bootstrap.sh"

# Single-thread rows use the Sequential backend: with TBB, VTK 9.1 cannot be held to one thread.
VTK_SMP_BACKEND_IN_USE=Sequential "$build/bin/MeshLODBenchmark" \
  --output "$repo/Benchmarks/RESULTS.md" \
  --command "Benchmarks/run-benchmarks.sh${*:+ $*}" \
  "$@"
echo "Wrote $repo/Benchmarks/RESULTS.md"
