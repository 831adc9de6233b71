// The greedy schedule in parallel: greedy collapses inside spatial blocks, the blocks at once.
//
// Cheapest-first collapses far apart from each other do not interact, and most of a greedy
// run's time is spent on them, in an order that jumps across the whole mesh (cache misses on
// large meshes). So the run goes in rounds. A round cuts space into cells of a grid (a vertex
// belongs to the cell holding it), takes as candidates the triangles whose three corners lie in
// one cell and whose cost is below a threshold shared by all cells, and runs the greedy loop in
// every cell at once: cheapest candidate first, costs around each collapse updated, until the
// cell's heap is empty or its share of the round's budget is removed. A collapse whose star
// reaches a vertex of another cell is left for a later round (Star::Owner): then no cell reads
// or writes what another may change, and every cell's result depends on the mesh at the start
// of the round only, whatever the number of threads. Rounds alternate between two grids
// shifted by half a cell, so that what one round leaves at cell borders the next finds inside
// a cell.
//
// The threshold is the cost quantile that holds about as many candidates as the round may
// remove, so every cell stops near the same cost: together the cells follow the global
// cheapest-first order closely. A round removes at most RoundShare of what is left to the next
// level's triangle count. The last collapses before each level are a serial round (one cell
// holding everything, its budget exactly what is left), which lands the level on its count;
// when thresholds find nothing more, the plain greedy loop (GreedySteps) finishes the level.
//
// The curvature method's evaluations reach further than a star: a fit reads the triangles around
// each corner, and a collapse marks the triangles one ring further out for re-fitting. A cell
// changes only its own vertices and the triangles whose corners are all its own, and a vertex
// next to another cell's vertex never moves in a round (its star would reach that cell), so a
// fit reads what no other cell changes as long as it walks around its own vertices only (the
// extended stencil skips the others); triangles one ring out with a corner in another cell are
// marked after the round. Its last collapses before each level are the plain greedy loop's.
#include "Collapser.h"
#include "ParallelCompact.h"
#include "RankSelection.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace meshlod
{
namespace
{
// Cells are sized for about this many triangles (more cells: more parallel work, shorter
// heaps; fewer: less left at cell borders) ...
constexpr std::int64_t TrianglesPerCell = 32768;
// ... but a round has at least this many cells (to keep two threads busy) when every cell
// still gets MinimumTrianglesPerCell. (At 4096, the levels below 30,000 triangles had 2 to 6
// cells, too few to balance two threads: 1.5x on the 154k benchmark mesh, 1.7x at 2048.)
constexpr std::int64_t MinimumCells = 16;
constexpr std::int64_t MinimumTrianglesPerCell = 2048;
// The grid never has more cells than this (each round counts candidates per cell).
constexpr std::int64_t MaximumCells = 1 << 16;
// A round removes at most this fraction of what is left to the next level's count ...
constexpr double RoundShare = 0.8;
// ... and the collapses before a level are serial once fewer than max(SerialGap, live
// triangles / SerialShare) triangles are left to remove.
constexpr std::int64_t SerialGap = 1024;
constexpr std::int64_t SerialShare = 32;
// The threshold is a quantile of about this many sampled costs.
constexpr Id CostSamples = 1 << 16;
// A serial round's threshold holds this many candidates per triangle of its budget: it must
// reach the budget although collapses kill some of its candidates.
constexpr double SerialCandidateFactor = 2.0;
// ListCandidates sorts the candidates by cell in this many slices of the listed triangles
// (when there are fewer cells than a slice holds triangles).
constexpr Id SortSlices = 8;

constexpr std::uint32_t NoCell = 0xffffffffu;

// How many cells a round aims at for `alive` triangles.
std::int64_t CellsFor(std::int64_t alive)
{
  return std::max(
    std::min(MinimumCells, alive / MinimumTrianglesPerCell), alive / TrianglesPerCell);
}
} // namespace

// Per-thread scratch of the cells' greedy loops.
struct CellScratch
{
  IndexedHeap Heap;
  Star Stars;
  CostScratch Cost;
  CollapseCandidate Candidate;
  std::vector<Id> Touched;
  // Curvature method: triangles one ring out from a collapse with corners in other cells, to
  // be marked stale after the round (another cell may change them too).
  std::vector<Id> Shared;
};

// What one cell did in a round.
struct CellOutcome
{
  std::int64_t Removed = 0;
  std::int64_t Collapses = 0;
  std::int64_t Swaps = 0;
  bool ErrorLimited = false;
  std::vector<Id> Parked;
};

// One round of BlockRound: what its cells share (read only while they run), the per-thread
// scratch of their greedy loops and what each did.
struct CellRound
{
  std::vector<std::uint32_t> Busy; // cells with candidates, in increasing order
  double Threshold = 0.0;          // no candidate costs more
  std::int64_t Budget = 0;         // of the whole round
  Id Candidates = 0;               // in all its cells
  bool Parallel = false;
  bool Widen = false;                   // RefitsLazily(): the curvature method
  std::int64_t Clock = 0, Sequence = 0; // the collapser's at the start of the round
  std::vector<CellOutcome> Outcomes;    // per busy cell
  vtkSMPThreadLocal<CellScratch> Scratch;
};

// A uniform grid over a box; cell ids are x + nx (y + ny z).
struct CellGrid
{
  double Origin[3] = { 0, 0, 0 };
  double Size = 1.0;
  int Dims[3] = { 1, 1, 1 };

  // Cells of about `size` (at most half the box's longest side) centred on the box; `shifted`
  // moves every cell border by half a cell, so that the borders of the two grids are far apart.
  void Set(const double bounds[6], double size, bool shifted)
  {
    double longest = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      longest = std::max(longest, bounds[2 * i + 1] - bounds[2 * i]);
    }
    size = std::min(size, 0.5 * longest);
    if (!(size > 0.0) || !std::isfinite(size))
    {
      // Every point at one place (or a box of no size): one cell, which leaves the round to
      // the serial loop.
      for (int i = 0; i < 3; ++i)
      {
        this->Dims[i] = 1;
        this->Origin[i] = bounds[2 * i];
      }
      this->Size = 1.0;
      return;
    }
    for (;;)
    {
      std::int64_t cells = 1;
      for (int i = 0; i < 3; ++i)
      {
        const double extent = bounds[2 * i + 1] - bounds[2 * i];
        const int dims = static_cast<int>(std::min(1.0e6, std::ceil(extent / size)));
        this->Dims[i] = std::max(1, dims) + (shifted ? 1 : 0);
        this->Origin[i] = 0.5 * (bounds[2 * i] + bounds[2 * i + 1]) - 0.5 * this->Dims[i] * size;
        cells *= this->Dims[i];
      }
      if (cells <= MaximumCells)
      {
        break;
      }
      size *= 1.26; // about twice fewer cells
    }
    this->Size = size;
  }

  std::uint32_t CellOf(const double* x) const
  {
    int index[3];
    for (int i = 0; i < 3; ++i)
    {
      const double u = std::floor((x[i] - this->Origin[i]) / this->Size);
      index[i] = static_cast<int>(std::min<double>(this->Dims[i] - 1, std::max(0.0, u)));
    }
    return static_cast<std::uint32_t>(
      index[0] + this->Dims[0] * (index[1] + this->Dims[1] * index[2]));
  }

  std::int64_t Cells() const
  {
    return static_cast<std::int64_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  }
};

