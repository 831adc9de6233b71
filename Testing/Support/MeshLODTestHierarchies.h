// LOD hierarchies for the tests and the benchmark of vtkLODGeomorph, built without the
// decimation filters: a small independent-set triangle collapse (the level structure of Gieng
// et al., "Smooth Hierarchical Surface Triangulations", section 6, with the simplest choices)
// fed to meshlod::HierarchyBuilder, so the levels carry real morph data.
#ifndef MeshLODTestHierarchies_h
#define MeshLODTestHierarchies_h

#include "Core/TriangleMesh.h"
#include "vtkSmartPointer.h"

#include <vector>

class vtkMultiBlockDataSet;
class vtkPolyData;

namespace meshlod
{
namespace testing
{
struct CollapseHierarchyOptions
{
  int MaximumLevels = 4;        // level 0 included
  double MaximumFraction = 1.0; // at most this fraction of a level's triangles is removed
  bool MeasureErrors = false;   // MeasuredHausdorff / MeasuredRMS field data
};

/// Each next level collapses a set of triangles of the previous one to their centroids, smallest
/// area first, keeping only collapses whose closed stencils (the triangle's corners and all
/// their neighbours) are disjoint and that keep the mesh manifold without flipping a triangle:
/// the three corners interior, the three edge-neighbour apexes distinct and of valence >= 4,
/// no other vertex joined to two corners. Every collapse removes 4 triangles and gets its own
/// CollapseRank (in the order chosen). Stops early when nothing can collapse. The input must be
/// a triangle mesh that ReadInputMesh accepts; its point and cell data are carried through.
vtkSmartPointer<vtkMultiBlockDataSet> MakeCollapseHierarchy(
  vtkPolyData* mesh, const CollapseHierarchyOptions& options = CollapseHierarchyOptions());

/// The points (as doubles) and triangles of a polydata whose polygons are all triangles.
TriangleMesh ToTriangleMesh(vtkPolyData* poly);

/// A hierarchy without morph data: the given meshes as levels "Level i" (finest first).
vtkSmartPointer<vtkMultiBlockDataSet> GatherLevels(const std::vector<vtkPolyData*>& levels);

} // namespace testing
} // namespace meshlod

#endif
