#include "Collapser.h"

#include "LevelData.h"
#include "Vector3.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace meshlod
{
namespace
{
// Rows are rebuilt once this fraction of the triangles alive at the last rebuild has died.
constexpr double RebuildAfterDying = 0.5;
// Size of the table of recently solved edges in the first evaluation (CostScratch::RecentEdges).
constexpr std::size_t RecentEdgeSlots = 64;

// Moves the points so that their bounding box is centred on the origin; centre gets the shift.
// Returns the bounding box's diagonal (TriangleMesh::BoundingDiagonal, from the same bounds).
double TranslateToCentre(TriangleMesh& mesh, double centre[3])
{
  double lo[3], hi[3];
  mesh.GetBounds(lo, hi);
  for (int c = 0; c < 3; ++c)
  {
    centre[c] = 0.5 * (lo[c] + hi[c]);
  }
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
  {
    mesh.Points[i] -= centre[i % 3];
  }
  return BoxDiagonal(lo, hi);
}
} // namespace

//------------------------------------------------------------------------------
Collapser::Collapser(TriangleMesh&& mesh, TriangleTopology&& topology,
  const TriangleCollapseOptions& options, const TriangleCollapseCallbacks& callbacks)
  : Options(options)
  , Callbacks(callbacks)
  , Model(options, State, Tracker, OriginalPoints)
{
  // The engine works about the centre of the bounding box: a quadric's constant term grows
  // with the square of the distance to the origin, and far from it (a mesh in world or map
  // coordinates) its evaluation cancels away the error it measures. Levels are moved back.
  const double diagonal = TranslateToCentre(mesh, this->Centre);
  this->SpreadUnit = SquaredLengthUnit(diagonal);
  const bool curvature = options.Method == CollapseMethod::Curvature;
  if (curvature) // the fits use the ancestral (original) points
  {
    OriginalPointReader& original = this->OriginalPoints;
    std::copy_n(this->Centre, 3, original.Centre);
    original.Float = options.InputPointsFloat;
    original.Double = options.InputPointsFloat ? nullptr : options.InputPointsDouble;
    original.Ids = options.InputPointIds;
    if (!original.Float && !original.Double)
    {
      original.Copy = mesh.Points;
    }
  }
  this->InitialTriangles = mesh.GetNumberOfTriangles();
  // (The input's parts were oriented consistently where they can be: see ReadInputMesh.)
  this->Rules.StarShapedBySide = !topology.OrientedWhenBuilt;
  this->Tracker.Initialize(mesh.GetNumberOfPoints(), curvature);
  // Boundary planes weigh BoundaryWeight per unit of boundary length and of diagonal: the same
  // per unit length at every input resolution (see TriangleCollapseOptions::BoundaryWeight).
  // Uniform plane weights: every plane weighs the mean triangle area, so that the boundary
  // planes keep their weight relative to the surface's (and the two weightings agree on a mesh
  // of equal triangles).
  const double planeWeight = options.UniformPlaneWeights ? mesh.MeanTriangleArea() : 0.0;
  this->State.Initialize(std::move(mesh), std::move(topology), options.BoundaryWeight,
    diagonal > 0.0 ? diagonal : 1.0, planeWeight);
  if (!options.PreserveTopology)
  {
    this->State.TrackPieces();
  }
  this->Rules.MinimumNormalCosine =
    std::cos(std::min(180.0, std::max(0.0, options.MaximumNormalDeviation)) * M_PI / 180.0);
  this->Rules.ForbidValenceThreeForEdges = options.Schedule == CollapseSchedule::IndependentSets;
  this->Targets = options.LevelTargets;
  this->LastEmitted = this->InitialTriangles;
  AssignFresh(this->Costs, this->InitialTriangles, InfiniteCost);
  AssignFresh(this->Spreads, this->InitialTriangles, 0.0f);
  AssignFresh(this->Choices, this->InitialTriangles, TriangleChoice);
  this->Lot.Reset(this->InitialTriangles, this->State.Mesh.GetNumberOfPoints());
}

//------------------------------------------------------------------------------
double Collapser::EvaluateCost(Id t, CostScratch& scratch)
{
  CollapseCandidate c;
  if (!this->State.IsAlive(t))
  {
    return InfiniteCost;
  }
  // (A piece reaching another block is costed as an ordinary triangle here; a check without
  // blocks may still find it vanishing.)
  if (this->Vanishes(t, scratch.Owner, scratch.Block, c) != PieceKind::Vanishing &&
    !this->Model.Evaluate(t, c, scratch))
  {
    return InfiniteCost;
  }
  this->Choices[t] = static_cast<std::uint8_t>(c.Choice);
  this->Spreads[t] = this->SpreadOf(c);
  return c.Cost;
}

float Collapser::SpreadOf(const CollapseCandidate& c) const
{
  double spread = 0.0;
  for (int m = 0; m < c.MemberCount; ++m)
  {
    const double* p = this->State.Mesh.Point(c.Members[m]);
    for (int i = 0; i < 3; ++i)
    {
      spread += (p[i] - c.Position[i]) * (p[i] - c.Position[i]);
    }
  }
  return static_cast<float>(spread * this->SpreadUnit);
}

void Collapser::EvaluateAll()
{
  const Id nt = this->InitialTriangles;
  vtkSMPThreadLocal<CostScratch> scratch;
  if (this->Options.Method == CollapseMethod::Quadric ||
    this->Options.CurvatureRanking == CurvatureCost::FitDeviation)
  {
    vtkSMPTools::For(0, nt, [&](Id begin, Id end) {
      CostScratch& local = scratch.Local();
      local.RecentEdges.assign(RecentEdgeSlots, CostScratch::RecentEdge());
      for (Id t = begin; t < end; ++t)
      {
        this->Costs[t] = this->EvaluateCost(t, local);
      }
    });
    return;
  }
  // Paper 000's weight: first the raw curvatures (kept in Costs), then the weights.
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
      this->Costs[t] = this->Costs[t] < 0.0 ? InfiniteCost : this->EvaluateCost(t, local);
    }
  });
}