//------------------------------------------------------------------------------
TriangleCollapseResult Collapser::RunPartitionedGreedy()
{
  const bool curvature = this->RefitsLazily();
  if (curvature && this->Options.CurvatureRanking == CurvatureCost::Weight)
  {
    // Paper 000's weight in parallel rounds: on a sphere with radii perturbed by up to 8% the
    // 1% level was 5.9x vtkQuadricDecimation's Hausdorff distance, against 2.1x in the serial
    // order.
    return this->RunGreedy();
  }
  this->EvaluateAll();
  if (curvature)
  {
    this->Stale.resize(this->InitialTriangles, 0);
  }
  int round = 0;
  while (!this->Finished())
  {
    // In parallel while much is left to the next level, then a serial round (one cell, the
    // whole budget) lands on its count.
    const std::int64_t alive = this->State.AliveTriangles;
    const std::int64_t gap = alive - this->CurrentTarget();
    const std::int64_t cells = CellsFor(alive);
    const std::int64_t budget = static_cast<std::int64_t>(RoundShare * gap) - 4 * cells;
    const bool parallel =
      cells >= 2 && gap > std::max(SerialGap, alive / SerialShare) && budget > 0;
    if (curvature && !parallel)
    {
      // The curvature method lands on a level with the plain greedy loop, which re-weighs
      // its stale triangles as they come up.
      if (this->GreedySteps(this->CurrentTarget()) != StepsEnd::Reached)
      {
        break;
      }
      continue;
    }
    bool errorLimited = false;
    const std::int64_t removed =
      this->BlockRound(parallel ? budget : gap, parallel ? round++ : -1, errorLimited);
    if (removed == 0 || errorLimited)
    {
      // The rounds' thresholds found nothing more (or the error limit is near): finish the
      // level with the plain greedy loop, which retries refused triangles as it goes.
      if (this->GreedySteps(this->CurrentTarget()) != StepsEnd::Reached)
      {
        break;
      }
      continue;
    }
    if (!this->AfterProgress())
    {
      return this->Result;
    }
  }
  return this->FinishRun();
}

