"""Both filters and vtkLODGeomorph on generated awkward input, the kinds real files hold: spheres
and a plane appended, then (each at random, fixed seeds) triangles fanned onto existing edges
(non-manifold edges), duplicated triangles (in some meshes reversed), degenerate and
collinear triangles, vertices merged into others anywhere on the mesh (bow ties), a large
offset, unused points and a point that triangles use made NaN (unused points are dropped).

Every level must keep finite points and the point array, lose triangles from level to level
(the octree may repeat a level, with a warning), have no degenerate or duplicate triangle (nor
two on the same points in opposite orders, which the octree keeps with PreserveTopology off
where a thin part folds flat, as documented) and valid MorphTargetId values, one per point;
level 0, the validated input, must be free of degenerate and duplicate triangles too, and a
simplified level must follow it. A NaN point must stop the filter with an empty hierarchy.
The geomorph must report no error, give finite points and never more triangles than level 0.

    TestAwkwardInput.py [seeds]   (meshes to try, default 100: a few seconds)
"""

import random
import sys

from vtkmodules.vtkCommonCore import (
    vtkCommand,
    vtkFloatArray,
    vtkLogger,
    vtkOutputWindow,
    vtkPoints,
    vtkStringOutputWindow,
)
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource

import meshlod
from meshlod_testing import check, finish, first_nonfinite_point, morph_target_ids



def triangles_of(mesh):
    ids = mesh.GetPolys().GetConnectivityArray()
    return [tuple(int(ids.GetValue(3 * t + k)) for k in range(3))
            for t in range(mesh.GetNumberOfPolys())]


def base_mesh(rnd):
    append = vtkAppendPolyData()
    for _ in range(rnd.randint(1, 3)):
        sphere = vtkSphereSource()
        sphere.SetRadius(rnd.uniform(0.1, 1.0))
        sphere.SetCenter(rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-1, 1))
        sphere.SetThetaResolution(rnd.randint(6, 30))
        sphere.SetPhiResolution(rnd.randint(6, 30))
        append.AddInputConnection(sphere.GetOutputPort())
    if rnd.random() < 0.5:
        plane = vtkPlaneSource()
        plane.SetResolution(rnd.randint(1, 20), rnd.randint(1, 20))
        append.AddInputConnection(plane.GetOutputPort())
    triangulate = vtkTriangleFilter()
    triangulate.SetInputConnection(append.GetOutputPort())
    triangulate.Update()
    mesh = triangulate.GetOutput()
    points = [list(mesh.GetPoint(p)) for p in range(mesh.GetNumberOfPoints())]
    return points, [list(t) for t in triangles_of(mesh)]


def awkward_mesh(seed):
    """The mesh of `seed` and whether it has a NaN point."""
    rnd = random.Random(seed)
    points, tris = base_mesh(rnd)
    if rnd.random() < 0.3:  # fins: a third triangle on existing edges
        for _ in range(rnd.randint(1, 10)):
            a, b, _c = tris[rnd.randrange(len(tris))]
            points.append([x + rnd.uniform(-0.2, 0.2) for x in points[a]])
            tris.append([a, b, len(points) - 1])
    if rnd.random() < 0.3:  # duplicates, some reversed
        copies = [list(tris[rnd.randrange(len(tris))]) for _ in range(rnd.randint(1, 10))]
        tris += [c[::-1] for c in copies] if rnd.random() < 0.5 else copies
    if rnd.random() < 0.3:  # degenerate triangles
        for _ in range(rnd.randint(1, 10)):
            a, b = rnd.randrange(len(points)), rnd.randrange(len(points))
            tris.append([a, a, b])
    if rnd.random() < 0.3:  # bow ties: a vertex merged into another
        for _ in range(rnd.randint(1, 3)):
            keep, gone = rnd.randrange(len(points)), rnd.randrange(len(points))
            tris = [[keep if v == gone else v for v in t] for t in tris]
    if rnd.random() < 0.2:  # far from the origin
        points = [[p[0] + 1e6, p[1] - 3e5, p[2] + 7e4] for p in points]
    if rnd.random() < 0.2:  # collinear (zero-area) triangles
        for _ in range(5):
            a, b = rnd.randrange(len(points)), rnd.randrange(len(points))
            points.append([(x + y) / 2 for x, y in zip(points[a], points[b])])
            tris.append([a, b, len(points) - 1])
    if rnd.random() < 0.2:  # unused points
        points += [[rnd.random(), rnd.random(), rnd.random()] for _ in range(10)]
    nan = rnd.random() < 0.1
    if nan:
        points[rnd.choice(tris[rnd.randrange(len(tris))])][0] = float("nan")  # a used point
    mesh = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetDataTypeToDouble()
    for p in points:
        vtk_points.InsertNextPoint(p)
    mesh.SetPoints(vtk_points)
    cells = vtkCellArray()
    for t in tris:
        cells.InsertNextCell(3, t)
    mesh.SetPolys(cells)
    values = vtkFloatArray()
    values.SetName("s")
    for p in range(len(points)):
        values.InsertNextValue(p)
    mesh.GetPointData().AddArray(values)
    return mesh, nan


