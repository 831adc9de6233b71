"""vtkTriangleCollapseDecimation from Python: a flying-edges isosurface made in Python, the
hierarchy's levels, block names, morph arrays and field data, then vtkLODGeomorph driven by the
pipeline time, compared with the explicit LevelOfDetail and an exact triangle count."""

from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import (vtkCompositeDataSet, vtkImplicitBoolean, vtkPolyData,
                                            vtkSphere)
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkImagingHybrid import vtkSampleFunction

import meshlod
from meshlod_testing import check, finish, same_mesh, triangles_of

LEVELS = 3  # levels after level 0 (ComputeLevelError measures each: the slow part)
MORPH_ARRAYS = ("MorphTarget", "MorphTargetId", "CollapseRank")



def three_blobs(resolution, speck=False):
    """A closed genus-0 isosurface: the union of three overlapping spheres (and, with `speck`,
    a small separate one)."""
    union = vtkImplicitBoolean()
    union.SetOperationTypeToUnion()
    spheres = [((-0.45, 0, 0), 0.4), ((0.1, 0.15, 0), 0.35), ((0.5, -0.1, 0.1), 0.3)]
    for center, radius in spheres + ([((0.0, 0.7, 0.6), 0.06)] if speck else []):
        sphere = vtkSphere()
        sphere.SetCenter(*center)
        sphere.SetRadius(radius)
        union.AddFunction(sphere)
    volume = vtkSampleFunction()
    volume.SetImplicitFunction(union)
    volume.SetModelBounds(-1, 1, -1, 1, -1, 1)
    volume.SetSampleDimensions(resolution, resolution, resolution)
    volume.ComputeNormalsOff()
    contour = vtkFlyingEdges3D()
    contour.SetInputConnection(volume.GetOutputPort())
    contour.SetValue(0, 0.0)
    return contour


def field(level, name):
    array = level.GetFieldData().GetArray(name)
    return None if array is None else array.GetTuple1(0)


def test_hierarchy(contour, decimate, largest_hausdorff=0.1):
    contour.Update()
    input_triangles = contour.GetOutput().GetNumberOfPolys()
    check(input_triangles > 5000, "input has %d triangles" % input_triangles)
    decimate.Update()
    hierarchy = decimate.GetHierarchy()
    n = hierarchy.GetNumberOfBlocks()
    check(n == LEVELS + 1, "%d levels" % n)
    check(decimate.GetNumberOfLevelsProduced() == n, "NumberOfLevelsProduced")
    check(abs(decimate.GetActualReduction() - 0.99) < 0.001, "ActualReduction")
    previous = None
    for i in range(n):
        level = hierarchy.GetBlock(i)
        triangles = level.GetNumberOfPolys()
        name = hierarchy.GetMetaData(i).Get(vtkCompositeDataSet.NAME())
        check(name == "Level %d" % i, "block %d named %r" % (i, name))
        if previous is not None:
            check(triangles < previous, "level %d: %d after %d" % (i, triangles, previous))
            # Level i keeps 0.01^(i / LEVELS) of the input; a collapse removes at most 4.
            target = int(input_triangles * 0.01 ** (i / LEVELS))
            check(target - 4 <= triangles <= target, "level %d: %d for %d" % (i, triangles, target))
        previous = triangles
        point_data = level.GetPointData()
        for array in MORPH_ARRAYS:
            present = point_data.GetArray(array) is not None
            check(present == (i < n - 1), "level %d has %s: %s" % (i, array, present))
        if i < n - 1:
            check(point_data.GetArray("MorphTarget").GetNumberOfComponents() == 3, "MorphTarget")
            next_points = hierarchy.GetBlock(i + 1).GetNumberOfPoints()
            ids = point_data.GetArray("MorphTargetId").GetRange()
            check(0 <= ids[0] and ids[1] < next_points, "MorphTargetId range on level %d" % i)
        check(field(level, "LevelIndex") == i, "LevelIndex of level %d" % i)
        check(field(level, "NumberOfTriangles") == triangles, "NumberOfTriangles of level %d" % i)
        estimated = field(level, "EstimatedError")
        hausdorff = field(level, "MeasuredHausdorff")
        rms = field(level, "MeasuredRMS")
        check(None not in (estimated, hausdorff, rms), "error fields on level %d" % i)
        if None in (estimated, hausdorff, rms):
            continue
        if i == 0:
            check(estimated == 0 and hausdorff == 0 and rms == 0, "level 0 has no error")
        else:
            check(estimated > 0 and 0 < rms <= hausdorff, "errors of level %d" % i)
            # World units; the volume spans 2, the surface about 1.8: the quadric method stays
            # far below 5% of that.
            check(hausdorff < largest_hausdorff, "Hausdorff %g on level %d" % (hausdorff, i))
    return hierarchy