//------------------------------------------------------------------------------
double Collapser::CostQuantile(double count)
{
  const Id live = static_cast<Id>(this->LiveTriangles.size());
  const Id stride = std::max<Id>(1, live / CostSamples);
  // Every stride-th listed triangle's cost, NaN for one dead, of infinite cost or waiting: one
  // pass, each read far from the last, so the reads a few samples ahead are hinted. (The
  // quantile does not depend on the samples' order.)
  constexpr Id Ahead = 8;
  std::vector<double>& sample = this->CostSample;
  ResizeFresh(sample, (live + stride - 1) / stride);
  const Id samples = static_cast<Id>(sample.size());
  vtkSMPThreadLocal<Id> counted(0);
  vtkSMPTools::For(0, samples, [&](Id begin, Id end) {
    Id& mine = counted.Local();
    for (Id i = begin; i < end; ++i)
    {
      if (i + Ahead < end)
      {
        const Id ahead = this->LiveTriangles[(i + Ahead) * stride];
        CacheHint(this->Costs.data() + ahead);
        CacheHint(this->State.Mesh.Triangle(ahead));
        this->Lot.Hint(ahead);
      }
      const Id t = this->LiveTriangles[i * stride];
      const bool wanted =
        this->State.IsAlive(t) && this->Costs[t] < InfiniteCost && !this->Lot.IsParked(t);
      sample[i] = wanted ? this->Costs[t] : std::numeric_limits<double>::quiet_NaN();
      mine += wanted ? 1 : 0;
    }
  });
  Id valid = 0;
  for (const Id c : counted)
  {
    valid += c;
  }
  if (valid == 0)
  {
    return -InfiniteCost;
  }
  const double share = count / (static_cast<double>(valid) * stride);
  const Id k = std::min(valid - 1, static_cast<Id>(std::max(0.0, share) * valid));
  return SelectRank(sample, valid, k);
}

