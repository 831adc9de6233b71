#include "CollapseSchedule.h"
#include "CollapseScheduleBuilder.h"
#include "GroupByKey.h"
#include "LinkFan.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace meshlod
{
namespace
{
// A collapse of m points tries at most max(1, CollapseTestBudget / m) next points per step (see
// NextOfCollapse). A test reads the merged vertex's link, kept up to date for a collapse of
// CollapseSchedule's TrackedCollapsePoints or more (with the default 8, a smaller one has fewer
// choices than tries anyway; with a larger setting an untracked collapse's tests list its whole
// merge, up to 8 times as many of them as at 16,384). At 16,384 a faceted cylinder's cap of 5,032
// points merging into its centre had three tries per step and left its target without one fan
// every 20 to 40 steps, for a few steps each time; with 26 (and its waiting group made around it,
// SettleGroupAroundLargest) 2.3% of the counts of that transition (48,128 to 4,812 triangles) are
// out of reach instead of 23%. Schedules with such collapses take longer: a UV sphere's octree
// level of 540 triangles from 636,800, 0.85 s instead of 0.65.
constexpr size_t CollapseTestBudget = 131072;
// A step of a waiting group joined interleaved tests at most max(1, TestBudget / m) points, m
// its largest collapse (each test lists the whole merged vertex).
constexpr size_t TestBudget = 16384;
// The points of collapses left waiting at the end join interleaved when together they number at
// most this many (each step may test up to TestBudget / m candidates, m the group's largest
// collapse), else one collapse after the other, the largest first (SettleGroupAroundLargest).
constexpr size_t InterleavedGroupPoints = 2048;
// In a larger group, the collapses of at most this many points are made as soon as their merge
// is valid while the largest one's points settle (tested after each step next to them: a test
// reads the whole merge, and on a UV sphere's single level of 636,800 -> 636 triangles testing
// collapses of thousands of points doubled the time of the schedule).
constexpr size_t ReadyCollapsePoints = 1024;
// Moving points sorted by collapse: (rank, -1 last), then target, then id.
std::vector<Id> SortMovingPoints(
  Id numberOfPoints, const Id* target, const std::int64_t* rank, const std::uint8_t* atTarget)
{
  std::vector<Id> moving;
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    if (!atTarget[p])
    {
      moving.push_back(p);
    }
  }
  auto key = [&](Id p) { return rank[p] < 0 ? std::numeric_limits<std::int64_t>::max() : rank[p]; };
  std::sort(moving.begin(), moving.end(), [&](Id a, Id b) {
    const std::int64_t ka = key(a), kb = key(b);
    if (ka != kb)
    {
      return ka < kb;
    }
    if (target[a] != target[b])
    {
      return target[a] < target[b];
    }
    return a < b;
  });
  return moving;
}
} // namespace

//------------------------------------------------------------------------------
CollapseScheduleBuilder::CollapseScheduleBuilder(CollapseSchedule& schedule, const Id* triangles,
  Id numberOfTriangles, Id numberOfPoints, const Id* target, const std::int64_t* rank,
  const std::uint8_t* atTarget, const double* positions, const double* targetPositions,
  bool waitForFolds)
  : Schedule(schedule)
  , Step(schedule.Step)
  , Triangles(triangles)
  , NumberOfTriangles(numberOfTriangles)
  , NumberOfPoints(numberOfPoints)
  , Target(target)
  , Rank(rank)
  , Positions(positions)
  , TargetPositions(targetPositions)
  , Geometry(positions != nullptr && targetPositions != nullptr)
  , WaitForFolds(waitForFolds && positions != nullptr && targetPositions != nullptr)
  , Valid(1, 1)
{
  this->Step.assign(numberOfPoints, Unassigned);
  this->Schedule.Order.clear();
  this->Schedule.WaitedForFolds = false;
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    if (atTarget[p])
    {
      this->Step[p] = 0;
    }
  }
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    this->NumberOfTargets = std::max(this->NumberOfTargets, target[p] + 1);
  }
  GroupByKey(
    static_cast<size_t>(this->NumberOfTargets),
    [&](auto&& emit) {
      for (Id p = 0; p < numberOfPoints; ++p)
      {
        emit(target[p], p);
      }
    },
    this->TargetOffsets, this->TargetPoints);
  this->Adjacency.Build(triangles, numberOfTriangles, numberOfPoints);

  this->Moving = SortMovingPoints(numberOfPoints, target, rank, atTarget);
  this->Schedule.Order.reserve(this->Moving.size());

  this->Parent.resize(numberOfPoints);
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    this->Parent[p] = p;
  }
  this->SettledOn.assign(this->NumberOfTargets, Unassigned);
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    if (this->Step[p] == 0)
    {
      const Id t = target[p];
      if (this->SettledOn[t] == Unassigned)
      {
        this->SettledOn[t] = p;
      }
      this->Parent[FindRoot(this->Parent, p)] = FindRoot(this->Parent, this->SettledOn[t]);
    }
  }
  this->SheetsOf.assign(this->NumberOfTargets, 0);
  this->NextLevelValid.assign(this->NumberOfTargets, 0);
  this->InconsistentAt.assign(this->NumberOfTargets, 0);

  this->ListCollapses();
  this->Frontier.In.assign(numberOfPoints, 0);
  this->Waiting.assign(this->Collapses.size(), 0);
}

