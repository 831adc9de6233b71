"""vtkLODGeomorph from Python: a hand-made two-level hierarchy with morph arrays and a pair of
vtkQuadricDecimation outputs without them; the time-driven update must give the same mesh as
the explicit LevelOfDetail, and an upstream with time steps of its own is asked for its first.
Exact counts on an extruded vector text, whose large flat faces make clusters that are valid
only together. Frames keep their arrays' component names while a user holds arrays of earlier
frames (the filter recycles its output arrays)."""

import os
import tempfile

from vtkmodules.util.vtkAlgorithm import VTKPythonAlgorithmBase
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkFloatArray, vtkIdTypeArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkMultiBlockDataSet, vtkPolyData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkQuadricDecimation, vtkTriangleFilter
from vtkmodules.vtkFiltersModeling import vtkAdaptiveSubdivisionFilter, vtkLinearExtrusionFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader, vtkXMLMultiBlockDataWriter
from vtkmodules.vtkRenderingFreeType import vtkVectorText

import meshlod
from meshlod_testing import check, finish, same_mesh



def make_polydata(points, triangles):
    poly = vtkPolyData()
    pts = vtkPoints()
    pts.SetDataTypeToDouble()
    for p in points:
        pts.InsertNextPoint(*p)
    cells = vtkCellArray()
    for t in triangles:
        cells.InsertNextCell(3, t)
    poly.SetPoints(pts)
    poly.SetPolys(cells)
    return poly


def add_array(poly, name, values, array_type=vtkDoubleArray, components=1):
    array = array_type()
    array.SetName(name)
    array.SetNumberOfComponents(components)
    for v in values:
        if components == 1:
            array.InsertNextValue(v)
        else:
            array.InsertNextTuple(v)
    poly.GetPointData().AddArray(array)


def gather(levels):
    hierarchy = vtkMultiBlockDataSet()
    hierarchy.SetNumberOfBlocks(len(levels))
    for i, level in enumerate(levels):
        hierarchy.SetBlock(i, level)
    return hierarchy


def morph_hierarchy():
    """The 2x1 grid; points 1 and 4 collapse onto (1, 0.5)."""
    fine_points = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (1, 1, 0), (2, 1, 0)]
    coarse_points = [(0, 0, 0), (1, 0.5, 0), (2, 0, 0), (0, 1, 0), (2, 1, 0)]
    fine = make_polydata(fine_points, [(0, 1, 4), (0, 4, 3), (1, 2, 5), (1, 5, 4)])
    coarse = make_polydata(coarse_points, [(0, 1, 3), (1, 2, 4)])
    target_id = [0, 1, 2, 3, 1, 4]
    add_array(fine, "Height", [0, 1, 2, 3, 4, 5])
    add_array(coarse, "Height", [0, 2.5, 2, 3, 5])
    add_array(fine, "MorphTarget", [coarse_points[i] for i in target_id], components=3)
    add_array(fine, "MorphTargetId", target_id, vtkIdTypeArray)
    add_array(fine, "CollapseRank", [-1, 0, -1, -1, 0, -1], vtkIdTypeArray)
    return gather([fine, coarse])


def test_morph():
    hierarchy = morph_hierarchy()
    timed = meshlod.vtkLODGeomorph()
    timed.SetInputData(hierarchy)
    timed.UpdateInformation()
    info = timed.GetOutputInformation(0)
    check(info.Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS()) == (0.0, 1.0), "time steps")

    explicit = meshlod.vtkLODGeomorph()
    explicit.SetInputData(hierarchy)
    explicit.UsePipelineTimeOff()
    explicit.SetLevelOfDetail(0.5)
    explicit.Update()
    out = explicit.GetOutput()
    check(out.GetPoint(1) == (1.0, 0.25, 0.0), "point 1 halfway")
    check(out.GetPoint(4) == (1.0, 0.75, 0.0), "point 4 halfway")
    check(out.GetPointData().GetArray("Height").GetValue(1) == 1.75, "Height blended")
    check(out.GetPointData().GetArray("MorphTarget") is None, "morph arrays not passed")
    check(out.GetNumberOfPolys() == 4, "connectivity of level 0")

    for time in (0.0, 0.25, 0.5, 0.8, 1.0):
        timed.UpdateTimeStep(time)
        explicit.SetLevelOfDetail(time)
        explicit.Update()
        check(same_mesh(timed.GetOutput(), explicit.GetOutput()), "time %g" % time)
        check(timed.GetActualLevelOfDetail() == time, "level of detail at time %g" % time)

    timed.SetTargetNumberOfTriangles(3)  # not reachable: two triangles go together
    timed.Update()
    check(timed.GetOutput().GetNumberOfPolys() == 2, "exact count")


