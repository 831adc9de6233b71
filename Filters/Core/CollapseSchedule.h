// MeshLOD core: the order in which the collapses of one transition M_i -> M_i+1 are applied one
// point at a time, and how many triangles are left after each step. vtkLODGeomorph uses it to
// produce a mesh with an exact number of triangles.
//
// A point "settles" when it reaches its target (the point of level i+1 it becomes). A triangle
// disappears as soon as two of its corners have settled on the same target. The steps:
// - Step 0: the points already at their target (among them the points with CollapseRank -1,
//   which keep their position).
// - Then every other point, one per step. Collapses in increasing CollapseRank (a moving point
//   with rank -1 counts as a collapse after all the others), the collapses of one rank in
//   increasing target id. Points of one rank with the same target form one collapse; inside
//   it, the next point is the lowest-id point joined by an edge to a point already settled on
//   that target, or the lowest-id point left when none is.
//   Settling a point next to a settled one is an edge collapse, so the intermediate meshes of a
//   valid triangle collapse stay manifold, and a closed manifold loses two triangles per step.
//   A level transition composes several collapses, though, and joining its points one by one
//   can pass through a mesh that is not manifold (a pinched vertex, a doubled triangle). Each
//   step is therefore checked: the merged point must keep one fan of triangles (a disk or a
//   half-disk) with no edge used twice, or, when one of its target's points is on a curve
//   where k > 2 sheets meet, k fans between its two neighbours on the curve. (The fan follows
//   the triangles' winding; on a mesh whose orientation is not consistent, such as a Moebius
//   strip or Boy's surface, its link edges need only form one path or cycle whatever their
//   direction.) Steps that fail are passed through, never stopped at, and so are the steps
//   after them until every target such a step left without one fan has one again (a step's own
//   check sees its own target only): their triangle counts are not reachable.
// - A collapse whose whole merge would leave its target without one fan at its turn waits:
//   a transition composes a level's collapses per target, and the rank order can come to a
//   target before the neighbour whose merge makes it valid (two points sharing two neighbours
//   merge into a doubled triangle until those neighbours are merged). Made in rank order, all
//   the steps up to that neighbour were unreachable. After each collapse, the waiting ones with
//   a point next to it are tried again and made as soon as they are valid. Those still waiting
//   at the end need each other: they are made last, by groups of neighbours one group after
//   the other, so that the steps between groups can be stopped at. Inside a group of at most
//   2,048 points the points of its collapses join interleaved: each step the first point (in
//   the group's order, among those next to a point settled on their target and the first point
//   of each target not begun) whose join leaves its target with one fan, one of a target left
//   without one first, one that folds nothing first. (Joined one collapse after the other, the
//   thin strokes of an extruded text, shrunk into single points each merging up to 103, left
//   433 of a transition's 5,487 counts out of reach, by up to 472 triangles; now 21, by 36.)
//   A larger group goes around its largest collapse: that one first, each other one of another
//   target and of at most 1,024 points made whole as soon as its merge is valid as the largest
//   one's points settle (tested after each of its steps next to it), the rest after it.
//   (Typically a flat region merging into one point, next to small collapses that wait for
//   part of it while it waits for them: made one after the other, the first small one left
//   its target without one fan through most of the large one's steps.)
// - Both rules apply only to targets that have one fan in the next level (every point merged).
//   A level with non-manifold vertices (vertex clustering with PreserveTopology off) has
//   targets that no step can give one: they neither wait nor hold later steps up, so the steps
//   through them are stops like any other (each step still checks its own target; a target
//   passed through this way may be in a state the next level does not have).
#ifndef meshlod_CollapseSchedule_h
#define meshlod_CollapseSchedule_h

#include "TriangleMesh.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT CollapseSchedule
{
  /// RemovalStep of a triangle that survives the whole transition.
  static constexpr Id Never = 0x7fffffff;

  std::vector<Id> Step;        // per point: the step at which it settles (0: from the start)
  std::vector<Id> Order;       // Order[s - 1] is the point that settles at step s
  std::vector<Id> RemovalStep; // per triangle: the step at which it disappears, or Never
  std::vector<Id> CountAfter;  // triangles left after k steps, k = 0 .. NumberOfSteps()
  std::vector<Id> Stops;       // the steps whose mesh is valid to stop at, increasing (0 first)
  bool WaitedForFolds = false; // a collapse waited because its merge would fold (waitForFolds)
  /// A collapse of at least this many points keeps its merged vertex's link up to date as its
  /// points join, in time that grows with the points of the collapse times the length of its
  /// rim; a smaller one lists the link again from every merged point at each test, which costs
  /// less for a few points and about m^2 for m points (a UV sphere's octree levels of 636,800
  /// -> 540 triangles took 44 s). The schedule is the same either way. Range [1, any], default 8.
  size_t TrackedCollapsePoints = 8;
  /// Asked between collapses while the order is made (every AbortCheckInterval collapses):
  /// true stops the build, and Build returns false with the schedule left unusable. Empty: never
  /// asked.
  std::function<bool()> AbortCheck;
  static constexpr std::size_t AbortCheckInterval = 1024;

  /// `target` and `rank` hold one entry per point; `atTarget[p]` is non-zero when point p is
  /// already at its target position. With `positions` and `targetPositions` (x, y, z per point:
  /// where it is, where it goes), a collapse's points join, where they can, in an order that folds
  /// no triangle over (see IsFolded, CollapseScheduleFans.cxx); with `waitForFolds` too, a collapse
  /// whose whole merge would fold a triangle waits like one that would leave its target without one
  /// fan.
  /// Returns false when AbortCheck stopped it.
  bool Build(const Id* triangles, Id numberOfTriangles, Id numberOfPoints, const Id* target,
    const std::int64_t* rank, const std::uint8_t* atTarget, const double* positions = nullptr,
    const double* targetPositions = nullptr, bool waitForFolds = false);

  /// How many different triangle counts the steps that can be stopped at give.
  Id NumberOfReachableCounts() const;

  Id NumberOfSteps() const { return static_cast<Id>(this->Order.size()); }

  /// The fewest steps, among those that can be stopped at, that leave at most `count`
  /// triangles, or -1 when even all steps leave more.
  Id StepsForCount(std::int64_t count) const;

  /// The first step after `steps` that can be stopped at and leaves fewer triangles, or -1
  /// when none does.
  Id NextRemovingStep(Id steps) const;
};

} // namespace meshlod

#endif
