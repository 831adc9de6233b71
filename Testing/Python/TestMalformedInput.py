"""Malformed or unusual input that once crashed a filter, or passed through it wrongly.

Each case states what a user gets: an error naming the problem (and no levels), a warning
(and levels that are still right), or levels without NaN. Checked for
vtkTriangleCollapseDecimation, vtkVertexClusterOctree and vtkLODGeomorph:

- a cell array whose offsets run past its connectivity: an error, not a read past the end;
- a NaN point used only by a quad: the error a NaN point of a triangle gets (the triangulation
  used to drop the quad, leaving a hole);
- a quad that crosses itself, which vtkTriangleFilter cannot triangulate: a warning with the
  number of triangles missing; none for triangles stored as quads with a repeated point, and
  none of them lost wherever the repeat stands;
- a point array with +inf and -inf: no level and no geomorph output holds a NaN;
- a texture whose scalars are shorter than its points: an error; a texture in the XZ plane is
  baked like one in the XY plane; int colours count 0-255 like unsigned char ones;
- input arrays named like the arrays the octree makes (Normals, TCoords): a warning;
- a TextureResolution that is not a power of two: no warning about its rounding up;
- vtkLODGeomorph on levels with integer points: blended in double, not truncated;
- a two-component MorphTargetId, or a CollapseRank of 1e30: one error;
- an exact count on a level of triangle strips: the error for levels that are not triangles;
- a triangle soup whose copies of a corner differ by rounding in all three coordinates: stitched
  into the closed surface (copies were compared in three sorted orders, which missed them), but
  not where a string array differs;
- a thin closed cone, whose cross-section fits in one octree cluster: the octree keeps a closed
  surface on every level instead of ending the hierarchy at level 0;
- a small sphere beside a triangle a million times farther away than its size: the octree's
  finest cells hold the whole sphere, which a warning says (and no warning without the
  outlier);
- polygons whose point ids refer to an input without points: the out-of-range error; an
  unnamed field-data array of the input: on every level;
- vtkLODGeomorph on a multiblock of textures: no time steps published.
"""

import math
import random

from vtkmodules.vtkCommonCore import (
    vtkDoubleArray,
    vtkFloatArray,
    vtkIdTypeArray,
    vtkIntArray,
    vtkLogger,
    vtkOutputWindow,
    vtkPoints,
    vtkStringArray,
    vtkStringOutputWindow,
    vtkUnsignedCharArray,
)
from vtkmodules.vtkCommonDataModel import (
    vtkCellArray,
    vtkImageData,
    vtkMultiBlockDataSet,
    vtkPolyData,
)
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkFiltersCore import vtkQuadricDecimation, vtkStripper, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkConeSource, vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkFiltersTexture import vtkTextureMapToSphere

import meshlod
from meshlod_testing import check, finish

FILTERS = ("vtkTriangleCollapseDecimation", "vtkVertexClusterOctree")


MESSAGES = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(MESSAGES)
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)


def run(algorithm):
    """Update `algorithm`; the errors and warnings it printed."""
    before = len(MESSAGES.GetOutput())
    algorithm.Update()
    return MESSAGES.GetOutput()[before:]


def run_filter(name, mesh):
    """A new filter of class `name` run on `mesh`; it and the messages it printed."""
    algorithm = getattr(meshlod, name)()
    algorithm.SetInputData(mesh)
    return algorithm, run(algorithm)


def geomorph_of(hierarchy):
    """A vtkLODGeomorph of `hierarchy` driven by its settings, not by pipeline time."""
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputData(hierarchy)
    geomorph.UsePipelineTimeOff()
    return geomorph


def sphere(resolution=16):
    source = vtkSphereSource()
    source.SetThetaResolution(resolution)
    source.SetPhiResolution(resolution)
    source.Update()
    return source.GetOutput()


