// MeshLOD core: Morton codes, and the spatial renumbering of a mesh whose ids are scattered.
//
// Both engines read their per-vertex arrays (points, quadrics, adjacency rows) at the vertices
// around each collapse or cluster. Where neighbouring vertices have nearby ids, as in the output
// of a contouring filter, a scanner's grid or a parametric source, those reads mostly hit the
// cache; where the ids are scattered over the whole range (a mesh written from a hash map, its
// points shuffled), nearly every one misses. On the 611k-triangle gyroid isosurface with its
// point and triangle ids shuffled, one thread, vtkTriangleCollapseDecimation took 1.80 times as
// long as on the contoured mesh, vtkVertexClusterOctree 1.88 times (vtkQuadricDecimation 1.57),
// in a trial run without the renumbering; run on a copy renumbered in space
// (SpatialRenumbering), with what they report numbered back, 1.13-1.29 and 1.17-1.27 times in
// two runs (vtkQuadricDecimation 1.37-1.54; Benchmarks/RESULTS.md, "Input order").
#ifndef meshlod_SpatialOrder_h
#define meshlod_SpatialOrder_h

#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace meshlod
{
/// The lowest 21 bits of x, spread to every third bit of the result (bit i to bit 3 i): the
/// Morton code of a cell with integer coordinates (x, y, z) is the three spread coordinates,
/// each shifted by its axis.
inline std::uint64_t SpreadBits(std::uint32_t x)
{
  std::uint64_t v = x & 0x1fffffu;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// How scattered the vertex ids of the triangles are: the mean, over the triangles, of the
/// number of bits of the difference between their highest and lowest corner id (0 for a mesh
/// without triangles). An integer sum, the same for any thread count.
VTKFILTERSMESHLOD_EXPORT double MeanCornerSpreadBits(const TriangleMesh& mesh);

/// Whether the mesh's ids are scattered enough for the renumbering to pay: it has at least
/// 4,096 vertices (below, its arrays stay in cache in any order) and the mean corner spread
/// (MeanCornerSpreadBits) is within ScatteredMarginBits of the bit count of the number of
/// vertices, that is, a triangle's corners lie about an eighth of the whole range apart or more
/// (shuffled ids: within one bit). The benchmark's isosurfaces, written by a contouring filter a
/// row of cells after the other, are 9.4 to 11.7 bits below; of the meshes made by VTK's
/// sources in Benchmarks/RESULTS.md's "Beyond isosurfaces", twelve measured were 6 or more below,
/// two subdivided ones (whose new points are numbered edge by edge) 3.1 and 3.4.
constexpr int ScatteredMarginBits = 3;
VTKFILTERSMESHLOD_EXPORT bool IsOrderScattered(const TriangleMesh& mesh);

/// A renumbering of a mesh's vertices in Morton order (21 bits per axis over the bounding
/// box; vertices in one cell keep their order) and of its triangles by their corners' new ids
/// (lowest, middle, highest), each triangle keeping its corner order. For a mesh without
/// coincident points the result depends only on the geometry and the triangles' corners, not on
/// how the mesh was numbered before.
struct VTKFILTERSMESHLOD_EXPORT SpatialRenumbering
{
  std::vector<Id> NewVertex;   // old vertex -> new
  std::vector<Id> OldVertex;   // new vertex -> old
  std::vector<Id> OldTriangle; // new triangle -> old
  std::vector<Id> NewTriangle; // old triangle -> new

  /// Renumber `mesh` in place and keep the maps.
  void Apply(TriangleMesh& mesh);

  /// Where IsOrderScattered(mesh): Apply, and build `topology` again for the renumbered mesh.
  /// Returns whether it renumbered.
  bool ApplyIfScattered(TriangleMesh& mesh, TriangleTopology& topology);

  /// The next level made from the renumbered mesh (levels in order, finest first), in the mesh's
  /// old ids: the level-0 triangles its triangles descend from and, for the first level (whose
  /// previous level is level 0), the previous-level parents of its points and the rows indexed
  /// by previous-level points (MorphTargetId, CollapseRank; an empty row stays empty). Nothing
  /// when the mesh was not renumbered.
  void NumberBack(std::vector<Id>& levelZeroTriangles, std::vector<Id>& parents,
    std::vector<Id>& target, std::vector<Id>& rank);

private:
  bool FirstLevelNumberedBack = false;
};

} // namespace meshlod

#endif
