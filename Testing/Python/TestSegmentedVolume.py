"""vtkTriangleCollapseDecimation and vtkVertexClusterOctree from Python on a segmented volume:
three labelled balls, vtkDiscreteFlyingEdges3D, points merged (the faces between two labels then
come twice, which the filters drop). The sheets meet along curves of edges with three
triangles; every level must keep the topology (Euler characteristic, no boundary, the same
kinds of edges, the curves), the coarsest must reach its target (the octree: come near it
without the error of a level that crushes the sheets), and vtkLODGeomorph must give exact
counts between the levels."""

from vtkmodules.vtkCommonCore import vtkShortArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersCore import vtkCleanPolyData
from vtkmodules.vtkFiltersGeneral import vtkDiscreteFlyingEdges3D

import meshlod
from meshlod_testing import check, edge_counts, finish



def labelled_balls(size):
    """Labels 1, 2, 3 of three overlapping balls (the first listed wins), 0 outside."""
    balls = ((-0.3, 0.0, 0.0, 0.55), (0.3, 0.0, 0.0, 0.55), (0.0, 0.35, 0.1, 0.45))
    image = vtkImageData()
    image.SetDimensions(size, size, size)
    spacing = 2.0 / (size - 1)
    image.SetSpacing(spacing, spacing, spacing)
    image.SetOrigin(-1.0, -1.0, -1.0)
    labels = vtkShortArray()
    labels.SetName("label")
    labels.SetNumberOfTuples(size ** 3)
    index = 0
    for k in range(size):
        z = -1.0 + k * spacing
        for j in range(size):
            y = -1.0 + j * spacing
            for i in range(size):
                x = -1.0 + i * spacing
                label = 0
                for b, (cx, cy, cz, r) in reversed(list(enumerate(balls))):
                    if (x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2 < r * r:
                        label = b + 1
                labels.SetValue(index, label)
                index += 1
    image.GetPointData().SetScalars(labels)
    return image


def check_topology(levels, name):
    """Every level after the first keeps level 0's Euler characteristic, kinds of edges and
    curves, with fewer triangles than the level before it."""
    kinds, euler = edge_counts(levels[0])
    print("%s level 0: %d triangles, edges by triangle count %s, Euler characteristic %d"
          % (name, levels[0].GetNumberOfPolys(), dict(kinds), euler))
    check(kinds.get(3, 0) > 0, "level 0 has curves where three sheets meet")
    check(kinds.get(1, 0) == 0, "level 0 has no boundary")
    previous = levels[0].GetNumberOfPolys()
    for i, level in enumerate(levels[1:], 1):
        counts, chi = edge_counts(level)
        print("%s level %d: %d triangles, edges %s, Euler characteristic %d"
              % (name, i, level.GetNumberOfPolys(), dict(counts), chi))
        check(level.GetNumberOfPolys() < previous, "%s level %d has fewer triangles" % (name, i))
        previous = level.GetNumberOfPolys()
        check(chi == euler, "%s level %d keeps the Euler characteristic" % (name, i))
        check(set(counts) <= set(kinds), "%s level %d has no new kind of edge" % (name, i))
        check(counts.get(3, 0) > 0, "%s level %d keeps the curves" % (name, i))


def check_octree(merged):
    """The octree's clusters may hold one open piece of a curve each, so its levels come near
    their targets, a tenth and a hundredth of the input's 15,597 triangles (before, curve points
    never merged and both levels kept over 3,100 triangles). The 1% level cannot be reached
    without merging the curves further than they may; it then backs off to an error near what
    its count warrants (without that, 726 triangles at 5.8 times level 1's error; with it 924
    at 2.2 times, and 854 at 2.9 times since a vertex of a cluster may stand in for a
    representative that would flip a triangle: other clusters merge, the fewest triangles found
    are fewer, and the back-off keeps at most a tenth more)."""
    octree = meshlod.vtkVertexClusterOctree()
    octree.SetInputConnection(merged.GetOutputPort())
    octree.SetLevelModeToTargetTriangleCounts()
    octree.GlobalWarningDisplayOff()  # the duplicated faces, and the count missed at 1%
    merged.Update()
    total = merged.GetOutput().GetNumberOfPolys()
    octree.AddTargetTriangleCount(total // 10)
    octree.AddTargetTriangleCount(total // 100)
    octree.Update()
    hierarchy = octree.GetHierarchy()
    levels = [hierarchy.GetBlock(i) for i in range(hierarchy.GetNumberOfBlocks())]
    check(len(levels) == 3, "octree: 3 levels, got %d" % len(levels))
    if len(levels) != 3:
        return
    check_topology(levels, "octree")
    error = [level.GetFieldData().GetArray("EstimatedError").GetTuple1(0) for level in levels]
    print("octree estimated errors: %s" % ["%.4g" % e for e in error])
    check(levels[1].GetNumberOfPolys() <= 1.25 * (total // 10),
          "octree level 1 near 10%%: %d, asked %d" % (levels[1].GetNumberOfPolys(), total // 10))
    check(levels[2].GetNumberOfPolys() <= 0.75 * levels[1].GetNumberOfPolys(),
          "octree level 2 well below level 1: %d" % levels[2].GetNumberOfPolys())
    check(error[2] <= 3.0 * error[1], "octree level 2's error %.4g within 3 times level 1's %.4g"
          % (error[2], error[1]))


def main():
    contour = vtkDiscreteFlyingEdges3D()
    contour.SetInputData(labelled_balls(48))
    contour.GenerateValues(3, 1, 3)
    contour.ComputeNormalsOff()
    contour.ComputeGradientsOff()
    contour.ComputeScalarsOff()
    merged = vtkCleanPolyData()
    merged.SetInputConnection(contour.GetOutputPort())

    decimate = meshlod.vtkTriangleCollapseDecimation()
    decimate.SetInputConnection(merged.GetOutputPort())
    decimate.SetTargetReduction(0.99)
    decimate.GlobalWarningDisplayOff()  # it reports the duplicated faces it drops
    decimate.Update()
    hierarchy = decimate.GetHierarchy()
    levels = [hierarchy.GetBlock(i) for i in range(hierarchy.GetNumberOfBlocks())]
    check(len(levels) >= 6, "at least 6 levels, got %d" % len(levels))
    check_topology(levels, "triangle collapse")
    target = levels[0].GetNumberOfPolys() // 100
    check(levels[-1].GetNumberOfPolys() <= target + 2,
          "the coarsest level reaches 1%%: %d, asked %d" % (levels[-1].GetNumberOfPolys(), target))

    # Exact counts between levels: a collapse along a curve removes three triangles, one on a
    # sheet two, so a count may be missed by what one step removes. (A step whose intermediate
    # mesh is pinched cannot be stopped at; before the schedule knew curves, every step after a
    # curve's first merge was, and nearly every count between levels fell to the next level's;
    # before a collapse could wait for the neighbour that makes it valid, 43 of these 49 counts
    # were within 2 triangles.)
    geomorph = meshlod.vtkLODGeomorph()
    geomorph.SetInputConnection(decimate.GetOutputPort())
    asked_counts, near = 0, 0
    for i in range(1, len(levels) - 1):
        finer, coarser = levels[i].GetNumberOfPolys(), levels[i + 1].GetNumberOfPolys()
        for step in range(1, 8):
            asked = coarser + (finer - coarser) * step // 8
            geomorph.SetTargetNumberOfTriangles(asked)
            geomorph.Update()
            got = geomorph.GetOutput().GetNumberOfPolys()
            check(got <= asked, "geomorph at most %d triangles, got %d" % (asked, got))
            asked_counts += 1
            near += 1 if asked - got <= 2 else 0
    print("exact counts between levels: %d of %d within 2 triangles" % (near, asked_counts))
    check(near == asked_counts, "exact counts within 2 triangles: %d of %d" % (near, asked_counts))

    check_octree(merged)


if __name__ == "__main__":
    main()
    finish()
