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
// (see DeferInHeap). (0.7: about 10% faster on the 154k metaballs, same levels, but on a noisy
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
  if (!this->Stale.empty()) // (the curvature method's, once a greedy loop has sized it)
  {
    this->Stale[s] = 0;
  }
  this->Costs[s] = this->EvaluateCost(s, scratch);
}

//------------------------------------------------------------------------------
Collapser::StepsEnd Collapser::GreedySteps(std::int64_t until)
{
  IndexedHeap heap;
  this->BuildGreedyHeap(heap);
  this->Reweighed.clear(); // (the heap has their costs: it was built after them)

  Star star;
  CostScratch scratch;
  CollapseCandidate c;
  const std::int64_t progressEvery = std::max<std::int64_t>(1000, this->InitialTriangles / 200);
  const bool widen = this->RefitsLazily();
  std::vector<Id> touched;
  auto reweigh = [&](Id s) { this->ReweighInHeap(s, heap, scratch); };
  auto defer = [&](Id s) { this->DeferInHeap(s, heap, scratch); };
  if (widen)
  {
    this->Stale.resize(this->InitialTriangles, 0);
  }
  std::int64_t nextRelease = this->Clock + ParkedRetryCollapses;
  while (this->State.AliveTriangles > until)
  {
    if ((heap.Empty() || this->Clock >= nextRelease) && !this->ReleaseParked(heap, nextRelease))
    {
      return StepsEnd::Stuck;
    }
    const Id t = heap.Pop();
    if (widen && this->Stale[t])
    {
      reweigh(t);
      continue;
    }
    const UpcomingCandidates upcoming(heap, this->State);
    upcoming.Prefetch(0);
    const Legality legality = this->Check(t, star, c, scratch);
    if (legality == Legality::Illegal && this->OtherLegalEdge(t, star, c))
    {
      this->Requeue(t, c);
      heap.Update(t);
      continue;
    }
    if (legality != Legality::Legal)
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
    this->ReweighAroundSurvivor(survivor, this->Clock, scratch, reweigh, defer);
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
    this->UpdateAfterRetriangulation(heap);
  }
  return StepsEnd::Reached;
}

//------------------------------------------------------------------------------
void Collapser::BuildGreedyHeap(IndexedHeap& heap)
{
  // The heap's positions are the parallel rounds' (PartitionedGreedy.cxx), which hold no heap
  // now: the curvature method lands every level here, and a second array of a position per
  // triangle alive with the first was 4 bytes per input triangle of its peak memory.
  ResizeFresh(this->HeapPositions, this->InitialTriangles, InvalidId);
  heap.Attach(&this->Costs, &this->Spreads, this->HeapPositions.data());
  heap.Build([&](Id t) {
    return this->State.IsAlive(t) && this->Costs[t] < InfiniteCost && !this->Lot.IsParked(t);
  });
}

//------------------------------------------------------------------------------
bool Collapser::ReleaseParked(IndexedHeap& heap, std::int64_t& nextRelease)
{
  auto release = [&](Id s) { heap.Update(s); };
  this->Lot.Release(this->State, release);
  // A check costs time in proportion to the waiting triangles: space the checks so that
  // they cost a bounded amount per collapse however many triangles wait.
  nextRelease = this->Clock +
    std::max<std::int64_t>(ParkedRetryCollapses,
      static_cast<std::int64_t>(this->Lot.GetNumberOfWaiting() / ParkedRetryShare));
  if (heap.Empty() && !(this->RelaxForStall(release) && !heap.Empty()))
  {
    return false; // stuck
  }
  return true;
}

} // namespace meshlod