def check_hierarchy(name, hierarchy, may_repeat, may_fold_flat):
    count = hierarchy.GetNumberOfBlocks()
    check(count >= 2, "%s: no simplified level" % name)
    for i in range(count):
        level = hierarchy.GetBlock(i)
        bad = first_nonfinite_point(level)
        check(bad < 0, "%s: level %d point %d not finite" % (name, i, bad))
        check(level.GetPointData().GetArray("s") is not None,
              "%s: level %d lost the point array" % (name, i))
        tris = triangles_of(level)
        check(all(len(set(t)) == 3 for t in tris),
              "%s: level %d has a degenerate triangle" % (name, i))
        same = [min(t[k:] + t[:k] for k in range(3)) for t in tris]
        check(len(set(same)) == len(same), "%s: level %d has a duplicate triangle" % (name, i))
        if i == 0 or not may_fold_flat:
            keys = [tuple(sorted(t)) for t in tris]
            check(len(set(keys)) == len(keys),
                  "%s: level %d has two triangles on the same points" % (name, i))
        if i > 0:
            before = hierarchy.GetBlock(i - 1).GetNumberOfPolys()
            fewer = len(tris) < before or (may_repeat and len(tris) == before)
            check(fewer, "%s: level %d has %d triangles after %d" % (name, i, len(tris), before))
        if i + 1 < count:
            ids = morph_target_ids(level)
            check(ids is not None, "%s: level %d has no MorphTargetId" % (name, i))
            if ids is not None:
                check(len(ids) == level.GetNumberOfPoints(),
                      "%s: level %d has %d MorphTargetId values for %d points"
                      % (name, i, len(ids), level.GetNumberOfPoints()))
                coarser = hierarchy.GetBlock(i + 1).GetNumberOfPoints()
                bad = [v for v in ids if v < 0 or v >= coarser]
                check(not bad, "%s: level %d has MorphTargetId out of range" % (name, i))


def check_geomorph(name, algorithm, rnd, input_triangles):
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputConnection(algorithm.GetOutputPort())
    errors = []
    geomorph.AddObserver(vtkCommand.ErrorEvent, lambda _caller, _event: errors.append(1))
    for _ in range(4):
        if rnd.random() < 0.5:
            geomorph.SetTargetNumberOfTriangles(-1)
            geomorph.SetLevelOfDetail(rnd.uniform(0.0, 6.0))
        else:
            geomorph.SetTargetNumberOfTriangles(rnd.randint(0, input_triangles + 10))
        geomorph.SetCorrespondence(rnd.randint(0, 2))
        geomorph.Update()
        out = geomorph.GetOutput()
        check(not errors, "%s: the geomorph reported an error" % name)
        check(out.GetNumberOfPolys() <= input_triangles,
              "%s: geomorph has %d triangles, the input %d"
              % (name, out.GetNumberOfPolys(), input_triangles))
        bad = first_nonfinite_point(out)
        check(bad < 0, "%s: geomorph point %d not finite" % (name, bad))


SEEDS = int(sys.argv[1]) if len(sys.argv) > 1 else 100
# The awkward input is meant to draw warnings and errors: kept out of the log (an error of the
# geomorph still reaches its observer).
vtkOutputWindow.SetInstance(vtkStringOutputWindow())
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
for seed in range(SEEDS):
    mesh, nan = awkward_mesh(seed)
    rnd = random.Random(1000 + seed)
    for name in ("vtkTriangleCollapseDecimation", "vtkVertexClusterOctree"):
        label = "seed %d %s" % (seed, name)
        algorithm = getattr(meshlod, name)()
        algorithm.SetInputData(mesh)
        algorithm.SetNumberOfLevels(rnd.randint(1, 5))
        algorithm.SetPreserveTopology(rnd.random() < 0.8)
        algorithm.Update()
        hierarchy = algorithm.GetHierarchy()
        if nan:
            check(hierarchy is None or hierarchy.GetNumberOfBlocks() == 0,
                  "%s: a NaN point gave levels" % label)
            continue
        octree = name == "vtkVertexClusterOctree"
        check_hierarchy(label, hierarchy, octree, octree and not algorithm.GetPreserveTopology())
        check_geomorph(label, algorithm, rnd, hierarchy.GetBlock(0).GetNumberOfPolys())

finish()