def test_nearest():
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(40)
    sphere.SetPhiResolution(40)
    levels = []
    for reduction in (0.5, 0.9):
        decimate = vtkQuadricDecimation()
        decimate.SetInputConnection(sphere.GetOutputPort())
        decimate.SetTargetReduction(reduction)
        decimate.Update()
        level = vtkPolyData()
        level.ShallowCopy(decimate.GetOutput())
        levels.append(level)
    hierarchy = gather(levels)

    timed = meshlod.vtkLODGeomorph()
    timed.SetInputData(hierarchy)
    explicit = meshlod.vtkLODGeomorph()
    explicit.SetInputData(hierarchy)
    explicit.UsePipelineTimeOff()
    for time in (0.0, 0.3, 0.7, 1.0):
        timed.UpdateTimeStep(time)
        explicit.SetLevelOfDetail(time)
        explicit.Update()
        check(same_mesh(timed.GetOutput(), explicit.GetOutput()), "nearest, time %g" % time)
    check(timed.GetActualCorrespondence() == meshlod.vtkLODGeomorph.NEAREST_VERTICES,
          "nearest-vertex correspondence")
    check(timed.GetNumberOfCorrespondenceBuilds() == 1, "correspondence built once")
    check(timed.GetOutput().GetNumberOfPoints() == levels[1].GetNumberOfPoints(), "t = 1")


def extruded_text():
    text = vtkVectorText()
    text.SetText("MeshLOD")
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(text.GetOutputPort())
    extrude = vtkLinearExtrusionFilter()
    extrude.SetInputConnection(triangles.GetOutputPort())
    extrude.SetExtrusionTypeToNormalExtrusion()
    extrude.SetVector(0, 0, 1)
    extrude.SetScaleFactor(0.3)
    extrude.CappingOn()
    closed = vtkTriangleFilter()
    closed.SetInputConnection(extrude.GetOutputPort())
    clean = vtkCleanPolyData()
    clean.SetInputConnection(closed.GetOutputPort())
    subdivide = vtkAdaptiveSubdivisionFilter()
    subdivide.SetInputConnection(clean.GetOutputPort())
    subdivide.SetMaximumEdgeLength(0.04)
    subdivide.SetMaximumNumberOfPasses(100)
    final = vtkCleanPolyData()
    final.SetInputConnection(subdivide.GetOutputPort())
    final.Update()
    return final.GetOutput()


def test_clusters_valid_together():
    # Collapses still waiting at the end of a transition need each other. Made in plain order,
    # one that stayed without one fan made every later step unstoppable: asked for counts
    # between the text's first two levels, 10 of 61 were missed by more than 2 triangles, the
    # worst by 11,753. Made group by group, the mesh is valid again after each group (54 of 61
    # within 2 triangles, the worst miss 597); with a group's points joining interleaved, all
    # 61, the worst miss 1.
    mesh = extruded_text()
    decimate = meshlod.vtkTriangleCollapseDecimation()
    decimate.SetInputData(mesh)
    decimate.AddLevelReduction(0.75)
    decimate.AddLevelReduction(0.95)
    decimate.Update()
    hierarchy = decimate.GetHierarchy()
    levels = range(hierarchy.GetNumberOfBlocks())
    counts = [hierarchy.GetBlock(i).GetNumberOfPolys() for i in levels]
    check(len(counts) == 3, "extruded text: three levels, got %s" % counts)
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputData(hierarchy)
    geomorph.UsePipelineTimeOff()
    near, worst = 0, 0
    for k in range(61):
        asked = counts[-1] + (counts[0] - counts[-1]) * k // 60
        geomorph.SetTargetNumberOfTriangles(asked)
        geomorph.Update()
        got = geomorph.GetOutput().GetNumberOfPolys()
        check(got <= asked, "extruded text: at most %d triangles, got %d" % (asked, got))
        near += 1 if asked - got <= 2 else 0
        worst = max(worst, asked - got)
    print("extruded text %s: %d of 61 counts within 2 triangles, worst miss %d"
          % (counts, near, worst))
    check(near >= 60, "extruded text: counts within 2 triangles: %d of 61" % near)
    check(worst <= 40, "extruded text: worst miss %d" % worst)


