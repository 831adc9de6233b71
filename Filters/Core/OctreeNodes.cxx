// Octree clustering: evaluating a node of the cluster tree (see OctreeClusteringInternals.h).
#include "OctreeClusteringInternals.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace meshlod
{
using namespace octree;

namespace
{
// A cluster's surface normal counts as coherent (see Evaluate) from this ratio up.
constexpr double CoherentNormal = 0.25;
// A representative that would flip a triangle is replaced by the best of the cluster's vertices
// that flip none: every vertex of a cluster of up to this many, else between this many and
// twice as many, evenly spaced in its order (see Evaluate).
constexpr Id FlipFreeCandidates = 32;
// A quadric value below this times the squared cell size and the planes' weight is rounding (an
// RMS distance of a millionth of the cell): the placement is exact.
constexpr double ExactPlacement = 1e-12;
// The threshold of a node of zero error, relative to its cell size (see UpdateThreshold).
constexpr double ZeroErrorOrder = 1e-7;
// A boundary vertex whose two boundary edges meet at less than this many degrees is a tip
// (LabelTips).
constexpr double TipAngle = 30.0;
// LabelTips' mark of a vertex on more than two boundary edges.
constexpr Id NoTip = -2;
// Places in [0, 1) spread evenly whatever the run of indices (the fractional parts of multiples
// of the golden ratio's fraction).
constexpr double GoldenFraction = 0.6180339887498949;
} // namespace

//------------------------------------------------------------------------------
bool OctreeClustering::Internals::CheapInadmissible(Id index) const
{
  const ClusterNode& n = this->Tree.Nodes[index];
  return n.Locked != 0 ||
    (this->Options.MaximumPointsPerCell > 0 && n.Count > this->Options.MaximumPointsPerCell) ||
    (this->Options.MaximumCellSize > 0.0 &&
      this->Tree.CellSize(n.Depth) > this->Options.MaximumCellSize);
}

// The smallest epsilon at which the node may be a cluster: its error once evaluated in full, before
// that e1 (a lower bound). The tree's e1 comes from quadrics summed with cancellations, so values
// at rounding level (under 1e-6 of the tree's size) are taken as zero; so are the full evaluation's
// with OrderFlatClusters (target counts; in the epsilon modes a cluster's error stays within
// epsilon). The evaluation recomputes the quadric directly, but the planes of a flat part's
// triangles still differ by the rounding of their single-precision points: a subdivided octagonal
// prism's flat clusters evaluated to 5e-8 to 7e-7 of its size, in no order and above the tie-break
// below, so a search for 1% of its 114,688 triangles found no level between 4,752 and 290 triangles
// and took one of clusters across its edges (1,252 triangles at 8% of the diagonal); with them at
// zero it found 2,172 without error.
//
// With OrderFlatClusters (target counts), nodes of zero error (or almost) get a threshold of
// their own, far below any error that matters: ZeroErrorOrder times their cell size, times 1 to
// 1.25 by a scrambled place in the tree (so that a count stopping part way through a depth
// spreads its merges over a flat region instead of coarsening one end of it first). Without it
// a flat part merged whole at the first epsilon above 0, so no count between its input and its
// fewest triangles was reachable (a flat 32 x 32 grid asked for 200 triangles got 8, a disk of
// 120,000 asked for 12,000 got 4,488); with it the smallest cells merge first. A tie-break
// only: the factor stays below the 2^(1/3) between binary depths, so a parent's threshold stays
// above its children's; it is 0 when all points lie at one place (every cluster then merges at
// once, as before). (For a mesh under about 1e-24 across the smallest of these fall below
// single precision's normal range and tie: flat parts there merge in larger steps again.)
void OctreeClustering::Internals::UpdateThreshold(Id index)
{
  float& thr = this->Thr[index];
  if (this->State[index] == NodeState::Inadmissible || this->Refused[index] ||
    this->CheapInadmissible(index))
  {
    thr = Infinite;
    return;
  }
  const ClusterNode& node = this->Tree.Nodes[index];
  const bool evaluated = this->State[index] == NodeState::Admissible;
  const double error =
    evaluated ? static_cast<double>(this->Slot(index)[6]) : static_cast<double>(node.E1);
  // (An evaluated error counts as zero for the order of flat clusters only: in the epsilon
  // modes a cluster's error stays within its level's epsilon.)
  const bool rounding =
    error < 1e-6 * this->Tree.Size && (!evaluated || this->Options.OrderFlatClusters);
  thr = rounding ? 0.0f : static_cast<float>(error);
  if (this->Options.OrderFlatClusters)
  {
    const double place = std::fmod(static_cast<double>(index) * GoldenFraction, 1.0);
    const double tieBreak =
      ZeroErrorOrder * this->Tree.Extent * std::exp2(-node.Depth / 3.0) * (1.0 + 0.25 * place);
    thr = std::max(thr, static_cast<float>(tieBreak));
  }
}

//------------------------------------------------------------------------------
// Normal (not normalised) of crossing triangle i with its corner inside moved to v0 (its corners
// in their order: the same arithmetic as the triangle's own normal).
void OctreeClustering::Internals::MovedNormal(
  const EvaluationScratch& crossing, size_t i, const double v0[3], double moved[3]) const
{
  const int c = static_cast<int>(crossing.Crossing[i] % 3);
  const double* ends = crossing.CrossingEnds.data() + 6 * i;
  const double* p[3];
  p[c] = v0;
  p[(c + 1) % 3] = ends;
  p[(c + 2) % 3] = ends + 3;
  Normal(p[0], p[1], p[2], moved);
}

//------------------------------------------------------------------------------
// e2 (§3): the squared distance of the vertex inside a crossing triangle (v, a, b) to the new
// triangle (v0, a, b) is (area(v, a, b) / area(v0, a, b))^2 times the squared distance of v0 to
// the original plane, so e2 reweights the crossing triangles' planes.
void OctreeClustering::Internals::AddCrossingTerms(const double v0[3],
  const EvaluationScratch& crossing,
  Quadric& q) const
{
  for (size_t i = 0; i < crossing.Crossing.size(); ++i)
  {
    double moved[3];
    this->MovedNormal(crossing, i, v0, moved);
    const double* n = crossing.CrossingNormals.data() + 3 * i;
    const double before = Dot(n, n);
    const double after = Dot(moved, moved);
    const double weight =
      after * MaximumCrossingWeight > before ? before / after : MaximumCrossingWeight;
    q.Add(crossing.CrossingPlanes[i], weight);
  }
}

//------------------------------------------------------------------------------
// §2.4: clustering must not flip a triangle joining the cluster to the outside. A crossing
// triangle whose two outside vertices share a cell of the cluster's size will most likely fall
// into one neighbouring cluster and vanish, so it is not held against the cluster (otherwise the
// thin triangles of isosurfaces would forbid almost every cluster on a curved surface).
//
// With `surface` (the cluster's area-weighted normal, given when it is coherent), a moved
// triangle that turns against its own normal but still faces the way the cluster's surface does
// is not a flip: on a rough surface (a scan, noisy data) the input triangles' normals scatter
// about the surface's, and the test against them alone refused nearly every node up to the
// coarsest (a noisy sphere asked for 1% of its triangles kept eleven times that many). The
// level's triangles are still checked against the surface around their clusters (MarkFolds).
bool OctreeClustering::Internals::HasFlip(const double v0[3],
  const EvaluationScratch& crossing,
  int depth,
  const double* surface) const
{
  for (size_t i = 0; i < crossing.Crossing.size(); ++i)
  {
    const Id item = crossing.Crossing[i];
    const Id* tri = this->Mesh.Triangle(item / 3);
    const int c = static_cast<int>(item % 3);
    if (this->Tree.CommonDepth(tri[(c + 1) % 3], tri[(c + 2) % 3]) >= depth)
    {
      continue;
    }
    double moved[3];
    this->MovedNormal(crossing, i, v0, moved);
    if (!(Dot(crossing.CrossingNormals.data() + 3 * i, moved) > 0.0) &&
      !(surface != nullptr && Dot(surface, moved) > 0.0))
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
// The largest distance from v0 (relative coordinates) to the planes through the given boundary
// edges perpendicular to their triangles (the planes of BoundaryEdgeQuadric).
double OctreeClustering::Internals::BoundaryDistance(const std::vector<Id>& edges,
  const double v0[3]) const
{
  double largest = 0.0;
  for (const Id item : edges)
  {
    const Id* tri = this->Mesh.Triangle(item / 3);
    const int k = static_cast<int>(item % 3);
    double p[3][3];
    this->Tree.RelativeTriangle(tri, p);
    double n[3], m[3];
    Normal(p[0], p[1], p[2], n);
    const double* a = p[k];
    if (BoundaryEdgePlane(a, p[(k + 1) % 3], n, m))
    {
      const double w[3] = { v0[0] - a[0], v0[1] - a[1], v0[2] - a[2] };
      largest = std::max(largest, std::abs(Dot(m, w)));
    }
  }
  return largest;
}

//------------------------------------------------------------------------------
// Tips: boundary vertices whose two boundary edges meet at less than TipAngle (a spike, the
// pointed corner of a sheet, the end of a slit). The planes through the boundary edges that
// hold an open boundary within epsilon are almost parallel there and barely see a tip pulled
// back along them: a sheet's 3-degree corner lost 15% of its length at 1% of its triangles, and
// the spike of Dini's surface (vtkParametricDini, 300 x 300) 5% of the diagonal. A cluster
// holding a tip is placed at it and its error is at least the distance to any other tip it
// holds (PlaceAtTip), so tips stay within epsilon.
void OctreeClustering::Internals::LabelTips()
{
  this->Tip.clear();
  // The two boundary neighbours of each boundary vertex (InvalidId, or a third: not a tip).
  std::vector<std::array<Id, 2>> ends;
  this->ForEachBoundaryEdge([&](Id a, Id b) {
    if (ends.empty())
    {
      ends.assign(this->NV, { InvalidId, InvalidId });
    }
    for (const auto& [v, w] : { std::make_pair(a, b), std::make_pair(b, a) })
    {
      std::array<Id, 2>& e = ends[v];
      if (e[0] == InvalidId)
      {
        e[0] = w;
      }
      else
      {
        e[1] = e[1] == InvalidId ? w : NoTip;
      }
    }
  });
  if (ends.empty())
  {
    return;
  }
  const double cosine = std::cos(TipAngle * M_PI / 180.0);
  this->Tip.assign(this->NV, 0);
  for (Id v = 0; v < this->NV; ++v)
  {
    const std::array<Id, 2>& e = ends[v];
    if (e[0] == InvalidId || e[1] == InvalidId || e[1] == NoTip)
    {
      continue;
    }
    const double* p = this->Mesh.Point(v);
    const double* a = this->Mesh.Point(e[0]);
    const double* b = this->Mesh.Point(e[1]);
    const double u[3] = { a[0] - p[0], a[1] - p[1], a[2] - p[2] };
    const double w[3] = { b[0] - p[0], b[1] - p[1], b[2] - p[2] };
    const double lengths = std::sqrt(Dot(u, u) * Dot(w, w));
    this->Tip[v] = lengths > 0.0 && Dot(u, w) > cosine * lengths ? 1 : 0;
  }
}

// The boundary tips node holds among the ends of its boundary edges: v0 (relative coordinates)
// moves to the first (in edge order), and the distance to the farthest is returned (0 without
// any), a bound on the cluster's error.
double OctreeClustering::Internals::PlaceAtTip(
  Id node, const std::vector<Id>& edges, double v0[3]) const
{
  if (this->Tip.empty())
  {
    return 0.0;
  }
  bool placed = false;
  double farthest = 0.0;
  for (const Id item : edges)
  {
    const Id* tri = this->Mesh.Triangle(item / 3);
    const int k = static_cast<int>(item % 3);
    for (const Id v : { tri[k], tri[(k + 1) % 3] })
    {
      if (!this->Tip[v] || !this->Tree.Contains(node, v))
      {
        continue;
      }
      double x[3];
      this->Tree.RelativePoint(v, x);
      if (!placed)
      {
        std::copy_n(x, 3, v0);
        placed = true;
      }
      farthest = std::max(farthest, std::sqrt(Distance2(x, v0)));
    }
  }
  return farthest;
}

//------------------------------------------------------------------------------
// Move v0 (relative coordinates) to the closest point of the given boundary edges.
void OctreeClustering::Internals::ProjectOnBoundary(const std::vector<Id>& edges,
  double v0[3]) const
{
  double best[3] = { v0[0], v0[1], v0[2] };
  double bestDistance = std::numeric_limits<double>::max();
  for (const Id item : edges)
  {
    const Id* tri = this->Mesh.Triangle(item / 3);
    const int k = static_cast<int>(item % 3);
    double a[3], b[3];
    this->Tree.RelativePoint(tri[k], a);
    this->Tree.RelativePoint(tri[(k + 1) % 3], b);
    const double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double w[3] = { v0[0] - a[0], v0[1] - a[1], v0[2] - a[2] };
    const double length = Dot(d, d);
    const double t = length > 0.0 ? std::min(1.0, std::max(0.0, Dot(w, d) / length)) : 0.0;
    const double p[3] = { a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2] };
    const double e[3] = { v0[0] - p[0], v0[1] - p[1], v0[2] - p[2] };
    const double distance = Dot(e, e);
    if (distance < bestDistance)
    {
      bestDistance = distance;
      std::copy_n(p, 3, best);
    }
  }
  std::copy_n(best, 3, v0);
}

//------------------------------------------------------------------------------
// Where sheets meet along curves, a cluster holding curve points must hold one piece of one
// curve, with the curve going on outside it at both ends: then the curve keeps its course through
// the cluster's representative. Two pieces (of one curve or two) would be joined at one point,
// and a whole closed curve would shrink to a point, both changes of topology. (Junctions, where
// curves meet, are locked; every other curve point is on two curve edges.) The test walks the
// piece from an end and must meet every curve point of the node on the way.
bool OctreeClustering::Internals::CurveMayMerge(Id node) const
{
  if (!this->Tree.HoldsCurve(node))
  {
    return true;
  }
  const ClusterTree& tree = this->Tree;
  Id points = 0, start = InvalidId;
  const Id first = tree.Position(node);
  for (Id pos = first; pos < first + tree.Count(node); ++pos)
  {
    const Id v = tree.Order[pos];
    if (tree.IsCurve(v))
    {
      ++points;
      const Id* next = tree.Curves[v].Neighbours;
      if (start == InvalidId && (!tree.Contains(node, next[0]) || !tree.Contains(node, next[1])))
      {
        start = v;
      }
    }
  }
  if (start == InvalidId)
  {
    return false; // a closed curve lies wholly inside
  }
  Id walked = 1;
  for (Id previous = InvalidId, v = start;; ++walked)
  {
    const Id* next = tree.Curves[v].Neighbours;
    const Id step = tree.Contains(node, next[0]) && next[0] != previous ? next[0]
      : (tree.Contains(node, next[1]) && next[1] != previous ? next[1] : InvalidId);
    if (step == InvalidId)
    {
      // The other end: its second curve edge leads outside too (both, for a single point).
      const int leads =
        (tree.Contains(node, next[0]) ? 0 : 1) + (tree.Contains(node, next[1]) ? 0 : 1);
      return walked == points && leads == (walked == 1 ? 2 : 1);
    }
    if (!tree.IsCurve(step) || walked > points)
    {
      return false;
    }
    previous = v;
    v = step;
  }
}

//------------------------------------------------------------------------------
// The representative and error of a node (§2.3, §3), and whether it may be a cluster.
void OctreeClustering::Internals::Evaluate(Id index, EvaluationScratch& scratch)
{
  const Id node = this->NV + index;
  const ClusterNode& n = this->Tree.Nodes[index];
  Quadric q1;
  double* slot = this->Slot(index);
  this->Tree.RelatedQuadric(node, q1, slot + 3, &scratch);
  const EvaluationScratch& crossing = scratch;

  double centre[3];
  this->Tree.Centroid(node, centre);
  double v0[3];
  this->PlaceRepresentative(q1, crossing, centre, this->Tree.CellSize(n.Depth), v0);
  double value = this->KeepInsideCell(node, q1, crossing, centre, v0);
  // A cluster on an open boundary keeps its representative on the input's boundary: the closest
  // point of its boundary edges (a small move, paid for in the error below), or the boundary's
  // tip when it holds one (PlaceAtTip).
  double tipDistance = 0.0;
  if (!scratch.BoundaryEdges.empty())
  {
    this->ProjectOnBoundary(scratch.BoundaryEdges, v0);
    tipDistance = this->PlaceAtTip(node, scratch.BoundaryEdges, v0);
    value = this->PlacementError(q1, crossing, v0);
  }
  // The cluster's normal is coherent when its triangles mostly face one way: the length of their
  // summed normals (twice their area each) is at least CoherentNormal times twice their area
  // (the weight of the face planes, plus the boundary planes' if any).
  const double weight = q1.Weight();
  const double* normal = slot + 3;
  const bool coherent =
    Dot(normal, normal) >= 4.0 * CoherentNormal * CoherentNormal * weight * weight;
  const double* surface = coherent ? normal : nullptr;
  // Where the representative would flip a triangle, one of the cluster's vertices may stand in
  // for it (StandInVertex). (Not on an open boundary, whose representative stays on the
  // boundary.)
  bool flips = this->HasFlip(v0, crossing, n.Depth, surface);
  if (flips && scratch.BoundaryEdges.empty())
  {
    flips = this->StandInVertex(node, q1, crossing, surface, weight, value, v0);
  }
  const double error = this->ClusterError(scratch, value, weight, v0, tipDistance);
  std::copy_n(v0, 3, slot);
  slot[6] = static_cast<float>(error); // as a threshold, in single precision
  this->State[index] =
    flips || !this->CurveMayMerge(node) ? NodeState::Inadmissible : NodeState::Admissible;
  this->UpdateThreshold(index);
}

//------------------------------------------------------------------------------
// The representative before the checks, into v0: the minimiser of q1, then that of q1 with the
// crossing terms (e2, §3) at the last placement, until a step moves it by at most 1e-9 times the
// cell size or the iterations run out.
void OctreeClustering::Internals::PlaceRepresentative(const Quadric& q1,
  const EvaluationScratch& crossing,
  const double centre[3],
  double cell,
  double v0[3]) const
{
  const double tolerance = this->Options.PlacementTolerance;
  MinimizeQuadric(q1, centre, tolerance, v0);
  const int iterations = this->Options.RepresentativeIterations;
  for (int it = 0; it < iterations; ++it)
  {
    Quadric q = q1;
    this->AddCrossingTerms(v0, crossing, q);
    double v1[3];
    MinimizeQuadric(q, centre, tolerance, v1);
    const double d[3] = { v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2] };
    std::copy_n(v1, 3, v0);
    if (Dot(d, d) <= 1e-18 * cell * cell)
    {
      break;
    }
  }
}

//------------------------------------------------------------------------------
// The quadric error of a representative at x: q1, with the crossing terms at x when the
// representative is iterated (PlaceRepresentative).
double OctreeClustering::Internals::PlacementError(
  const Quadric& q1, const EvaluationScratch& crossing, const double x[3]) const
{
  Quadric q = q1;
  if (this->Options.RepresentativeIterations > 0)
  {
    this->AddCrossingTerms(x, crossing, q);
  }
  return q.Evaluate(x);
}

//------------------------------------------------------------------------------
// A placement far outside the cell means near-parallel planes met far away: fall back to the
// best of the centroid and the cluster's vertices (§2.3). Returns the error at v0.
double OctreeClustering::Internals::KeepInsideCell(Id node,
  const Quadric& q1,
  const EvaluationScratch& crossing,
  const double centre[3],
  double v0[3]) const
{
  const ClusterNode& n = this->Tree.Nodes[node - this->NV];
  double low[3], extent[3];
  this->Tree.CellBox(this->FirstVertex(node), n.Depth, low, extent);
  bool outside = false;
  for (int c = 0; c < 3; ++c)
  {
    outside = outside || v0[c] < low[c] - 0.5 * extent[c] || v0[c] > low[c] + 1.5 * extent[c];
  }
  double value = 0.0;
  if (outside)
  {
    std::copy_n(centre, 3, v0);
    value = this->PlacementError(q1, crossing, v0);
    const Id first = this->Tree.Position(node);
    for (Id pos = first; pos < first + n.Count; ++pos)
    {
      double p[3];
      this->Tree.RelativePoint(this->Tree.Order[pos], p);
      const double e = this->PlacementError(q1, crossing, p);
      if (e < value)
      {
        value = e;
        std::copy_n(p, 3, v0);
      }
    }
  }
  else
  {
    value = this->PlacementError(q1, crossing, v0);
  }
  return value;
}

//------------------------------------------------------------------------------
// Beyond §2.3: where the quadric's minimiser would flip a triangle, the best of the cluster's
// own vertices (a sample: FlipFreeCandidates) that flips none stands for it, and the cluster
// is refused only when none is left. The refusals split such clusters down to small cells,
// and the search for a count made up for them by coarser clusters elsewhere: on the 154k
// metaballs isosurface at 1% the Hausdorff and RMS distances fell from 1.10 and 0.80 to 0.73
// and 0.59 times vtkQuadricClustering's, on a torus and noisy spheres from 1.24-1.49 to
// 1.01-1.15 (Benchmarks/RESULTS.md). A vertex with an error stands in only where the
// minimiser has one: where the planes meet without one (a solid's corner or edge), a vertex
// that cuts it would not be refused but would take the cluster's error from nothing to
// much, and a search for a count then cut the corners of a flat-faced solid (a subdivided
// icosahedron asked for 205 triangles got 206 at 7.7% of its diagonal; vtkQuadricClustering
// had none at 192): there only a vertex without error may stand in (one in a flat part's
// plane).
// The stand-in goes into v0 and its error into `value`; returns whether the representative
// still flips a triangle (no vertex may stand in).
bool OctreeClustering::Internals::StandInVertex(Id node,
  const Quadric& q1,
  const EvaluationScratch& crossing,
  const double* surface,
  double weight,
  double& value,
  double v0[3]) const
{
  const ClusterNode& n = this->Tree.Nodes[node - this->NV];
  const double cell = this->Tree.CellSize(n.Depth);
  bool flips = true;
  const double exact = ExactPlacement * cell * cell * weight; // a value of rounding size
  const double acceptable = value > exact ? std::numeric_limits<double>::infinity() : exact;
  const Id first = this->Tree.Position(node);
  const Id stride = std::max<Id>(1, n.Count / FlipFreeCandidates);
  for (Id pos = first; pos < first + n.Count; pos += stride)
  {
    double p[3];
    this->Tree.RelativePoint(this->Tree.Order[pos], p);
    const double e = this->PlacementError(q1, crossing, p);
    if ((flips ? e <= acceptable : e < value) && !this->HasFlip(p, crossing, n.Depth, surface))
    {
      flips = false;
      value = e;
      std::copy_n(p, 3, v0);
    }
  }
  return flips;
}

//------------------------------------------------------------------------------
// The error: the root mean squared distance to the planes of the related triangle set, and
// separately the largest distance to a boundary edge's perpendicular plane (few, so they would
// hardly count in the mean: an open boundary is kept within epsilon too; their own root mean
// square let a large cluster at a corner of a rough height field sit 39 edges along one side,
// cutting the corner off). No single plane may be farther than twice that: a mean lets
// elongated or bent clusters stray far at their ends. `value`: the quadric's value at v0,
// `weight` its weight.
double OctreeClustering::Internals::ClusterError(const EvaluationScratch& scratch,
  double value,
  double weight,
  const double v0[3],
  double tipDistance) const
{
  double error = std::max(tipDistance, weight > 0.0 ? std::sqrt(value / weight) : 0.0);
  if (this->Options.BoundaryWeight > 0.0)
  {
    error = std::max(error, this->BoundaryDistance(scratch.BoundaryEdges, v0));
  }
  double farthest = 0.0;
  for (size_t i = 0; i < scratch.Planes.size(); i += 4)
  {
    const double* plane = scratch.Planes.data() + i;
    farthest = std::max(farthest, std::abs(Dot(plane, v0) + plane[3]));
  }
  return std::max(error, 0.5 * farthest);
}

//------------------------------------------------------------------------------
void OctreeClustering::Internals::RepresentativeOf(Id node, double out[3]) const
{
  if (this->Tree.IsLeaf(node))
  {
    std::copy_n(this->Mesh.Point(node), 3, out);
    return;
  }
  const double* r = this->Slot(node - this->NV);
  for (int c = 0; c < 3; ++c)
  {
    out[c] = r[c] + this->Tree.Centre[c];
  }
}

double OctreeClustering::Internals::NodeError(Id node) const
{
  return this->Tree.IsLeaf(node)
    ? 0.0
    : this->Slot(node - this->NV)[6];
}

// The area-weighted normal of the input surface at a node's vertices (not normalised); kept
// from the evaluation for internal nodes.
void OctreeClustering::Internals::SurfaceNormal(Id node, double normal[3]) const
{
  if (!this->Tree.IsLeaf(node))
  {
    std::copy_n(this->Slot(node - this->NV) + 3, 3, normal);
    return;
  }
  normal[0] = normal[1] = normal[2] = 0.0;
  const VertexTriangleAdjacency& adj = this->Topology.VertexTriangles;
  const Id first = this->Tree.Position(node);
  for (Id pos = first; pos < first + this->Tree.Count(node); ++pos)
  {
    const Id v = this->Tree.Order[pos];
    for (Id i = adj.Begin(v); i < adj.End(v); ++i)
    {
      const Id* tri = this->Mesh.Triangle(adj.Triangles[i]);
      double n[3];
      Normal(this->Mesh.Point(tri[0]), this->Mesh.Point(tri[1]), this->Mesh.Point(tri[2]), n);
      for (int c = 0; c < 3; ++c)
      {
        normal[c] += n[c];
      }
    }
  }
}

} // namespace meshlod
