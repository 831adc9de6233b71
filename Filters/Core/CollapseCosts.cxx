#include "CollapseCosts.h"

#include "CollapseMesh.h"
#include "LevelTracker.h"
#include "LocalSurfaceFit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshlod
{
namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();

// Curvature method, ranked by the fit's deviation, TrianglesAndEdges: a triangle's cheapest edge
// collapses instead when the triangle would cost more than this many times the edge's merged
// planes. On a smooth surface a triangle collapse costs a few times its cheapest edge (three
// points merge instead of two), so the triangles keep collapsing there, as paper 000 does; at a
// crease (the rim of a faceted solid) a triangle collapse across it costs orders of magnitude
// more than an edge along it, and without the edges such a solid cannot go below about a fifth
// of its triangles without losing its rims.
constexpr double CreaseEdgeFactor = 1.0e6;
// ListStencil drops duplicate stencil vertices as they come until it has listed more than this
// many (in a set of StencilSlots places); past them it lists every vertex it meets.
constexpr std::size_t LinearStencil = 32;
constexpr std::size_t StencilSlots = 128; // a power of two, at least twice LinearStencil + 1

// The slot where vertex x's probe in ListStencil's set starts.
std::size_t StencilHome(Id x)
{
  return (static_cast<std::uint32_t>(x) * 0x9E3779B1u >> 25) & (StencilSlots - 1);
}

double Distance(const double* a, const double* b)
{
  const double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
  return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

// alpha(T) = 2 (cos a1 + cos a2 + cos a3 - 1): 1 for equilateral, 0 for degenerate triangles.
double ShapeMeasure(const double* p0, const double* p1, const double* p2)
{
  const double a = Distance(p1, p2), b = Distance(p0, p2), c = Distance(p0, p1);
  if (a <= 0.0 || b <= 0.0 || c <= 0.0)
  {
    return 0.0;
  }
  const double cosA = (b * b + c * c - a * a) / (2.0 * b * c);
  const double cosB = (a * a + c * c - b * b) / (2.0 * a * c);
  const double cosC = (a * a + b * b - c * c) / (2.0 * a * b);
  return std::max(0.0, 2.0 * (cosA + cosB + cosC - 1.0));
}

// Every how many of the triangles around v the fit reads (see FanTriangleLimit).
Id EveryNthAround(const CollapseMesh& state, Id v)
{
  const Id around = state.TriangleCount(v);
  return around > FanTriangleLimit ? (around + FanTriangleLimit - 1) / FanTriangleLimit : Id(1);
}
} // namespace

//------------------------------------------------------------------------------
void CollapseWeights(const double* const* points, int count, const double x[3], double weights[3])
{
  weights[0] = weights[1] = weights[2] = 0.0;
  if (count == 2)
  {
    const double* a = points[0];
    const double* b = points[1];
    const double ab[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double ax[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
    const double length2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    const double s = length2 > 0.0
      ? std::min(1.0, std::max(0.0, (ax[0] * ab[0] + ax[1] * ab[1] + ax[2] * ab[2]) / length2))
      : 0.5;
    weights[0] = 1.0 - s;
    weights[1] = s;
    return;
  }
  // Barycentric coordinates of the projection of x on the triangle's plane.
  const double* a = points[0];
  const double* b = points[1];
  const double* c = points[2];
  const double v0[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v1[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double v2[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
  auto dot = [](const double* p, const double* q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
  const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1);
  const double d20 = dot(v2, v0), d21 = dot(v2, v1);
  const double denominator = d00 * d11 - d01 * d01;
  if (!(denominator > 0.0))
  {
    weights[0] = weights[1] = weights[2] = 1.0 / 3.0;
    return;
  }
  const double wb = (d11 * d20 - d01 * d21) / denominator;
  const double wc = (d00 * d21 - d01 * d20) / denominator;
  weights[0] = std::max(0.0, 1.0 - wb - wc);
  weights[1] = std::max(0.0, wb);
  weights[2] = std::max(0.0, wc);
  const double sum = weights[0] + weights[1] + weights[2];
  for (int k = 0; k < 3; ++k)
  {
    weights[k] /= sum;
  }
}

//------------------------------------------------------------------------------
CollapseCostModel::CollapseCostModel(const TriangleCollapseOptions& options,
  const CollapseMesh& state, const LevelTracker& tracker, const OriginalPointReader& originalPoints)
  : Options(options)
  , State(state)
  , Tracker(tracker)
  , OriginalPoints(originalPoints)
  , AreaPower(options.Method == CollapseMethod::Quadric ? options.AreaNormalization : 0.0)
{
}

//------------------------------------------------------------------------------
double CollapseCostModel::SurfaceScale(const Id* members, int count) const
{
  if (this->AreaPower == 0.0)
  {
    return 1.0;
  }
  double surfaceWeight = 0.0;
  for (int k = 0; k < count; ++k)
  {
    surfaceWeight += this->State.SurfaceWeights[members[k]];
  }
  if (!(surfaceWeight > 0.0))
  {
    return 1.0; // (no surface, no planes: a quadric value of 0)
  }
  const double x = surfaceWeight / this->State.SurfaceWeightUnit;
  // Square roots where they do: faster than pow on the evaluations' path, and exactly scaled
  // by a power-of-two change of the input's size.
  return this->AreaPower == 0.25 ? std::sqrt(std::sqrt(x))
    : this->AreaPower == 0.5     ? std::sqrt(x)
    : this->AreaPower == 1.0     ? x
                                 : std::pow(x, this->AreaPower);
}

//------------------------------------------------------------------------------
double CollapseCostModel::CurvatureWeight(const CollapseCandidate& c) const
{
  const double kappa = std::min(1.0, c.Kappa * this->CurvatureNormalization);
  return c.Area *
    (this->Options.CurvatureWeight * kappa + this->Options.AngleWeight * c.Alpha +
      this->Options.ValenceWeight * c.ValenceTerm);
}

//------------------------------------------------------------------------------
bool CollapseCostModel::Evaluate(Id t, CollapseCandidate& c, CostScratch& scratch) const
{
  const Id* tri = this->State.Mesh.Triangle(t);
  if (this->Options.Method == CollapseMethod::Quadric &&
    this->Options.Operator == CollapseOperator::TrianglesAndEdges)
  {
    return this->EvaluateTriangleOrEdge(tri, c, scratch);
  }
  if (this->Options.Method == CollapseMethod::Curvature &&
    this->Options.Operator == CollapseOperator::TrianglesAndEdges &&
    this->Options.CurvatureRanking == CurvatureCost::FitDeviation)
  {
    return this->EvaluateTriangleOrCreaseEdge(tri, c, scratch);
  }
  return this->EvaluateTriple(tri, c, scratch);
}

//------------------------------------------------------------------------------
bool CollapseCostModel::EvaluateTriangleOrCreaseEdge(
  const Id* tri, CollapseCandidate& c, CostScratch& scratch) const
{
  const bool triangle = this->EvaluateTriple(tri, c, scratch);
  CollapseCandidate edge;
  // (With the scratch: the edges solved lately and around a survivor are reused, as for the
  // quadric method, to the same numbers.)
  if (!this->EvaluateBestEdge(tri, edge, &scratch))
  {
    return triangle; // a locked corner: no edge either
  }
  // (A triangle with a corner on a curve where sheets meet cannot collapse: its edges can.)
  if (!triangle || c.Cost > CreaseEdgeFactor * edge.Cost)
  {
    c = edge;
  }
  return true;
}

//------------------------------------------------------------------------------
bool CollapseCostModel::EvaluateChoice(
  Id t, int choice, CollapseCandidate& c, CostScratch& scratch) const
{
  const Id* tri = this->State.Mesh.Triangle(t);
  if (choice == TriangleChoice)
  {
    return this->EvaluateTriple(tri, c, scratch);
  }
  if (this->State.IsLocked(tri[choice]) || this->State.IsLocked(tri[(choice + 1) % 3]))
  {
    return false;
  }
  this->Edge(tri, choice, c);
  return true;
}

//------------------------------------------------------------------------------
void CollapseCostModel::EvaluateVanish(const Id* members, int count, CollapseCandidate& c) const
{
  Quadric q;
  double centroid[3] = { 0.0, 0.0, 0.0 };
  for (int k = 0; k < count; ++k)
  {
    q += this->State.Quadrics[members[k]];
    const double* p = this->State.Mesh.Point(members[k]);
    for (int i = 0; i < 3; ++i)
    {
      centroid[i] += p[i] / count;
    }
  }
  std::copy_n(members, count, c.Members);
  c.MemberCount = count;
  c.Choice = VanishChoice;
  c.Swapped = false;
  c.Area = 0.0;
  q.MinimizeRegularized(centroid, c.Position);
  const double value = q.Evaluate(c.Position);
  c.Cost = value / this->SurfaceScale(members, count);
  c.Error = q.Weight() > 0.0 ? std::sqrt(value / q.Weight()) : 0.0;
}

//------------------------------------------------------------------------------
bool CollapseCostModel::EvaluateTriple(const Id* members, CollapseCandidate& c, CostScratch& scratch) const
{
  const double* p[3];
  for (int k = 0; k < 3; ++k)
  {
    if (this->State.IsLocked(members[k]) || this->State.IsCurve(members[k]))
    {
      return false; // where sheets meet, only edges collapse
    }
    p[k] = this->State.Mesh.Point(members[k]);
  }
  c.Area = 0.5 * TriangleNormal(p[0], p[1], p[2], c.Normal);
  std::copy_n(members, 3, c.Members);
  c.MemberCount = 3;
  c.Choice = TriangleChoice;
  c.Swapped = false;
  const Quadric q = this->State.Quadrics[members[0]] + this->State.Quadrics[members[1]] +
    this->State.Quadrics[members[2]];
  double centroid[3];
  for (int i = 0; i < 3; ++i)
  {
    centroid[i] = (p[0][i] + p[1][i] + p[2][i]) / 3.0;
  }
  if (this->Options.Method == CollapseMethod::Quadric)
  {
    this->Place(q, p, 3, centroid, c.Position);
    const double value = q.Evaluate(c.Position);
    c.Cost = value / this->SurfaceScale(members, 3);
    c.Error = q.Weight() > 0.0 ? std::sqrt(value / q.Weight()) : 0.0;
    if (this->Options.Operator == CollapseOperator::TrianglesAndEdges)
    {
      c.Cost /= this->Options.TriangleCostFactor; // ranked against edges, see below
    }
    return true;
  }

  // Curvature method (paper 000): fit, collapse point c + f(0,0) n, weight terms.
  const bool boundary = this->State.IsBoundary(members[0]) ||
    this->State.IsBoundary(members[1]) || this->State.IsBoundary(members[2]);
  this->FitSurface(members, c, scratch, !boundary);
  if (boundary)
  {
    // Paper 000 collapses only triangles with a complete stencil, none on a boundary; on an
    // open mesh (an isosurface cut by its volume) that would keep every boundary triangle. Such
    // a triangle goes to the point minimising its merged planes instead, whose planes through
    // the boundary edges keep the boundary in place: the fit, blind to the boundary, would pull
    // it inwards.
    q.MinimizeRegularized(centroid, c.Position);
  }
  c.Alpha = ShapeMeasure(p[0], p[1], p[2]);
  // The merged vertex's valence: the triangles around the three vertices, less the ones
  // counted twice or dying (6 for the collapsing triangle's corners, 3 for its neighbours').
  int triangles = 0;
  for (int k = 0; k < 3; ++k)
  {
    triangles += this->State.TriangleCount(members[k]);
  }
  const int valence = std::max(0, triangles - 9 + (boundary ? 1 : 0));
  c.ValenceTerm = std::abs(valence - 6) / ValenceNormalization;
  if (this->Options.CurvatureRanking == CurvatureCost::Weight)
  {
    c.Cost = this->CurvatureWeight(c);
  }
  else
  {
    // The merged planes measure the same kind of thing, an area-weighted squared distance, at
    // the collapse point: the larger of the two counts. The planes see what a quadratic
    // smooths over (a crease, a stencil grown around much of a small sphere), the fit sees the
    // new triangles between the point and the rim. Where the fit fails even on the extended
    // stencil (too few distinct points) the planes alone.
    c.Cost = q.Evaluate(c.Position);
    if (scratch.Fit.Valid)
    {
      c.Cost = std::max(c.Cost,
        this->FitDeviation(scratch, c.Position));
      if (!boundary)
      {
        // A second collapse point competes, the merged planes' minimiser, off the normal where
        // the planes say so: the point of lower cost is taken. (On the benchmark isosurfaces
        // the Hausdorff distance fell by up to 18% and the RMS distance by 3-4%, except on the
        // metaballs at 1%, where it rose by 17%. Only the planes' optimal height on the
        // normal instead: no gain, and half as much error again on a noisy sphere.)
        double planes[3];
        q.MinimizeRegularized(centroid, planes);
        const double cost =
          std::max(q.Evaluate(planes), this->FitDeviation(scratch, planes));
        if (cost < c.Cost)
        {
          c.Cost = cost;
          std::copy_n(planes, 3, c.Position);
        }
      }
    }
  }
  c.Error = q.RmsDistance(c.Position);
  return true;
}

//------------------------------------------------------------------------------
void CollapseCostModel::Place(const Quadric& q, const double* const* points, int count,
  const double origin[3], double position[3]) const
{
  if (this->Options.Placement == CollapsePlacement::PaperCandidates &&
    this->Options.Method == CollapseMethod::Quadric)
  {
    PlaceByCandidates(q, points, count, PaperSolvableTolerance, position);
  }
  else
  {
    q.MinimizeRegularized(origin, position);
  }
}

//------------------------------------------------------------------------------
double CollapseCostModel::Edge(const Id* tri, int k, CollapseCandidate& c) const
{
  const int l = (k + 1) % 3;
  EdgeSolution e;
  this->SolveEdge(tri[k], tri[l], e, nullptr);
  c.Cost = e.Cost;
  c.Error = e.Error();
  std::copy_n(e.Position, 3, c.Position);
  c.Members[0] = tri[k];
  c.Members[1] = tri[l];
  c.MemberCount = 2;
  c.Choice = k;
  c.Swapped = false;
  return c.Cost;
}

void CollapseCostModel::SolveEdge(Id a, Id b, EdgeSolution& e, CostScratch* scratch) const
{
  const bool spoke = scratch != nullptr && (a == scratch->SpokeCentre || b == scratch->SpokeCentre);
  const Id other = spoke && a == scratch->SpokeCentre ? b : a;
  if (spoke)
  {
    for (const EdgeSolution& known : scratch->Spokes)
    {
      if (known.Other == other)
      {
        e = known;
        return;
      }
    }
  }
  CostScratch::RecentEdge* recent = nullptr;
  if (scratch != nullptr && !scratch->RecentEdges.empty())
  {
    const Id low = std::min(a, b), high = std::max(a, b);
    const std::uint32_t hash = static_cast<std::uint32_t>(low) * 0x9e3779b1u ^
      static_cast<std::uint32_t>(high) * 0x85ebca6bu;
    recent = &scratch->RecentEdges[(hash >> 16) & (scratch->RecentEdges.size() - 1)];
    if (recent->Low == low && recent->High == high)
    {
      e = recent->Solution; // the same numbers whichever end comes first
      e.Other = other;
      return;
    }
    recent->Low = low;
    recent->High = high;
  }
  const double* pa = this->State.Mesh.Point(a);
  const double* pb = this->State.Mesh.Point(b);
  if (!this->State.EdgeMayMerge(a, b))
  {
    // Never legal (see CollapseMesh::EdgeMayMerge): priced out, so that a triangle with a
    // legal edge besides does not wait on this one.
    e.Cost = Infinity;
    e.Value = Infinity;
    e.Weight = 0.0;
    e.Other = other;
    for (int i = 0; i < 3; ++i)
    {
      e.Position[i] = 0.5 * (pa[i] + pb[i]);
    }
    if (spoke)
    {
      scratch->Spokes.push_back(e);
    }
    if (recent != nullptr)
    {
      recent->Solution = e;
    }
    return;
  }
  const Quadric q = this->State.Quadrics[a] + this->State.Quadrics[b];
  const double middle[3] = { 0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2]) };
  const double* ends[2] = { pa, pb };
  this->Place(q, ends, 2, middle, e.Position);
  e.Value = q.Evaluate(e.Position);
  const Id pair[2] = { a, b };
  e.Cost = e.Value / this->SurfaceScale(pair, 2);
  e.Weight = q.Weight();
  e.Other = other;
  if (spoke)
  {
    scratch->Spokes.push_back(e);
  }
  if (recent != nullptr)
  {
    recent->Solution = e;
  }
}

int CollapseCostModel::HubEdgesToSkip(const Id* tri) const
{
  int hubs = 0;
  for (int k = 0; k < 3; ++k)
  {
    hubs |= this->State.TriangleCount(tri[k]) > FanTriangleLimit ? 1 << k : 0;
  }
  if (hubs == 0)
  {
    return 0;
  }
  // Edge k joins corners k and k + 1: it is skipped when either is a hub, unless that leaves
  // no edge (two or three hubs).
  int skip = 0;
  for (int k = 0; k < 3; ++k)
  {
    skip |= (hubs & ((1 << k) | (1 << ((k + 1) % 3)))) != 0 ? 1 << k : 0;
  }
  return skip == 7 ? 0 : skip;
}

double CollapseCostModel::BestEdge(
  const Id* tri, int skip, CollapseCandidate& c, double& worst, CostScratch* scratch) const
{
  // Solve the three edges, keep the cheapest (ties: the first), leaving out those in `skip`.
  EdgeSolution edge, best;
  best.Cost = Infinity;
  int bestEdge = 0;
  worst = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    if ((skip & (1 << k)) != 0)
    {
      continue;
    }
    this->SolveEdge(tri[k], tri[(k + 1) % 3], edge, scratch);
    worst = std::max(worst, edge.Value);
    if (edge.Cost < best.Cost)
    {
      best = edge;
      bestEdge = k;
    }
  }
  c.Cost = best.Cost;
  c.Error = best.Error();
  std::copy_n(best.Position, 3, c.Position);
  c.Members[0] = tri[bestEdge];
  c.Members[1] = tri[(bestEdge + 1) % 3];
  c.MemberCount = 2;
  c.Choice = bestEdge;
  c.Swapped = false;
  return best.Cost;
}

bool CollapseCostModel::EvaluateBestEdge(
  const Id* tri, CollapseCandidate& c, CostScratch* scratch) const
{
  if (this->State.IsLocked(tri[0]) || this->State.IsLocked(tri[1]) || this->State.IsLocked(tri[2]))
  {
    return false;
  }
  double worst;
  this->BestEdge(tri, this->HubEdgesToSkip(tri), c, worst, scratch);
  return true;
}

//------------------------------------------------------------------------------
bool CollapseCostModel::EvaluateTriangleOrEdge(
  const Id* tri, CollapseCandidate& c, CostScratch& scratch) const
{
  if (this->State.IsLocked(tri[0]) || this->State.IsLocked(tri[1]) || this->State.IsLocked(tri[2]))
  {
    return false;
  }
  double worst;
  const int hubEdges = this->HubEdgesToSkip(tri);
  const double best = this->BestEdge(tri, hubEdges, c, worst, &scratch);
  if (hubEdges != 0)
  {
    return true; // the triangle collapse would move the hub
  }
  // A triangle collapse removes twice the triangles of an edge collapse: it is taken when it
  // costs at most TriangleCostFactor times the cheapest edge, and ranked by its cost over that
  // factor. Its quadric contains each edge's, so its value is at least the largest edge's: when
  // that over the triangle's surface scale alone exceeds the limit, the edge wins without
  // solving for the triangle.
  const double limit = this->Options.TriangleCostFactor * best;
  if (worst / this->SurfaceScale(tri, 3) > limit)
  {
    return true;
  }
  CollapseCandidate triangle;
  CostScratch unused;
  if (this->EvaluateTriple(tri, triangle, unused) &&
    triangle.Cost * this->Options.TriangleCostFactor <= limit)
  {
    c = triangle;
  }
  return true;
}

//------------------------------------------------------------------------------
double CollapseCostModel::CollapseHeight(const CostScratch& scratch, bool leastDeviation) const
{
  const SurfaceFitResult& fit = scratch.Fit;
  // The new triangles join the collapse point p = c + h n to the stencil boundary polygon. Over
  // one of them, (p, a, b) seen in the fit's frame, the mean of the linear triangle is the mean
  // of its corner heights, and the mean of the quadratic f is the mean of f at the edge
  // midpoints (exact for quadratics). The h that makes the area-weighted mean difference zero is
  // linear in h. At h = f(0, 0) (the paper's point, on the surface) the triangles are chords
  // lying inside a convex surface, which costs error everywhere along them.
  // FitDeviation's squared differences at the midpoints of the spokes (p, a) and (p, b) are
  // quadratic in h, the one at the midpoint of (a, b) does not depend on it: its least h
  // leaves out the (a, b) term, which the mean-difference height makes up for by lifting p.
  double weighted = 0.0, total = 0.0;
  for (std::size_t e = 0; e < scratch.RimMidpoints.size(); ++e)
  {
    const double* a = scratch.RimPoint(scratch.RimEnds[2 * e]);
    const double* b = scratch.RimPoint(scratch.RimEnds[2 * e + 1]);
    const double area = scratch.RimWeights[e] * 0.5 * std::abs(a[0] * b[1] - a[1] * b[0]);
    const double spokes = a[3] + b[3] - 0.5 * (a[2] + b[2]);
    weighted += area * (leastDeviation ? spokes : spokes + scratch.RimMidpoints[e]);
    total += area;
  }
  return total > 0.0 ? weighted / total : fit.Height;
}

//------------------------------------------------------------------------------
double CollapseCostModel::FitDeviation(CostScratch& scratch, const double position[3]) const
{
  const SurfaceFitResult& fit = scratch.Fit;
  // Over a new triangle (p, a, b) the height difference g = linear - f is quadratic, and the
  // midpoint rule (the mean of g^2 at the edge midpoints) integrates quadratics exactly; for
  // g^2, of degree four, it is an estimate that is exact where g is linear.
  double up, vp, dp;
  fit.Frame(position, up, vp, dp);
  // g at the midpoint of each spoke (p, a), once per rim vertex.
  std::vector<double>& spokes = scratch.RimSpokes;
  spokes.resize(scratch.Listed.size());
  for (const std::uint32_t i : scratch.RimPlaces)
  {
    const double* a = scratch.RimPoint(i);
    spokes[i] = 0.5 * (dp + a[2]) - fit.At(0.5 * (up + a[0]), 0.5 * (vp + a[1]));
  }
  double deviation = 0.0;
  for (std::size_t e = 0; e < scratch.RimMidpoints.size(); ++e)
  {
    const std::uint32_t ia = scratch.RimEnds[2 * e], ib = scratch.RimEnds[2 * e + 1];
    const double* a = scratch.RimPoint(ia);
    const double* b = scratch.RimPoint(ib);
    const double area = scratch.RimWeights[e] * 0.5 *
      std::abs((a[0] - up) * (b[1] - vp) - (a[1] - vp) * (b[0] - up));
    const double pa = spokes[ia], pb = spokes[ib];
    const double ab = scratch.RimMidpoints[e]; // g there with the opposite sign, squared alike
    deviation += area * (pa * pa + pb * pb + ab * ab) / 3.0;
  }
  return deviation;
}

//------------------------------------------------------------------------------
void CollapseCostModel::FrameRim(CostScratch& scratch) const
{
  const SurfaceFitResult& fit = scratch.Fit;
  const std::size_t places = scratch.Listed.size();
  const std::size_t edges = scratch.RimWeights.size();
  scratch.RimPoints.resize(CostScratch::RimPointSize * places);
  scratch.RimFramed.assign(places, 0);
  scratch.RimPlaces.clear();
  for (const std::uint32_t i : scratch.RimEnds)
  {
    if (!scratch.RimFramed[i])
    {
      scratch.RimFramed[i] = 1;
      scratch.RimPlaces.push_back(i);
      double* f = scratch.RimPoint(i);
      fit.Frame(this->State.Mesh.Point(scratch.Listed[i]), f[0], f[1], f[2]);
      f[3] = fit.At(0.5 * f[0], 0.5 * f[1]);
    }
  }
  scratch.RimMidpoints.resize(edges);
  for (std::size_t e = 0; e < edges; ++e)
  {
    const double* a = scratch.RimPoint(scratch.RimEnds[2 * e]);
    const double* b = scratch.RimPoint(scratch.RimEnds[2 * e + 1]);
    scratch.RimMidpoints[e] = fit.At(0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])) - 0.5 * (a[2] + b[2]);
  }
}

//------------------------------------------------------------------------------
void CollapseCostModel::FitSurface(
  const Id* tri, CollapseCandidate& c, CostScratch& scratch, bool place) const
{
  double centroid[3] = { 0, 0, 0 };
  double scale = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double* a = this->State.Mesh.Point(tri[k]);
    const double* b = this->State.Mesh.Point(tri[(k + 1) % 3]);
    scale += Distance(a, b) / 3.0;
    for (int i = 0; i < 3; ++i)
    {
      centroid[i] += a[i] / 3.0;
    }
  }

  this->ListStencil(tri, scratch);
  this->ListFitPoints(tri, scratch);
  std::vector<double>& points = scratch.Points;
  SurfaceFitResult fit = FitQuadraticHeightField(
    centroid, c.Normal, points.data(), static_cast<int>(points.size() / 3), scale);
  if (!fit.Valid)
  {
    // Extended stencil: add the next ring of vertices.
    this->AddNextRing(scratch);
    fit = FitQuadraticHeightField(
      centroid, c.Normal, points.data(), static_cast<int>(points.size() / 3), scale);
  }
  // The collapse point is on the normal through the centroid (paper 000: at the fitted
  // surface, c + f(0, 0) n), at the height where the new triangles lie on the fitted surface on
  // average or, ranked by FitDeviation, at its least (see CollapseHeight). A quadratic fitted
  // to points spread far beyond the triangle can extrapolate wildly at its centre; the surface
  // cannot be further from the centroid than about the triangle's size.
  scratch.Fit = fit;
  if (fit.Valid)
  {
    this->FrameRim(scratch);
  }
  double height = 0.0;
  if (fit.Valid && place)
  {
    const double best =
      this->CollapseHeight(scratch, this->Options.CurvatureRanking == CurvatureCost::FitDeviation);
    height = std::max(-scale, std::min(scale, best));
  }
  c.Kappa = fit.Valid ? fit.AbsoluteCurvature : 0.0;
  for (int i = 0; i < 3; ++i)
  {
    c.Position[i] = centroid[i] + height * c.Normal[i];
  }
}