def quad_grid():
    plane = vtkPlaneSource()
    plane.SetResolution(10, 10)
    plane.Update()
    mesh = vtkPolyData()
    mesh.DeepCopy(plane.GetOutput())
    return mesh


def levels_of(algorithm):
    hierarchy = algorithm.GetHierarchy()
    return [] if hierarchy is None else [hierarchy.GetBlock(i)
                                         for i in range(hierarchy.GetNumberOfBlocks())]


def has_nan(array):
    return any(math.isnan(array.GetComponent(t, c))
               for t in range(array.GetNumberOfTuples())
               for c in range(array.GetNumberOfComponents()))


# Offsets past the end of the connectivity (vtkCellArray::IsValid is false).
for name in FILTERS:
    mesh = vtkPolyData()
    mesh.DeepCopy(sphere(8))
    cells = vtkCellArray()
    offsets = vtkIdTypeArray()
    connectivity = vtkIdTypeArray()
    for value in (0, 3, 6, 900):
        offsets.InsertNextValue(value)
    for value in range(9):
        connectivity.InsertNextValue(value)
    cells.SetData(offsets, connectivity)
    mesh.SetPolys(cells)
    algorithm, text = run_filter(name, mesh)
    check("Polygon 2 has an invalid offset" in text,
          "%s: bad offsets: no error naming them (%r)" % (name, text[:300]))
    check(not levels_of(algorithm), "%s: bad offsets gave levels" % name)

    # The geomorph refuses a level with such cells too.
    good = getattr(meshlod, name)()
    good.SetInputData(sphere(12))
    good.Update()
    hierarchy = good.GetHierarchy().NewInstance()
    hierarchy.DeepCopy(good.GetHierarchy())
    hierarchy.GetBlock(1).SetPolys(cells)
    geomorph = geomorph_of(hierarchy)
    geomorph.SetLevelOfDetail(0.5)
    text = run(geomorph)
    check("level 1 has a cell array with invalid offsets" in text,
          "%s: geomorph: bad offsets not reported (%r)" % (name, text[:300]))
    check(geomorph.GetOutput().GetNumberOfPoints() == 0,
          "%s: geomorph: bad offsets gave an output" % name)

# A NaN point that only quads use.
for name in FILTERS:
    mesh = quad_grid()
    mesh.GetPoints().SetPoint(60, float("nan"), 0.1, 0.0)
    algorithm, text = run_filter(name, mesh)
    check("Point 60 has a NaN or infinite coordinate" in text,
          "%s: NaN point of a quad: no error (%r)" % (name, text[:300]))
    check(not levels_of(algorithm), "%s: NaN point of a quad gave levels" % name)

# A quad crossing itself: vtkTriangleFilter drops it, and the filters say so.
for name in FILTERS:
    mesh = quad_grid()
    polys = mesh.GetPolys()
    ids = [polys.GetConnectivityArray().GetValue(k) for k in range(4 * 55, 4 * 55 + 4)]
    for k, value in enumerate((ids[0], ids[2], ids[1], ids[3])):
        polys.GetConnectivityArray().SetValue(4 * 55 + k, value)
    mesh.Modified()
    algorithm, text = run_filter(name, mesh)
    check("made 2 triangles fewer than their points allow" in text,
          "%s: dropped bow-tie quad not reported (%r)" % (name, text[:300]))
    levels = levels_of(algorithm)
    check(levels and levels[0].GetNumberOfPolys() == 198,
          "%s: level 0 of the grid with a bow-tie quad" % name)