//------------------------------------------------------------------------------
std::uint32_t Collapser::ListCandidates(double threshold, const CellGrid* grid)
{
  const TriangleMesh& mesh = this->State.Mesh;
  const Id live = static_cast<Id>(this->LiveTriangles.size());
  if (grid != nullptr)
  {
    ResizeFresh(this->Owner, mesh.GetNumberOfPoints(), NoCell);
    const Id liveVertices = static_cast<Id>(this->LiveVertices.size());
    vtkSMPTools::For(0, liveVertices, [&](Id begin, Id end) {
      for (Id i = begin; i < end; ++i)
      {
        const Id v = this->LiveVertices[i];
        this->Owner[v] = grid->CellOf(mesh.Point(v));
      }
    });
  }
  // Every candidate's cell (0 without a grid), NoCell for the others.
  ResizeFresh(this->CandidateCell, live);
  vtkSMPTools::For(0, live, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      const Id t = this->LiveTriangles[i];
      std::uint32_t cell = NoCell;
      if (this->State.IsAlive(t) && this->Costs[t] <= threshold && !this->Lot.IsParked(t))
      {
        const Id* tri = mesh.Triangle(t);
        const std::uint32_t c = grid ? this->Owner[tri[0]] : 0;
        cell = !grid || CornersOwnedBy(this->Owner.data(), tri, c) ? c : NoCell;
      }
      this->CandidateCell[i] = cell;
    }
  });
  // Counting sort by cell: the candidates of cell c are Candidates[CellFirst[c] ..
  // CellFirst[c + 1]), in increasing id order. The listed triangles are cut into a fixed
  // number of slices (whatever the thread count) that are counted and scattered in parallel,
  // each slice's candidates of a cell after those of the slices before it.
  const std::uint32_t cells = grid ? static_cast<std::uint32_t>(grid->Cells()) : 1;
  const Id slices = static_cast<std::int64_t>(cells) * SortSlices <= live ? SortSlices : 1;
  const Id sliceSize = (live + slices - 1) / slices;
  // Per (cell, slice), cell-major: the slice's candidates in the cell, then where they start.
  std::vector<Id>& slots = this->CellSliceSlots;
  slots.assign(static_cast<std::size_t>(cells) * slices, 0);
  // Calls f(i, slot of its cell and slice) for every listed candidate i, slices in parallel.
  const auto forEachCandidate = [&](auto&& f) {
    vtkSMPTools::For(0, slices, 1, [&](Id begin, Id end) {
      for (Id s = begin; s < end; ++s)
      {
        for (Id i = s * sliceSize; i < std::min(live, (s + 1) * sliceSize); ++i)
        {
          const std::uint32_t cell = this->CandidateCell[i];
          if (cell != NoCell)
          {
            f(i, slots[cell * slices + s]);
          }
        }
      }
    });
  };
  forEachCandidate([](Id, Id& slot) { ++slot; });
  this->CellFirst.resize(cells + 1);
  Id total = 0;
  for (std::uint32_t c = 0; c < cells; ++c)
  {
    this->CellFirst[c] = total;
    for (Id s = 0; s < slices; ++s)
    {
      const Id n = slots[c * slices + s];
      slots[c * slices + s] = total;
      total += n;
    }
  }
  this->CellFirst[cells] = total;
  ResizeFresh(this->Candidates, total);
  forEachCandidate([&](Id i, Id& slot) { this->Candidates[slot++] = this->LiveTriangles[i]; });
  return cells;
}

