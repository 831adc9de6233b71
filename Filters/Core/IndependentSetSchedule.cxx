// The independent-set schedule (paper 000, section 6): passes of simultaneous collapses.
#include "Collapser.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <iterator>

namespace meshlod
{
namespace
{
// A pass chooses among the cheapest PoolFactor times as many triangles as its budget of
// removed triangles.
constexpr std::int64_t PoolFactor = 4;

// Triangles found illegal are retried after this many passes.
constexpr std::int64_t ParkedRetryPasses = 8;

// After this many passes in a row that each removed under StallShare of their budget, the
// greedy loop makes the rest of the level (see RunIndependentSets).
constexpr int StallPasses = 64;
constexpr double StallShare = 0.01;

// Passes with fewer items than this to evaluate, check or collapse do them on the calling
// thread: around a vertex of very high valence passes make one collapse each, and handing a
// few items to the thread pool thousands of times cost a quarter of such a run in waking and
// parking threads.
constexpr Id SerialItems = 32;

// What became of a triangle chosen in a pass (IndependentSetPass::Outcome).
enum : unsigned char
{
  Refused = 0,
  Collapsed = 1,
  NeedsSwap = 2,
  TooLarge = 3, // legal, but above MaximumError
  Skipped = 4,  // legal, not needed for this pass's budget
};

// f(begin, end) over [0, n): with vtkSMPTools, or on this thread when n is small.
template <typename F>
void ForItems(Id n, F&& f)
{
  if (n < SerialItems)
  {
    f(0, n);
  }
  else
  {
    vtkSMPTools::For(0, n, f);
  }
}
} // namespace

// The lists and scratch of the independent-set passes, kept from one pass to the next.
struct IndependentSetPass
{
  IndependentSetPass(Id triangles, Id vertices)
    : IsDirty(triangles, 0)
    , Owner(vertices, 0)
    , Live(triangles)
  {
    for (Id t = 0; t < triangles; ++t)
    {
      this->Live[t] = t;
    }
  }

