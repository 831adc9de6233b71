// MeshLOD core: whether the vertex that points merge into keeps a valid neighbourhood, for
// CollapseSchedule, which joins a collapse's points one at a time and may stop only where the
// mesh is valid: the link of the merged vertex (the edge opposite it in each triangle around
// it) must be one fan (a disk or a half-disk), or the fans of a point on a curve where more than
// two sheets meet, or one fan whatever the edges' directions on a surface whose orientation is
// not consistent. MergedLink keeps one such link up to date as points join; these functions
// list and test it from scratch.
#ifndef meshlod_LinkFan_h
#define meshlod_LinkFan_h

#include "TriangleMesh.h"

#include <utility>
#include <vector>

namespace meshlod
{
// Calls f(length) for each run of equal values in the sorted `values`.
template <typename F>
void ForEachRun(const std::vector<Id>& values, F&& f)
{
  for (size_t i = 0; i < values.size();)
  {
    size_t j = i;
    while (j < values.size() && values[j] == values[i])
    {
      ++j;
    }
    f(static_cast<int>(j - i));
    i = j;
  }
}

// Whether a merged vertex's link edges from[i] -> to[i], without regard to direction, have a
// given shape: no link edge twice, all connected, `ends` link vertices on `endDegree` link
// edges and every other on two (see LinkFan.cxx).
bool LinkHasShape(const std::vector<Id>& from, const std::vector<Id>& to, int endDegree, int ends);

// Whether two of the triangles around `members` use the same directed edge (see LinkFan.cxx);
// `around` and `edges` are scratch space.
bool HasRepeatedDirectedEdge(const Id* triangles, const VertexTriangleAdjacency& adjacency,
  const std::vector<Id>& members, std::vector<Id>& around, std::vector<std::pair<Id, Id>>& edges);

// Whether the vertex `merged` (a class of the union-find `parent`) has one fan; its link edges
// are left in `from` and `to` (see LinkFan.cxx).
bool HasOneFan(const Id* triangles, const VertexTriangleAdjacency& adjacency,
  std::vector<Id>& parent, const std::vector<Id>& members, Id merged, std::vector<Id>& from,
  std::vector<Id>& to);

} // namespace meshlod

#endif