// The collapses: runs of Moving with one rank and one target (points of rank -1 with one
// target together), and the collapse of each point.
void CollapseScheduleBuilder::ListCollapses()
{
  const Id* target = this->Target;
  const std::int64_t* rank = this->Rank;
  for (size_t begin = 0; begin < this->Moving.size();)
  {
    const Id first = this->Moving[begin];
    size_t end = begin + 1;
    while (end < this->Moving.size() && target[this->Moving[end]] == target[first] &&
      (rank[this->Moving[end]] < 0) == (rank[first] < 0) &&
      (rank[first] < 0 || rank[this->Moving[end]] == rank[first]))
    {
      ++end;
    }
    this->Collapses.emplace_back(begin, end);
    begin = end;
  }
  this->CollapseOfPoint.assign(this->NumberOfPoints, this->Collapses.size());
  for (size_t c = 0; c < this->Collapses.size(); ++c)
  {
    for (size_t i = this->Collapses[c].first; i < this->Collapses[c].second; ++i)
    {
      this->CollapseOfPoint[this->Moving[i]] = c;
    }
  }
}

//------------------------------------------------------------------------------
// Point p of target t settles as the next step; `ok`: the mesh after it is valid at t.
void CollapseScheduleBuilder::Record(Id p, Id t, bool ok)
{
  std::vector<Id>& order = this->Schedule.Order;
  order.push_back(p);
  this->Step[p] = static_cast<Id>(order.size());
  if (this->SettledOn[t] == Unassigned)
  {
    this->SettledOn[t] = p;
    if (t == this->Tracked)
    {
      this->Track(t);
    }
  }
  else if (t == this->Tracked)
  {
    this->Join(p, FindRoot(this->Parent, this->SettledOn[t]), nullptr);
  }
  this->Parent[FindRoot(this->Parent, p)] = FindRoot(this->Parent, this->SettledOn[t]);
  std::vector<Id>& broken = this->Broken;
  if (!ok && std::find(broken.begin(), broken.end(), t) == broken.end())
  {
    broken.push_back(t);
  }
  // The broken targets (this one included, when it was broken before) may have one fan
  // again now: t, and those with a point settled next to p. (Another target's vertex keeps
  // its link: only triangles with p as a corner change, and those with a corner settled on
  // it are next to p. Testing every broken target again after every step cost a single
  // level of 158,400 -> 1,584 triangles 3.4 of its 3.8 s.)
  std::vector<Id>& near = this->Near;
  near.clear();
  for (Id j = this->Adjacency.Begin(p); j < this->Adjacency.End(p) && !broken.empty(); ++j)
  {
    const Id* tri = this->Triangle(this->Adjacency.Triangles[j]);
    for (int k = 0; k < 3; ++k)
    {
      if (this->Step[tri[k]] != Unassigned)
      {
        near.push_back(this->Target[tri[k]]);
      }
    }
  }
  broken.erase(std::remove_if(broken.begin(), broken.end(),
                 [&](Id b) {
                   const bool changed =
                     b == t || std::find(near.begin(), near.end(), b) != near.end();
                   return changed && (b != t || ok) && this->SettledHaveOneFan(b);
                 }),
    broken.end());
  this->Valid.push_back(ok && broken.empty() ? 1 : 0);
}