def test_geomorph(decimate, hierarchy):
    n = hierarchy.GetNumberOfBlocks()
    runs = []
    decimate.AddObserver("EndEvent", lambda caller, event: runs.append(event))

    timed = meshlod.vtkLODGeomorph()
    timed.SetInputConnection(decimate.GetOutputPort())
    timed.UpdateInformation()
    steps = timed.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS())
    check(steps == tuple(float(i) for i in range(n)), "time steps %s" % (steps,))

    explicit = meshlod.vtkLODGeomorph()
    explicit.SetInputConnection(decimate.GetOutputPort())
    explicit.UsePipelineTimeOff()
    for time in (0.0, 0.5, 1.0, 1.25, 2.875, n - 1.5, n - 1.0):
        timed.UpdateTimeStep(time)
        explicit.SetLevelOfDetail(time)
        explicit.Update()
        check(timed.GetActualLevelOfDetail() == time, "level of detail at time %g" % time)
        check(same_mesh(timed.GetOutput(), explicit.GetOutput()), "same mesh at time %g" % time)
        lod = timed.GetOutput().GetFieldData().GetArray("LevelOfDetail").GetValue(0)
        check(lod == time, "LevelOfDetail field %g at time %g" % (lod, time))
        level = hierarchy.GetBlock(min(int(time), n - 1))
        check(timed.GetOutput().GetNumberOfPolys() == level.GetNumberOfPolys(),
              "connectivity of level %d at time %g" % (int(time), time))
        if time == int(time):
            check(same_mesh(timed.GetOutput(), level), "time %g is level %d" % (time, time))

    # An exact count between levels 1 and 2 (a closed surface: even counts are reachable).
    fine = hierarchy.GetBlock(1).GetNumberOfPolys()
    coarse = hierarchy.GetBlock(2).GetNumberOfPolys()
    count = (fine + coarse) // 4 * 2
    timed.SetTargetNumberOfTriangles(count)
    timed.Update()
    check(timed.GetOutput().GetNumberOfPolys() == count, "exact count %d" % count)
    check(1.0 < timed.GetActualLevelOfDetail() < 2.0, "exact count between levels 1 and 2")
    check(not runs, "the decimation re-ran %d times for the geomorph" % len(runs))


contour = three_blobs(48)
decimate = meshlod.vtkTriangleCollapseDecimation()
decimate.SetInputConnection(contour.GetOutputPort())
decimate.SetNumberOfLevels(LEVELS)
decimate.ComputeLevelErrorOn()
hierarchy = test_hierarchy(contour, decimate)
test_geomorph(decimate, hierarchy)

# The curvature method, ranked by default by its fitted surface's deviation; the setters of
# the ranking through the wrapping.
curvature = meshlod.vtkTriangleCollapseDecimation()
curvature.SetInputConnection(contour.GetOutputPort())
curvature.SetNumberOfLevels(LEVELS)
curvature.ComputeLevelErrorOn()
curvature.SetMethodToCurvature()
check(curvature.GetCurvatureCostAsString() == "FitDeviation", "CurvatureCost default")
curvature.SetCurvatureCostToWeight()
check(curvature.GetCurvatureCostAsString() == "Weight", "CurvatureCost setter")
curvature.SetCurvatureCostToFitDeviation()
check(curvature.GetCurvatureCost() == curvature.FIT_DEVIATION, "CurvatureCost setter")
# At the last level, 64 triangles for three spheres, the curvature method's Hausdorff distance
# is 0.089 here, as the quadric method's (0.095); paper 000's weight gives 0.21.
test_hierarchy(contour, curvature, 0.13)

def contour_filter():
    """A filter on the contour with the levels of the tests above and measured errors."""
    decimate = meshlod.vtkTriangleCollapseDecimation()
    decimate.SetInputConnection(contour.GetOutputPort())
    decimate.SetNumberOfLevels(LEVELS)
    decimate.ComputeLevelErrorOn()
    return decimate


def coarsest_points(hierarchy):
    level = hierarchy.GetBlock(hierarchy.GetNumberOfBlocks() - 1)
    return [level.GetPoint(i) for i in range(level.GetNumberOfPoints())]