//------------------------------------------------------------------------------
void CollapseCostModel::ListStencil(const Id* tri, CostScratch& scratch) const
{
  // The stencil: every vertex of the triangles around the three corners (current positions):
  // the corners and, from every triangle of their fans, the other vertices. (Only the vertices
  // that follow the corner would do around a consistently oriented closed fan, but not across
  // the seam of a non-orientable surface.)
  std::vector<Id>& listed = scratch.Listed;
  std::vector<std::uint32_t>& rimEnds = scratch.RimEnds;
  std::vector<double>& rimWeights = scratch.RimWeights;
  listed.clear();
  rimEnds.clear();
  rimWeights.clear();
  const auto member = [&](Id x) { return x == tri[0] || x == tri[1] || x == tri[2]; };
  // Duplicates are dropped as they come (a dozen or so distinct vertices, most seen two to four
  // times), by a small hash set: sorting the list with its duplicates had been a tenth of the
  // curvature method's time, and a linear search for each a twentieth. Around a vertex of high
  // valence (a cone's tip, a UV sphere's pole) the set would fill up: once more than
  // LinearStencil vertices are listed, duplicates are listed again (each place is framed on its
  // own, to the same numbers) and dropped by the sort. add returns x's place.
  std::vector<Id>& set = scratch.StencilSet;
  std::vector<std::uint32_t>& setPlaces = scratch.StencilPlaces;
  if (set.size() != StencilSlots)
  {
    set.assign(StencilSlots, InvalidId);
    setPlaces.assign(StencilSlots, 0);
  }
  const auto slotOf = [&](Id x) {
    std::size_t slot = StencilHome(x);
    while (set[slot] != InvalidId && set[slot] != x)
    {
      slot = (slot + 1) & (StencilSlots - 1);
    }
    return slot;
  };
  const auto add = [&](Id x) {
    const auto place = static_cast<std::uint32_t>(listed.size());
    if (listed.size() > LinearStencil)
    {
      listed.push_back(x);
      return place;
    }
    const std::size_t slot = slotOf(x);
    if (set[slot] == x)
    {
      return setPlaces[slot];
    }
    set[slot] = x;
    setPlaces[slot] = place;
    listed.push_back(x);
    return place;
  };
  add(tri[0]);
  add(tri[1]);
  add(tri[2]);
  for (int k = 0; k < 3; ++k)
  {
    const Id corner = tri[k];
    // Around a fan's centre about every `every`-th ring triangle, standing for `every` of them
    // (see FanTriangleLimit; the neighbours of the collapsing triangle still come from the walks
    // around its other corners, unless those are fans' centres too).
    const Id every = EveryNthAround(this->State, corner);
    this->State.ForEachTriangle(corner, every, [&](Id s) {
      const Id* st = this->State.Mesh.Triangle(s);
      const int c = CornerOf(st, corner);
      const Id next = st[(c + 1) % 3], previous = st[(c + 2) % 3];
      if (!member(next) && !member(previous))
      {
        rimEnds.push_back(add(next)); // a ring triangle: its far edge bounds a new triangle
        rimEnds.push_back(add(previous));
        rimWeights.push_back(static_cast<double>(every));
      }
      else
      {
        add(member(next) ? previous : next);
      }
    });
  }
  // Empty the set for the next stencil: the slots of the vertices it holds, the first ones
  // listed (each probe goes on past the slots emptied before it, to where its vertex went).
  for (std::size_t i = 0; i < std::min(listed.size(), LinearStencil + 1); ++i)
  {
    std::size_t slot = StencilHome(listed[i]);
    while (set[slot] != listed[i])
    {
      slot = (slot + 1) & (StencilSlots - 1);
    }
    set[slot] = InvalidId;
  }
  // The sorted stencil, the order the fit sums its points in.
  std::vector<Id>& stencil = scratch.Vertices;
  stencil.assign(listed.begin(), listed.end());
  std::sort(stencil.begin(), stencil.end());
  stencil.erase(std::unique(stencil.begin(), stencil.end()), stencil.end());
}