//------------------------------------------------------------------------------
// Whether point q has a neighbour settled on target t.
bool CollapseScheduleBuilder::NextToSettled(Id q, Id t)
{
  for (Id j = this->Adjacency.Begin(q); j < this->Adjacency.End(q); ++j)
  {
    const Id* tri = this->Triangle(this->Adjacency.Triangles[j]);
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] != q && this->Target[tri[k]] == t && this->Step[tri[k]] != Unassigned)
      {
        return true;
      }
    }
  }
  return false;
}

// The points of collapse Moving[begin, end) not settled yet, in increasing id, into Joined.
void CollapseScheduleBuilder::ListLeft(size_t begin, size_t end)
{
  this->Joined.clear();
  for (size_t i = begin; i < end; ++i)
  {
    if (this->Step[this->Moving[i]] == Unassigned)
    {
      this->Joined.push_back(this->Moving[i]);
    }
  }
}

// The frontier of collapse Moving[begin, end) of target t listed from scratch: for a large
// collapse once, then kept up to date.
void CollapseScheduleBuilder::ListFrontier(size_t begin, size_t end, Id t)
{
  this->Frontier.Clear();
  for (size_t i = begin; i < end; ++i)
  {
    const Id q = this->Moving[i]; // increasing id: a collapse's points are sorted by id
    if (this->Step[q] == Unassigned && this->NextToSettled(q, t))
    {
      this->Frontier.Add(q); // (at the end: the ids come in increasing order)
    }
  }
}

// The next point of a collapse of `points` points among `choices`; `ok`: its merge keeps a
// valid mesh. Each test reads the whole merged vertex (its link, when tracked), so trying every
// joined point of every step cost a collapse of m points about m^3 (a sphere with points
// crowded at a pole had one of 6,971 points: 97 s). At most CollapseTestBudget / m joined
// points are tried per step: the first valid merge that folds nothing, else the first valid
// merge, else the first point. The fold test
// reads q's own triangles, the fan test the merged vertex's link: the fold test goes first,
// and the fan test of the first valid point is made only when none of them passes both (where
// merged points drag long triangles across, most tries fold; a UV sphere's octree levels spent
// 13 s on fan tests of points that folded).
Id CollapseScheduleBuilder::NextOfCollapse(const std::vector<Id>& choices, size_t points, bool& ok)
{
  const size_t tries = std::min(choices.size(), std::max<size_t>(1, CollapseTestBudget / points));
  Id p = Unassigned;
  for (size_t i = 0; i < tries && p == Unassigned; ++i)
  {
    const Id q = choices[i];
    p = !this->FoldsAround(q) && this->ValidWith(q) ? q : Unassigned;
  }
  for (size_t i = 0; i < tries && p == Unassigned; ++i)
  {
    p = this->ValidWith(choices[i]) ? choices[i] : Unassigned;
  }
  ok = p != Unassigned;
  return ok ? p : choices.front();
}

// Settle a collapse's points one by one, each time among the points joined by an edge to the
// settled ones (all the collapse's points left, when none is), in increasing id: the first
// whose merge keeps a valid mesh and folds no triangle around it; else the first whose merge
// keeps a valid mesh; else the first anyway (the step is then passed through, not stopped
// at). `wholeValid`: the whole merge was found valid, so the last point needs no test.
// Those joined points, the frontier, are kept sorted as points settle: a point settling
// joins its neighbours in the collapse, and nothing else does.
void CollapseScheduleBuilder::Settle(size_t c, bool wholeValid, bool aroundLargest)
{
  const size_t begin = this->Collapses[c].first, end = this->Collapses[c].second;
  const Id t = this->Target[this->Moving[begin]];
  const bool large = end - begin >= std::max<size_t>(1, this->Schedule.TrackedCollapsePoints);
  if (large)
  {
    this->Track(t);
  }
  for (size_t settled = begin; settled < end; ++settled)
  {
    if (settled == begin || !large)
    {
      this->ListFrontier(begin, end, t);
    }
    if (wholeValid && settled + 1 == end)
    {
      this->ListLeft(begin, end);
      this->Record(this->Joined.front(), t, true);
      break;
    }
    // None joined to a settled one (the target's first point, among others): any may go.
    const std::vector<Id>* choices = &this->Frontier.Items;
    if (this->Frontier.Items.empty())
    {
      this->ListLeft(begin, end);
      choices = &this->Joined;
    }
    bool ok = false;
    const Id p = this->NextOfCollapse(*choices, end - begin, ok);
    this->Record(p, t, ok);
    if (large)
    {
      this->Frontier.Remove(p);
      for (Id j = this->Adjacency.Begin(p); j < this->Adjacency.End(p); ++j)
      {
        const Id* tri = this->Triangle(this->Adjacency.Triangles[j]);
        for (int k = 0; k < 3; ++k)
        {
          const Id q = tri[k];
          if (this->CollapseOfPoint[q] == c && this->Step[q] == Unassigned)
          {
            this->Frontier.Add(q);
          }
        }
      }
    }
    if (aroundLargest)
    {
      this->MakeReadyNeighbours(p, c, large);
    }
  }
  this->Frontier.Clear();
  this->Link.Clear();
  this->Tracked = Unassigned;
}