//------------------------------------------------------------------------------
std::int64_t Collapser::BlockRound(std::int64_t budget, int round, bool& errorLimited)
{
  // Refused triangles whose neighbourhood changed in the last round compete again.
  this->Lot.Release(this->State, [](Id) {});
  // The live triangles and vertices, listed again when many died since the last listing.
  const Id alive = this->State.AliveTriangles;
  if (this->LiveTriangles.empty() || this->LiveTriangles.size() > 1.25 * alive)
  {
    this->ListLive();
  }

  // 1. The threshold: the cost quantile holding about `budget` candidates (twice that for a
  // serial round, which must reach its budget).
  const bool parallel = round >= 0;
  const double threshold =
    this->CostQuantile(static_cast<double>(budget) * (parallel ? 1.0 : SerialCandidateFactor));
  if (!(threshold > -InfiniteCost))
  {
    return 0;
  }

  // 2. The candidates, cell by cell: for a parallel round, the cells of a grid sized from the
  // surface area, shifted every other round.
  CellGrid grid;
  if (parallel)
  {
    const double wanted = static_cast<double>(CellsFor(alive));
    grid.Set(this->GridBounds, std::sqrt(1.5 * this->GridArea / wanted), round % 2 == 1);
  }
  const std::uint32_t cells = this->ListCandidates(threshold, parallel ? &grid : nullptr);
  const Id candidates = static_cast<Id>(this->Candidates.size());
  std::vector<std::uint32_t> busy; // cells with candidates, in increasing order
  for (std::uint32_t c = 0; c < cells; ++c)
  {
    if (this->CellFirst[c + 1] > this->CellFirst[c])
    {
      busy.push_back(c);
    }
  }
  if (busy.empty() || (parallel && busy.size() < 2))
  {
    return 0; // nothing to do, or nothing to do in parallel: the serial loop does better
  }

  // 3. Every cell's greedy loop, in parallel. A cell may remove its share of the budget (in
  // proportion to its candidates), and up to 3 triangles more with its last collapse (in the
  // serial round, which lands on a level, 1 unless no edge of that last triangle may collapse:
  // LandOnTarget), or up to VanishingPieceTriangles - 1 more when that is a piece vanishing.
  ResizeFresh(this->HeapPositions, this->State.Mesh.GetNumberOfTriangles(), InvalidId);
  if (parallel && !this->Options.PreserveTopology)
  {
    this->State.FreezePieceCounts(); // (see CollapseMesh::SmallPiece)
  }
  const Id cellsBusy = static_cast<Id>(busy.size());
  CellRound work;
  work.Busy = std::move(busy);
  work.Outcomes.resize(cellsBusy);
  work.Threshold = threshold;
  work.Budget = budget;
  work.Candidates = candidates;
  work.Parallel = parallel;
  work.Widen = this->RefitsLazily();
  work.Clock = this->Clock;
  work.Sequence = this->Sequence;
  vtkSMPTools::For(0, cellsBusy, 1, [&](Id begin, Id end) {
    CellScratch& mine = work.Scratch.Local();
    for (Id b = begin; b < end; ++b)
    {
      this->RunCell(work, b, mine);
    }
  });

  // 4. Sum up in cell order; the curvature method's triangles between cells that collapses
  // reached become stale now (in id order: the same for any number of threads).
  return this->EndRound(work, errorLimited);
}

//------------------------------------------------------------------------------
void Collapser::RunCell(CellRound& round, Id b, CellScratch& mine)
{
  const std::uint32_t cell = round.Busy[b];
  const Id first = this->CellFirst[cell];
  const Id count = this->CellFirst[cell + 1] - first;
  const std::int64_t quota = round.Budget * count / round.Candidates;
  const double threshold = round.Threshold;
  const bool parallel = round.Parallel;
  IndexedHeap& heap = mine.Heap;
  Star& star = mine.Stars;
  heap.Attach(&this->Costs, &this->Spreads, this->HeapPositions.data());
  heap.Build(this->Candidates.data() + first, static_cast<std::size_t>(count));
  star.Owner = parallel ? this->Owner.data() : nullptr;
  star.Block = cell;
  mine.Cost.Owner = star.Owner;
  mine.Cost.Block = cell;
  // A new cost for triangle s, which stays a candidate while it is below the threshold.
  const auto reweigh = [&](Id s) {
    this->Reweigh(s, mine.Cost);
    if (this->Costs[s] <= threshold)
    {
      heap.Update(s);
    }
    else
    {
      heap.Remove(s);
    }
  };
  // Curvature method: a triangle one ring out from a collapse. Only this cell changes the
  // triangles whose corners are all its own; the others wait for the end of the round.
  const auto defer = [&](Id s) {
    const Id* tri = this->State.Mesh.Triangle(s);
    if (parallel && !CornersOwnedBy(this->Owner.data(), tri, cell))
    {
      mine.Shared.push_back(s);
    }
    else if (!this->MarkStale(s))
    {
      reweigh(s);
    }
    else if (this->Costs[s] <= threshold)
    {
      heap.Update(s);
    }
  };
  this->CellSteps(round, b, quota, mine, reweigh, defer);
  heap.Clear();
  star.Owner = nullptr;
  mine.Cost.Owner = nullptr;
}

