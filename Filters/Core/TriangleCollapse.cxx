#include "TriangleCollapse.h"

#include "CollapseCosts.h"
#include "CollapseMesh.h"
#include "IndexedHeap.h"
#include "LevelData.h"
#include "LevelTracker.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <limits>

namespace meshlod
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

// Independent sets: a pass chooses among the cheapest PoolFactor times as many triangles as
// its budget of removed triangles.
constexpr std::int64_t PoolFactor = 4;

// Independent sets: triangles found illegal are retried after this many passes.
constexpr std::int64_t ParkedRetryPasses = 8;

// Rows are rebuilt once this fraction of the triangles alive at the last rebuild has died.
constexpr double RebuildAfterDying = 0.5;

// Triangles refused by the legality check wait here until something around them changes: a
// collapse moves vertices and changes valences, which can make a refused collapse legal.
// "Time" is any increasing counter (collapses for the greedy schedule, passes for the
// independent sets); rather than searching around every collapse for refused triangles, the
// lot is checked now and then.
class ParkingLot
{
public:
  ParkingLot(Id triangles, Id vertices)
    : ParkedAt(triangles, -1)
    , ChangedAt(vertices, 0)
  {
  }

  void Park(Id t, std::int64_t now)
  {
    if (this->ParkedAt[t] < 0)
    {
      this->Waiting.push_back(t);
    }
    this->ParkedAt[t] = now;
  }

  /// The triangle was re-weighted for another reason: it is no longer waiting.
  void Unpark(Id t) { this->ParkedAt[t] = -1; }

  /// Every vertex of triangle t changed (position, neighbours) at `now`.
  void Touch(const Id* t, std::int64_t now)
  {
    this->ChangedAt[t[0]] = this->ChangedAt[t[1]] = this->ChangedAt[t[2]] = now;
  }

  /// Call release(t) for every live waiting triangle with a vertex of a triangle around its
  /// corners changed after it was parked; those leave the lot.
  template <typename F>
  void Release(const CollapseMesh& state, F&& release)
  {
    std::size_t kept = 0;
    for (const Id t : this->Waiting)
    {
      if (this->ParkedAt[t] < 0 || !state.IsAlive(t))
      {
        this->ParkedAt[t] = -1;
        continue;
      }
      bool changed = false;
      const Id* tri = state.Mesh.Triangle(t);
      const std::int64_t since = this->ParkedAt[t];
      for (int k = 0; k < 3 && !changed; ++k)
      {
        state.ForEachTriangle(tri[k], [&](Id n) {
          const Id* nt = state.Mesh.Triangle(n);
          changed = changed || this->ChangedAt[nt[0]] > since || this->ChangedAt[nt[1]] > since ||
            this->ChangedAt[nt[2]] > since;
        });
      }
      if (changed)
      {
        this->ParkedAt[t] = -1;
        release(t);
      }
      else
      {
        this->Waiting[kept++] = t;
      }
    }
    this->Waiting.resize(kept);
  }

  std::size_t GetNumberOfWaiting() const { return this->Waiting.size(); }

private:
  std::vector<std::int64_t> ParkedAt; // per triangle, -1 when not waiting
  std::vector<std::int64_t> ChangedAt; // per vertex
  std::vector<Id> Waiting;
};

// Greedy schedule: the parking lot is checked after this many collapses.
constexpr std::int64_t ParkedRetryCollapses = 256;
// ... or after one collapse per this many waiting triangles, if that is later.
constexpr std::size_t ParkedRetryShare = 4;

