// Bookkeeping that turns a stream of collapses into output levels.
//
// Between two snapshots every live vertex of the last level heads a group; a collapse merges
// the groups of its members into the survivor's group and multiplies each member group's
// interpolation weights by the member's barycentric weight at the collapse point, so the
// weights of a group always sum to one and compose correctly over several collapses. At a
// snapshot the groups give the new level's point sources, the correspondence (MorphTargetId)
// and the collapse order (CollapseRank) of the previous level's points.
//
// It also keeps, for the whole run, the original vertices merged into each vertex (its
// ancestral points, paper 000 section 7): at each snapshot they are laid out one contiguous run
// per vertex of the new level, and a vertex's ancestral points are the runs of the vertices in
// its group, in the order the merges joined them. A fit that takes every k-th of them steps
// from run to run instead of walking a chain of every one (which had been a tenth of the
// curvature method's time at the coarse levels, with a few hundred ancestral points per fit).
#ifndef meshlod_LevelTracker_h
#define meshlod_LevelTracker_h

#include "TriangleMesh.h"

#include <cstdint>
#include <vector>

namespace meshlod
{
class CollapseMesh;
struct LevelData;
struct PointSources;

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

  /// Every `stride`-th ancestral point of v (original vertex ids, v first): those whose
  /// position in a sequence that reaches v's first point at `index` is a multiple of `stride`;
  /// `index` is advanced past v's points (so that consecutive calls stride over several
  /// vertices' points as one sequence).
  template <typename F>
  void ForEachAncestor(Id v, Id stride, Id& index, F&& f) const
  {
    for (Id u = v; u != InvalidId; u = this->GroupNext[u])
    {
      const Id run = this->PreviousIndex[u];
      const Id begin = this->AncestorStart[run], end = this->AncestorStart[run + 1];
      for (Id k = begin + (stride - index % stride) % stride; k < end; k += stride)
      {
        f(this->Ancestors[k]);
      }
      index += end - begin;
    }
  }
  Id AncestorCount(Id v) const { return this->AncestorTotal[v]; }
  /// The mesh vertex of point p of the last level built.
  Id LevelVertex(Id p) const { return this->PreviousVertices[p]; }

private:
  // Snapshot's steps (LevelTracker.cxx).
  std::vector<Id> ListLiveVertices(const CollapseMesh& state);
  void CopyLiveMesh(const CollapseMesh& state, const std::vector<Id>& vertices,
    const std::vector<Id>* triangles, LevelData& level) const;
  void WriteSources(const std::vector<Id>& vertices, PointSources& sources) const;
  std::vector<Id> RankCollapses(const std::vector<Id>& vertices);
  void WriteCorrespondence(
    const CollapseMesh& state, const std::vector<Id>& rankOf, LevelData& level) const;
  void LayOutAncestors(const std::vector<Id>& vertices);

  std::vector<Id> GroupNext;
  std::vector<Id> GroupTail;
  std::vector<float> GroupWeight;
  std::vector<std::int64_t> GroupSequence; // last collapse that touched the group, -1: none
  std::vector<Id> PreviousIndex;           // vertex -> its index in the last level
  std::vector<Id> PreviousVertices;        // index in the last level -> vertex
  std::vector<Id> Ancestors;      // the runs of the last level's vertices, in its order
  std::vector<Id> AncestorStart;  // index in the last level -> its run; one more at the end
  std::vector<Id> AncestorTotal;  // vertex -> number of its ancestral points
  std::vector<Id> NewAncestors;   // Snapshot's scratch
  std::vector<Id> NewIndex;   // Snapshot's scratch
  std::vector<Id> ByCollapse; // Snapshot's scratch
};

} // namespace meshlod

#endif