//------------------------------------------------------------------------------
template <typename ReweighF, typename DeferF>
void Collapser::CellSteps(CellRound& round, Id b, std::int64_t quota, CellScratch& mine,
  ReweighF&& reweigh, DeferF&& defer)
{
  const bool parallel = round.Parallel;
  const bool widen = round.Widen;
  const Id cellsBusy = static_cast<Id>(round.Busy.size());
  CellOutcome& out = round.Outcomes[b];
  IndexedHeap& heap = mine.Heap;
  Star& star = mine.Stars;
  CollapseCandidate& c = mine.Candidate;
  while (!heap.Empty() && out.Removed < quota)
  {
    const Id t = heap.Pop();
    if (widen && this->Stale[t])
    {
      reweigh(t);
      continue;
    }
    const UpcomingCandidates upcoming(heap, this->State);
    upcoming.Prefetch(0);
    const Legality legality = this->Check(t, star, c, mine.Cost);
    if (legality == Legality::Illegal && this->OtherLegalEdge(t, star, c))
    {
      this->Requeue(t, c); // (above the threshold: a later round's candidate)
      if (c.Cost <= round.Threshold)
      {
        heap.Update(t);
      }
      continue;
    }
    upcoming.Prefetch(1);
    if (legality == Legality::Foreign)
    {
      continue; // for a later round
    }
    const std::int64_t now = round.Clock + out.Collapses;
    if (legality != Legality::Legal)
    {
      this->Lot.Park(t, now, &out.Parked);
      continue;
    }
    if (!parallel)
    {
      this->LandOnTarget(t, quota - out.Removed, star, c); // the serial round's quota is the gap
    }
    if (!this->ErrorAllows(c.Error))
    {
      out.ErrorLimited = true;
      break;
    }
    const Id survivor = star.Members[0];
    // Collapse numbers interleave the cells, cheapest first in each.
    out.Removed += this->Collapse(star, c, round.Sequence + out.Collapses * cellsBusy + b);
    upcoming.Prefetch(2);
    out.Swaps += c.Swapped ? 1 : 0;
    ++out.Collapses;
    for (const Id d : star.Dying)
    {
      heap.Remove(d);
    }
    this->ReweighAroundSurvivor(survivor, now + 1, mine.Cost, reweigh, defer);
    upcoming.Prefetch(3);
    if (widen)
    {
      this->ForEachTriangleOneRingOut(survivor, mine.Touched, defer);
    }
  }
}

//------------------------------------------------------------------------------
std::int64_t Collapser::EndRound(CellRound& round, bool& errorLimited)
{
  if (round.Widen)
  {
    std::vector<Id> shared;
    for (CellScratch& mine : round.Scratch)
    {
      shared.insert(shared.end(), mine.Shared.begin(), mine.Shared.end());
      mine.Shared.clear();
    }
    std::sort(shared.begin(), shared.end());
    shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
    CostScratch cost;
    for (const Id s : shared)
    {
      if (this->State.IsAlive(s) && !this->MarkStale(s))
      {
        this->Reweigh(s, cost);
      }
    }
  }
  std::int64_t removed = 0, longest = 0;
  for (const CellOutcome& out : round.Outcomes)
  {
    removed += out.Removed;
    this->Result.Collapses += out.Collapses;
    this->Result.Swaps += out.Swaps;
    errorLimited = errorLimited || out.ErrorLimited;
    longest = std::max(longest, out.Collapses);
    this->Lot.Adopt(out.Parked);
  }
  if (round.Parallel && !this->Options.PreserveTopology)
  {
    this->WakePiecesTurnedSmall();
  }
  const Id cellsBusy = static_cast<Id>(round.Busy.size());
  this->State.AliveTriangles -= static_cast<Id>(removed);
  this->Clock += longest + 1;
  this->Sequence += (longest + 1) * cellsBusy;
  return removed;
}