// After point p of collapse c settled (c the largest of a waiting group, see
// SettleGroupAroundLargest): the group's other collapses of other targets, of at most
// ReadyCollapsePoints points, with a point next to p and whose whole merge is valid now (each
// tested once per step) are made at once. Their steps take the builder's frontier and link, so
// c's are listed again after them (its link only when c is `tracked`).
void CollapseScheduleBuilder::MakeReadyNeighbours(Id p, size_t c, bool tracked)
{
  const Id t = this->Target[p];
  const Id step = this->Step[p];
  std::vector<Id> frontier;
  bool made = false;
  for (Id j = this->Adjacency.Begin(p); j < this->Adjacency.End(p); ++j)
  {
    const Id* tri = this->Triangle(this->Adjacency.Triangles[j]);
    for (int k = 0; k < 3; ++k)
    {
      const size_t w = this->CollapseOfPoint[tri[k]];
      if (w >= this->Collapses.size() || !this->Waiting[w] || this->CheckedAt[w] == step ||
        this->Collapses[w].second - this->Collapses[w].first > ReadyCollapsePoints ||
        this->Target[this->Moving[this->Collapses[w].first]] == t)
      {
        continue;
      }
      this->CheckedAt[w] = step; // once per step, however many of p's triangles it touches
      if (!this->WholeIsValid(w))
      {
        continue;
      }
      if (!made)
      {
        // w's points join their target's class, which changes t's link where they touch it:
        // t is not tracked meanwhile (a test of t then lists its link afresh), and tracked
        // again after them.
        frontier = this->Frontier.Items;
        this->Link.Clear();
        this->Tracked = Unassigned;
        made = true;
      }
      this->Waiting[w] = 0;
      this->Settle(w, true);
    }
  }
  if (!made)
  {
    return;
  }
  this->Frontier.Clear();
  for (const Id q : frontier)
  {
    this->Frontier.Add(q);
  }
  if (tracked)
  {
    this->Track(t);
  }
}

// A waiting group too large to interleave: its largest collapse first, the others each made
// whole as soon as that is valid as the largest one's points settle (MakeReadyNeighbours),
// those left after it in the group's order. Such a group is typically one flat region merging
// into a single point, next to small collapses that each wait for part of it while it waits
// for them (a faceted cylinder's cap of 5,032 points merging into its centre, between levels
// of 48,128 and 4,812 triangles): made one after the other, the first small one left its
// target without one fan through most of the large one's steps, 939 steps in a row that no
// count could stop at.
void CollapseScheduleBuilder::SettleGroupAroundLargest()
{
  size_t largest = this->Group.front();
  for (const size_t made : this->Group)
  {
    const size_t points = this->Collapses[made].second - this->Collapses[made].first;
    if (points > this->Collapses[largest].second - this->Collapses[largest].first)
    {
      largest = made;
    }
  }
  if (this->CheckedAt.empty())
  {
    this->CheckedAt.assign(this->Collapses.size(), Unassigned);
  }
  for (const size_t made : this->Group)
  {
    this->Waiting[made] = made == largest ? 0 : 1;
  }
  this->Settle(largest, false, true);
  // Then those whose merge is valid now, as long as there are any, and the rest.
  for (bool any = true; any;)
  {
    any = false;
    for (const size_t made : this->Group)
    {
      if (this->Waiting[made] && this->WholeIsValid(made))
      {
        this->Waiting[made] = 0;
        this->Settle(made, true);
        any = true;
      }
    }
  }
  for (const size_t made : this->Group)
  {
    if (this->Waiting[made])
    {
      this->Waiting[made] = 0;
      this->Settle(made, false);
    }
  }
}

