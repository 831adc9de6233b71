#!/bin/sh
# Shared first step of the README commands (Examples/run-demo.sh, Testing/run-tests.sh,
# Benchmarks/run-benchmarks.sh) and of CI:
#   1. install the Debian 12 packages the build, the tests and the demo need, only if some are
#      missing (a second run does not touch apt at all);
#   2. configure a Release build in <repository>/build with everything on (module, Python
#      wrapping, tests, demo, benchmark);
#   3. build it with all cores.
# Sourcing is not needed: run it, it exits non-zero on the first failure.
#
# Environment (all optional):
#   MESHLOD_BUILD_DIR  build directory (default: build/ in the repository)
#   MESHLOD_JOBS       parallel build jobs (default: number of cores)
#   MESHLOD_CMAKE_ARGS extra arguments for the configure step
set -eu

repo=$(cd "$(dirname "$0")/.." && pwd)
build=${MESHLOD_BUILD_DIR:-"$repo/build"}
jobs=${MESHLOD_JOBS:-$(nproc)}

# libvtk9-dev pulls in the GL, X11, TBB, MPI and Python development packages VTK's CMake
# package asks for. The rest: the Python side of VTK, the compiler and build tools, and for the
# demo's off-screen pictures an X server in memory (xvfb-run needs xauth) with Mesa's software
# OpenGL driver (libgl1-mesa-dri), which VTK's X-only rendering in Debian uses under Xvfb.
packages="libvtk9-dev libeigen3-dev python3-vtk9 cmake g++ make xvfb xauth libgl1-mesa-dri"

missing=""
for package in $packages; do
  status=$(dpkg-query -W -f='${db:Status-Abbrev}' "$package" 2>/dev/null || true)
  case "$status" in
    ii*) ;;
    *) missing="$missing $package" ;;
  esac
done

if [ -n "$missing" ]; then
  echo "-- Installing missing Debian packages:$missing"
  if [ "$(id -u)" -eq 0 ]; then
    sudo=""
  elif command -v sudo >/dev/null 2>&1; then
    sudo="sudo"
  else
    echo "error: missing packages:$missing; run as root or install them first" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update
  # shellcheck disable=SC2086 # word splitting of the package list is intended
  $sudo apt-get install -y --no-install-recommends $missing
else
  echo "-- Debian packages present"
fi

# Debian's VTK Python modules are built for /usr/bin/python3; another python3 earlier on PATH
# would be picked by CMake otherwise.
# shellcheck disable=SC2086 # MESHLOD_CMAKE_ARGS holds several arguments
cmake -S "$repo" -B "$build" \
  -DCMAKE_BUILD_TYPE=Release \
  -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DBUILD_TESTING=ON \
  -DMESHLOD_WRAP_PYTHON=ON \
  -DMESHLOD_BUILD_EXAMPLES=ON \
  -DMESHLOD_BUILD_BENCHMARKS=ON \
  ${MESHLOD_CMAKE_ARGS:-}
cmake --build "$build" --parallel "$jobs"