// State shared by both schedules: the mesh, the level bookkeeping, the costs.
class Collapser
{
public:
  Collapser(TriangleMesh&& mesh, TriangleTopology&& topology,
    const TriangleCollapseOptions& options, const TriangleCollapseCallbacks& callbacks)
    : Options(options)
    , Callbacks(callbacks)
    , Model(options, State, Tracker, OriginalPoints)
  {
    const bool curvature = options.Method == CollapseMethod::Curvature;
    if (curvature)
    {
      this->OriginalPoints = mesh.Points; // the fits use the ancestral (original) points
    }
    this->InitialTriangles = mesh.GetNumberOfTriangles();
    this->Tracker.Initialize(mesh.GetNumberOfPoints(), curvature);
    this->State.Initialize(std::move(mesh), std::move(topology), options.BoundaryWeight);
    this->Rules.MinimumNormalCosine =
      std::cos(std::min(180.0, std::max(0.0, options.MaximumNormalDeviation)) * M_PI / 180.0);
    this->Targets = options.LevelTargets;
    this->LastEmitted = this->InitialTriangles;
    this->Costs.assign(this->InitialTriangles, Infinity);
    this->Spreads.assign(this->InitialTriangles, 0.0f);
    this->Choices.assign(this->InitialTriangles, TriangleChoice);
  }

  TriangleCollapseResult RunGreedy();
  TriangleCollapseResult RunIndependentSets();

private:
  // Evaluate every live triangle (in parallel); for the curvature method, normalise kappa by
  // the largest curvature found.
  void EvaluateAll();
  // The cost of collapsing triangle t; also records how many triangles it would remove.
  double EvaluateCost(Id t, CostScratch& scratch);