# Triangles stored as quads with a repeated point, as some exporters pad them, the repeat last
# ([a, b, c, c]) or not ([a, b, b, c], [a, a, b, c]: vtkTriangleFilter alone cut these into a
# degenerate triangle, and the surface lost one triangle each without a warning): one triangle
# of each, and no triangle is missing.
for name in FILTERS:
    mesh = quad_grid()
    polys = vtkCellArray()
    for c in range(mesh.GetNumberOfCells()):
        ids = mesh.GetCell(c).GetPointIds()
        quad = [ids.GetId(k) for k in range(4)]
        if c == 55:
            polys.InsertNextCell(4, [quad[0], quad[1], quad[2], quad[2]])
            polys.InsertNextCell(4, [quad[0], quad[2], quad[3], quad[3]])
        elif c == 33:
            polys.InsertNextCell(4, [quad[0], quad[1], quad[1], quad[2]])
            polys.InsertNextCell(4, [quad[0], quad[0], quad[2], quad[3]])
        else:
            polys.InsertNextCell(4, quad)
    mesh.SetPolys(polys)
    algorithm, text = run_filter(name, mesh)
    check("fewer than their points allow" not in text,
          "%s: padded triangles drew the warning about dropped polygons" % name)
    levels = levels_of(algorithm)
    check(levels and levels[0].GetNumberOfPolys() == 200,
          "%s: level 0 of the grid with padded triangles" % name)

# +inf and -inf in one array: a point merging both has no mean, but never a NaN.
for name in FILTERS:
    mesh = vtkPolyData()
    mesh.DeepCopy(sphere(20))
    values = vtkDoubleArray()
    values.SetName("Values")
    for p in range(mesh.GetNumberOfPoints()):
        values.InsertNextValue(float(p))
    values.SetValue(17, float("inf"))
    values.SetValue(18, float("-inf"))
    mesh.GetPointData().AddArray(values)
    algorithm, _ = run_filter(name, mesh)
    levels = levels_of(algorithm)
    check(len(levels) > 2, "%s: infinite values: %d levels" % (name, len(levels)))
    for i, level in enumerate(levels):
        check(not has_nan(level.GetPointData().GetArray("Values")),
              "%s: level %d has NaN values from +inf and -inf" % (name, i))
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputConnection(algorithm.GetOutputPort())
    geomorph.UsePipelineTimeOff()
    for lod in (0.25, 0.5, 1.0, 1.5, 2.999):
        geomorph.SetLevelOfDetail(lod)
        geomorph.Update()
        check(not has_nan(geomorph.GetOutput().GetPointData().GetArray("Values")),
              "%s: geomorph at %g has NaN values" % (name, lod))


# Textures.
def textured_sphere():
    mapper = vtkTextureMapToSphere()
    mapper.SetInputData(sphere(24))
    mapper.PreventSeamOff()
    mapper.Update()
    return mapper.GetOutput()


def texture(dimensions, tuples, rgb):
    image = vtkImageData()
    image.SetDimensions(*dimensions)
    scalars = vtkUnsignedCharArray()
    scalars.SetNumberOfComponents(3)
    scalars.SetNumberOfTuples(tuples)
    for t in range(tuples):
        scalars.SetTuple3(t, *rgb)
    image.GetPointData().SetScalars(scalars)
    return image


def baker(mesh, image=None):
    octree = meshlod.vtkVertexClusterOctree()
    octree.SetInputData(mesh)
    if image is not None:
        octree.SetTextureData(image)
    octree.BakeTextureOn()
    octree.SetTextureResolution(64)
    octree.SetNumberOfLevels(2)
    return octree


def add_colours(mesh, colours):
    """`colours` (an empty array) filled with (255, 0, 128) at every point, added as Colour."""
    colours.SetName("Colour")
    colours.SetNumberOfComponents(3)
    for p in range(mesh.GetNumberOfPoints()):
        colours.InsertNextTuple3(255, 0, 128)
    mesh.GetPointData().AddArray(colours)


def mean_texel(octree, level):
    scalars = octree.GetTextures().GetBlock(level).GetPointData().GetScalars()
    n = scalars.GetNumberOfTuples()
    return [sum(scalars.GetComponent(t, c) for t in range(n)) / n for c in range(3)]


