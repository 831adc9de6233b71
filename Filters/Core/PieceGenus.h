// The genus of each piece of a triangle mesh, for vtkVertexClusterOctree's check that a level
// keeps the handles of the level it is made from (its other repairs are local and cannot see a
// handle close).
#ifndef meshlod_PieceGenus_h
#define meshlod_PieceGenus_h

#include "TriangleMesh.h"

#include <vector>

namespace meshlod
{
/// Marks a group that HandleMeasures does not measure.
constexpr Id UnmeasuredGroup = -1;

/// HandleMeasures' flags of a triangle's side c.
inline bool SideOnBoundary(unsigned char flags, int c)
{
  return (flags >> c & 1) != 0;
}
inline bool SideNonManifold(unsigned char flags, int c)
{
  return (flags >> (c + 3) & 1) != 0;
}

/// For each group of points (pointGroup[p] in 0 .. groups - 1, one per point of the mesh the
/// triangles refer to): 2 - V + E - F - L, where V counts the points of the group that
/// triangles use, E the distinct edges whose lower point is in the group, F the triangles whose
/// first corner is, and L the boundary loops (the cycles of edges of one triangle) through its
/// points. For a group that is one connected manifold piece, that is twice its genus when it is
/// orientable and its number of cross-caps when not: a hole that closes (a loop less, a face
/// more in the Euler characteristic) leaves it as it was, a handle that closes lowers it by 2.
/// UnmeasuredGroup for a group without triangles and for one with an edge of three triangles or
/// more (what it measures is not defined there). Points where the surface touches itself (two
/// fans of triangles or more) count once per fan, so that the measure is the surface's.
/// `sides`, when given, receives per triangle bit c set when its side from corner c to the next
/// has no other triangle (SideOnBoundary), bit c + 3 when it has two others or more
/// (SideNonManifold).
VTKFILTERSMESHLOD_EXPORT std::vector<Id> HandleMeasures(const Id* triangles,
  Id count,
  const std::vector<Id>& pointGroup,
  Id groups,
  std::vector<unsigned char>* sides = nullptr);
} // namespace meshlod

#endif