def test_strokes_merged_interleaved():
    # The default levels of the extruded text: between levels 2 and 3 (25,070 and 14,098
    # triangles) thin strokes shrink into single points, each target merging up to 103 points
    # that are pinched until their neighbours' merge too. Joined one collapse after the other,
    # 433 of the transition's 5,487 counts were out of reach, by up to 472 triangles; with
    # the points of such a group joining interleaved (each step one whose target keeps one
    # fan, where there is one), 21, by up to 36.
    decimate = meshlod.vtkTriangleCollapseDecimation()
    decimate.SetInputData(extruded_text())
    decimate.Update()
    hierarchy = decimate.GetHierarchy()
    counts = [hierarchy.GetBlock(i).GetNumberOfPolys()
              for i in range(hierarchy.GetNumberOfBlocks())]
    check(counts[2:4] == [25070, 14098], "extruded text: default levels %s" % counts)
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputData(hierarchy)
    geomorph.UsePipelineTimeOff()
    asked_counts = range(counts[3], counts[2] + 1, 4)
    missed, worst = 0, 0
    for asked in asked_counts:
        geomorph.SetTargetNumberOfTriangles(asked)
        geomorph.Update()
        got = geomorph.GetOutput().GetNumberOfPolys()
        missed += 1 if asked - got > 1 else 0  # a closed surface: even counts
        worst = max(worst, asked - got)
    print("extruded text, levels 2 -> 3: %d of %d counts missed, worst by %d"
          % (missed, len(asked_counts), worst))
    check(missed <= len(asked_counts) // 100, "extruded text: %d counts missed" % missed)
    check(worst <= 48, "extruded text: worst miss %d" % worst)


def test_saved_hierarchy_in_pieces():
    # A hierarchy saved as .vtm and read back with a request for pieces: the reader hands each
    # piece only some of the levels, so the geomorph asks for the whole file and produces the
    # whole mesh as piece 0 (it used to fail on every piece: "block 3 is not a vtkPolyData").
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(48)
    sphere.SetPhiResolution(24)
    decimate = meshlod.vtkTriangleCollapseDecimation()
    decimate.SetInputConnection(sphere.GetOutputPort())
    decimate.SetNumberOfLevels(4)
    decimate.Update()
    hierarchy = decimate.GetHierarchy()
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "hierarchy.vtm")
        writer = vtkXMLMultiBlockDataWriter()
        writer.SetInputData(hierarchy)
        writer.SetFileName(path)
        check(writer.Write() == 1, "saved hierarchy: written")
        reader = vtkXMLMultiBlockDataReader()
        reader.SetFileName(path)
        geomorph = meshlod.vtkLODGeomorph()
        geomorph.SetInputConnection(reader.GetOutputPort())
        geomorph.UsePipelineTimeOff()
        geomorph.SetLevelOfDetail(2.0)
        total = 0
        for piece in range(2):
            geomorph.UpdatePiece(piece, 2, 0)
            check(geomorph.GetNumberOfLevels() == hierarchy.GetNumberOfBlocks(),
                  "saved hierarchy, piece %d: %d levels, expected %d" % (
                      piece, geomorph.GetNumberOfLevels(), hierarchy.GetNumberOfBlocks()))
            total += geomorph.GetOutput().GetNumberOfPolys()
        expected = hierarchy.GetBlock(2).GetNumberOfPolys()
        check(total == expected,
              "saved hierarchy: the pieces hold %d triangles, level 2 has %d" % (total, expected))