octree = baker(textured_sphere(), texture((512, 512, 1), 10, (128, 128, 128)))
text = run(octree)
check("the texture's scalars have 10 tuples, not one for each of its 262144 points" in text,
      "short texture scalars: no error (%r)" % text[:300])
check(not levels_of(octree), "short texture scalars gave levels")

octree = baker(textured_sphere(), texture((16, 1, 16), 256, (10, 200, 30)))
text = run(octree)
check("ERR" not in text and "rror" not in text, "XZ texture refused (%r)" % text[:300])
levels = levels_of(octree)
check(len(levels) == 3, "XZ texture: %d levels" % len(levels))
if len(levels) == 3:
    check(all(abs(a - b) < 1.0 for a, b in zip(mean_texel(octree, 2), (10, 200, 30))),
          "XZ texture: baked colour %s, not (10, 200, 30)" % mean_texel(octree, 2))

mesh = vtkPolyData()
mesh.DeepCopy(sphere(24))
add_colours(mesh, vtkIntArray())
octree = baker(mesh)
octree.SetColorArrayName("Colour")
run(octree)
if len(levels_of(octree)) == 3:
    baked = mean_texel(octree, 2)
    check(all(abs(a - b) < 1.0 for a, b in zip(baked, (255, 0, 128))),
          "int colours (255, 0, 128) baked as %s" % baked)
else:
    check(False, "int colours: no levels")

# Input arrays named like the ones the octree makes.
mesh = vtkPolyData()
mesh.DeepCopy(textured_sphere())
mesh.GetPointData().SetNormals(None)
for array_name in ("Normals", "TCoords"):
    clash = vtkFloatArray()
    clash.SetName(array_name)
    clash.SetNumberOfTuples(mesh.GetNumberOfPoints())
    clash.Fill(1.0)
    mesh.GetPointData().AddArray(clash)
add_colours(mesh, vtkUnsignedCharArray())
mesh.GetPointData().SetTCoords(None)
octree = baker(mesh)
octree.SetColorArrayName("Colour")
octree.ComputeNormalsOn()
octree.SetTextureResolution(100)
text = run(octree)
for array_name in ("Normals", "TCoords"):
    check('array "%s" is replaced on the simplified levels' % array_name in text,
          "no warning about replacing the input's %s array (%r)" % (array_name, text[:400]))
check("too many for a" not in text,
      "TextureResolution 100 drew a warning about its rounding (%r)" % text[:400])



# The geomorph on user-made levels.
def quadric_levels(integer_points):
    source = vtkSphereSource()
    source.SetRadius(50.0)
    source.SetThetaResolution(40)
    source.SetPhiResolution(40)
    levels = vtkMultiBlockDataSet()
    for i, reduction in enumerate((0.5, 0.9)):
        decimate = vtkQuadricDecimation()
        decimate.SetInputConnection(source.GetOutputPort())
        decimate.SetTargetReduction(reduction)
        decimate.Update()
        level = vtkPolyData()
        level.DeepCopy(decimate.GetOutput())
        if integer_points:
            points = vtkPoints()
            points.SetDataTypeToInt()
            points.SetNumberOfPoints(level.GetNumberOfPoints())
            for p in range(level.GetNumberOfPoints()):
                points.SetPoint(p, [round(v) for v in level.GetPoint(p)])
            level.SetPoints(points)
        levels.SetBlock(i, level)
    return levels


geomorph = geomorph_of(quadric_levels(True))
geomorph.SetLevelOfDetail(0.3)
run(geomorph)
out = geomorph.GetOutput()
fractional = sum(1 for p in range(out.GetNumberOfPoints())
                 if any(abs(v - round(v)) > 1e-6 for v in out.GetPoint(p)))
check(out.GetNumberOfPoints() > 700 and fractional > out.GetNumberOfPoints() // 2,
      "integer points blended to %d of %d non-integer points"
      % (fractional, out.GetNumberOfPoints()))