# Paper 002's placement, uniform plane weights (vtkQuadricDecimation's weighting) and paper 002's
# cost (AreaNormalization 0) through the wrapping: the same checks on every level, and levels
# unlike the defaults' (the setting reaches the engine).
by_default = contour_filter()
by_default.Update()
paper = contour_filter()
check(paper.GetPlacementAsString() == "Regularized", "Placement default")
paper.SetPlacementToPaperCandidates()
check(paper.GetPlacement() == paper.PAPER_CANDIDATES, "Placement setter")
uniform = contour_filter()
check(uniform.GetPlaneWeightsAsString() == "Area", "PlaneWeights default")
uniform.SetPlaneWeightsToUniform()
check(uniform.GetPlaneWeights() == uniform.UNIFORM_WEIGHTS, "PlaneWeights setter")
paper_cost = contour_filter()
check(paper_cost.GetAreaNormalization() == 0.25, "AreaNormalization default")
paper_cost.SetAreaNormalization(0.0)
check(paper_cost.GetAreaNormalization() == 0.0, "AreaNormalization setter")
for name, changed in (("Placement", paper), ("PlaneWeights", uniform),
                      ("AreaNormalization", paper_cost)):
    test_hierarchy(contour, changed)
    check(coarsest_points(changed.GetHierarchy()) != coarsest_points(by_default.GetHierarchy()),
          "%s changes the coarsest level" % name)

# FlipEdges (default off) through the wrapping: every level keeps its points and its count, and
# some of its triangles are flipped.
flipped = contour_filter()
check(not flipped.GetFlipEdges(), "FlipEdges default")
flipped.FlipEdgesOn()
check("FlipEdges: On" in str(flipped), "PrintSelf shows FlipEdges")
flipped.Update()
check(flipped.GetNumberOfFlips() > 0, "%d flips" % flipped.GetNumberOfFlips())
changed_levels = 0
for i in range(LEVELS + 1):
    plain_level = by_default.GetHierarchy().GetBlock(i)
    flipped_level = flipped.GetHierarchy().GetBlock(i)
    points = lambda level: [level.GetPoint(p) for p in range(level.GetNumberOfPoints())]
    check(points(plain_level) == points(flipped_level), "level %d: points kept" % i)
    check(plain_level.GetNumberOfPolys() == flipped_level.GetNumberOfPolys(),
          "level %d: count kept" % i)
    changed_levels += triangles_of(plain_level) != triangles_of(flipped_level)
check(changed_levels > 0, "%d levels flipped" % changed_levels)



def check_no_counts(decimate, run):
    check(decimate.GetNumberOfFlips() == 0 and decimate.GetNumberOfSwaps() == 0,
          "%s: %d flips, %d swaps" % (run, decimate.GetNumberOfFlips(),
                                      decimate.GetNumberOfSwaps()))


# The after-execution counts are the last run's: a run on an empty input, and one refused for a
# bad setting, report no flips and no swaps (they kept the run before's).
flipped.SetInputData(vtkPolyData())
flipped.Update()
check_no_counts(flipped, "empty input after a run")
refused = contour_filter()
refused.FlipEdgesOn()
refused.Update()
check(refused.GetNumberOfFlips() > 0, "%d flips before the refused run" % refused.GetNumberOfFlips())
refused.SetTargetReduction(float("nan"))
refused.Update()
check_no_counts(refused, "refused run after a run")
# An aborted run outputs no level, and counts no flip of the levels it made before the abort.
aborted = contour_filter()
aborted.FlipEdgesOn()


def abort_late(algorithm, event):
    if algorithm.GetProgress() > 0.6:
        algorithm.AbortExecuteOn()


aborted.AddObserver(vtkCommand.ProgressEvent, abort_late)
aborted.Update()
check(aborted.GetHierarchy().GetNumberOfBlocks() == 0,
      "aborted run: %d blocks" % aborted.GetHierarchy().GetNumberOfBlocks())
check_no_counts(aborted, "aborted run")


def unused_points(poly):
    return poly.GetNumberOfPoints() - len(set(triangles_of(poly)))


# PreserveTopology: by default the speck stays to the coarsest level; off, it vanishes into one
# point of no cell, which its points' MorphTargetId chains end at.
with_speck = three_blobs(48, speck=True)
for preserve in (True, False):
    pieces = meshlod.vtkTriangleCollapseDecimation()
    pieces.SetInputConnection(with_speck.GetOutputPort())
    check(pieces.GetPreserveTopology(), "PreserveTopology default")
    pieces.SetPreserveTopology(preserve)
    pieces.Update()
    levels = pieces.GetHierarchy()
    coarsest = levels.GetBlock(levels.GetNumberOfBlocks() - 1)
    check(unused_points(coarsest) == (0 if preserve else 1),
          "PreserveTopology %s: %d points of no cell" % (preserve, unused_points(coarsest)))

finish()