//------------------------------------------------------------------------------
void Collapser::WakePiecesTurnedSmall()
{
  std::vector<Id> firsts;
  this->State.PiecesTurnedSmall(firsts);
  CostScratch cost;
  for (const Id v : firsts)
  {
    Id t = InvalidId;
    this->State.ForEachTriangle(v, [&](Id s) { t = t == InvalidId ? s : t; });
    Id members[VanishingPieceVertices];
    int count = 0;
    if (t == InvalidId ||
      this->State.SmallPiece(t, nullptr, 0, members, count) != PieceKind::Vanishing)
    {
      continue;
    }
    for (int m = 0; m < count; ++m)
    {
      this->State.ForEachTriangle(members[m], [&](Id s) { this->Reweigh(s, cost); });
    }
  }
}

//------------------------------------------------------------------------------
void Collapser::ListLive()
{
  const auto alive = [&](Id t) { return this->State.IsAlive(t); };
  const auto unmerged = [&](Id v) { return this->State.Survivor[v] == v; };
  if (this->LiveTriangles.empty())
  {
    ListPassing(this->State.Mesh.GetNumberOfTriangles(), alive, this->LiveTriangles);
    ListPassing(this->State.Mesh.GetNumberOfPoints(), unmerged, this->LiveVertices);
    this->PrepareGrid();
    return;
  }
  KeepInOrder(this->LiveTriangles, alive);
  KeepInOrder(this->LiveVertices, unmerged);
}

//------------------------------------------------------------------------------
void Collapser::PrepareGrid()
{
  // Bounds and area of the live triangles, per fixed block of triangles in parallel, then the
  // blocks in order: the same sums for any number of threads.
  const TriangleMesh& mesh = this->State.Mesh;
  const FixedBlocks blocks{ mesh.GetNumberOfTriangles() };
  struct Extent
  {
    double Bounds[6] = { InfiniteCost, -InfiniteCost, InfiniteCost, -InfiniteCost, InfiniteCost,
      -InfiniteCost };
    double Area = 0.0;
  };
  std::vector<Extent> extents(blocks.Count());
  vtkSMPTools::For(0, blocks.Count(), [&](Id begin, Id end) {
    for (Id b = begin; b < end; ++b)
    {
      Extent& e = extents[b];
      for (Id t = blocks.Begin(b); t < blocks.End(b); ++t)
      {
        if (!this->State.IsAlive(t))
        {
          continue;
        }
        double n[3];
        mesh.AreaVector(t, n);
        e.Area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; ++k)
        {
          const double* x = mesh.Point(mesh.Triangle(t)[k]);
          for (int i = 0; i < 3; ++i)
          {
            e.Bounds[2 * i] = std::min(e.Bounds[2 * i], x[i]);
            e.Bounds[2 * i + 1] = std::max(e.Bounds[2 * i + 1], x[i]);
          }
        }
      }
    }
  });
  Extent all;
  for (const Extent& e : extents)
  {
    all.Area += e.Area;
    for (int i = 0; i < 3; ++i)
    {
      all.Bounds[2 * i] = std::min(all.Bounds[2 * i], e.Bounds[2 * i]);
      all.Bounds[2 * i + 1] = std::max(all.Bounds[2 * i + 1], e.Bounds[2 * i + 1]);
    }
  }
  std::copy_n(all.Bounds, 6, this->GridBounds);
  const double area = all.Area;
  // A surface of zero area (all triangles degenerate) still needs cells of some size.
  double diagonal = 0.0;
  for (int i = 0; i < 3; ++i)
  {
    diagonal = std::max(diagonal, this->GridBounds[2 * i + 1] - this->GridBounds[2 * i]);
  }
  this->GridArea = area > 0.0 ? area : std::max(1e-300, diagonal * diagonal);
}

} // namespace meshlod
