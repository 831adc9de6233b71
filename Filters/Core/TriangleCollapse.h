// A hierarchy of levels of detail by triangle collapses, VTK-free.
//
// Two weighting methods pick the triangles to collapse and the point they collapse to:
// - Quadric (Pan, Zhou, Shi, "A New Mesh Simplification Algorithm Based on Triangle
//   Collapses"): the error of collapsing T is the quadric of all original planes merged into
//   its three vertices, at the point minimising it.
// - Curvature (Gieng, Hamann, Joy, Schussman, Trotts, "Smooth Hierarchical Surface
//   Triangulations"): W = A (wk kappa + wa alpha + wv V) from a local quadratic fit over the
//   triangle's stencil and ancestral points; the collapse point is c + f(0, 0) n.
// and two schedules order the collapses:
// - IndependentSets (paper 000, section 6): each pass picks, cheapest first, triangles whose
//   stencils share no vertex, collapses them all at once, and re-weights only what changed.
// - Greedy (paper 002, section 2.4): one collapse at a time from a priority queue.
// Output levels are snapshots at requested triangle counts; the collapses between two snapshots
// are composed into the per-vertex correspondence of the level transition.
#ifndef meshlod_TriangleCollapse_h
#define meshlod_TriangleCollapse_h

#include "TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"

#include <functional>
#include <vector>

