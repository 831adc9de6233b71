// Bookkeeping that turns a stream of collapses into output levels.
//
// Between two snapshots every live vertex of the last level heads a group; a collapse merges
// the groups of its members into the survivor's group and multiplies each member group's
// interpolation weights by the member's barycentric weight at the collapse point, so the
// weights of a group always sum to one and compose correctly over several collapses. At a
// snapshot the groups give the new level's point sources, the correspondence (MorphTargetId)
// and the collapse order (CollapseRank) of the previous level's points.
//
// It also keeps, for the whole run, the chain of original vertices merged into each vertex
// (its ancestral points, paper 000 section 7).
#ifndef meshlod_LevelTracker_h
#define meshlod_LevelTracker_h

#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace meshlod
{
class CollapseMesh;
struct LevelData;

class LevelTracker
{
public:
  /// Every vertex of the mesh is a point of level 0.
  void Initialize(Id numberOfPoints, bool trackAncestors);

  /// Record the merge of members[1..] into members[0] with barycentric weights, as collapse
  /// number `sequence` (a global, increasing order). Collapses with disjoint members may be
  /// recorded concurrently.
  void Merge(const Id* members, const double* weights, int count, std::int64_t sequence);

  /// Build the next level from the live part of the mesh, and start new groups. `triangles`,
  /// when given, lists every live triangle (and possibly dead ones) in increasing id order:
  /// only those are looked at; null: every triangle.
  void Snapshot(const CollapseMesh& mesh, double estimatedError, LevelData& level,
    const std::vector<Id>* triangles = nullptr);

  /// Ancestral points of v (original vertex ids, v first).
  template <typename F>
  void ForEachAncestor(Id v, F&& f) const
  {
    for (Id u = v; u != InvalidId; u = this->AncestorNext[u])
    {
      f(u);
    }
  }
  Id AncestorCount(Id v) const { return this->AncestorTotal[v]; }

private:
  std::vector<Id> GroupNext;
  std::vector<Id> GroupTail;
  std::vector<float> GroupWeight;
  std::vector<std::int64_t> GroupSequence; // last collapse that touched the group, -1: none
  std::vector<Id> PreviousIndex;           // vertex -> its index in the last level
  std::vector<Id> PreviousVertices;        // index in the last level -> vertex
  std::vector<Id> AncestorNext;
  std::vector<Id> AncestorTail;
  std::vector<Id> AncestorTotal;
  std::vector<Id> NewIndex;   // Snapshot's scratch
  std::vector<Id> ByCollapse; // Snapshot's scratch
};

} // namespace meshlod

#endif