//------------------------------------------------------------------------------
Legality Collapser::CheckDirect(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const
{
  c.MemberCount = 0;
  if (!this->State.IsAlive(t))
  {
    return Legality::Illegal;
  }
  switch (this->Vanishes(t, star.Owner, star.Block, c))
  {
    case PieceKind::Vanishing:
      // Its vanishing changes nothing around it, so it is legal where its star is gathered.
      if (!this->State.GatherStar(c.Members, c.MemberCount, star))
      {
        return star.Foreign ? Legality::Foreign : Legality::Illegal;
      }
      return Legality::Legal;
    case PieceKind::Foreign:
      return Legality::Foreign;
    case PieceKind::Other:
      break;
  }
  // (Never read a vanishing's choice as an edge; pieces only shrink, so it does not happen.)
  if (this->Choices[t] == VanishChoice ||
    !this->Model.EvaluateChoice(t, this->Choices[t], c, scratch))
  {
    return Legality::Illegal;
  }
  const Legality legality = this->Legal(star, c);
  if (legality == Legality::Legal || legality == Legality::Foreign || c.MemberCount != 3 ||
    (this->Options.Method != CollapseMethod::Quadric && !this->EdgesForRefusedTriangles) ||
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
  if (legality == Legality::LowValenceApex)
  {
    this->Legal(star, c); // restore the triangle's star for the swap (nothing else reads it)
  }
  return legality;
}

Legality Collapser::Check(Id t, Star& star, CollapseCandidate& c, CostScratch& scratch) const
{
  const Legality legality = this->CheckDirect(t, star, c, scratch);
  if (legality != Legality::LowValenceApex || c.MemberCount != 3)
  {
    return legality == Legality::Legal || legality == Legality::Foreign ? legality
                                                                        : Legality::Illegal;
  }
  if (this->TrySwap(t, star, c, scratch))
  {
    return Legality::Legal;
  }
  return star.Foreign ? Legality::Foreign : Legality::Illegal;
}

bool Collapser::OtherLegalEdge(Id t, Star& star, CollapseCandidate& c) const
{
  if (this->Options.Method != CollapseMethod::Quadric ||
    this->Options.Operator != CollapseOperator::TrianglesAndEdges || c.Choice == VanishChoice)
  {
    return false;
  }
  const int refused = c.MemberCount == 2 ? 1 << c.Choice : 0;
  // Of equal costs (a flat part's, all zero) the shortest: taking the first edge of the
  // triangle among equals instead left the geomorph's exact counts between a faceted
  // cylinder's levels of 48,128 and 4,812 triangles short by up to 9,096 triangles.
  return this->FirstLegalEdge(
    t, refused | this->Model.HubEdgesToSkip(this->State.Mesh.Triangle(t)), true, star, c);
}

bool Collapser::FirstLegalEdge(
  Id t, int leaveOut, bool shortestFirst, Star& star, CollapseCandidate& c) const
{
  CollapseCandidate edges[3];
  float spreads[3] = { 0.0f, 0.0f, 0.0f };
  int order[3], count = 0;
  CostScratch unused;
  for (int k = 0; k < 3; ++k)
  {
    if ((leaveOut & (1 << k)) == 0 && this->Model.EvaluateChoice(t, k, edges[k], unused) &&
      edges[k].Cost < InfiniteCost)
    {
      spreads[k] = shortestFirst ? this->SpreadOf(edges[k]) : 0.0f;
      order[count++] = k;
    }
  }
  std::sort(order, order + count, [&](int a, int b) {
    return edges[a].Cost < edges[b].Cost ||
      (edges[a].Cost == edges[b].Cost &&
        (spreads[a] < spreads[b] || (spreads[a] == spreads[b] && a < b)));
  });
  for (int i = 0; i < count; ++i)
  {
    const Legality legality = this->Legal(star, edges[order[i]]);
    if (legality == Legality::Legal)
    {
      c = edges[order[i]];
      return true;
    }
    if (legality == Legality::Foreign)
    {
      return false;
    }
  }
  return false;
}

void Collapser::Requeue(Id t, const CollapseCandidate& c)
{
  this->Costs[t] = c.Cost;
  this->Choices[t] = static_cast<std::uint8_t>(c.Choice);
  this->Spreads[t] = this->SpreadOf(c);
}

// A triangle collapse removes four triangles, an edge collapse two (one on a boundary): with
// the cheapest legal edge of the triangle taken instead whenever the triangle would pass the
// target, the greedy schedule lands a level within one triangle of its target unless no edge
// of that triangle may collapse.
void Collapser::LandOnTarget(Id t, std::int64_t needed, Star& star, CollapseCandidate& c) const
{
  if (static_cast<std::int64_t>(star.Dying.size()) <= needed || c.MemberCount != 3 ||
    c.Swapped || c.Choice == VanishChoice || this->Options.Method != CollapseMethod::Quadric ||
    this->Options.Operator != CollapseOperator::TrianglesAndEdges)
  {
    return;
  }
  // The triangle's edges, cheapest first (ties: the first); the first legal one goes. (Only
  // serial loops land on a target: no star reaches another block.)
  if (!this->FirstLegalEdge(t, 0, false, star, c))
  {
    this->Legal(star, c); // the triangle's star again
  }
}

Legality Collapser::Legal(Star& star, const CollapseCandidate& c) const
{
  // The star-shape test of paper 000 projects on the collapsing triangle's plane; an edge
  // collapse has no such plane and relies on the normal test alone.
  if (!this->State.GatherStar(c.Members, c.MemberCount, star))
  {
    return star.Foreign ? Legality::Foreign : Legality::Illegal;
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

void Collapser::PrefetchRing(const Star& star) const
{
  for (std::size_t i = 0; i < star.Ring.size(); ++i)
  {
    const Id r = star.Ring[i];
    const Id* tri = this->State.Mesh.Triangle(r);
    const int k = star.RingCorner[i];
    for (const Id u : { tri[(k + 1) % 3], tri[(k + 2) % 3] })
    {
      const double* q = this->State.Quadrics[u].Q;
      CacheHint(q);
      CacheHint(q + 9);
    }
    CacheHint(this->Costs.data() + r);
    CacheHint(this->Spreads.data() + r);
    CacheHint(this->Choices.data() + r);
    if (!this->HeapPositions.empty())
    {
      CacheHint(this->HeapPositions.data() + r);
    }
  }
}

int Collapser::Collapse(const Star& star, CollapseCandidate& c, std::int64_t sequence)
{
  this->PrefetchRing(star);
  double weights[VanishingPieceVertices];
  if (c.Choice == VanishChoice) // (a closed piece of 3 points too: two triangles back to back)
  {
    std::fill_n(weights, star.MemberCount, 1.0 / star.MemberCount); // a vanishing piece
  }
  else
  {
    const double* points[3];
    for (int m = 0; m < star.MemberCount; ++m)
    {
      points[m] = this->State.Mesh.Point(star.Members[m]);
    }
    CollapseWeights(points, star.MemberCount, c.Position, weights);
  }
  this->Tracker.Merge(star.Members, weights, star.MemberCount, sequence);
  this->State.Apply(star, c.Position);
  c.Dying = static_cast<int>(star.Dying.size());
  return c.Dying;
}

//------------------------------------------------------------------------------
double Collapser::LevelError() const
{
  // The largest RMS distance of a live vertex to the original planes merged into it (a
  // largest value: the same whichever thread finds it).
  // (Over the listed live vertices when a partitioned run keeps such a list: on a coarse level
  // a small part of the mesh.)
  vtkSMPThreadLocal<double> largest(0.0);
  const std::vector<Id>& listed = this->LiveVertices;
  const Id n =
    listed.empty() ? this->State.Mesh.GetNumberOfPoints() : static_cast<Id>(listed.size());
  vtkSMPTools::For(0, n, [&](Id begin, Id end) {
    double& error = largest.Local();
    for (Id i = begin; i < end; ++i)
    {
      const Id v = listed.empty() ? i : listed[i];
      if (this->State.Survivor[v] == v)
      {
        error = std::max(error, this->State.Quadrics[v].RmsDistance(this->State.Mesh.Point(v)));
      }
    }
  });
  double error = 0.0;
  for (const double e : largest)
  {
    error = std::max(error, e);
  }
  return error;
}

void Collapser::EmitLevel()
{
  // The parallel rounds' lists were sized for the live triangles and vertices of earlier levels:
  // give the room back before the level is built, which comes near the peak of the run (at the
  // last level all of the output is built and the lists hold a few percent of what they had).
  Release(this->CandidateCell);
  Release(this->Candidates);
  ShrinkLoose(this->LiveTriangles);
  ShrinkLoose(this->LiveVertices);
  LevelData level;
  // (The partitioned run's list of live triangles, when it keeps one, spares a pass over all.)
  this->Tracker.Snapshot(this->State, this->LevelError(), level,
    this->LiveTriangles.empty() ? nullptr : &this->LiveTriangles);
  const std::size_t coordinates = level.Mesh.Points.size();
  for (std::size_t i = 0; i < coordinates; ++i)
  {
    level.Mesh.Points[i] += this->Centre[i % 3];
  }
  this->LastEmitted = this->State.AliveTriangles;
  ++this->Result.LevelsEmitted;
  this->Retriangulation.Clear();
  this->Reweighed.clear();
  if (this->Callbacks.EmitLevel)
  {
    this->Callbacks.EmitLevel(level, this->Retriangulation);
  }
  if (!this->Retriangulation.Triangles.empty())
  {
    this->Retriangulate();
  }
}

void Collapser::Retriangulate()
{
  // The flips come after every collapse so far: a triangle parked now (in the pass that reached
  // the level) sees its neighbourhood changed after it was parked.
  ++this->Clock;
  const LevelRetriangulation& flips = this->Retriangulation;
  std::vector<Id> corners; // of the flipped triangles, before and after
  for (std::size_t k = 0; k < flips.Triangles.size(); ++k)
  {
    const Id t = flips.Triangles[k];
    const Id* before = this->State.Mesh.Triangle(t);
    corners.insert(corners.end(), before, before + 3);
    Id after[3];
    for (int i = 0; i < 3; ++i)
    {
      after[i] = this->Tracker.LevelVertex(flips.Corners[3 * k + i]);
    }
    this->State.SetCorners(t, after);
    corners.insert(corners.end(), after, after + 3);
  }
  this->State.RebuildRows();
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  std::vector<Id>& reweighed = this->Reweighed;
  std::vector<Id> touched;
  for (const Id v : corners)
  {
    this->State.ForEachTriangle(v, [&](Id s) {
      this->Lot.Touch(this->State.Mesh.Triangle(s), this->Clock);
      reweighed.push_back(s);
    });
    if (this->RefitsLazily())
    {
      this->ForEachTriangleOneRingOut(v, touched, [&](Id s) { reweighed.push_back(s); });
    }
  }
  std::sort(reweighed.begin(), reweighed.end());
  reweighed.erase(std::unique(reweighed.begin(), reweighed.end()), reweighed.end());
  CostScratch scratch;
  for (const Id s : reweighed)
  {
    this->Reweigh(s, scratch);
  }
}

void Collapser::UpdateAfterRetriangulation(IndexedHeap& heap)
{
  for (const Id s : this->Reweighed)
  {
    this->PlaceInHeap(s, heap);
  }
  this->Reweighed.clear();
}

bool Collapser::AfterProgress()
{
  if (!this->Finished() && this->State.AliveTriangles <= this->CurrentTarget())
  {
    // Targets closer together than the triangles one collapse removes (many levels on a small
    // mesh) are passed at once: one level for all of them, so that every level has fewer
    // triangles than the one before.
    this->EmitLevel();
    while (!this->Finished() && this->State.AliveTriangles <= this->CurrentTarget())
    {
      ++this->NextTarget;
      ++this->Result.TargetsReached;
    }
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
  this->Result.ErrorLimited = this->ErrorRefused.load();
  if (!this->Finished() && !this->Result.Aborted) // short of the last target: say why
  {
    // (The heap's positions are not needed any more: their room serves the count.)
    this->Result.FinalPieces = this->State.CountLivePieces(this->HeapPositions);
  }
  return this->Result;
}

} // namespace meshlod