//------------------------------------------------------------------------------
// Whether collapse c, made whole now, would leave its target with one fan: its points merged
// for the test and put back (unsettled points are their own roots, so the union-find is
// restored by resetting them).
bool CollapseScheduleBuilder::WholeIsValid(size_t c)
{
  const size_t begin = this->Collapses[c].first, end = this->Collapses[c].second;
  const Id t = this->Target[this->Moving[begin]];
  const Id savedOn = this->SettledOn[t];
  if (this->SettledOn[t] == Unassigned)
  {
    this->SettledOn[t] = this->Moving[begin];
  }
  const Id root = FindRoot(this->Parent, this->SettledOn[t]);
  for (size_t i = begin; i < end; ++i)
  {
    this->Step[this->Moving[i]] = CollapseSchedule::Never; // settled, for the test
    this->Parent[this->Moving[i]] = root;
  }
  bool whole = this->SettledHaveOneFan(t);
  for (size_t i = begin; i < end && whole && this->WaitForFolds; ++i)
  {
    whole = !this->FoldsAround(this->Moving[i]);
    this->Schedule.WaitedForFolds = this->Schedule.WaitedForFolds || !whole;
  }
  for (size_t i = begin; i < end; ++i)
  {
    this->Step[this->Moving[i]] = Unassigned;
    this->Parent[this->Moving[i]] = this->Moving[i];
  }
  this->SettledOn[t] = savedOn;
  return whole;
}