//------------------------------------------------------------------------------
void CollapseCostModel::ListFitPoints(const Id* tri, CostScratch& scratch) const
{
  const std::vector<Id>& stencil = scratch.Vertices;
  std::vector<double>& points = scratch.Points;
  points.resize(3 * stencil.size());
  for (std::size_t i = 0; i < stencil.size(); ++i)
  {
    std::copy_n(this->State.Mesh.Point(stencil[i]), 3, points.data() + 3 * i);
  }
  // Ancestral points (paper 000, section 7): the original vertices merged into the three
  // corners, as an evenly strided subset when there are more than MaximumFitPoints.
  Id ancestors = 0;
  for (int k = 0; k < 3; ++k)
  {
    ancestors += this->Tracker.AncestorCount(tri[k]);
  }
  const Id stride = std::max<Id>(1, (ancestors + this->Options.MaximumFitPoints - 1) /
      std::max(1, this->Options.MaximumFitPoints));
  Id index = 0;
  for (int k = 0; k < 3; ++k)
  {
    this->Tracker.ForEachAncestor(tri[k], stride, index, [&](Id u) {
      double x[3];
      this->OriginalPoints.Get(u, x);
      points.push_back(x[0]);
      points.push_back(x[1]);
      points.push_back(x[2]);
    });
  }
}

//------------------------------------------------------------------------------
void CollapseCostModel::AddNextRing(CostScratch& scratch) const
{
  const std::vector<Id>& stencil = scratch.Vertices;
  std::vector<double>& points = scratch.Points;
  const std::size_t firstRing = stencil.size();
  for (std::size_t i = 0; i < firstRing; ++i)
  {
    if (scratch.Owner != nullptr && scratch.Owner[stencil[i]] != scratch.Block)
    {
      continue;
    }
    this->State.ForEachTriangle(stencil[i], EveryNthAround(this->State, stencil[i]), [&](Id s) {
      const Id* st = this->State.Mesh.Triangle(s);
      for (int k = 0; k < 3; ++k)
      {
        if (!std::binary_search(stencil.begin(), stencil.begin() + firstRing, st[k]))
        {
          const double* x = this->State.Mesh.Point(st[k]);
          points.insert(points.end(), x, x + 3);
        }
      }
    });
  }
}

} // namespace meshlod