class TimeSphere(VTKPythonAlgorithmBase):
    """A source with time steps 0, 1, 2: a sphere of radius 1 + t (1 when no time is asked)."""

    def __init__(self):
        VTKPythonAlgorithmBase.__init__(self, nInputPorts=0, nOutputPorts=1,
                                        outputType="vtkPolyData")
        self.times = []

    continuous = False  # only a time range, no time steps

    def RequestInformation(self, request, in_info, out_info):
        info = out_info.GetInformationObject(0)
        if not self.continuous:
            info.Set(vtkStreamingDemandDrivenPipeline.TIME_STEPS(), [0.0, 1.0, 2.0], 3)
        info.Set(vtkStreamingDemandDrivenPipeline.TIME_RANGE(), [0.0, 2.0], 2)
        return 1

    def RequestData(self, request, in_info, out_info):
        info = out_info.GetInformationObject(0)
        key = vtkStreamingDemandDrivenPipeline.UPDATE_TIME_STEP()
        time = info.Get(key) if info.Has(key) else None
        self.times.append(time)
        sphere = vtkSphereSource()
        sphere.SetRadius(1.0 + (time or 0.0))
        sphere.SetThetaResolution(20)
        sphere.SetPhiResolution(20)
        sphere.Update()
        vtkPolyData.GetData(out_info).ShallowCopy(sphere.GetOutput())
        return 1


def test_time_aware_upstream(continuous):
    """With pipeline time, an upstream with time steps gives its first (or the start of its time
    range), whatever time was asked of it while UsePipelineTime was off; without, the time goes
    upstream."""
    source = TimeSphere()
    source.continuous = continuous
    levels = meshlod.vtkTriangleCollapseDecimation()
    levels.SetInputConnection(source.GetOutputPort())
    levels.SetNumberOfLevels(2)
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputConnection(levels.GetOutputPort())
    geomorph.UsePipelineTimeOff()
    geomorph.UpdateTimeStep(2.0)
    radius = geomorph.GetOutput().GetBounds()[1]
    check(abs(radius - 3.0) < 0.05, "time off at t = 2: radius %g, expected 3" % radius)
    geomorph.UsePipelineTimeOn()
    geomorph.UpdateTimeStep(0.5)
    radius = geomorph.GetOutput().GetBounds()[1]
    check(abs(radius - 1.0) < 0.05,
          "time on after t = 2 off: radius %g, expected 1 (upstream asked for %s)"
          % (radius, source.times))
    check(source.times[-1] == 0.0, "time on: the upstream was last asked for %s" % source.times)


def test_component_names_while_frames_are_held():
    """Each frame's arrays have their own component names. The geomorph recycles output arrays
    nobody holds; one recycled from a named Velocity once came back as the Normals with the
    components Vx, Vy, Vz (VTK cannot take component names away)."""
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(40)
    sphere.SetPhiResolution(40)
    sphere.SetOutputPointsPrecision(1)
    sphere.Update()
    mesh = sphere.GetOutput()
    count = mesh.GetNumberOfPoints()
    velocity = vtkFloatArray()
    velocity.SetName("Velocity")
    velocity.SetNumberOfComponents(3)
    velocity.SetNumberOfTuples(count)
    for i in range(count):
        velocity.SetTuple3(i, i % 7, 1.0, -1.0)
    for k, name in enumerate(("Vx", "Vy", "Vz")):
        velocity.SetComponentName(k, name)
    mesh.GetPointData().AddArray(velocity)
    decimate = meshlod.vtkTriangleCollapseDecimation()
    decimate.SetInputData(mesh)
    decimate.Update()
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputData(decimate.GetHierarchy())
    geomorph.UsePipelineTimeOff()
    held = []
    for lod in (0.5, 0.4, 0.3, 0.2):
        geomorph.SetLevelOfDetail(lod)
        geomorph.Update()
        data = geomorph.GetOutput().GetPointData()
        normals, speed = data.GetArray("Normals"), data.GetArray("Velocity")
        check([normals.GetComponentName(k) for k in range(3)] == [None] * 3 and
              [speed.GetComponentName(k) for k in range(3)] == ["Vx", "Vy", "Vz"],
              "L = %g: component names of Normals %s, Velocity %s" % (
                  lod, [normals.GetComponentName(k) for k in range(3)],
                  [speed.GetComponentName(k) for k in range(3)]))
        held.append(normals)  # a user keeps this frame's normals


test_morph()
test_component_names_while_frames_are_held()
test_time_aware_upstream(False)
test_time_aware_upstream(True)
test_nearest()
test_clusters_valid_together()
test_strokes_merged_interleaved()
test_saved_hierarchy_in_pieces()
finish()