  // Merge the star's members (safe in parallel for stars with disjoint stencils: it touches
  // only their triangles and groups). Returns the number of triangles removed.
  int Collapse(const Star& star, CollapseCandidate& c, std::int64_t sequence);
  // Whether the collapse evaluated for triangle t (or a fallback: the swap variant, the
  // cheapest edge) is legal; on success c and star describe the collapse to make.
  bool Check(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const;
  // The same without the swap (which reaches beyond the triangle's neighbourhood).
  Legality CheckDirect(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const;
  Legality Legal(Star& star, const CollapseCandidate& c) const;
  bool TrySwap(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const;

  // Emit levels whose target is reached; returns false on abort.
  bool AfterProgress();
  void EmitLevel();
  // When the run stops before the last target (nothing collapsible left, or MaximumError),
  // the coarsest mesh reached still becomes a level.
  TriangleCollapseResult FinishRun();
  bool Finished() const { return this->NextTarget >= this->Targets.size(); }
  std::int64_t CurrentTarget() const { return this->Targets[this->NextTarget]; }
  bool ErrorAllows(double error) const
  {
    return this->Options.MaximumError <= 0.0 || error <= this->Options.MaximumError;
  }
  double LevelError() const;

  const TriangleCollapseOptions& Options;
  const TriangleCollapseCallbacks& Callbacks;
  std::vector<double> OriginalPoints; // curvature method only
  CollapseMesh State;
  LevelTracker Tracker;
  CollapseCostModel Model;
  CollapseRules Rules;
  std::vector<double> Costs;
  // Per triangle, how far its chosen collapse moves the merged vertices (sum of squared
  // distances): the greedy order between equal costs. On an exactly flat region every collapse
  // costs 0; taking the ones that move vertices least first decimates it evenly.
  std::vector<float> Spreads;
  // What the last evaluation of each triangle chose (CollapseCandidate::Choice), so that the
  // check of a chosen triangle solves for that collapse only.
  std::vector<std::uint8_t> Choices;
  std::vector<std::int64_t> Targets;
  std::size_t NextTarget = 0;
  Id InitialTriangles = 0;
  std::int64_t Sequence = 0;
  Id LastEmitted = 0; // triangles of the last level handed over
  TriangleCollapseResult Result;
};

//------------------------------------------------------------------------------
double Collapser::EvaluateCost(Id t, CostScratch& scratch)
{
  CollapseCandidate c;
  if (!this->State.IsAlive(t) || !this->Model.Evaluate(t, c, scratch))
  {
    return Infinity;
  }
  this->Choices[t] = static_cast<std::uint8_t>(c.Choice);
  double spread = 0.0;
  for (int m = 0; m < c.MemberCount; ++m)
  {
    const double* p = this->State.Mesh.Point(c.Members[m]);
    for (int i = 0; i < 3; ++i)
    {
      spread += (p[i] - c.Position[i]) * (p[i] - c.Position[i]);
    }
  }
  this->Spreads[t] = static_cast<float>(spread);
  return c.Cost;
}

void Collapser::EvaluateAll()
{
  const Id nt = this->InitialTriangles;
  vtkSMPThreadLocal<CostScratch> scratch;
  if (this->Options.Method == CollapseMethod::Quadric)
  {
    vtkSMPTools::For(0, nt, [&](Id begin, Id end) {
      CostScratch& local = scratch.Local();
      for (Id t = begin; t < end; ++t)
      {
        this->Costs[t] = this->EvaluateCost(t, local);
      }
    });
    return;
  }
  // Curvature: first the raw curvatures (kept in Costs), then the weights.
  vtkSMPTools::For(0, nt, [&](Id begin, Id end) {
    CostScratch& local = scratch.Local();
    for (Id t = begin; t < end; ++t)
    {
      CollapseCandidate c;
      this->Costs[t] = this->State.IsAlive(t) && this->Model.Evaluate(t, c, local) ? c.Kappa : -1.0;
    }
  });
  double maximum = 0.0;
  for (const double kappa : this->Costs)
  {
    maximum = std::max(maximum, kappa);
  }
  this->Model.SetCurvatureNormalization(maximum);
  vtkSMPTools::For(0, nt, [&](Id begin, Id end) {
    CostScratch& local = scratch.Local();
    for (Id t = begin; t < end; ++t)
    {
      this->Costs[t] = this->Costs[t] < 0.0 ? Infinity : this->EvaluateCost(t, local);
    }
  });
}

//------------------------------------------------------------------------------
Legality Collapser::CheckDirect(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const
{
  c.MemberCount = 0;
  if (!this->State.IsAlive(t) || !this->Model.EvaluateChoice(t, this->Choices[t], c, scratch))
  {
    return Legality::Illegal;
  }
  const Legality legality = this->Legal(star, c);
  if (legality == Legality::Legal || c.MemberCount != 3 ||
    this->Options.Method != CollapseMethod::Quadric ||
    this->Options.Operator != CollapseOperator::TrianglesAndEdges)
  {
    return legality;
  }
  // The triangle cannot go: with edges allowed, its cheapest edge may. (A swap is still
  // possible for the triangle when the edge is not legal either.)
  CollapseCandidate edge;
  if (this->Model.EvaluateBestEdge(this->State.Mesh.Triangle(t), edge) &&
    this->Legal(star, edge) == Legality::Legal)
  {
    c = edge;
    return Legality::Legal;
  }
  this->Legal(star, c); // restore the triangle's star for a swap
  return legality;
}

bool Collapser::Check(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const
{
  const Legality legality = this->CheckDirect(t, star, c, scratch);
  return legality == Legality::Legal ||
    (legality == Legality::LowValenceApex && c.MemberCount == 3 &&
      this->TrySwap(t, star, c, scratch));
}

Legality Collapser::Legal(Star& star, const CollapseCandidate& c) const
{
  // The star-shape test of paper 000 projects on the collapsing triangle's plane; an edge
  // collapse has no such plane and relies on the normal test alone.
  if (!this->State.GatherStar(c.Members, c.MemberCount, star))
  {
    return Legality::Illegal;
  }
  return this->State.IsLegal(star, c.Position, c.MemberCount == 3 ? c.Normal : nullptr, this->Rules);
}

//------------------------------------------------------------------------------
// Paper 000, figure 3: when a neighbour's apex p has too low a valence, swap the edge (a, b)
// between triangle t = (a, b, c) and that neighbour, then collapse one of the two new
// triangles, (c, a, p) or (c, b, p). The swap and the collapse together merge three vertices
// joined by a path of two edges and remove the same triangles whichever diagonal the quad had,
// so they are done as one merge and the levels' correspondence stays exact.
bool Collapser::TrySwap(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const
{
  const Id p = star.BlockingApex;
  const Id* tri = this->State.Mesh.Triangle(t);
  Id a = InvalidId, b = InvalidId;
  for (const Id d : star.Dying)
  {
    const Id* dt = this->State.Mesh.Triangle(d);
    if (d != t && CornerOf(dt, p) >= 0)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (dt[k] != p)
        {
          (a == InvalidId ? a : b) = dt[k];
        }
      }
      break;
    }
  }
  if (a == InvalidId || b == InvalidId || this->State.IsBoundary(p))
  {
    return false;
  }
  Id apexCorner = InvalidId;
  for (int k = 0; k < 3; ++k)
  {
    apexCorner = (tri[k] != a && tri[k] != b) ? tri[k] : apexCorner;
  }
  CollapseCandidate best;
  bool found = false;
  for (const Id other : { a, b })
  {
    // The new triangle keeps the orientation of t: (c, a, p) or (c, p, b).
    const Id triple[3] = { apexCorner, other == a ? a : p, other == a ? p : b };
    CollapseCandidate trial;
    if (this->Model.EvaluateTriple(triple, trial, scratch) && (!found || trial.Cost < best.Cost) &&
      this->Legal(star, trial) == Legality::Legal)
    {
      best = trial;
      found = true;
    }
  }
  if (!found)
  {
    return false;
  }
  c = best;
  c.Swapped = true;
  return this->State.GatherStar(c.Members, c.MemberCount, star);
}

int Collapser::Collapse(const Star& star, CollapseCandidate& c, std::int64_t sequence)
{
  const double* points[3];
  for (int m = 0; m < star.MemberCount; ++m)
  {
    points[m] = this->State.Mesh.Point(star.Members[m]);
  }
  double weights[3];
  CollapseWeights(points, star.MemberCount, c.Position, weights);
  this->Tracker.Merge(star.Members, weights, star.MemberCount, sequence);
  this->State.Apply(star, c.Position);
  c.Dying = static_cast<int>(star.Dying.size());
  return c.Dying;
}

//------------------------------------------------------------------------------
double Collapser::LevelError() const
{
  // The largest RMS distance of a live vertex to the original planes merged into it.
  double error = 0.0;
  const Id nv = this->State.Mesh.GetNumberOfPoints();
  for (Id v = 0; v < nv; ++v)
  {
    if (this->State.Survivor[v] == v)
    {
      error = std::max(error, this->State.Quadrics[v].RmsDistance(this->State.Mesh.Point(v)));
    }
  }
  return error;
}

void Collapser::EmitLevel()
{
  LevelData level;
  this->Tracker.Snapshot(this->State, this->LevelError(), level);
  this->LastEmitted = this->State.AliveTriangles;
  ++this->Result.LevelsEmitted;
  if (this->Callbacks.EmitLevel)
  {
    this->Callbacks.EmitLevel(level);
  }
}

bool Collapser::AfterProgress()
{
  while (!this->Finished() && this->State.AliveTriangles <= this->CurrentTarget())
  {
    this->EmitLevel();
    ++this->NextTarget;
  }
  if (this->State.AliveTriangles < RebuildAfterDying * this->State.AliveAtLastRebuild)
  {
    this->State.RebuildRows();
  }
  if (this->Callbacks.Progress && !this->Targets.empty())
  {
    const double total = static_cast<double>(this->InitialTriangles - this->Targets.back());
    const double done = static_cast<double>(this->InitialTriangles - this->State.AliveTriangles);
    if (!this->Callbacks.Progress(total > 0.0 ? std::min(1.0, done / total) : 1.0))
    {
      this->Result.Aborted = true;
      return false;
    }
  }
  return true;
}

TriangleCollapseResult Collapser::FinishRun()
{
  if (!this->Result.Aborted && this->AfterProgress() && !this->Finished() &&
    this->State.AliveTriangles < this->LastEmitted)
  {
    this->EmitLevel();
  }
  this->Result.FinalTriangles = this->State.AliveTriangles;
  return this->Result;
}

//------------------------------------------------------------------------------
// Greedy: always the cheapest legal collapse next (paper 002, section 2.4).
TriangleCollapseResult Collapser::RunGreedy()
{
  this->EvaluateAll();
  IndexedHeap heap;
  heap.Reset(&this->Costs, this->InitialTriangles, &this->Spreads);
  heap.Build([&](Id t) { return this->Costs[t] < Infinity; });

  Star star;
  CostScratch scratch;
  CollapseCandidate c;
  ParkingLot lot(this->InitialTriangles, this->State.Mesh.GetNumberOfPoints());
  const std::int64_t progressEvery = std::max<std::int64_t>(1000, this->InitialTriangles / 200);
  const bool widen = this->Options.Method == CollapseMethod::Curvature;
  std::vector<Id> touched;
  auto release = [&](Id s) { heap.Update(s); };
  // A new cost for triangle s; a triangle that cannot collapse any more leaves the heap.
  auto reweigh = [&](Id s) {
    lot.Unpark(s);
    this->Costs[s] = this->EvaluateCost(s, scratch);
    if (this->Costs[s] < Infinity)
    {
      heap.Update(s);
    }
    else
    {
      heap.Remove(s);
    }
  };
  std::int64_t nextRelease = ParkedRetryCollapses;
  while (!this->Finished())
  {
    if (heap.Empty() || this->Result.Collapses >= nextRelease)
    {
      lot.Release(this->State, release);
      // A check costs time in proportion to the waiting triangles: space the checks so that
      // they cost a bounded amount per collapse however many triangles wait.
      nextRelease = this->Result.Collapses +
        std::max<std::int64_t>(ParkedRetryCollapses,
          static_cast<std::int64_t>(lot.GetNumberOfWaiting() / ParkedRetryShare));
      if (heap.Empty())
      {
        break;
      }
    }
    const Id t = heap.Pop();
    if (!this->Check(t, star, c, scratch))
    {
      lot.Park(t, this->Result.Collapses);
      continue;
    }
    if (!this->ErrorAllows(c.Error))
    {
      break;
    }
    const Id survivor = star.Members[0];
    const int dying = this->Collapse(star, c, this->Sequence++);
    this->Result.Swaps += c.Swapped ? 1 : 0;
    this->State.AliveTriangles -= dying;
    ++this->Result.Collapses;
    for (const Id d : star.Dying)
    {
      heap.Remove(d);
    }

    // New costs around the survivor; its neighbours' valences and its position changed, which
    // the parking lot takes note of. For the curvature method the triangles one ring further
    // out are re-weighted too: their stencils moved.
    touched.clear();
    this->State.ForEachTriangle(survivor, [&](Id s) {
      const Id* tri = this->State.Mesh.Triangle(s);
      lot.Touch(tri, this->Result.Collapses);
      reweigh(s);
      if (widen)
      {
        touched.insert(touched.end(), tri, tri + 3);
      }
    });
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (const Id u : touched)
    {
      this->State.ForEachTriangle(u, [&](Id s) {
        if (CornerOf(this->State.Mesh.Triangle(s), survivor) < 0)
        {
          reweigh(s);
        }
      });
    }
    if (this->Result.Collapses % progressEvery == 0 || this->State.AliveTriangles <= this->CurrentTarget())
    {
      if (!this->AfterProgress())
      {
        return this->Result;
      }
    }
  }
  return this->FinishRun();
}

//------------------------------------------------------------------------------
// Independent sets (paper 000, section 6): each pass collapses at once many cheap triangles
// whose stencils share no vertex.
TriangleCollapseResult Collapser::RunIndependentSets()
{
  this->EvaluateAll();
  const Id nt = this->InitialTriangles;
  std::vector<unsigned char> isDirty(nt, 0);
  ParkingLot lot(nt, this->State.Mesh.GetNumberOfPoints());
  // Vertex -> 1 + the index of the pass's candidate whose neighbourhood holds it, 0 if none.
  std::vector<Id> owner(this->State.Mesh.GetNumberOfPoints(), 0);
  std::vector<Id> live(nt), dirty, pool, chosen, owned, survivors, neighbourhood;
  for (Id t = 0; t < nt; ++t)
  {
    live[t] = t;
  }
  std::vector<CollapseCandidate> candidates;
  std::vector<unsigned char> outcome;
  vtkSMPThreadLocal<CostScratch> scratch;
  vtkSMPThreadLocal<Star> stars;
  enum : unsigned char
  {
    Refused = 0,
    Collapsed = 1,
    NeedsSwap = 2,
    TooLarge = 3, // legal, but above MaximumError
    Skipped = 4,  // legal, not needed for this pass's budget
  };

  while (!this->Finished())
  {
    ++this->Result.Passes;
    // 1. Re-weight what changed in the last pass (in parallel).
    vtkSMPTools::For(0, static_cast<Id>(dirty.size()), [&](Id begin, Id end) {
      CostScratch& mine = scratch.Local();
      for (Id i = begin; i < end; ++i)
      {
        this->Costs[dirty[i]] = this->EvaluateCost(dirty[i], mine);
      }
    });
    for (const Id t : dirty)
    {
      isDirty[t] = 0;
    }
    dirty.clear();

    // 2. The cheapest candidates: a pool a few times larger than what one pass can take.
    live.erase(std::remove_if(live.begin(), live.end(), [&](Id t) { return !this->State.IsAlive(t); }),
      live.end());
    const Id alive = this->State.AliveTriangles;
    // LevelFraction is the paper's fraction of triangles selected per pass; a triangle
    // collapse removes four, so a pass removes up to 4 * LevelFraction of the triangles, in
    // whatever mix of triangle and edge collapses.
    const std::int64_t budget = std::min<std::int64_t>(
      std::max<std::int64_t>(1, static_cast<std::int64_t>(4.0 * this->Options.LevelFraction * alive)),
      static_cast<std::int64_t>(alive) - this->CurrentTarget());
    pool.clear();
    std::copy_if(live.begin(), live.end(), std::back_inserter(pool),
      [&](Id t) { return this->Costs[t] < Infinity; });
    auto cheaper = [&](Id a, Id b) {
      return this->Costs[a] < this->Costs[b] || (this->Costs[a] == this->Costs[b] && a < b);
    };

    // 3. Choose, cheapest first, triangles whose neighbourhoods (every triangle around their
    // corners: it holds the stencil of the triangle's collapse and of each edge's) share no
    // vertex, until the pass's budget of removed triangles is reached (a little beyond it,
    // and a few dozen at least: some of the chosen will not be legal). These collapses are independent: none can change
    // another's legality, so they can be checked and made at once. Only the cheapest
    // PoolFactor * budget triangles are eligible, so that a pass stays greedy even when their
    // neighbourhoods overlap a lot; they are ordered a block at a time, as far as the choice gets.
    chosen.clear();
    std::int64_t estimate = 0;
    const std::int64_t wanted = budget + budget / 4 + 64;
    const std::size_t eligible =
      std::min<std::size_t>(pool.size(), static_cast<std::size_t>(PoolFactor * budget + 64));
    if (eligible < pool.size())
    {
      std::nth_element(pool.begin(), pool.begin() + eligible, pool.end(), cheaper);
    }
    const std::size_t block = static_cast<std::size_t>(std::max<std::int64_t>(64, budget));
    for (std::size_t first = 0; first < eligible && estimate < wanted; first += block)
    {
      const std::size_t last = std::min(eligible, first + block);
      if (last < eligible)
      {
        std::nth_element(pool.begin() + first, pool.begin() + last, pool.begin() + eligible, cheaper);
      }
      std::sort(pool.begin() + first, pool.begin() + last, cheaper);
      for (std::size_t i = first; i < last && estimate < wanted; ++i)
      {
        const Id t = pool[i];
        const Id* tri = this->State.Mesh.Triangle(t);
        if (owner[tri[0]] || owner[tri[1]] || owner[tri[2]])
        {
          continue;
        }
        neighbourhood.clear();
        bool blocked = false;
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
        if (blocked)
        {
          continue;
        }
        chosen.push_back(t);
        const Id mark = static_cast<Id>(chosen.size());
        for (const Id v : neighbourhood)
        {
          if (!owner[v])
          {
            owner[v] = mark;
            owned.push_back(v);
          }
        }
        estimate += this->Choices[t] == TriangleChoice ? 4 : 2; // at most
      }
    }

    // 4. Check the chosen ones (in parallel), keep the cheapest legal ones up to the pass's
    // budget, and collapse those (in parallel). Collapse numbers follow the choice order, so
    // the levels' ranks do not depend on the thread count.
    const Id count = static_cast<Id>(chosen.size());
    candidates.resize(count);
    outcome.assign(count, Refused);
    survivors.assign(count, InvalidId);
    vtkSMPTools::For(0, count, [&](Id begin, Id end) {
      CostScratch& mine = scratch.Local();
      Star& star = stars.Local();
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
    std::int64_t removed = 0;
    bool errorLimited = false;
    for (Id i = 0; i < count; ++i)
    {
      if (outcome[i] == Collapsed && removed >= budget)
      {
        outcome[i] = Skipped; // the level's target is reached without it
      }
      removed += outcome[i] == Collapsed ? candidates[i].Dying : 0;
    }
    const std::int64_t base = this->Sequence;
    vtkSMPTools::For(0, count, [&](Id begin, Id end) {
      Star& star = stars.Local();
      for (Id i = begin; i < end; ++i)
      {
        if (outcome[i] == Collapsed)
        {
          this->State.GatherStar(candidates[i].Members, candidates[i].MemberCount, star);
          this->Collapse(star, candidates[i], base + i);
          survivors[i] = star.Members[0];
        }
      }
    });
    this->Sequence += count;

    // 5. Triangles blocked by a low-valence apex try the swap (paper 000, figure 3), one after
    // the other: the swap reaches one ring beyond the chosen neighbourhood.
    Star& star = stars.Local();
    CostScratch& mine = scratch.Local();
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
            survivors[i] = star.Members[0];
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
        this->Costs[chosen[i]] = Infinity;
        lot.Park(chosen[i], this->Result.Passes);
      }
    }
    this->State.AliveTriangles -= static_cast<Id>(removed);
    for (const Id v : owned)
    {
      owner[v] = 0;
    }
    owned.clear();

    // 6. List for re-weighting the triangles whose weight changed: those around the survivors
    // (for the curvature method also one ring further out, whose stencils moved).
    const bool widen = this->Options.Method == CollapseMethod::Curvature;
    auto markDirty = [&](Id s) {
      if (!isDirty[s])
      {
        isDirty[s] = 1;
        lot.Unpark(s);
        dirty.push_back(s);
      }
    };
    for (const Id survivor : survivors)
    {
      if (survivor == InvalidId)
      {
        continue;
      }
      this->State.ForEachTriangle(survivor, [&](Id s) {
        markDirty(s);
        lot.Touch(this->State.Mesh.Triangle(s), this->Result.Passes);
        if (widen)
        {
          const Id* st = this->State.Mesh.Triangle(s);
          for (int k = 0; k < 3; ++k)
          {
            this->State.ForEachTriangle(st[k], markDirty);
          }
        }
      });
    }
    // Parked triangles further out may have become legal (valences and positions changed);
    // rather than searching for them around every collapse, look now and then.
    if (this->Result.Passes % ParkedRetryPasses == 0 || count == 0)
    {
      lot.Release(this->State, markDirty);
    }
    // Stuck when nothing could be chosen and no refused triangle has a changed neighbourhood.
    if (count == 0 && dirty.empty())
    {
      break; // nothing collapsible (or allowed by MaximumError) is left
    }
    if (errorLimited || !this->AfterProgress())
    {
      break;
    }
  }
  return this->FinishRun();
}

} // namespace

//------------------------------------------------------------------------------
TriangleCollapseResult RunTriangleCollapse(TriangleMesh mesh, TriangleTopology topology,
  const TriangleCollapseOptions& options, const TriangleCollapseCallbacks& callbacks)
{
  Collapser collapser(std::move(mesh), std::move(topology), options, callbacks);
  TriangleCollapseResult result = options.Schedule == CollapseSchedule::Greedy
    ? collapser.RunGreedy()
    : collapser.RunIndependentSets();
  return result;
}

} // namespace meshlod