  std::vector<unsigned char> IsDirty; // per triangle: listed in Dirty
  // Vertex -> 1 + the index of the pass's candidate whose neighbourhood holds it, 0 if none.
  std::vector<Id> Owner;
  std::vector<Id> Live, Dirty, Pool, Chosen, Owned, Survivors, Neighbourhood, Touched;
  // Per chosen triangle: its collapse and what became of it.
  std::vector<CollapseCandidate> Candidates;
  std::vector<unsigned char> Outcome;
  vtkSMPThreadLocal<CostScratch> Scratch;
  vtkSMPThreadLocal<Star> Stars;
};

//------------------------------------------------------------------------------
// Independent sets (paper 000, section 6): each pass collapses at once many cheap triangles
// whose stencils share no vertex.
TriangleCollapseResult Collapser::RunIndependentSets()
{
  this->EvaluateAll();
  IndependentSetPass pass(this->InitialTriangles, this->State.Mesh.GetNumberOfPoints());
  const auto markDirty = [&](Id s) { this->MarkDirty(pass, s); };
  int stalled = 0; // passes in a row that removed under StallShare of their budget
  while (!this->Finished())
  {
    ++this->Result.Passes;
    ++this->Clock;
    // 1. Re-weight what changed in the last pass.
    this->ReweighDirty(pass);

    // 2. The cheapest candidates: a pool a few times larger than what one pass can take.
    const std::int64_t budget = this->PassBudget();
    this->ListPool(pass);

    // 3. Choose, cheapest first, triangles whose neighbourhoods (every triangle around their
    // corners: it holds the stencil of the triangle's collapse and of each edge's) share no
    // vertex, until the pass's budget of removed triangles is reached (a little beyond it,
    // and a few dozen at least: some of the chosen will not be legal). These collapses are
    // independent: none can change another's legality, so they can be checked and made at
    // once. Only the cheapest PoolFactor * budget triangles are eligible, so that a pass stays
    // greedy even when their neighbourhoods overlap a lot; they are ordered a block at a time,
    // as far as the choice gets.
    this->ChooseIndependent(pass, budget);

    // 4. Check the chosen ones (in parallel), keep the cheapest legal ones up to the pass's
    // budget, and collapse those (in parallel). Collapse numbers follow the choice order, so
    // the levels' ranks do not depend on the thread count.
    const Id count = static_cast<Id>(pass.Chosen.size());
    this->CheckChosen(pass);
    std::int64_t removed = this->CollapseChosen(pass, budget);

    // 5. Triangles blocked by a low-valence apex try the swap (paper 000, figure 3), one after
    // the other: the swap reaches one ring beyond the chosen neighbourhood.
    const bool errorLimited = this->SettleChosen(pass, budget, removed);
    this->State.AliveTriangles -= static_cast<Id>(removed);
    for (const Id v : pass.Owned)
    {
      pass.Owner[v] = 0;
    }
    pass.Owned.clear();

    // 6. List for re-weighting the triangles whose weight changed: those around the survivors
    // (for the curvature method also one ring further out, whose stencils moved).
    this->ListChangedAroundSurvivors(pass);
    // Parked triangles further out may have become legal (valences and positions changed);
    // rather than searching for them around every collapse, look now and then.
    if (this->Result.Passes % ParkedRetryPasses == 0 || count == 0)
    {
      this->Lot.Release(this->State, markDirty);
    }
    // Stuck when nothing could be chosen and no refused triangle has a changed neighbourhood
    // (unless the star-shape test can still be relaxed).
    if (count == 0 && pass.Dirty.empty() &&
      !(this->RelaxForStall(markDirty) && !pass.Dirty.empty()))
    {
      break; // nothing collapsible (or allowed by MaximumError) is left
    }
    if (errorLimited || !this->AfterProgress())
    {
      break;
    }

    // 7. Passes that stall hand the rest of the level to the greedy loop, which takes the next
    // candidate as soon as one is made or refused instead of a pass later. Around a vertex of
    // very high valence a pass makes one collapse (a fan of 30,000 triangles took 12 s, 0.8 s
    // now); on a UV sphere of long thin triangles (116,000, theta resolution 1,000, phi 60)
    // with the TRIANGLES operator most choices were refused and the few candidates left were
    // crowded together: below 25,000 triangles passes removed a tenth of a triangle each, and
    // the run had not ended after five minutes (7 s now).
    stalled = removed < StallShare * static_cast<double>(budget) ? stalled + 1 : 0;
    if (stalled >= StallPasses && !this->Finished())
    {
      stalled = 0;
      if (!this->HandLevelToGreedy(pass))
      {
        break; // stuck, MaximumError reached or aborted
      }
    }
  }
  return this->FinishRun();
}

//------------------------------------------------------------------------------
void Collapser::MarkDirty(IndependentSetPass& pass, Id s)
{
  if (!pass.IsDirty[s])
  {
    pass.IsDirty[s] = 1;
    this->Lot.Unpark(s);
    pass.Dirty.push_back(s);
  }
}

//------------------------------------------------------------------------------
// New costs for the listed triangles (in parallel), which leave the list.
void Collapser::ReweighDirty(IndependentSetPass& pass)
{
  std::vector<Id>& dirty = pass.Dirty;
  ForItems(static_cast<Id>(dirty.size()), [&](Id begin, Id end) {
    CostScratch& mine = pass.Scratch.Local();
    for (Id i = begin; i < end; ++i)
    {
      this->Costs[dirty[i]] = this->EvaluateCost(dirty[i], mine);
    }
  });
  for (const Id t : dirty)
  {
    pass.IsDirty[t] = 0;
  }
  dirty.clear();
}

//------------------------------------------------------------------------------
std::int64_t Collapser::PassBudget() const
{
  const Id alive = this->State.AliveTriangles;
  // LevelFraction is the paper's fraction of triangles selected per pass; a triangle
  // collapse removes four, so a pass removes up to 4 * LevelFraction of the triangles, in
  // whatever mix of triangle and edge collapses.
  return std::min<std::int64_t>(
    std::max<std::int64_t>(1, static_cast<std::int64_t>(4.0 * this->Options.LevelFraction * alive)),
    static_cast<std::int64_t>(alive) - this->CurrentTarget());
}

//------------------------------------------------------------------------------
void Collapser::ListPool(IndependentSetPass& pass)
{
  std::vector<Id>& live = pass.Live;
  live.erase(
    std::remove_if(live.begin(), live.end(), [&](Id t) { return !this->State.IsAlive(t); }),
    live.end());
  // (A triangle refused here gets an infinite cost; one the greedy loop refused (step 7)
  // keeps its cost and waits in the parking lot.)
  pass.Pool.clear();
  std::copy_if(live.begin(), live.end(), std::back_inserter(pass.Pool),
    [&](Id t) { return this->Costs[t] < InfiniteCost && !this->Lot.IsParked(t); });
}

//------------------------------------------------------------------------------
void Collapser::ChooseIndependent(IndependentSetPass& pass, std::int64_t budget)
{
  std::vector<Id>& pool = pass.Pool;
  std::vector<Id>& owner = pass.Owner;
  std::vector<Id>& chosen = pass.Chosen;
  auto cheaper = [&](Id a, Id b) {
    return this->Costs[a] < this->Costs[b] || (this->Costs[a] == this->Costs[b] && a < b);
  };
  chosen.clear();
  std::int64_t estimate = 0;
  const std::int64_t wanted = budget + budget / 4 + 64;
  const std::size_t eligible =
    std::min<std::size_t>(pool.size(), static_cast<std::size_t>(PoolFactor * budget + 64));
  if (eligible < pool.size())
  {
    std::nth_element(pool.begin(), pool.begin() + eligible, pool.end(), cheaper);
  }
  // A candidate with a corner in a chosen neighbourhood stays blocked for the rest of the
  // pass, so the blocked ones are dropped before the next block is ordered (the same choice:
  // they would be skipped). Around a vertex of very high valence every stencil holds that
  // vertex: one choice there blocks the others, which a pass would otherwise sort in full.
  const auto cornerOwned = [&](Id t) {
    const Id* tri = this->State.Mesh.Triangle(t);
    return owner[tri[0]] || owner[tri[1]] || owner[tri[2]];
  };
  std::size_t left = eligible; // candidates [first, left) are still in the running
  std::size_t block = static_cast<std::size_t>(std::max<std::int64_t>(64, budget / 4));
  for (std::size_t first = 0; first < left && estimate < wanted; block *= 2)
  {
    if (first > 0)
    {
      left = static_cast<std::size_t>(
        std::remove_if(pool.begin() + first, pool.begin() + left, cornerOwned) - pool.begin());
    }
    const std::size_t last = std::min(left, first + block);
    if (last < left)
    {
      std::nth_element(pool.begin() + first, pool.begin() + last, pool.begin() + left, cheaper);
    }
    std::sort(pool.begin() + first, pool.begin() + last, cheaper);
    for (std::size_t i = first; i < last && estimate < wanted; ++i)
    {
      const Id t = pool[i];
      if (cornerOwned(t) || !this->ListNeighbourhood(pass, t))
      {
        continue;
      }
      chosen.push_back(t);
      const Id mark = static_cast<Id>(chosen.size());
      for (const Id v : pass.Neighbourhood)
      {
        if (!owner[v])
        {
          owner[v] = mark;
          pass.Owned.push_back(v);
        }
      }
      estimate += this->Choices[t] >= TriangleChoice ? 4 : 2; // at most
    }
    first = last;
  }
}

//------------------------------------------------------------------------------
bool Collapser::ListNeighbourhood(IndependentSetPass& pass, Id t) const
{
  const std::vector<Id>& owner = pass.Owner;
  std::vector<Id>& neighbourhood = pass.Neighbourhood;
  const Id* tri = this->State.Mesh.Triangle(t);
  neighbourhood.clear();
  bool blocked = false;
  // A vanishing piece may reach beyond the triangles around t's corners: all of it.
  Id piece[VanishingPieceVertices];
  int pieceCount = 0;
  if (this->Choices[t] == VanishChoice &&
    this->State.SmallPiece(t, nullptr, 0, piece, pieceCount) == PieceKind::Vanishing)
  {
    neighbourhood.assign(piece, piece + pieceCount);
    for (int m = 0; m < pieceCount; ++m)
    {
      blocked = blocked || owner[piece[m]];
    }
  }
  for (int k = 0; k < 3 && !blocked; ++k)
  {
    this->State.ForEachTriangle(tri[k], [&](Id n) {
      const Id* nt = this->State.Mesh.Triangle(n);
      blocked = blocked || owner[nt[0]] || owner[nt[1]] || owner[nt[2]];
      neighbourhood.push_back(nt[0]);
      neighbourhood.push_back(nt[1]);
      neighbourhood.push_back(nt[2]);
    });
  }
  return !blocked;
}

//------------------------------------------------------------------------------
void Collapser::CheckChosen(IndependentSetPass& pass) const
{
  const std::vector<Id>& chosen = pass.Chosen;
  std::vector<CollapseCandidate>& candidates = pass.Candidates;
  std::vector<unsigned char>& outcome = pass.Outcome;
  const Id count = static_cast<Id>(chosen.size());
  candidates.resize(count);
  outcome.assign(count, Refused);
  pass.Survivors.assign(count, InvalidId);
  ForItems(count, [&](Id begin, Id end) {
    CostScratch& mine = pass.Scratch.Local();
    Star& star = pass.Stars.Local();
    for (Id i = begin; i < end; ++i)
    {
      const Legality legality = this->CheckDirect(chosen[i], star, candidates[i], mine);
      candidates[i].Dying = static_cast<int>(star.Dying.size());
      if (legality == Legality::Legal)
      {
        outcome[i] = this->ErrorAllows(candidates[i].Error) ? Collapsed : TooLarge;
      }
      else if (legality == Legality::LowValenceApex && candidates[i].MemberCount == 3)
      {
        outcome[i] = NeedsSwap;
      }
    }
  });
}

//------------------------------------------------------------------------------
std::int64_t Collapser::CollapseChosen(IndependentSetPass& pass, std::int64_t budget)
{
  std::vector<CollapseCandidate>& candidates = pass.Candidates;
  std::vector<unsigned char>& outcome = pass.Outcome;
  const Id count = static_cast<Id>(pass.Chosen.size());
  std::int64_t removed = 0;
  for (Id i = 0; i < count; ++i)
  {
    if (outcome[i] == Collapsed && removed >= budget)
    {
      outcome[i] = Skipped; // the level's target is reached without it
    }
    removed += outcome[i] == Collapsed ? candidates[i].Dying : 0;
  }
  const std::int64_t base = this->Sequence;
  ForItems(count, [&](Id begin, Id end) {
    Star& star = pass.Stars.Local();
    for (Id i = begin; i < end; ++i)
    {
      if (outcome[i] == Collapsed)
      {
        this->State.GatherStar(candidates[i].Members, candidates[i].MemberCount, star);
        this->Collapse(star, candidates[i], base + i);
        pass.Survivors[i] = star.Members[0];
      }
    }
  });
  this->Sequence += count;
  return removed;
}

//------------------------------------------------------------------------------
bool Collapser::SettleChosen(IndependentSetPass& pass, std::int64_t budget, std::int64_t& removed)
{
  const std::vector<Id>& chosen = pass.Chosen;
  std::vector<CollapseCandidate>& candidates = pass.Candidates;
  std::vector<unsigned char>& outcome = pass.Outcome;
  const Id count = static_cast<Id>(chosen.size());
  bool errorLimited = false;
  Star& star = pass.Stars.Local();
  CostScratch& mine = pass.Scratch.Local();
  for (Id i = 0; i < count; ++i)
  {
    if (outcome[i] == NeedsSwap && removed < budget)
    {
      const Id t = chosen[i];
      outcome[i] = Refused;
      if (this->CheckDirect(t, star, candidates[i], mine) == Legality::LowValenceApex &&
        this->TrySwap(t, star, candidates[i], mine))
      {
        outcome[i] = this->ErrorAllows(candidates[i].Error) ? Collapsed : TooLarge;
        if (outcome[i] == Collapsed)
        {
          removed += this->Collapse(star, candidates[i], this->Sequence++);
          pass.Survivors[i] = star.Members[0];
        }
      }
    }
    if (outcome[i] == Collapsed)
    {
      this->Result.Swaps += candidates[i].Swapped ? 1 : 0;
      ++this->Result.Collapses;
    }
    else if (outcome[i] == TooLarge)
    {
      errorLimited = true;
    }
    else if (outcome[i] == Refused)
    {
      // Parked until a collapse nearby changes its neighbourhood (see step 6).
      this->Costs[chosen[i]] = InfiniteCost;
      this->Lot.Park(chosen[i], this->Clock);
    }
  }
  return errorLimited;
}

//------------------------------------------------------------------------------
void Collapser::ListChangedAroundSurvivors(IndependentSetPass& pass)
{
  const bool widen = this->Options.Method == CollapseMethod::Curvature;
  const auto markDirty = [&](Id s) { this->MarkDirty(pass, s); };
  for (const Id survivor : pass.Survivors)
  {
    if (survivor == InvalidId)
    {
      continue;
    }
    this->State.ForEachTriangle(survivor, [&](Id s) {
      markDirty(s);
      this->Lot.Touch(this->State.Mesh.Triangle(s), this->Clock);
    });
    if (widen)
    {
      this->ForEachTriangleOneRingOut(survivor, pass.Touched, markDirty);
    }
  }
}

//------------------------------------------------------------------------------
bool Collapser::HandLevelToGreedy(IndependentSetPass& pass)
{
  const auto markDirty = [&](Id s) { this->MarkDirty(pass, s); };
  // Every refused triangle gets its cost back (a refusal here set it to infinity) and the
  // triangles changed since are re-weighted, as the greedy loop expects of its costs.
  this->Lot.ReleaseAll(this->State, markDirty);
  this->ReweighDirty(pass);
  if (this->GreedySteps(this->CurrentTarget()) != StepsEnd::Reached)
  {
    return false;
  }
  // The curvature method's greedy loop left triangles to re-weigh (at a lowered cost): the
  // passes re-weigh them.
  for (Id t = 0; t < static_cast<Id>(this->Stale.size()); ++t)
  {
    if (this->Stale[t])
    {
      this->Stale[t] = 0;
      markDirty(t);
    }
  }
  return true;
}

} // namespace meshlod