namespace meshlod
{
struct LevelData;

enum class CollapseMethod
{
  Quadric = 0,
  Curvature = 1,
};

/// What one collapse merges (quadric method).
enum class CollapseOperator
{
  Triangles = 0,         // always the triangle's three vertices (the papers' operator)
  TrianglesAndEdges = 1, // the triangle, or its cheapest edge when that is much cheaper
};

/// How the curvature method ranks its collapses.
enum class CurvatureCost
{
  Weight = 0,       // paper 000's weight W = A (wk kappa + wa alpha + wv V)
  FitDeviation = 1, // the new triangles' squared deviation from the fitted surface
};

enum class CollapseSchedule
{
  IndependentSets = 0,
  Greedy = 1,
};

/// Quadric method: where a collapse goes. Regularized: the merged quadric's minimiser in its
/// well-determined directions, the centroid along the others (Quadric::MinimizeRegularized).
/// PaperCandidates (paper 002): the minimiser when the 3x3 system is solvable, else the
/// cheapest of the centroid, the merging vertices and their midpoints (PlaceByCandidates).
enum class CollapsePlacement
{
  Regularized,
  PaperCandidates
};

struct TriangleCollapseOptions
{
  CollapseMethod Method = CollapseMethod::Quadric;
  CollapseSchedule Schedule = CollapseSchedule::Greedy;
  CollapseOperator Operator = CollapseOperator::TrianglesAndEdges;
  /// Greedy schedule: run the greedy order in parallel over spatial blocks
  /// (PartitionedGreedy.cxx) rather than strictly one collapse after the other (the curvature
  /// method ranked by Weight always takes the strict order).
  bool PartitionedGreedy = true;
  /// Quadric method: where a collapse goes (see CollapsePlacement).
  CollapsePlacement Placement = CollapsePlacement::Regularized;
  /// TrianglesAndEdges: a triangle collapses whole when that costs at most this many times its
  /// cheapest edge collapse (>= 1).
  double TriangleCostFactor = 1.5;
  /// Triangle counts of the output levels after level 0, strictly decreasing.
  std::vector<std::int64_t> LevelTargets;
  /// Stop when the next collapse's estimated error (RMS distance to its merged planes) exceeds
  /// this, in world units; <= 0: no limit.
  double MaximumError = -1.0;
  /// IndependentSets: fraction of the live triangles selected per pass.
  double LevelFraction = 0.025;
  double CurvatureWeight = 1.0 / 3.0;
  double AngleWeight = 1.0 / 3.0;
  double ValenceWeight = 1.0 / 3.0;
  CurvatureCost CurvatureRanking = CurvatureCost::FitDeviation;
  /// Weight of the planes through boundary edges, relative to the area-weighted surface
  /// planes (the plane of an edge of length l gets BoundaryWeight * l * the bounding-box
  /// diagonal).
  double BoundaryWeight = 0.3;
  /// Off: each triangle's plane weighs the triangle's area. On: every plane weighs the same, the
  /// input's mean triangle area (vtkQuadricDecimation's weighting, kept scale-invariant).
  bool UniformPlaneWeights = false;
  /// Quadric method: a collapse costs its merged quadric's value (the summed weighted squared
  /// distances to the original planes) divided by the merged original surface (the plane
  /// weight of the original triangles around the collapsing vertices, in units of the input's
  /// mean triangle's) to this power, in [0, 1]. 0: the quadric value itself (paper 002); 1:
  /// the mean squared distance alone.
  double AreaNormalization = 0.25;
  /// Largest angle (degrees) a triangle's normal may turn in one collapse (see CollapseMesh).
  double MaximumNormalDeviation = 90.0;
  /// Off: a small closed piece of genus 0 (CollapseMesh::SmallPiece; a tetrahedron cannot lose
  /// a triangle otherwise) may vanish when its cost comes up: its vertices merge into one point
  /// that keeps no triangle (CollapseMesh::FlagVanished). The isosurface of a noisy volume has
  /// hundreds of specks that otherwise stay to the coarsest level. Genus is kept either way.
  bool PreserveTopology = true;
  /// Curvature method: at most this many ancestral points per triangle fit (a strided subset).
  int MaximumFitPoints = 48;
  /// Curvature method: the input's own point coordinates, which the fits read instead of a
  /// copy of the mesh's points (3 * 8 bytes per point saved): x, y, z of input point
  /// InputPointIds[v] (of v when InputPointIds is null) for the engine's vertex v, exactly the
  /// coordinates of the mesh passed in. At most one of the two arrays; neither: the engine
  /// copies the points it is given.
  const float* InputPointsFloat = nullptr;
  const double* InputPointsDouble = nullptr;
  const long long* InputPointIds = nullptr;
};

/// Triangles of an emitted level that its receiver re-triangulated (edge flips that keep every
/// point and the count): the collapses towards the next level go on from them.
struct LevelRetriangulation
{
  std::vector<Id> Triangles; // those that changed, each once, as LevelData::LevelZeroTriangle names them
  std::vector<Id> Corners;   // their new corners, three per triangle, in the level's point ids
  void Clear()
  {
    this->Triangles.clear();
    this->Corners.clear();
  }
};

struct TriangleCollapseCallbacks
{
  /// Called on the calling thread with the fraction done; returns false to abort.
  std::function<bool(double)> Progress;
  /// Receives each level as soon as it is complete; it may take the level's arrays (the engine
  /// does not use them afterwards), and may fill the retriangulation (empty when called).
  std::function<void(LevelData&, LevelRetriangulation&)> EmitLevel;
};

struct TriangleCollapseResult
{
  bool Aborted = false;
  int LevelsEmitted = 0;
  int TargetsReached = 0; // more than LevelsEmitted where one collapse passed several targets
  std::int64_t FinalTriangles = 0;
  std::int64_t Collapses = 0;
  std::int64_t Passes = 0;
  std::int64_t Swaps = 0; // collapses that followed an edge swap (paper 000, figure 3)
  bool ErrorLimited = false; // MaximumError refused at least one collapse
  std::int64_t FinalPieces = 0; // connected pieces of the coarsest level, when short of its target
};

/// Run on a validated mesh (see MeshLODInputMesh.h) with its topology; both are taken over
/// (pass them with std::move when the caller is done with them, to save a copy).
VTKFILTERSMESHLOD_EXPORT TriangleCollapseResult RunTriangleCollapse(TriangleMesh mesh,
  TriangleTopology topology, const TriangleCollapseOptions& options,
  const TriangleCollapseCallbacks& callbacks);

} // namespace meshlod

#endif
