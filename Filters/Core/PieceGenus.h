// The genus of each piece of a triangle mesh, for vtkVertexClusterOctree's check that a level
// keeps the handles of the level it is made from (its other repairs are local and cannot see a
// handle close).
#ifndef meshlod_PieceGenus_h
#define meshlod_PieceGenus_h

#include "TriangleMesh.h"

#include <vector>

namespace meshlod
{
/// HandleMeasures' result for one group of points.
struct PieceMeasure
{
  /// Connected pieces of the group's triangles, where a point the surface touches itself at
  /// (two fans of triangles or more) joins nothing: two spheres touching at a point are two.
  Id Pieces = 0;
  /// Twice the genus of those pieces, summed (a piece that cannot be oriented counts its
  /// cross-caps): 2 Pieces - V + E - F - L, with V the group's points counted once per fan, E
  /// its distinct edges, F its triangles and L its boundary loops. A hole that closes (a loop
  /// less, one more in V - E + F) leaves it as it was; a handle that closes lowers it by 2.
  Id Handles = 0;
  /// False for a group without triangles and for one with an edge of three triangles or more
  /// (what it measures is not defined there): not compared.
  bool Measured = false;
  bool operator==(const PieceMeasure& other) const
  {
    return this->Pieces == other.Pieces && this->Handles == other.Handles &&
      this->Measured == other.Measured;
  }
  bool operator!=(const PieceMeasure& other) const { return !(*this == other); }
};

/// HandleMeasures' flags of a triangle's side c.
inline bool SideOnBoundary(unsigned char flags, int c)
{
  return (flags >> c & 1) != 0;
}
inline bool SideNonManifold(unsigned char flags, int c)
{
  return (flags >> (c + 3) & 1) != 0;
}

/// The pieces and handles of each group of points (pointGroup[p] in 0 .. groups - 1, one per
/// point of the mesh the triangles refer to); an edge counts in the group of its lower point,
/// a triangle and a piece in that of its first corner. `sides`, when given, receives per
/// triangle bit c set when its side from corner c to the next has no other triangle
/// (SideOnBoundary), bit c + 3 when it has two others or more (SideNonManifold).
VTKFILTERSMESHLOD_EXPORT std::vector<PieceMeasure> HandleMeasures(const Id* triangles,
  Id count,
  const std::vector<Id>& pointGroup,
  Id groups,
  std::vector<unsigned char>* sides = nullptr);
} // namespace meshlod

#endif
