// The engine behind RunTriangleCollapse (TriangleCollapse.h): the mesh, the costs and the level
// bookkeeping shared by the schedules, each schedule in a file of its own:
// - GreedySchedule.cxx: one collapse at a time from a priority queue (paper 002, section 2.4);
// - PartitionedGreedy.cxx: the same order, run in parallel over spatial blocks;
// - IndependentSetSchedule.cxx: passes of collapses with disjoint stencils (paper 000, section 6).
#ifndef meshlod_Collapser_h
#define meshlod_Collapser_h

#include "CollapseCosts.h"
#include "CollapseMesh.h"
#include "FreshMemory.h"
#include "IndexedHeap.h"
#include "LevelTracker.h"
#include "TriangleCollapse.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

namespace meshlod
{
struct CellGrid;           // PartitionedGreedy.cxx
struct CellRound;          // PartitionedGreedy.cxx
struct CellScratch;        // PartitionedGreedy.cxx
struct IndependentSetPass; // IndependentSetSchedule.cxx

constexpr double InfiniteCost = std::numeric_limits<double>::infinity();

// Triangles refused by the legality check wait here until something around them changes: a
// collapse moves vertices and changes valences, which can make a refused collapse legal.
// "Time" is the collapser's Clock; rather than searching around every collapse for refused
// triangles, the lot is checked now and then. Times are kept in 32 bits (8 bytes less per
// triangle and vertex pair): the clock advances about once per candidate taken from a queue, a
// small multiple of the triangle count. Beyond 2^31 the stamps saturate: parked triangles then
// stay parked (fewer collapses), nothing breaks.
class ParkingLot
{
public:
  void Reset(Id triangles, Id vertices)
  {
    AssignFresh(this->ParkedAt, triangles, -1);
    AssignFresh(this->ChangedAt, vertices, 0);
    this->Waiting.clear();
  }

  bool IsParked(Id t) const { return this->ParkedAt[t] >= 0; }
  /// Cache hint for IsParked(t).
  void Hint(Id t) const { CacheHint(this->ParkedAt.data() + t); }

  /// Park t at `now`; a new waiting triangle joins `list` (the lot's own list by default;
  /// collapses running in parallel keep lists of their own and Adopt them afterwards).
  void Park(Id t, std::int64_t now, std::vector<Id>* list = nullptr)
  {
    if (this->ParkedAt[t] < 0)
    {
      (list ? *list : this->Waiting).push_back(t);
    }
    this->ParkedAt[t] = Stamp(now);
  }
  void Adopt(const std::vector<Id>& list)
  {
    this->Waiting.insert(this->Waiting.end(), list.begin(), list.end());
  }

  /// The triangle was re-weighted for another reason: it is no longer waiting.
  void Unpark(Id t) { this->ParkedAt[t] = -1; }

  /// Every vertex of triangle t changed (position, neighbours) at `now`.
  void Touch(const Id* t, std::int64_t now)
  {
    this->ChangedAt[t[0]] = this->ChangedAt[t[1]] = this->ChangedAt[t[2]] = Stamp(now);
  }

  /// Call release(t) for every live waiting triangle with a vertex of a triangle around its
  /// corners changed after it was parked; those leave the lot. Around a corner where more than
  /// FanTriangleLimit triangles meet, only the corner itself is looked at: a collapse that
  /// moves one of its neighbours, or merges two, changes a triangle around it and so the corner
  /// too, and walking the whole fan for every triangle waiting in it made the checks grow with
  /// the square of the valence (a fan of 3,000 triangles waiting to be refused took seconds).
  template <typename F>
  void Release(const CollapseMesh& state, F&& release)
  {
    this->ReleaseIf(state,
      [&](Id t) {
        bool changed = false;
        const Id* tri = state.Mesh.Triangle(t);
        const std::int32_t since = this->ParkedAt[t];
        for (int k = 0; k < 3 && !changed; ++k)
        {
          if (state.TriangleCount(tri[k]) > FanTriangleLimit)
          {
            changed = this->ChangedAt[tri[k]] > since;
            continue;
          }
          state.ForEachTriangle(tri[k], [&](Id n) {
            const Id* nt = state.Mesh.Triangle(n);
            changed = changed || this->ChangedAt[nt[0]] > since ||
              this->ChangedAt[nt[1]] > since || this->ChangedAt[nt[2]] > since;
          });
        }
        return changed;
      },
      release);
  }