//------------------------------------------------------------------------------
// The collapses in order; one whose whole merge would leave its target without one fan waits
// for a neighbour's merge (see the header). After each collapse made, the waiting ones next
// to it are tried again.
bool CollapseScheduleBuilder::MakeCollapsesInOrder()
{
  const size_t collapses = this->Collapses.size();
  std::vector<size_t> waitingOfTarget(this->NumberOfTargets, collapses);
  std::vector<size_t> triedAfter(collapses, collapses); // at most once per made
  std::vector<size_t> retry;
  for (size_t c = 0; c < collapses; ++c)
  {
    if (this->AbortedAt(c))
    {
      return false;
    }
    const Id t = this->Target[this->Moving[this->Collapses[c].first]];
    if (waitingOfTarget[t] < collapses || !this->WholeIsValid(c))
    {
      // (A second collapse of a target that waits waits until the end.)
      this->Waiting[c] = 1;
      waitingOfTarget[t] = std::min(waitingOfTarget[t], c);
      ++this->WaitingNow;
      continue;
    }
    retry.assign(1, c);
    while (!retry.empty())
    {
      const size_t made = retry.back();
      retry.pop_back();
      this->Settle(made, true);
      // Waiting collapses whose target has a point next to this collapse's points (none to
      // look for, the usual case, when nothing waits).
      for (size_t i = this->Collapses[made].first;
           i < this->Collapses[made].second && this->WaitingNow > 0; ++i)
      {
        const Id q = this->Moving[i];
        for (Id j = this->Adjacency.Begin(q); j < this->Adjacency.End(q); ++j)
        {
          const Id* tri = this->Triangle(this->Adjacency.Triangles[j]);
          for (int k = 0; k < 3; ++k)
          {
            const size_t w = waitingOfTarget[this->Target[tri[k]]];
            if (w >= collapses || !this->Waiting[w] || triedAfter[w] == made)
            {
              continue;
            }
            triedAfter[w] = made;
            if (this->WholeIsValid(w))
            {
              this->Waiting[w] = 0;
              --this->WaitingNow;
              waitingOfTarget[this->Target[tri[k]]] = collapses;
              retry.push_back(w);
            }
          }
        }
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
// Those still waiting at the end need each other (each valid only once the other is made).
// They are made by groups of neighbours, one group after the other, each in the order its
// members are reached from its first: once a group is whole, its targets are as in the next
// level, so the steps between groups can be stopped at (made in plain order, one broken
// target kept every later step unstoppable: an extruded text's 19,820-triangle level was the
// only count below 31,579).
bool CollapseScheduleBuilder::MakeWaitingGroups()
{
  if (this->WaitingNow > 0)
  {
    this->GroupIndex.assign(this->NumberOfPoints, -1);
    this->StarterSeen.assign(this->NumberOfTargets, 0);
  }
  for (size_t c = 0; c < this->Collapses.size(); ++c)
  {
    if (this->AbortedAt(c))
    {
      return false;
    }
    if (!this->Waiting[c])
    {
      continue;
    }
    this->GatherGroup(c);
    size_t groupSize = 0, largest = 0;
    for (const size_t made : this->Group)
    {
      const size_t points = this->Collapses[made].second - this->Collapses[made].first;
      groupSize += points;
      largest = std::max(largest, points);
    }
    if (groupSize > InterleavedGroupPoints)
    {
      this->SettleGroupAroundLargest();
      continue;
    }
    this->SettleInterleaved(largest);
  }
  return true;
}

// Waiting collapse c and the waiting collapses reached from it over their points' triangles,
// into Group (no longer waiting).
void CollapseScheduleBuilder::GatherGroup(size_t c)
{
  this->Waiting[c] = 0;
  this->Group.assign(1, c);
  for (size_t g = 0; g < this->Group.size(); ++g)
  {
    const size_t made = this->Group[g];
    for (size_t i = this->Collapses[made].first; i < this->Collapses[made].second; ++i)
    {
      const Id q = this->Moving[i];
      for (Id j = this->Adjacency.Begin(q); j < this->Adjacency.End(q); ++j)
      {
        const Id* tri = this->Triangle(this->Adjacency.Triangles[j]);
        for (int k = 0; k < 3; ++k)
        {
          const size_t w = this->CollapseOfPoint[tri[k]];
          if (w < this->Collapses.size() && this->Waiting[w])
          {
            this->Waiting[w] = 0;
            this->Group.push_back(w);
          }
        }
      }
    }
  }
}

// The next point of the group among the candidates (see SettleInterleaved), `largest` the
// group's largest collapse; `ok`: its join leaves its target with one fan.
Id CollapseScheduleBuilder::NextOfGroup(size_t largest, bool& ok)
{
  Id best = Unassigned;
  // 1 + 2 when it fixes a broken target, + 1 when it folds nothing around it; 0: its
  // target is left without one fan.
  int bestClass = 0;
  const int topClass = this->Broken.empty() ? 2 : 4;
  size_t tests = std::max<size_t>(1, TestBudget / largest);
  const std::vector<Id>& candidates = this->Candidates.Items;
  for (size_t c = 0; c < candidates.size() && tests > 0 && bestClass < topClass; ++c, --tests)
  {
    const Id q = this->GroupPoints[static_cast<size_t>(candidates[c])];
    const bool fixes =
      std::find(this->Broken.begin(), this->Broken.end(), this->Target[q]) != this->Broken.end();
    const int least = 1 + (fixes ? 2 : 0); // its class if valid, folding or not
    if (least + 1 <= bestClass || !this->ValidWith(q))
    {
      continue;
    }
    const int cls = least + (this->FoldsAround(q) ? 0 : 1);
    if (cls > bestClass)
    {
      best = q;
      bestClass = cls;
    }
  }
  ok = best != Unassigned;
  Id p = best;
  if (p == Unassigned)
  {
    p = candidates.empty() ? Unassigned
                           : this->GroupPoints[static_cast<size_t>(candidates.front())];
    for (size_t i = 0; p == Unassigned && i < this->GroupPoints.size(); ++i)
    {
      p = this->Step[this->GroupPoints[i]] == Unassigned ? this->GroupPoints[i] : Unassigned;
    }
  }
  return p;
}

// The group's points join their targets interleaved. The candidates, in the group's order:
// the points next to a point settled on their target, and the first point of each target with
// none settled. Each step takes the first candidate whose join leaves its target with one fan,
// one of a broken target first, one that folds nothing around it first; else the first
// candidate.
void CollapseScheduleBuilder::SettleInterleaved(size_t largest)
{
  this->GroupPoints.clear();
  for (const size_t made : this->Group)
  {
    for (size_t i = this->Collapses[made].first; i < this->Collapses[made].second; ++i)
    {
      this->GroupIndex[this->Moving[i]] = static_cast<Id>(this->GroupPoints.size());
      this->GroupPoints.push_back(this->Moving[i]);
    }
  }
  this->Candidates.Items.clear();
  this->Candidates.In.assign(this->GroupPoints.size(), 0);
  const auto candidate = [&](Id q) {
    if (this->GroupIndex[q] >= 0 && this->Step[q] == Unassigned)
    {
      this->Candidates.Add(this->GroupIndex[q]);
    }
  };
  for (const Id q : this->GroupPoints)
  {
    const Id t = this->Target[q];
    if (this->SettledOn[t] == Unassigned ? !this->StarterSeen[t] : this->NextToSettled(q, t))
    {
      this->StarterSeen[t] = 1;
      candidate(q);
    }
  }
  for (size_t left = this->GroupPoints.size(); left > 0; --left)
  {
    bool ok = false;
    const Id p = this->NextOfGroup(largest, ok);
    this->Record(p, this->Target[p], ok);
    this->Candidates.Remove(this->GroupIndex[p]);
    for (Id j = this->Adjacency.Begin(p); j < this->Adjacency.End(p); ++j)
    {
      const Id* tri = this->Triangle(this->Adjacency.Triangles[j]);
      for (int k = 0; k < 3; ++k)
      {
        if (this->Target[tri[k]] == this->Target[p])
        {
          candidate(tri[k]);
        }
      }
    }
  }
  for (const Id q : this->GroupPoints)
  {
    this->GroupIndex[q] = -1;
    this->StarterSeen[this->Target[q]] = 0;
  }
}

//------------------------------------------------------------------------------
bool CollapseSchedule::Build(const Id* triangles, Id numberOfTriangles, Id numberOfPoints,
  const Id* target, const std::int64_t* rank, const std::uint8_t* atTarget,
  const double* positions, const double* targetPositions, bool waitForFolds)
{
  {
    CollapseScheduleBuilder builder(*this, triangles, numberOfTriangles, numberOfPoints, target,
      rank, atTarget, positions, targetPositions, waitForFolds);
    if (!builder.MakeCollapsesInOrder() || !builder.MakeWaitingGroups())
    {
      return false;
    }
    const std::vector<std::uint8_t>& valid = builder.ValidSteps();
    this->Stops.clear();
    for (size_t step = 0; step < valid.size(); ++step)
    {
      if (valid[step])
      {
        this->Stops.push_back(static_cast<Id>(step));
      }
    }
  }

  // A triangle disappears when the second of two corners with the same target settles.
  this->RemovalStep.resize(numberOfTriangles);
  vtkSMPTools::For(0, numberOfTriangles, [&](Id b, Id e) {
    for (Id tri = b; tri < e; ++tri)
    {
      const Id* v = triangles + 3 * static_cast<size_t>(tri);
      Id removal = Never;
      for (int k = 0; k < 3; ++k)
      {
        const Id x = v[k], y = v[(k + 1) % 3];
        if (target[x] == target[y])
        {
          removal = std::min(removal, std::max(this->Step[x], this->Step[y]));
        }
      }
      this->RemovalStep[tri] = removal;
    }
  });

  const Id steps = this->NumberOfSteps();
  this->CountAfter.assign(static_cast<size_t>(steps) + 1, 0);
  for (Id tri = 0; tri < numberOfTriangles; ++tri)
  {
    if (this->RemovalStep[tri] != Never)
    {
      ++this->CountAfter[this->RemovalStep[tri]];
    }
  }
  // Removed by step k -> left after step k.
  Id removed = 0;
  for (Id k = 0; k <= steps; ++k)
  {
    removed += this->CountAfter[k];
    this->CountAfter[k] = numberOfTriangles - removed;
  }
  return true;
}

//------------------------------------------------------------------------------
Id CollapseSchedule::NumberOfReachableCounts() const
{
  Id counts = 0;
  for (size_t i = 0; i < this->Stops.size(); ++i)
  {
    counts += i == 0 || this->CountAfter[this->Stops[i]] != this->CountAfter[this->Stops[i - 1]];
  }
  return counts;
}

//------------------------------------------------------------------------------
Id CollapseSchedule::StepsForCount(std::int64_t count) const
{
  // Counts only decrease along the steps, so they do along the stops too.
  const auto it = std::partition_point(this->Stops.begin(), this->Stops.end(),
    [&](Id step) { return this->CountAfter[step] > count; });
  return it == this->Stops.end() ? -1 : *it;
}

//------------------------------------------------------------------------------
Id CollapseSchedule::NextRemovingStep(Id steps) const
{
  const Id now = this->CountAfter[steps];
  const auto it = std::partition_point(this->Stops.begin(), this->Stops.end(),
    [&](Id step) { return step <= steps || this->CountAfter[step] == now; });
  return it == this->Stops.end() ? -1 : *it;
}

} // namespace meshlod