decimation = meshlod.vtkTriangleCollapseDecimation()
decimation.SetInputData(sphere(20))
decimation.SetNumberOfLevels(2)
decimation.Update()
for array_name, problem in (("MorphTargetId", "two components"),
                            ("CollapseRank", "a rank of 1e30")):
    hierarchy = decimation.GetHierarchy().NewInstance()
    hierarchy.DeepCopy(decimation.GetHierarchy())
    level = hierarchy.GetBlock(0)
    given = level.GetPointData().GetArray(array_name)
    bad = vtkDoubleArray()
    bad.SetName(array_name)
    if problem == "two components":
        bad.SetNumberOfComponents(2)
        for p in range(given.GetNumberOfTuples()):
            bad.InsertNextTuple2(given.GetTuple1(p), 0)
    else:
        for p in range(given.GetNumberOfTuples()):
            bad.InsertNextValue(given.GetTuple1(p))
        bad.SetValue(0, 1e30)
    level.GetPointData().AddArray(bad)
    geomorph = geomorph_of(hierarchy)
    geomorph.SetLevelOfDetail(0.5)
    text = run(geomorph)
    check(text.count("ERR|") + text.count("ERROR") >= 1 and len(text) < 5000,
          "%s with %s: not one clear error (%d characters)" % (array_name, problem, len(text)))
    check(geomorph.GetOutput().GetNumberOfPoints() == 0,
          "%s with %s gave an output" % (array_name, problem))

hierarchy = quadric_levels(False)
stripper = vtkStripper()
stripper.SetInputData(hierarchy.GetBlock(0))
stripper.Update()
hierarchy.SetBlock(0, stripper.GetOutput())
geomorph = geomorph_of(hierarchy)
geomorph.SetTargetNumberOfTriangles(500)
text = run(geomorph)
check("Level 0 has cells other than triangles" in text,
      "exact count on a level of strips: no error (%r)" % text[:300])


def jittered_soup(labels):
    """A 16 x 16 UV sphere (226 points) as a soup of triangles, each corner moved by up to 1e-15
    in x, y and z; with `labels`, a string array naming each point's triangle."""
    source = sphere(16)
    rnd = random.Random(1)
    points = vtkPoints()
    points.SetDataTypeToDouble()
    cells = vtkCellArray()
    names = vtkStringArray()
    names.SetName("Label")
    for c in range(source.GetNumberOfCells()):
        corners = source.GetCell(c).GetPointIds()
        ids = []
        for k in range(3):
            x = source.GetPoint(corners.GetId(k))
            ids.append(points.InsertNextPoint([v + rnd.uniform(-1e-15, 1e-15) for v in x]))
            names.InsertNextValue("triangle %d" % c)
        cells.InsertNextCell(3, ids)
    soup = vtkPolyData()
    soup.SetPoints(points)
    soup.SetPolys(cells)
    if labels:
        soup.GetPointData().AddArray(names)
    return soup


for name in FILTERS:
    algorithm, _ = run_filter(name, jittered_soup(False))
    levels = levels_of(algorithm)
    check(levels and levels[0].GetNumberOfPoints() == 226,
          "%s: jittered soup: level 0 has %s points, 226 when stitched"
          % (name, levels[0].GetNumberOfPoints() if levels else None))
    check(len(levels) > 2 and levels[-1].GetNumberOfPolys() < 100,
          "%s: jittered soup did not simplify: %s"
          % (name, [level.GetNumberOfPolys() for level in levels]))
    algorithm.SetInputData(jittered_soup(True))
    text = run(algorithm)
    levels = levels_of(algorithm)
    check(levels and levels[0].GetNumberOfPoints() == 3 * 448,
          "%s: soup with a label per triangle was stitched (%s points)"
          % (name, levels[0].GetNumberOfPoints() if levels else None))
    check("Did not stitch" in text, "%s: labelled soup: no warning about the seam" % name)


