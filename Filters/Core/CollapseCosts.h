// What a triangle collapse costs and where it goes, for both methods of TriangleCollapse.h.
#ifndef meshlod_CollapseCosts_h
#define meshlod_CollapseCosts_h

#include "CollapseMesh.h"
#include "TriangleCollapse.h"
#include "LocalSurfaceFit.h"
#include "Quadric.h"
#include "TriangleMesh.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace meshlod
{
class LevelTracker;

/// CollapseCandidate::Choice for a collapse of the whole triangle ...
constexpr int TriangleChoice = 3;
/// ... and for the vanishing of the small piece it belongs to (see EvaluateVanish).
constexpr int VanishChoice = 4;

/// CollapsePlacement::PaperCandidates: the 3x3 system counts as solvable when every eigenvalue
/// of A exceeds this times the largest (the regularised solve's epsilon, relative to the trace,
/// is of the same size).
constexpr double PaperSolvableTolerance = 1e-6;

/// The evaluation of one triangle collapse.
struct CollapseCandidate
{
  double Cost = 0.0;  // priority: lower collapses first
  double Error = 0.0; // RMS distance of the collapse point to the original planes merged into it
  double Position[3] = { 0, 0, 0 };
  double Normal[3] = { 0, 0, 1 }; // unit normal of the collapsing triangle
  // The merging vertices: 3, 2 for an edge, more for a vanishing piece.
  Id Members[VanishingPieceVertices] = { InvalidId, InvalidId, InvalidId };
  int MemberCount = 0;
  int Choice = TriangleChoice; // edge k (0, 1, 2) of the evaluated triangle, or the triangle
  bool Swapped = false; // the members are the path left by an edge swap, not a triangle
  int Dying = 0;        // set when made: the number of triangles the collapse removed
  // Curvature method: the terms of W = A (wk kappa + wa alpha + wv V) before normalisation.
  double Area = 0.0, Kappa = 0.0, Alpha = 0.0, ValenceTerm = 0.0;
};

/// The best collapse of one edge.
struct EdgeSolution
{
  Id Other = InvalidId; // the endpoint that is not the spoke centre (see CostScratch)
  double Cost = 0.0;   // Value over CollapseCostModel::SurfaceScale
  double Value = 0.0;  // the merged quadric's value at Position
  double Weight = 0.0; // of the merged quadric: Error() is the RMS distance to its planes
  double Position[3] = { 0, 0, 0 };
  double Error() const { return this->Weight > 0.0 ? std::sqrt(this->Value / this->Weight) : 0.0; }
};

/// Per-thread scratch for the evaluations.
struct CostScratch
{
  std::vector<Id> Vertices;
  std::vector<double> Points;
  // Curvature method. ListStencil lists the stencil's vertices in Listed (each once, but
  // around a vertex of very high valence) and, per far edge (a, b) of a ring triangle (a rim
  // edge), the places of a and b in that list (RimEnds) and the ring triangles it stands for
  // (RimWeights).
  std::vector<Id> Listed;
  std::vector<std::uint32_t> RimEnds;
  std::vector<double> RimWeights;
  SurfaceFitResult Fit; // the last fit
  /// After a valid fit (FrameRim): per place of Listed that a rim edge ends at, RimPointSize
  /// numbers (u, v, d in the fit's frame and the fit's height at (u / 2, v / 2)), those places
  /// in RimPlaces, and per rim edge the fit's height over its midpoint above the edge's own
  /// (RimMidpoints). The collapse height and each FitDeviation read them instead of framing
  /// the rim again: three times per fit, and each vertex twice, had been a fifth of the
  /// curvature method's time.
  static constexpr std::size_t RimPointSize = 4;
  std::vector<double> RimPoints;
  double* RimPoint(std::uint32_t place) { return this->RimPoints.data() + RimPointSize * place; }
  const double* RimPoint(std::uint32_t place) const
  {
    return this->RimPoints.data() + RimPointSize * place;
  }
  std::vector<std::uint32_t> RimPlaces;
  std::vector<std::uint8_t> RimFramed;
  std::vector<double> RimMidpoints;
  std::vector<double> RimSpokes; // FitDeviation's, per place
  /// ListStencil's set of the vertices listed so far (open addressing, InvalidId where empty,
  /// emptied again after each use) with their places in Listed.
  std::vector<Id> StencilSet;
  std::vector<std::uint32_t> StencilPlaces;
  /// After a collapse every triangle around the survivor is evaluated again, and each edge
  /// from the survivor belongs to two of them: between BeginSpokes(v) and EndSpokes() the
  /// solutions of edges from v are kept and reused (they are the same numbers either way).
  /// They are looked up one by one, so not around a vertex of more than FanTriangleLimit
  /// triangles (`triangles`): there every lookup scanned the whole fan, and a flat disc whose
  /// centre had 16,000 triangles spent most of a minute in the lookups. Such spokes are solved
  /// twice instead, to the same numbers.
  Id SpokeCentre = InvalidId;
  std::vector<EdgeSolution> Spokes;
  void BeginSpokes(Id centre, Id triangles)
  {
    this->SpokeCentre = triangles <= FanTriangleLimit ? centre : InvalidId;
    this->Spokes.clear();
  }
  void EndSpokes() { this->SpokeCentre = InvalidId; }
  /// While every triangle is evaluated in id order (Collapser::EvaluateAll), the solutions of
  /// the edges met lately, in a small table indexed by a hash of the edge's ends: neighbouring
  /// triangles mostly have neighbouring ids (a contouring filter writes a cell's triangles
  /// together), so each edge, shared by two triangles, is mostly solved once. Empty otherwise.
  struct RecentEdge
  {
    Id Low = InvalidId, High = InvalidId;
    EdgeSolution Solution;
  };
  std::vector<RecentEdge> RecentEdges; // a power of two entries, or none
  /// Collapses in parallel cells (PartitionedGreedy.cxx): a fit reads the triangles around a
  /// vertex only where Owner[vertex] is Block (another cell may be changing the others).
  const std::uint32_t* Owner = nullptr;
  std::uint32_t Block = 0;
};

/// The input's original points, which the curvature method's fits read (the ancestral points of
/// paper 000), relative to the engine's centre. Read from the caller's own coordinates where
/// TriangleCollapseOptions gives them, so that the engine keeps no copy; else from a copy.
struct OriginalPointReader
{
  const float* Float = nullptr;
  const double* Double = nullptr;
  const long long* Ids = nullptr; // engine vertex -> point of the arrays above; null: the same
  std::vector<double> Copy;       // x, y, z per vertex, relative to the centre; or empty
  double Centre[3] = { 0.0, 0.0, 0.0 };

  void Get(Id v, double x[3]) const
  {
    if (!this->Copy.empty())
    {
      const double* c = this->Copy.data() + 3 * static_cast<std::size_t>(v);
      x[0] = c[0];
      x[1] = c[1];
      x[2] = c[2];
      return;
    }
    // The same subtraction as the engine's move to the centre: the same numbers as a copy.
    const std::size_t i = 3 * static_cast<std::size_t>(this->Ids ? this->Ids[v] : v);
    for (int k = 0; k < 3; ++k)
    {
      x[k] = (this->Float ? static_cast<double>(this->Float[i + k]) : this->Double[i + k]) -
        this->Centre[k];
    }
  }
};

class CollapseCostModel
{
public:
  CollapseCostModel(const TriangleCollapseOptions& options, const CollapseMesh& state,
    const LevelTracker& tracker, const OriginalPointReader& originalPoints);

  /// Evaluate collapsing live triangle t (with the TrianglesAndEdges operator, possibly its
  /// cheapest edge instead); false when it cannot collapse (a locked vertex).
  bool Evaluate(Id t, CollapseCandidate& candidate, CostScratch& scratch) const;

  /// Evaluate merging three vertices into one: a triangle's corners, or the path of two edges
  /// left by swapping the edge between a triangle and a neighbour (paper 000, figure 3).
  bool EvaluateTriple(const Id* members, CollapseCandidate& candidate, CostScratch& scratch) const;

  /// Evaluate again the collapse an earlier Evaluate(t) chose (candidate.Choice), when nothing
  /// around t changed since: one solve instead of four.
  bool EvaluateChoice(Id t, int choice, CollapseCandidate& candidate, CostScratch& scratch) const;

  /// The merge of a small piece's vertices (CollapseMesh::SmallPiece) into one
  /// point without triangles, by either method: at the minimiser of their merged quadric
  /// (regularised about their centroid), at the cost of that quadric there (the error of
  /// standing for the piece's original planes by one point).
  void EvaluateVanish(const Id* members, int count, CollapseCandidate& candidate) const;

  /// The cheapest of the triangle's three edge collapses (the quadric method's, and the
  /// curvature method's edges at a crease); with a scratch, edges it has solved lately are
  /// taken from it (see CostScratch).
  bool EvaluateBestEdge(
    const Id* triangle, CollapseCandidate& candidate, CostScratch* scratch = nullptr) const;

  /// Curvature method: kappa is normalised by the largest absolute curvature of the input
  /// (paper 000, section 5); set it once from the first evaluation of every triangle.
  void SetCurvatureNormalization(double maximumCurvature)
  {
    this->CurvatureNormalization = maximumCurvature > 0.0 ? 1.0 / maximumCurvature : 0.0;
  }

  /// The weight W of paper 000 from a candidate's terms.
  double CurvatureWeight(const CollapseCandidate& c) const;

  /// Normalising factor m_v of the valence term |val - 6| / m_v.
  static constexpr double ValenceNormalization = 12.0;

  // Around a hub (a vertex of more than FanTriangleLimit triangles: a fan's centre, a cone's
  // tip, a UV sphere's pole) a collapse that moves the hub changes every triangle of its fan,
  // and the fan's triangles, re-weighed and re-checked against all of it after each such
  // move, made the work grow with the square of the valence or worse (a flat fan of 20,000
  // triangles inside a ring of 40,000: 36 s, now 0.7 s). So a triangle with one hub corner
  // collapses by its edge away from the hub only, which removes the triangle and lowers the
  // hub's valence without moving it; the hub itself may move once at most FanTriangleLimit
  // triangles meet there. Returns a bit per edge to skip (edge k joins corners k and k + 1), 0
  // for a triangle with no hub or with more than one (every edge touches a hub then).
  int HubEdgesToSkip(const Id* tri) const;

private:
  // TrianglesAndEdges: fill the candidate with the triangle collapse or, when that costs more
  // than TriangleCostFactor times the cheapest edge collapse, with that edge.
  bool EvaluateTriangleOrEdge(const Id* tri, CollapseCandidate& c, CostScratch& scratch) const;
  // Curvature method (FitDeviation), TrianglesAndEdges: the triangle collapse, or its cheapest
  // edge where the triangle costs CreaseEdgeFactor times more (a crease) or cannot collapse.
  bool EvaluateTriangleOrCreaseEdge(const Id* tri, CollapseCandidate& c, CostScratch& scratch) const;
  // The cheapest edge of the triangle, of those not in `skip` (bits as HubEdgesToSkip's), into
  // c; returns its cost, and the largest of the solved edges' quadric values in worst.
  double BestEdge(
    const Id* tri, int skip, CollapseCandidate& c, double& worst, CostScratch* scratch) const;
  // What a quadric value is divided by to make the cost of merging `count` vertices: the
  // surface they stand for (their CollapseMesh::SurfaceWeights, summed) in units of the input's
  // mean triangle (see CollapseMesh::SurfaceWeightUnit), to the power AreaNormalization
  // (quadric method only; 1 otherwise). Costs then compare distances more than areas: with the
  // quadric value alone, a collapse over much surface costs more than one as far from its
  // planes over little.
  double SurfaceScale(const Id* members, int count) const;
  // Where the merged `count` points (2 or 3) collapse to by the merged quadric alone: by the
  // option's placement for the quadric method, regularised for the curvature method's edges
  // (`origin`: the points' centroid).
  void Place(const Quadric& q, const double* const* points, int count, const double origin[3],
    double position[3]) const;
  // The collapse of edge (a, b), from the scratch's spokes when it is one of them.
  void SolveEdge(Id a, Id b, EdgeSolution& solution, CostScratch* scratch) const;
  // Edge k of the triangle into c; returns its cost.
  double Edge(const Id* tri, int k, CollapseCandidate& c) const;
  // Curvature method: the fit's curvature into the candidate and, with `place`, the collapse
  // point on the normal through the centroid (see CollapseHeight).
  void FitSurface(
    const Id* tri, CollapseCandidate& candidate, CostScratch& scratch, bool place) const;
  // The fit's stencil around the triangle, sorted, in scratch.Vertices, and the far edges of
  // its ring triangles (see CostScratch::Listed).
  void ListStencil(const Id* tri, CostScratch& scratch) const;
  // The points the fit reads, in scratch.Points: the stencil's, then the ancestral points of
  // the triangle's corners.
  void ListFitPoints(const Id* tri, CostScratch& scratch) const;
  // The extended stencil, for a fit that failed on the first: the points of the vertices one
  // ring beyond the stencil join scratch.Points (in a parallel round, only the rings around
  // the stencil's vertices of scratch.Block).
  void AddNextRing(CostScratch& scratch) const;
  // The rim in the frame of the valid scratch.Fit (see CostScratch::RimPoints).
  void FrameRim(CostScratch& scratch) const;
  // The height along the normal through the centroid at which the new triangles, from the
  // collapse point to the far edges of the ring triangles (FitSurface gathers them), lie on the
  // fitted surface on average or, with `leastDeviation`, at which their FitDeviation is least.
  double CollapseHeight(const CostScratch& scratch, bool leastDeviation) const;
  // The integral over the new triangles (from `position` to the rim edges) of their squared
  // height above the fitted surface, by the midpoint rule (exact for a quadratic integrand):
  // how far the collapse leaves the surface the fit sees, its ancestral points included.
  double FitDeviation(CostScratch& scratch, const double position[3]) const;

  const TriangleCollapseOptions& Options;
  const CollapseMesh& State;
  const LevelTracker& Tracker;
  const OriginalPointReader& OriginalPoints;
  const double AreaPower; // AreaNormalization for the quadric method, else 0
  double CurvatureNormalization = 1.0;
};

/// Barycentric weights of x projected on the triangle (or segment) of `count` points, clamped
/// to the simplex; used to interpolate point data at a collapse point.
void CollapseWeights(const double* const* points, int count, const double x[3], double weights[3]);

} // namespace meshlod

#endif
