"""The same output for every thread count, beyond the one and two threads of the C++ tests (a
machine with more cores runs more threads than the two of the test machine): both filters in
their main modes, and vtkLODGeomorph between two of a hierarchy's levels, on a wavelet
isosurface (about 60,000 triangles in several pieces, some open, enough for many cells and rounds
of the partitioned greedy schedule) with the Sequential backend, with TBB on 2, 3 and 5 threads
and with STDThread on 2 (it runs at most as many threads as there are cores). Each configuration
runs in a process of its own (the backend's thread count is set once per process) and reports a
digest of every level's points, triangles and point-data arrays. A backend that the VTK build
lacks is left out, with a note; at least one threaded configuration must run.

    TestThreadCounts.py                     (runs every configuration and compares)
    TestThreadCounts.py --run BACKEND N     (one configuration: prints its digests)
"""

import hashlib
import json
import subprocess
import sys

from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource

import meshlod
from meshlod_testing import check, finish

# (backend, threads); the first is the reference.
CONFIGURATIONS = [("Sequential", 1), ("TBB", 2), ("TBB", 3), ("TBB", 5), ("STDThread", 2)]


def wavelet_isosurface():
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-30, 30, -30, 30, -30, 30)
    contour = vtkFlyingEdges3D()
    contour.SetInputConnection(source.GetOutputPort())
    contour.SetValue(0, 160.0)
    contour.ComputeNormalsOn()
    contour.ComputeScalarsOn()
    contour.Update()
    return contour.GetOutput()


def digest_of(meshes):
    """A digest of the meshes' point coordinates, triangles and point-data values, bit for bit."""
    h = hashlib.sha1()
    for mesh in meshes:
        h.update(bytes(memoryview(mesh.GetPoints().GetData())))
        h.update(bytes(memoryview(mesh.GetPolys().GetConnectivityArray())))
        data = mesh.GetPointData()
        for a in range(data.GetNumberOfArrays()):
            h.update(data.GetArrayName(a).encode())
            h.update(bytes(memoryview(data.GetArray(a))))
    return h.hexdigest()


def levels_of(hierarchy):
    return [hierarchy.GetBlock(b) for b in range(hierarchy.GetNumberOfBlocks())]


def run_configuration():
    """Every mode's digest (and its level count) with this process's backend and threads."""
    surface = wavelet_isosurface()
    modes = {
        "triangle collapse": lambda f: None,
        "triangle collapse, flipped edges": lambda f: f.SetFlipEdges(True),
        "triangle collapse, curvature": lambda f: f.SetMethodToCurvature(),
        "triangle collapse, independent sets": lambda f: f.SetScheduleToIndependentSets(),
    }
    results = {}
    hierarchy = None
    for name, setup in modes.items():
        decimate = meshlod.vtkTriangleCollapseDecimation()
        decimate.SetInputData(surface)
        setup(decimate)
        decimate.Update()
        levels = levels_of(decimate.GetHierarchy())
        results[name] = [digest_of(levels), len(levels)]
        if hierarchy is None:
            hierarchy = decimate.GetHierarchy()
    for name, flip in (("octree", False), ("octree, flipped edges", True)):
        octree = meshlod.vtkVertexClusterOctree()
        octree.SetInputData(surface)
        octree.SetNumberOfLevels(5)
        octree.SetFlipEdges(flip)
        octree.Update()
        levels = levels_of(octree.GetHierarchy())
        results[name] = [digest_of(levels), len(levels)]
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputData(hierarchy)
    geomorph.SetLevelOfDetail(2.4)
    geomorph.Update()
    results["geomorph at 2.4"] = [digest_of([geomorph.GetOutput()]), 1]
    return results


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--run":
        if not vtkSMPTools.SetBackend(sys.argv[2]):
            print(json.dumps({"unavailable": sys.argv[2]}))
            return
        vtkSMPTools.Initialize(int(sys.argv[3]))
        print(json.dumps({"backend": vtkSMPTools.GetBackend(),
                          "threads": vtkSMPTools.GetEstimatedNumberOfThreads(),
                          "results": run_configuration()}))
        return
    runs = []
    for backend, threads in CONFIGURATIONS:
        done = subprocess.run([sys.executable, __file__, "--run", backend, str(threads)],
                              capture_output=True, text=True)
        check(done.returncode == 0, "%s, %d threads: exit code %d\n%s"
              % (backend, threads, done.returncode, done.stderr[-2000:]))
        if done.returncode != 0:
            continue
        run = json.loads(done.stdout.strip().splitlines()[-1])
        if "unavailable" in run:
            print("note: this VTK has no %s backend, left out" % backend)
            continue
        check(run["backend"] == backend and run["threads"] == threads,
              "%s, %d threads: ran with %s, %d threads"
              % (backend, threads, run["backend"], run["threads"]))
        runs.append((backend, threads, run["results"]))
    check(len(runs) >= 2 and runs[0][0] == "Sequential",
          "the one-thread run and at least one threaded run")
    if not runs:
        finish()
    reference = runs[0][2]
    for name, (digest, count) in reference.items():
        print("%-40s %d level(s), digest %s" % (name, count, digest[:12]))
        check(count > 1 or name.startswith("geomorph"), name + ": several levels")
        for backend, threads, results in runs[1:]:
            check(results[name] == reference[name],
                  "%s: %s with %d threads differs from one thread" % (name, backend, threads))
    finish()


if __name__ == "__main__":
    main()