  /// Call release(t) for every live waiting triangle, changed or not (the rules changed); the
  /// lot is empty afterwards.
  template <typename F>
  void ReleaseAll(const CollapseMesh& state, F&& release)
  {
    this->ReleaseIf(state, [](Id) { return true; }, release);
  }

  std::size_t GetNumberOfWaiting() const { return this->Waiting.size(); }

private:
  // Release the live waiting triangles for which leave(t) holds; drop the dead ones.
  template <typename Leave, typename F>
  void ReleaseIf(const CollapseMesh& state, Leave&& leave, F&& release)
  {
    std::size_t kept = 0;
    for (const Id t : this->Waiting)
    {
      if (this->ParkedAt[t] < 0 || !state.IsAlive(t))
      {
        this->ParkedAt[t] = -1;
        continue;
      }
      if (leave(t))
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

  static std::int32_t Stamp(std::int64_t now)
  {
    return static_cast<std::int32_t>(
      std::min<std::int64_t>(now, std::numeric_limits<std::int32_t>::max()));
  }
  std::vector<std::int32_t> ParkedAt;  // per triangle, -1 when not waiting
  std::vector<std::int32_t> ChangedAt; // per vertex
  std::vector<Id> Waiting;
};

// The few cheapest candidates after the one being made (a heap's top and the top's two
// children), whose neighbourhoods the greedy loops bring into the cache in stages
// (CollapseMesh::Prefetch) while the current candidate is checked and made. The next candidate
// is one of them or, as often, next to them: cheap candidates cluster where the surface is
// flattest, and a collapse raises its neighbours' costs. Most of a greedy step's time is spent
// waiting for memory: on the 611k gyroid, one thread, this takes about 12% off the whole run
// (the levels are the same, it only reads).
class UpcomingCandidates
{
public:
  UpcomingCandidates(const IndexedHeap& heap, const CollapseMesh& mesh)
    : Mesh(mesh)
  {
    this->Count = std::min<std::size_t>(3, heap.GetSize());
    for (std::size_t i = 0; i < this->Count; ++i)
    {
      this->Ids[i] = heap.At(i);
    }
  }
  void Prefetch(int stage) const
  {
    for (std::size_t i = 0; i < this->Count; ++i)
    {
      this->Mesh.Prefetch(this->Ids[i], stage);
    }
  }

private:
  const CollapseMesh& Mesh;
  Id Ids[3] = { InvalidId, InvalidId, InvalidId };
  std::size_t Count = 0;
};

class Collapser
{
public:
  Collapser(TriangleMesh&& mesh, TriangleTopology&& topology,
    const TriangleCollapseOptions& options, const TriangleCollapseCallbacks& callbacks);

  TriangleCollapseResult RunGreedy();
  TriangleCollapseResult RunPartitionedGreedy();
  TriangleCollapseResult RunIndependentSets();

private:
  // What a greedy run up to a triangle count ended with.
  enum class StepsEnd
  {
    Reached, // the live triangles reached the count
    Stuck,   // nothing collapsible left
    Stopped, // MaximumError reached, or aborted
  };
  // Greedy collapses, cheapest first, until at most `until` triangles are alive (levels are
  // emitted on the way).
  StepsEnd GreedySteps(std::int64_t until);
  // The greedy loop's heap: every live, unparked triangle with a finite cost.
  void BuildGreedyHeap(IndexedHeap& heap);
  // The greedy loop's check of the parking lot: the refused triangles whose neighbourhood
  // changed go back into the heap, and the next check is due at nextRelease. With the heap
  // still empty, a stalled run relaxes its rules (RelaxForStall); false when that leaves it
  // empty: the run is stuck.
  bool ReleaseParked(IndexedHeap& heap, std::int64_t& nextRelease);
  // A new cost for triangle s in the greedy loop's heap; a triangle that cannot collapse any
  // more leaves the heap. (This and DeferInHeap are defined here so that the loop's calls to
  // them inline: defined in the .cxx, they were calls through the library's PLT, and the loop
  // ran 1% more instructions.)
  void ReweighInHeap(Id s, IndexedHeap& heap, CostScratch& scratch)
  {
    this->Reweigh(s, scratch);
    this->PlaceInHeap(s, heap);
  }
  // Triangle s at its cost in the heap, or out of it when it cannot collapse any more.
  void PlaceInHeap(Id s, IndexedHeap& heap) const
  {
    if (this->Costs[s] < InfiniteCost)
    {
      heap.Update(s);
    }
    else
    {
      heap.Remove(s);
    }
  }
  // Curvature method: triangle s, one ring out from a collapse, is marked stale in the greedy
  // loop's heap (MarkStale), or re-weighed now when it has no finite cost to lower.
  // The curvature method's triangles one ring out are re-weighted lazily (each re-weighting is
  // a fit, a dozen per collapse): marked stale, they wait in the heap at StaleCostFactor times
  // their old cost and are re-weighted when they come to its top. Many are marked again, or
  // die, before they do. A stale triangle whose new cost is at least that fraction of its old
  // one comes up no later than it would have with its new cost, so wherever no cost falls
  // below half, the order is exactly that of re-weighting at once (ranked by the fit's
  // deviation, the 154k metaballs and a smooth sphere give the same levels), in about half the
  // time.
  void DeferInHeap(Id s, IndexedHeap& heap, CostScratch& scratch)
  {
    if (this->MarkStale(s))
    {
      heap.Update(s);
    }
    else
    {
      this->ReweighInHeap(s, heap, scratch);
    }
  }
  // New costs around a collapse's survivor: its neighbours' valences and its position changed,
  // which the parking lot takes note of at `now`. Each triangle around it goes to reweigh(s),
  // or to defer(s) around a hub (DefersAroundHub); the solutions of the edges from the
  // survivor are kept meanwhile and reused (CostScratch::BeginSpokes).
  template <typename ReweighF, typename DeferF>
  void ReweighAroundSurvivor(
    Id survivor, std::int64_t now, CostScratch& scratch, ReweighF&& reweigh, DeferF&& defer)
  {
    scratch.BeginSpokes(survivor, this->State.TriangleCount(survivor));
    const bool lazy = this->DefersAroundHub(survivor);
    this->State.ForEachTriangle(survivor, [&](Id s) {
      this->Lot.Touch(this->State.Mesh.Triangle(s), now);
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
  }

  // Partitioned greedy: one round of greedy collapses inside the cells of a grid, in
  // parallel, removing at most `budget` triangles (and 3 more per cell, or up to 11 for a
  // vanishing piece); returns how many it removed.
  std::int64_t BlockRound(std::int64_t budget, int round, bool& errorLimited);
  // Busy cell b of a round (round.Busy[b]): its candidates in the thread's heap, its own
  // vertices the only ones its checks and fits may reach (in a parallel round), how new costs
  // reach the heap, then its greedy loop (CellSteps).
  void RunCell(CellRound& round, Id b, CellScratch& mine);
  // The greedy loop of busy cell b, cheapest candidate first, until its heap is empty or it
  // removed its `quota` of triangles (what it did: round.Outcomes[b]). reweigh(s) gives
  // triangle s a new cost and defer(s) takes a triangle one ring out from a collapse (see
  // RunCell). (Defined and instantiated in PartitionedGreedy.cxx.)
  template <typename ReweighF, typename DeferF>
  void CellSteps(CellRound& round, Id b, std::int64_t quota, CellScratch& mine,
    ReweighF&& reweigh, DeferF&& defer);
  // After the cells' loops: the curvature method's triangles between cells that collapses
  // reached are marked stale, the cells' counts and parked triangles summed up in cell order,
  // the clock and the collapse numbers moved past the round. Returns the triangles removed;
  // errorLimited is set when MaximumError stopped a cell.
  std::int64_t EndRound(CellRound& round, bool& errorLimited);
  // The cost below which about `count` of the live, unparked triangles are (sampled);
  // -infinity when none has a finite cost.
  double CostQuantile(double count);
  // List the live, unparked triangles costing at most `threshold` by cell of the grid (one cell
  // without a grid), leaving out those with corners in several cells; returns the number of
  // cells (see CellFirst).
  std::uint32_t ListCandidates(double threshold, const CellGrid* grid);
  // The box and surface area the grids of BlockRound are sized from.
  void PrepareGrid();
  // List the live triangles and vertices again (the first time: all of them).
  void ListLive();

  // Independent sets (IndependentSetSchedule.cxx), the steps of a pass (see RunIndependentSets).
  // List triangle s for re-weighting (once); it leaves the parking lot.
  void MarkDirty(IndependentSetPass& pass, Id s);
  // New costs for the triangles listed for re-weighting.
  void ReweighDirty(IndependentSetPass& pass);
  // How many triangles a pass may remove.
  std::int64_t PassBudget() const;
  // The live, unparked triangles with a finite cost, in pass.Pool (pass.Live drops the dead).
  void ListPool(IndependentSetPass& pass);
  // Choose from the pool, cheapest first, triangles whose neighbourhoods share no vertex
  // (pass.Chosen) until they would remove a little more than `budget`; their neighbourhoods'
  // vertices are owned (pass.Owner) until the end of the pass.
  void ChooseIndependent(IndependentSetPass& pass, std::int64_t budget);
  // The vertices of the triangles around t's corners, and of the whole piece when t's choice is
  // its vanishing, in pass.Neighbourhood; false when a chosen candidate owns one of them (the
  // list may then be incomplete).
  bool ListNeighbourhood(IndependentSetPass& pass, Id t) const;
  // Check every chosen triangle (in parallel): its collapse and its outcome.
  void CheckChosen(IndependentSetPass& pass) const;
  // Make the legal collapses, in choice order, until they reach the budget (in parallel; the
  // others are skipped); returns how many triangles they removed.
  std::int64_t CollapseChosen(IndependentSetPass& pass, std::int64_t budget);
  // Chosen triangles blocked by a low-valence apex try the swap while `removed` (what the pass
  // removed so far, which the swaps add to) is short of the budget; then every chosen triangle
  // is counted as collapsed or parked as refused. Returns whether MaximumError refused one.
  bool SettleChosen(IndependentSetPass& pass, std::int64_t budget, std::int64_t& removed);
  // List for re-weighting the triangles around the pass's survivors (for the curvature method
  // also one ring further out), whose weight its collapses changed.
  void ListChangedAroundSurvivors(IndependentSetPass& pass);
  // The greedy loop makes the rest of the level (the passes stalled); false when it stopped
  // short of the level's target (stuck, MaximumError reached or aborted).
  bool HandLevelToGreedy(IndependentSetPass& pass);

  // The curvature method re-weights the triangles one ring out from a collapse lazily (see
  // DeferInHeap): MarkStale lowers the cost of triangle s once to StaleCostFactor times its
  // old cost and marks it for re-weighting when it comes to the top of a queue; false, with
  // nothing marked, when s has no finite cost to lower (re-weigh it now).
  bool MarkStale(Id s);
  // Whether this run re-weights the triangles one ring out lazily (the curvature method).
  bool RefitsLazily() const { return this->Options.Method == CollapseMethod::Curvature; }
  // A new cost for triangle s, now: it leaves the parking lot and is no longer stale.
  void Reweigh(Id s, CostScratch& scratch);
  // Whether the triangles around a collapse's survivor are marked stale (MarkStale) instead of
  // re-weighed at once: with paper 000's weight (CurvatureCost WEIGHT) around a survivor of
  // more than FanTriangleLimit triangles. Every triangle collapse at a fan's centre moves it,
  // and re-fitting the whole fan after each took 9 s for a fan of 2,000 triangles and 47 s for
  // 4,000 (now 2.2 s and 12 s: the fan's weights, raised by its valence, bring few of them to
  // the top before the next move marks them again). The other rankings keep the hub in place
  // (see CollapseCostModel::HubEdgesToSkip) or are not slowed.
  bool DefersAroundHub(Id survivor) const
  {
    return this->Options.Method == CollapseMethod::Curvature &&
      this->Options.CurvatureRanking == CurvatureCost::Weight &&
      this->State.TriangleCount(survivor) > FanTriangleLimit;
  }
  // Calls f(s) for every triangle that shares a vertex with a triangle around `survivor` but
  // does not have `survivor` as a corner, once per such shared vertex (`touched` is scratch).
  template <typename F>
  void ForEachTriangleOneRingOut(Id survivor, std::vector<Id>& touched, F&& f) const
  {
    touched.clear();
    this->State.ForEachTriangle(survivor, [&](Id s) {
      const Id* tri = this->State.Mesh.Triangle(s);
      touched.insert(touched.end(), tri, tri + 3);
    });
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (const Id u : touched)
    {
      if (this->State.TriangleCount(u) > FanTriangleLimit)
      {
        continue; // (see FanTriangleLimit)
      }
      this->State.ForEachTriangle(u, [&](Id s) {
        if (CornerOf(this->State.Mesh.Triangle(s), survivor) < 0)
        {
          f(s);
        }
      });
    }
  }

  // Whether live triangle t belongs to a small closed piece that may vanish (PreserveTopology
  // off; see CollapseMesh::SmallPiece): on Vanishing c is that vanishing, whose cost and check
  // stand for the triangle's. With `owner`, a piece reaching beyond `block` is Foreign.
  PieceKind Vanishes(
    Id t, const std::uint32_t* owner, std::uint32_t block, CollapseCandidate& c) const
  {
    if (this->Options.PreserveTopology)
    {
      return PieceKind::Other;
    }
    Id members[VanishingPieceVertices];
    int count = 0;
    const PieceKind kind = this->State.SmallPiece(t, owner, block, members, count);
    if (kind == PieceKind::Vanishing)
    {
      this->Model.EvaluateVanish(members, count, c);
    }
    return kind;
  }

  // After a parallel round (PreserveTopology off): the triangles of every piece that became
  // small enough to vanish during the round, which its blocks judged by its count at the start
  // (CollapseMesh::PiecesTurnedSmall), get their cost again and leave the parking lot.
  void WakePiecesTurnedSmall();

  // Evaluate every live triangle (in parallel); for the curvature method, normalise kappa by
  // the largest curvature found.
  void EvaluateAll();
  // The cost of collapsing triangle t; also records how many triangles it would remove.
  double EvaluateCost(Id t, CostScratch& scratch);

  // Merge the star's members (safe in parallel for stars with disjoint stencils: it touches
  // only their triangles and groups). Returns the number of triangles removed.
  int Collapse(const Star& star, CollapseCandidate& c, std::int64_t sequence);
  // Cache hints for the evaluations that follow a collapse of the star: the quadrics of the
  // ring triangles' far corners and the ring triangles' costs (see UpcomingCandidates).
  void PrefetchRing(const Star& star) const;
  // Whether the collapse evaluated for triangle t (or a fallback: the swap variant, the
  // cheapest edge) is legal; on Legal, c and star describe the collapse to make. Foreign when
  // the answer needs vertices of another block.
  Legality Check(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const;
  // The same without the swap (which reaches beyond the triangle's neighbourhood).
  Legality CheckDirect(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const;
  Legality Legal(Star& star, const CollapseCandidate& c) const;
  // After triangle t's candidate was refused: its other edges, cheapest first and the shortest
  // of equal costs (those of HubEdgesToSkip left out), the first legal one into c and star.
  // False when none is.
  //
  // A refused triangle used to wait in the parking lot, priced by its refused candidate, until
  // something around it changed, even where another of its edges could go. Near the end of a
  // flat part every edge costs nothing, and the refused ones kept triangles waiting while the
  // costly collapses went on: a box of 3 x 1 x 1 (3,072 triangles) down to 12 triangles came
  // out 20% of its diagonal away, where 12 triangles give it exactly. The triangle goes back
  // among the candidates at the cost of its cheapest legal edge (Requeue) instead; it is not
  // collapsed at once, which would take it out of the cost order.
  bool OtherLegalEdge(Id t, Star& star, CollapseCandidate& c) const;
  // Triangle t's edges but those in `leaveOut` (bit k: edge k) and those never legal (priced
  // infinite), cheapest first; of equal costs, with `shortestFirst` the one whose members lie
  // nearest its position (SpreadOf), else the first. The first legal one into c and star;
  // false when none is, or when the answer needs another block's vertices.
  bool FirstLegalEdge(
    Id t, int leaveOut, bool shortestFirst, Star& star, CollapseCandidate& c) const;
  // Triangle t's cost, choice and tie-break become candidate c's.
  void Requeue(Id t, const CollapseCandidate& c);
  // The tie-break of candidate c (Spreads): its members' squared distance to its position.
  float SpreadOf(const CollapseCandidate& c) const;
  bool TrySwap(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const;
  // When a legal triangle collapse would remove more than `needed` triangles (the rest to a
  // level's target), take the triangle's cheapest edge instead when that is legal (star and c
  // then describe the edge).
  void LandOnTarget(Id t, std::int64_t needed, Star& star, CollapseCandidate& c) const;

  // A run that finds nothing legal before its last target relaxes the star-shape test once
  // (CollapseRules::LetWrongSideStay) and gives every refused triangle to release(t) again;
  // when that is done or there is nothing to relax (the test is off, or it judges sides only:
  // CollapseRules::StarShapedBySide), the curvature method with TrianglesAndEdges (ranked by
  // FitDeviation: the Weight ranking keeps to triangles) lets a refused triangle take its
  // cheapest legal edge instead (as the quadric method always does:
  // on a rough surface triangle collapses run out long before edge collapses do), once. False
  // when nothing is left to relax: the run is stuck.
  template <typename F>
  bool RelaxForStall(F&& release)
  {
    if (this->Finished())
    {
      return false;
    }
    if (!this->Rules.LetWrongSideStay && this->Rules.RequireStarShaped &&
      !this->Rules.StarShapedBySide)
    {
      this->Rules.LetWrongSideStay = true;
    }
    else if (!this->EdgesForRefusedTriangles &&
      this->Options.Method == CollapseMethod::Curvature &&
      this->Options.Operator == CollapseOperator::TrianglesAndEdges &&
      this->Options.CurvatureRanking == CurvatureCost::FitDeviation)
    {
      this->EdgesForRefusedTriangles = true;
    }
    else
    {
      return false;
    }
    this->Lot.ReleaseAll(this->State, release);
    return true;
  }
  // Whether a refused triangle collapse may fall back to the triangle's cheapest legal edge:
  // always for the quadric method with TrianglesAndEdges, for the curvature method once a run
  // has stalled (RelaxForStall).
  bool EdgesForRefusedTriangles = false;

  // Emit levels whose target is reached; returns false on abort.
  bool AfterProgress();
  void EmitLevel();
  // The receiver's flips of the level just emitted (Retriangulation) made in the mesh, so that
  // the collapses go on from the flipped triangles; every triangle around a flipped one's
  // corners gets its cost again (for the curvature method also one ring further out, whose
  // stencils changed), listed in Reweighed for a heap that holds them.
  void Retriangulate();
  // A heap held across a level's emission takes the costs Retriangulate changed.
  void UpdateAfterRetriangulation(IndexedHeap& heap);
  // When the run stops before the last target (nothing collapsible left, or MaximumError),
  // the coarsest mesh reached still becomes a level.
  TriangleCollapseResult FinishRun();
  bool Finished() const { return this->NextTarget >= this->Targets.size(); }
  std::int64_t CurrentTarget() const { return this->Targets[this->NextTarget]; }
  // Whether MaximumError allows a collapse of this error; a refusal is remembered (the run's
  // result says whether the limit stopped anything). Safe in parallel.
  bool ErrorAllows(double error) const
  {
    const bool allowed = this->Options.MaximumError <= 0.0 || error <= this->Options.MaximumError;
    if (!allowed)
    {
      this->ErrorRefused.store(true, std::memory_order_relaxed);
    }
    return allowed;
  }
  mutable std::atomic<bool> ErrorRefused{ false };
  double LevelError() const;

  const TriangleCollapseOptions& Options;
  const TriangleCollapseCallbacks& Callbacks;
  OriginalPointReader OriginalPoints; // curvature method only
  double Centre[3] = { 0.0, 0.0, 0.0 };   // the engine's points are relative to it
  CollapseMesh State;
  LevelTracker Tracker;
  CollapseCostModel Model;
  CollapseRules Rules;
  ParkingLot Lot;
  std::vector<double> Costs;
  // Per triangle, how far its chosen collapse moves the merged vertices (sum of squared
  // distances, in units of SpreadUnit): the greedy order between equal costs. On an exactly flat
  // region every collapse costs 0; taking the ones that move vertices least first decimates it
  // evenly.
  std::vector<float> Spreads;
  // SquaredLengthUnit of the diagonal: Spreads in single precision at every scale.
  double SpreadUnit = 1.0;
  // What the last evaluation of each triangle chose (CollapseCandidate::Choice), so that the
  // check of a chosen triangle solves for that collapse only.
  std::vector<std::uint8_t> Choices;
  // Greedy schedule, curvature method: 1 for a triangle whose cost awaits re-evaluation.
  std::vector<std::uint8_t> Stale;
  std::vector<std::int64_t> Targets;
  std::size_t NextTarget = 0;
  Id InitialTriangles = 0;
  std::int64_t Sequence = 0; // numbers the collapses (CollapseRank order)
  std::int64_t Clock = 0;    // the parking lot's time
  Id LastEmitted = 0;        // triangles of the last level handed over
  LevelRetriangulation Retriangulation; // what the receiver flipped in the last level
  std::vector<Id> Reweighed;            // the triangles whose costs its flips changed
  TriangleCollapseResult Result;

  // Partitioned greedy (PartitionedGreedy.cxx): storage kept between rounds.
  double GridBounds[6] = { 0, 0, 0, 0, 0, 0 };
  double GridArea = 0.0;
  std::vector<Id> LiveTriangles;            // every live triangle, and some dead ones
  std::vector<Id> LiveVertices;             // the same for vertices
  std::vector<std::uint32_t> Owner;         // per vertex: its cell in this round
  std::vector<std::uint32_t> CandidateCell; // per live triangle: its cell, when a candidate
  std::vector<Id> Candidates;               // candidates, cell by cell
  std::vector<Id> CellFirst;                // cell -> its first candidate
  std::vector<Id> CellSliceSlots;           // ListCandidates' scratch
  std::vector<Id> HeapPositions;            // shared by the cells' heaps
  std::vector<double> CostSample;           // CostQuantile's scratch
};

} // namespace meshlod

#endif