def edge_uses(mesh):
    uses = {}
    for c in range(mesh.GetNumberOfCells()):
        ids = mesh.GetCell(c).GetPointIds()
        corners = [ids.GetId(k) for k in range(3)]
        for k in range(3):
            edge = tuple(sorted((corners[k], corners[(k + 1) % 3])))
            uses[edge] = uses.get(edge, 0) + 1
    return uses


cone = vtkConeSource()
cone.SetResolution(64)
cone.SetRadius(1e-3)
cone.SetHeight(1.0)
triangulate = vtkTriangleFilter()
triangulate.SetInputConnection(cone.GetOutputPort())
octree = meshlod.vtkVertexClusterOctree()
octree.SetInputConnection(triangulate.GetOutputPort())
run(octree)
levels = levels_of(octree)
check(len(levels) == 4 and all(level.GetNumberOfPolys() >= 4 for level in levels),
      "thin cone: levels %s" % [level.GetNumberOfPolys() for level in levels])
for i, level in enumerate(levels):
    uses = edge_uses(level)
    euler = level.GetNumberOfPoints() - len(uses) + level.GetNumberOfPolys()
    check(all(n == 2 for n in uses.values()) and euler == 2,
          "thin cone: level %d is not a closed sphere (Euler characteristic %d)" % (i, euler))


for far in (None, 1e6):
    mesh = vtkPolyData()
    mesh.DeepCopy(sphere(30))
    if far is not None:
        points = mesh.GetPoints()
        corners = [points.InsertNextPoint(far + dx, dy, 0.0)
                   for dx, dy in ((0.0, 0.0), (10.0, 0.0), (0.0, 10.0))]
        mesh.GetPolys().InsertNextCell(3, corners)
    octree = meshlod.vtkVertexClusterOctree()
    octree.SetInputData(mesh)
    text = run(octree)
    warned = "shorter than the octree's finest cells" in text
    check(warned == (far is not None),
          "sphere %s: warning about the octree's finest cells %s"
          % ("with a far outlier" if far else "alone", "given" if warned else "missing"))


for name in FILTERS:
    mesh = vtkPolyData()
    cells = vtkCellArray()
    cells.InsertNextCell(3, [0, 1, 2])
    mesh.SetPolys(cells)
    algorithm, text = run_filter(name, mesh)
    check("Polygon 0 refers to a point id outside [0, 0)" in text,
          "%s: polygon without points: no error (%r)" % (name, text[:300]))

    mesh = vtkPolyData()
    mesh.DeepCopy(sphere(16))
    unnamed = vtkIntArray()
    unnamed.InsertNextValue(7)
    mesh.GetFieldData().AddArray(unnamed)
    algorithm.SetInputData(mesh)
    run(algorithm)
    levels = levels_of(algorithm)
    for i, level in enumerate(levels):
        fd = level.GetFieldData()
        kept = [fd.GetAbstractArray(a) for a in range(fd.GetNumberOfArrays())
                if fd.GetAbstractArray(a).GetName() is None]
        check(len(kept) == 1 and kept[0].GetVariantValue(0).ToInt() == 7,
              "%s: level %d lost the unnamed field-data array" % (name, i))


# A multiblock whose blocks are not levels: the geomorph publishes no time steps for it.
textured = meshlod.vtkVertexClusterOctree()
textured.SetInputData(textured_sphere())
textured.SetTextureData(texture((16, 16, 1), 256, (10, 200, 30)))
textured.BakeTextureOn()
textured.SetTextureResolution(64)
geomorph = meshlod.vtkLODGeomorph()
geomorph.SetInputConnection(textured.GetOutputPort(1))
geomorph.UpdateInformation()
check(not geomorph.GetOutputInformation(0).Has(vtkStreamingDemandDrivenPipeline.TIME_STEPS()),
      "the geomorph published time steps for a multiblock of textures")

finish()
