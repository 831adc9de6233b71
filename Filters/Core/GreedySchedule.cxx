// The greedy schedule (paper 002, section 2.4): always the cheapest legal collapse next.
#include "Collapser.h"

#include <algorithm>

namespace meshlod
{
namespace
{
// The parking lot is checked after this many collapses ...
constexpr std::int64_t ParkedRetryCollapses = 256;
// ... or after one collapse per this many waiting triangles, if that is later.
constexpr std::size_t ParkedRetryShare = 4;
// A triangle whose cost awaits re-evaluation waits in the heap at this fraction of its old cost
// (see GreedySteps). (0.7: about 10% faster on the 154k metaballs, same levels, but on a noisy
// sphere at 1% the paper's weight went from 2.1x to 8x vtkQuadricDecimation's Hausdorff
// distance.)
constexpr double StaleCostFactor = 0.5;
} // namespace

//------------------------------------------------------------------------------
TriangleCollapseResult Collapser::RunGreedy()
{
  this->EvaluateAll();
  if (!this->Finished())
  {
    this->GreedySteps(this->Targets.back());
  }
  return this->FinishRun();
}

//------------------------------------------------------------------------------
bool Collapser::MarkStale(Id s)
{
  if (!(this->Costs[s] < InfiniteCost))
  {
    return false;
  }
  this->Lot.Unpark(s);
  if (!this->Stale[s])
  {
    this->Costs[s] *= StaleCostFactor;
    this->Stale[s] = 1;
  }
  return true;
}

void Collapser::Reweigh(Id s, CostScratch& scratch)
{
  this->Lot.Unpark(s);
  if (this->RefitsLazily())
  {
    this->Stale[s] = 0;
  }
  this->Costs[s] = this->EvaluateCost(s, scratch);
}

//------------------------------------------------------------------------------
Collapser::StepsEnd Collapser::GreedySteps(std::int64_t until)
{
  // The heap's positions are the parallel rounds' (PartitionedGreedy.cxx), which hold no heap
  // now: the curvature method lands every level here, and a second array of a position per
  // triangle alive with the first was 4 bytes per input triangle of its peak memory.
  ResizeFresh(this->HeapPositions, this->InitialTriangles, InvalidId);
  IndexedHeap heap;
  heap.Attach(&this->Costs, &this->Spreads, this->HeapPositions.data());
  heap.Build([&](Id t) {
    return this->State.IsAlive(t) && this->Costs[t] < InfiniteCost && !this->Lot.IsParked(t);
  });

  Star star;
  CostScratch scratch;
  CollapseCandidate c;
  const std::int64_t progressEvery = std::max<std::int64_t>(1000, this->InitialTriangles / 200);
  const bool widen = this->RefitsLazily();
  std::vector<Id> touched;
  auto release = [&](Id s) { heap.Update(s); };
  // A new cost for triangle s; a triangle that cannot collapse any more leaves the heap.
  auto reweigh = [&](Id s) {
    this->Reweigh(s, scratch);
    if (this->Costs[s] < InfiniteCost)
    {
      heap.Update(s);
    }
    else
    {
      heap.Remove(s);
    }
  };
  // The curvature method's triangles one ring out are re-weighted lazily (each re-weighting is
  // a fit, a dozen per collapse): marked stale, they wait in the heap at StaleCostFactor times
  // their old cost and are re-weighted when they come to its top. Many are marked again, or
  // die, before they do. A stale triangle whose new cost is at least that fraction of its old
  // one comes up no later than it would have with its new cost, so wherever no cost falls
  // below half, the order is exactly that of re-weighting at once (ranked by the fit's
  // deviation, the 154k metaballs and a smooth sphere give the same levels), in about half the
  // time.
  auto defer = [&](Id s) {
    if (this->MarkStale(s))
    {
      heap.Update(s);
    }
    else
    {
      reweigh(s);
    }
  };
  if (widen)
  {
    this->Stale.resize(this->InitialTriangles, 0);
  }
  std::int64_t nextRelease = this->Clock + ParkedRetryCollapses;
  while (this->State.AliveTriangles > until)
  {
    if (heap.Empty() || this->Clock >= nextRelease)
    {
      this->Lot.Release(this->State, release);
      // A check costs time in proportion to the waiting triangles: space the checks so that
      // they cost a bounded amount per collapse however many triangles wait.
      nextRelease = this->Clock +
        std::max<std::int64_t>(ParkedRetryCollapses,
          static_cast<std::int64_t>(this->Lot.GetNumberOfWaiting() / ParkedRetryShare));
      if (heap.Empty() && !(this->RelaxForStall(release) && !heap.Empty()))
      {
        return StepsEnd::Stuck;
      }
    }
    const Id t = heap.Pop();
    if (widen && this->Stale[t])
    {
      reweigh(t);
      continue;
    }
    const UpcomingCandidates upcoming(heap, this->State);
    upcoming.Prefetch(0);
    if (this->Check(t, star, c, scratch) != Legality::Legal)
    {
      this->Lot.Park(t, this->Clock);
      continue;
    }
    upcoming.Prefetch(1);
    if (!this->Finished())
    {
      this->LandOnTarget(t, this->State.AliveTriangles - this->CurrentTarget(), star, c);
    }
    if (!this->ErrorAllows(c.Error))
    {
      return StepsEnd::Stopped;
    }
    const Id survivor = star.Members[0];
    const int dying = this->Collapse(star, c, this->Sequence++);
    this->Result.Swaps += c.Swapped ? 1 : 0;
    this->State.AliveTriangles -= dying;
    ++this->Result.Collapses;
    ++this->Clock;
    for (const Id d : star.Dying)
    {
      heap.Remove(d);
    }
    upcoming.Prefetch(2);

    // New costs around the survivor; its neighbours' valences and its position changed, which
    // the parking lot takes note of. For the curvature method the triangles one ring further
    // out are re-weighted too: their stencils moved.
    scratch.BeginSpokes(survivor, this->State.TriangleCount(survivor));
    const bool lazy = this->DefersAroundHub(survivor);
    this->State.ForEachTriangle(survivor, [&](Id s) {
      this->Lot.Touch(this->State.Mesh.Triangle(s), this->Clock);
      if (lazy)
      {
        defer(s);
      }
      else
      {
        reweigh(s);
      }
    });
    scratch.EndSpokes();
    upcoming.Prefetch(3);
    if (widen)
    {
      this->ForEachTriangleOneRingOut(survivor, touched, defer);
    }
    const bool levelReached =
      !this->Finished() && this->State.AliveTriangles <= this->CurrentTarget();
    if ((this->Result.Collapses % progressEvery == 0 || levelReached) && !this->AfterProgress())
    {
      return StepsEnd::Stopped;
    }
  }
  return StepsEnd::Reached;
}

} // namespace meshlod
