// MeshLOD core: the builder of a CollapseSchedule, private to CollapseSchedule.cxx (the order of
// the steps) and CollapseScheduleFans.cxx (whether a step leaves a valid mesh).
#ifndef meshlod_CollapseScheduleBuilder_h
#define meshlod_CollapseScheduleBuilder_h

#include "CollapseSchedule.h"
#include "MergedLink.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace meshlod
{
// The order in which a transition's points settle (CollapseSchedule's Step, Order and which
// steps can be stopped at), built by replaying the merges with a union-find: the points settled
// on one target are one vertex. One builder per Build call; see CollapseSchedule.h for the rules.
// CollapseSchedule.cxx makes the steps, CollapseScheduleFans.cxx tests whether one leaves a valid
// mesh (one fan at each target) or folds a triangle.
class CollapseScheduleBuilder
{
public:
  static constexpr Id Unassigned = -1;

  // Ids in increasing order, each at most once, with a flag per possible id: the candidates of a
  // step, kept up to date as points settle instead of listed again.
  struct SortedIds
  {
    std::vector<Id> Items;
    std::vector<std::uint8_t> In; // per id

    void Add(Id i)
    {
      if (!this->In[i])
      {
        this->In[i] = 1;
        this->Items.insert(std::lower_bound(this->Items.begin(), this->Items.end(), i), i);
      }
    }
    void Remove(Id i)
    {
      if (this->In[i])
      {
        this->In[i] = 0;
        this->Items.erase(std::lower_bound(this->Items.begin(), this->Items.end(), i));
      }
    }
    void Clear()
    {
      for (const Id i : this->Items)
      {
        this->In[i] = 0;
      }
      this->Items.clear();
    }
  };

  CollapseScheduleBuilder(CollapseSchedule& schedule, const Id* triangles, Id numberOfTriangles,
    Id numberOfPoints, const Id* target, const std::int64_t* rank, const std::uint8_t* atTarget,
    const double* positions, const double* targetPositions, bool waitForFolds);

  // The collapses in rank order; one whose whole merge would leave its target without one fan
  // waits for a neighbour's merge. False when the schedule's AbortCheck stopped it.
  bool MakeCollapsesInOrder();
  // Those still waiting at the end, by groups of neighbours. False when the schedule's
  // AbortCheck stopped it.
  bool MakeWaitingGroups();
  // Per step (0 first): whether the mesh after it is valid to stop at.
  const std::vector<std::uint8_t>& ValidSteps() const { return this->Valid; }

private:
  // Whether the schedule's AbortCheck, asked before every AbortCheckInterval-th collapse c,
  // says to stop.
  bool AbortedAt(size_t c) const
  {
    const std::function<bool()>& aborted = this->Schedule.AbortCheck;
    return c % CollapseSchedule::AbortCheckInterval == 0 && aborted && aborted();
  }
  void ListCollapses();
  // Target t's sheets: those meeting at the one of its points on a curve where more than two
  // meet, else 1.
  int CountSheets(Id p);
  int SheetsAt(Id t);
  // When the link in From and To (of the vertex merged from Members) is not one fan: whether it
  // is the fan of a curve point where sheets meet, or one fan of a surface without consistent
  // orientation.
  bool OtherFanIsValid(Id t);
  // Whether Members of target t, merged into class `root` of `classes`, form one vertex with
  // one fan (or the fan of a curve point where sheets meet, or of a surface without consistent
  // orientation).
  bool FanIsValid(std::vector<Id>& classes, Id t, Id root);
  bool ValidInNextLevel(Id t);
  bool LinkEdge(Id tri, Id root, Id& from, Id& to);
  void Track(Id t);
  void Join(Id q, Id root, std::vector<std::array<Id, 3>>* removed);
  void Leave(Id q, const std::vector<std::array<Id, 3>>& removed);
  bool MayBeInconsistent(Id t);
  void ListMembers(Id t, Id extra);
  bool TrackedFanIsValid(Id t, Id extra);
  bool TargetHasOneFan(Id t, Id extra);
  bool ValidWith(Id p);
  // Whether the points settled on target t so far form one vertex with one fan.
  bool SettledHaveOneFan(Id t) { return this->TargetHasOneFan(t, Unassigned); }
  bool IsFolded(Id tri, Id extra);
  bool FoldsAround(Id p);
  void Record(Id p, Id t, bool ok);
  bool NextToSettled(Id q, Id t);
  void ListLeft(size_t begin, size_t end);
  void ListFrontier(size_t begin, size_t end, Id t);
  Id NextOfCollapse(const std::vector<Id>& choices, size_t points, bool& ok);
  // With `aroundLargest`, c is the largest collapse of a waiting group too large to interleave:
  // after each of its steps the group's small collapses of other targets next to it are made
  // whole when that is valid (MakeReadyNeighbours).
  void Settle(size_t c, bool wholeValid, bool aroundLargest = false);
  void MakeReadyNeighbours(Id p, size_t c, bool tracked);
  void SettleGroupAroundLargest();
  bool WholeIsValid(size_t c);
  void GatherGroup(size_t c);
  Id NextOfGroup(size_t largest, bool& ok);
  void SettleInterleaved(size_t largest);

  // Triangle t's three point ids.
  const Id* Triangle(Id t) const { return this->Triangles + 3 * static_cast<size_t>(t); }

  CollapseSchedule& Schedule;
  std::vector<Id>& Step; // the schedule's: per point, the step it settles at
  const Id* Triangles;
  const Id NumberOfTriangles;
  const Id NumberOfPoints;
  const Id* Target;
  const std::int64_t* Rank;
  // Geometry, when given: a point is at its own position until it settles, then at its
  // target's.
  const double* Positions;
  const double* TargetPositions;
  const bool Geometry;
  const bool WaitForFolds;

  Id NumberOfTargets = 0;
  std::vector<Id> TargetOffsets, TargetPoints; // the points of each target, in increasing id
  VertexTriangleAdjacency Adjacency;
  std::vector<Id> Moving; // the points that move, sorted by collapse (SortMovingPoints)
  std::vector<Id> Parent; // the union-find (FindRoot)
  std::vector<Id> SettledOn; // a settled point of each target

  // Per target, the sheets meeting at the one of its points on a curve where more than two
  // meet (the most triangles on one edge of a point), else 1; 0 until asked for (only when a
  // step fails the one-fan test, so that a manifold mesh never counts them).
  std::vector<int> SheetsOf;
  std::vector<Id> Neighbours;
  std::vector<Id> Members, From, To, Joined;
  std::vector<Id> Around;
  std::vector<std::pair<Id, Id>> Directed;
  // Per point, its target's first point: every point merged, as in the next level (built on
  // the first need); per target, whether its vertex there has one fan (0: not asked, 1 yes, 2
  // no).
  std::vector<Id> Merged;
  std::vector<std::uint8_t> NextLevelValid;
  // The link of the target whose collapse is being settled (`Tracked`), kept by `Link` (see
  // MergedLink); sized when first used (most transitions have no large collapse).
  MergedLink Link;
  bool LinkSized = false;
  Id Tracked = Unassigned;
  std::vector<std::array<Id, 3>> Undo;
  // Per target, whether two of the triangles around its points use the same directed edge (0:
  // not asked yet, 1: no, 2: yes).
  std::vector<std::uint8_t> InconsistentAt;
  // Targets that a step passed through left without one fan. A later step may stop only once
  // none is left: a step's own check sees its target only, and an earlier step's broken
  // target can stay broken (a non-manifold edge, a doubled triangle) while later steps
  // elsewhere pass theirs.
  std::vector<Id> Broken;
  std::vector<Id> Near; // the targets of the settled points next to a point that settles
  std::vector<std::uint8_t> Valid;

  // The collapses: Moving[begin, end) share their rank and target.
  std::vector<std::pair<size_t, size_t>> Collapses;
  std::vector<size_t> CollapseOfPoint; // Collapses.size() for a point that does not move
  // The points joined by an edge to a collapse's settled ones, kept sorted as points settle.
  SortedIds Frontier;
  std::vector<std::uint8_t> Waiting; // per collapse
  std::vector<Id> CheckedAt;          // per collapse: the step after which it was last tested
  size_t WaitingNow = 0;

  // A group of waiting collapses made together (MakeWaitingGroups).
  std::vector<size_t> Group;
  std::vector<Id> GroupPoints;
  SortedIds Candidates;       // indices into GroupPoints
  std::vector<Id> GroupIndex; // per point: its index in GroupPoints, or -1
  std::vector<std::uint8_t> StarterSeen;
};

} // namespace meshlod

#endif
