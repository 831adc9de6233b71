// MeshLOD core: merging the vertices joined by short edges (step 4 of the interpolation between
// two LOD models in Pan, Zhou, Shi, "A New Mesh Simplification Algorithm Based on Triangle
// Collapses", section 4), used by vtkLODGeomorph when the hierarchy has no morph arrays.
#ifndef meshlod_EdgeMerge_h
#define meshlod_EdgeMerge_h

#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace meshlod
{
/// The distinct edges of a triangle list, each once as (a, b) with a < b, ordered by a then b.
struct VTKFILTERSMESHLOD_EXPORT EdgeList
{
  std::vector<Id> Ends; // 2 ids per edge

  void Build(const Id* triangles, Id numberOfTriangles, Id numberOfPoints);
  std::size_t Size() const { return this->Ends.size() / 2; }
};

/// Groups of points joined by the flagged edges (`merge[e]` non-zero). On return
/// `representative[p]` is the lowest point id of p's group (p itself when it merges with
/// nothing); returns the number of points merged away.
VTKFILTERSMESHLOD_EXPORT Id MergeAlongEdges(const EdgeList& edges, const std::uint8_t* merge,
  Id numberOfPoints, std::vector<Id>& representative);

} // namespace meshlod

#endif
