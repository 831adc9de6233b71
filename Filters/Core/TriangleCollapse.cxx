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

// Independent sets: triangles found illegal are retried after this many passes.
constexpr std::int64_t ParkedRetryPasses = 8;

// Rows are rebuilt once this fraction of the triangles alive at the last rebuild has died.
constexpr double RebuildAfterDying = 0.5;

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
  }

  TriangleCollapseResult RunGreedy();
  TriangleCollapseResult RunIndependentSets();

private:
  // Evaluate every live triangle (in parallel); for the curvature method, normalise kappa by
  // the largest curvature found.
  void EvaluateAll();
  double EvaluateCost(Id t, CostScratch& scratch) const;

  int Collapse(const Star& star, const CollapseCandidate& c, std::int64_t sequence);
  // Whether the collapse evaluated for triangle t (or a fallback: the swap variant, the
  // cheapest edge) is legal; on success c and star describe the collapse to make.
  bool Check(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const;
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
  std::vector<std::int64_t> Targets;
  std::size_t NextTarget = 0;
  Id InitialTriangles = 0;
  std::int64_t Sequence = 0;
  Id LastEmitted = 0; // triangles of the last level handed over
  TriangleCollapseResult Result;
};

//------------------------------------------------------------------------------
double Collapser::EvaluateCost(Id t, CostScratch& scratch) const
{
  CollapseCandidate c;
  return this->State.IsAlive(t) && this->Model.Evaluate(t, c, scratch) ? c.Cost : Infinity;
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
bool Collapser::Check(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const
{
  if (!this->State.IsAlive(t) || !this->Model.Evaluate(t, c, scratch))
  {
    return false;
  }
  const Legality legality = this->Legal(star, c);
  if (legality == Legality::Legal)
  {
    return true;
  }
  if (c.MemberCount != 3)
  {
    return false;
  }
  if (legality == Legality::LowValenceApex && this->TrySwap(t, star, c, scratch))
  {
    return true;
  }
  // The triangle cannot go: with edges allowed, its cheapest edge may.
  return this->Options.Method == CollapseMethod::Quadric &&
    this->Options.Operator == CollapseOperator::TrianglesAndEdges &&
    this->Model.EvaluateBestEdge(this->State.Mesh.Triangle(t), c) &&
    this->Legal(star, c) == Legality::Legal;
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

int Collapser::Collapse(const Star& star, const CollapseCandidate& c, std::int64_t sequence)
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
  this->Result.Swaps += c.Swapped ? 1 : 0;
  return static_cast<int>(star.Dying.size());
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
  heap.Reset(&this->Costs, this->InitialTriangles);
  heap.Build([&](Id t) { return this->Costs[t] < Infinity; });

  Star star;
  CostScratch scratch;
  CollapseCandidate c;
  const std::int64_t progressEvery = std::max<std::int64_t>(1000, this->InitialTriangles / 200);
  std::vector<Id> touched;
  while (!this->Finished() && !heap.Empty())
  {
    const Id t = heap.Pop();
    if (!this->Check(t, star, c, scratch))
    {
      continue; // parked: comes back when its neighbourhood changes
    }
    if (!this->ErrorAllows(c.Error))
    {
      break;
    }
    const Id survivor = star.Members[0];
    const int dying = this->Collapse(star, c, this->Sequence++);
    this->State.AliveTriangles -= dying;
    ++this->Result.Collapses;
    for (const Id d : star.Dying)
    {
      heap.Remove(d);
    }

    // New costs around the survivor (for the curvature method also one ring further out,
    // whose stencils moved). Triangles parked nearby get another chance: a collapse changes the
    // valences and positions their legality depends on.
    touched.clear();
    this->State.ForEachTriangle(survivor, [&](Id s) {
      const Id* tri = this->State.Mesh.Triangle(s);
      touched.insert(touched.end(), tri, tri + 3);
      this->Costs[s] = this->EvaluateCost(s, scratch);
      if (this->Costs[s] < Infinity)
      {
        heap.Update(s);
      }
    });
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    const bool widen = this->Options.Method == CollapseMethod::Curvature;
    for (const Id u : touched)
    {
      if (u == survivor)
      {
        continue;
      }
      this->State.ForEachTriangle(u, [&](Id s) {
        if (CornerOf(this->State.Mesh.Triangle(s), survivor) >= 0)
        {
          return;
        }
        if (widen)
        {
          this->Costs[s] = this->EvaluateCost(s, scratch);
        }
        if (this->Costs[s] < Infinity && (widen || !heap.Contains(s)))
        {
          heap.Update(s);
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
  std::vector<unsigned char> isDirty(nt, 0), parked(nt, 0);
  std::vector<unsigned char> marked(this->State.Mesh.GetNumberOfPoints(), 0);
  std::vector<Id> live(nt), dirty, pool, stencilVertices, markedVertices, survivors;
  for (Id t = 0; t < nt; ++t)
  {
    live[t] = t;
  }
  vtkSMPThreadLocal<CostScratch> scratch;
  Star star;
  CostScratch& local = scratch.Local();
  CollapseCandidate candidate;

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
    const std::int64_t budget =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(4.0 * this->Options.LevelFraction * alive));
    const Id wanted = static_cast<Id>(std::max<std::int64_t>(1, budget / 2));
    pool.clear();
    std::copy_if(live.begin(), live.end(), std::back_inserter(pool),
      [&](Id t) { return this->Costs[t] < Infinity; });
    auto cheaper = [&](Id a, Id b) {
      return this->Costs[a] < this->Costs[b] || (this->Costs[a] == this->Costs[b] && a < b);
    };
    const std::size_t poolSize =
      std::min<std::size_t>(pool.size(), 3 * static_cast<std::size_t>(wanted) + 64);
    if (poolSize < pool.size())
    {
      std::nth_element(pool.begin(), pool.begin() + poolSize, pool.end(), cheaper);
      pool.resize(poolSize);
    }
    std::sort(pool.begin(), pool.end(), cheaper);

    // 3. Walk the pool cheapest first and collapse every legal candidate whose stencil shares
    // no vertex with one collapsed earlier in this pass (an independent set). Collapsing at
    // once is safe: a stencil disjoint from all earlier ones saw none of their changes, so
    // legality checked now equals legality at the start of the pass.
    survivors.clear();
    std::int64_t removing = 0;
    const std::int64_t needed = static_cast<std::int64_t>(alive) - this->CurrentTarget();
    bool errorLimited = false;
    for (std::size_t i = 0;
         i < pool.size() && removing < budget && removing < needed; ++i)
    {
      const Id t = pool[i];
      if (!this->State.IsAlive(t))
      {
        continue;
      }
      // Cheap rejection first: the triangle's whole neighbourhood (which contains the stencil
      // of its collapse and of its edges' collapses) must be unmarked.
      const Id* tri = this->State.Mesh.Triangle(t);
      if (marked[tri[0]] || marked[tri[1]] || marked[tri[2]])
      {
        continue;
      }
      bool blocked = false;
      for (int k = 0; k < 3 && !blocked; ++k)
      {
        this->State.ForEachTriangle(tri[k], [&](Id s) {
          const Id* st = this->State.Mesh.Triangle(s);
          blocked = blocked || marked[st[0]] || marked[st[1]] || marked[st[2]];
        });
      }
      if (blocked)
      {
        continue;
      }
      if (!this->Check(t, star, candidate, local))
      {
        // Parked until a collapse nearby changes its neighbourhood (see step 4).
        this->Costs[t] = Infinity;
        parked[t] = 1;
        continue;
      }
      if (!this->ErrorAllows(candidate.Error))
      {
        errorLimited = true;
        break;
      }
      stencilVertices.clear();
      auto collect = [&](Id s) {
        const Id* st = this->State.Mesh.Triangle(s);
        stencilVertices.insert(stencilVertices.end(), st, st + 3);
      };
      std::for_each(star.Dying.begin(), star.Dying.end(), collect);
      std::for_each(star.Ring.begin(), star.Ring.end(), collect);
      if (candidate.Swapped &&
        std::any_of(stencilVertices.begin(), stencilVertices.end(), [&](Id v) { return marked[v]; }))
      {
        continue; // a swap reaches one ring further than the check above
      }
      for (const Id v : stencilVertices)
      {
        if (!marked[v])
        {
          marked[v] = 1;
          markedVertices.push_back(v);
        }
      }
      this->Collapse(star, candidate, this->Sequence++);
      survivors.push_back(star.Members[0]);
      removing += static_cast<std::int64_t>(star.Dying.size());
    }
    if (survivors.empty())
    {
      break; // nothing collapsible (or allowed by MaximumError) is left
    }
    this->Result.Collapses += static_cast<std::int64_t>(survivors.size());
    this->State.AliveTriangles -= static_cast<Id>(removing);

    // 4. Unmark, and list for re-weighting the triangles whose weight changed: those around the
    // survivors (for the curvature method also one ring further out, whose stencils moved).
    for (const Id v : markedVertices)
    {
      marked[v] = 0;
    }
    markedVertices.clear();
    const bool widen = this->Options.Method == CollapseMethod::Curvature;
    auto markDirty = [&](Id s) {
      if (!isDirty[s])
      {
        isDirty[s] = 1;
        parked[s] = 0;
        dirty.push_back(s);
      }
    };
    for (const Id survivor : survivors)
    {
      this->State.ForEachTriangle(survivor, [&](Id s) {
        markDirty(s);
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
    // rather than searching for them around every collapse, retry them all now and then.
    if (this->Result.Passes % ParkedRetryPasses == 0)
    {
      for (const Id t : live)
      {
        if (parked[t] && this->State.IsAlive(t))
        {
          markDirty(t);
        }
      }
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
