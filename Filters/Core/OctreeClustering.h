// MeshLOD core: adaptive octree vertex clustering (Zhou, Zhang, Shi, Pan, "A New Simplification
// Algorithm for Colored or Textured Polygonal Models") as a nested hierarchy of levels.
//
// Candidates
// ----------
// The candidates are the nodes of a ClusterTree: the sets of vertices that lie in one cell of
// the octree over the bounding cube and are connected by edges inside that cell (the paper's
// "related" vertices, §3; a few vertices poking through a cell face count as lying in their
// neighbours' cell, ClusterTree::PlaceIslands). A cell holding several connected parts yields
// one candidate per part, and each part is clustered on its own. Every octree split is made as
// three binary splits, so between an octree cell and its eight children lie its halves and
// quarters: a candidate slightly too coarse halves instead of falling apart in eight.
//
// Refinement (§2.4, §2.5)
// -----------------------
// A node may become one cluster (all its vertices replaced by one representative) when
//   - its cell is no larger than MaximumCellSize and it has at most MaximumPointsPerCell
//     vertices (both optional),
//   - it holds no locked vertex (non-manifold vertices other than regular points of curves
//     where sheets meet never merge), and its curve points, if any, form one open piece of one
//     curve that goes on outside the node at both ends (CurveMayMerge),
//   - no triangle joining it to the outside flips when its inside vertex moves to the
//     representative (triangles whose two outside vertices share a cell of the node's size are
//     not counted: they fall into one neighbouring cluster and vanish; nor are those that still
//     face the way the node's coherent surface normal does, see HasFlip),
//   - and its error is at most epsilon.
// For a given epsilon the clusters are the topmost such nodes (a single vertex always qualifies,
// with error 0): the octree is refined exactly where the error requires it.
//
// Representative and error (§2.3, §3)
// -----------------------------------
// The representative minimises e = e1 + e2: e1 sums the squared distances to the planes of the
// related triangle set (area-weighted, plus BoundaryWeight-weighted planes through the boundary
// edges perpendicular to their triangle); e2 sums the squared distances of the vertices of
// crossing triangles (one vertex inside) to the new triangles around the representative, by the
// paper's fixed-point iteration from e2 = 0. The placement is a pseudo-inverse solve that stays
// at the vertex centroid along directions the planes leave free; a cluster on an open boundary
// then moves to the closest point of its boundary edges, so boundaries stay in place. The error
// is the largest of the root mean squared distance to all planes, the largest distance to a
// boundary plane, and half the distance to the farthest plane, in world units. Every node's e1
// is known from the tree (a lower bound); a node is evaluated in full only when a cut reaches
// it.
//
// Levels nest
// -----------
// Nothing but the error depends on epsilon and a node's error is computed once, so a larger
// epsilon selects nodes at or above those of a smaller one: every cluster of a coarser level is
// a union of clusters of the finer one. Each level is built from the one before it (triangles
// re-indexed to clusters, degenerate and duplicate triangles removed, orientation kept). A kept
// triangle whose normal opposes the input surface around its clusters, or two on the same
// clusters in opposite order (a thin part folded onto itself), marks the clusters that
// changed as not mergeable, and the level is cut again (such nodes lie above the previous cut,
// so nesting holds). Where sheets meet along curves, the same holds for a triangle folded
// against the previous level's triangle it comes from (the surface normal at a curve sums
// every sheet's), for a curve edge left with fewer triangles than its curve has sheets, and for
// a closed curve down to two clusters; an edge the curve's k triangles share is not a pinch.
// (All of these repairs only with PreserveTopology; without it the cut stands, and of two
// triangles on the same clusters in opposite orders both stay.)
// A target triangle count is met by a search over epsilon on the count
// estimate (input triangles minus those that degenerate in collapsed nodes), corrected by what
// a trial level actually keeps; the trial closest to the target in ratio is kept. Nodes refused
// for a fold stay refused at later levels, unless a level would otherwise keep under a quarter
// of its target: then the search is repeated without those refusals (on a rough surface they
// can leave nothing to merge but the octree's roots).
#ifndef meshlod_OctreeClustering_h
#define meshlod_OctreeClustering_h

#include "ClusterTree.h"
#include "Quadric.h"
#include "TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"

#include <cstdint>
#include <vector>

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT OctreeClusteringOptions
{
  /// Largest cell edge a cluster may span, world units; 0: no limit.
  double MaximumCellSize = 0.0;
  /// Most vertices a cluster may hold; 0: no limit.
  Id MaximumPointsPerCell = 0;
  /// Fixed-point iterations for the e2 term of the representative; 0: e1 only.
  int RepresentativeIterations = 3;
  /// Weight of the perpendicular boundary-edge planes relative to the face planes.
  double BoundaryWeight = 1.0;
  /// Eigenvalues below this fraction of the largest are treated as zero when placing.
  double PlacementTolerance = 1e-3;
  /// How many times a level is cut again to remove flipped triangles and pinched edges with
  /// the least refinement (each pass refuses the clusters that made them, whose children then
  /// compete; a rough surface can need a dozen, a noisy terrain thirty). Later passes split
  /// such clusters back into the previous level's points, which cannot fold or pinch, so a
  /// level never keeps either.
  int FlipPasses = 64;
  /// Keep each level's topology and orientation: a trial level that folds a triangle against
  /// the surface around it, folds a thin part onto itself, pinches an edge or a vertex or
  /// breaks a connected piece is cut again below the clusters concerned (FlipPasses). Off: the
  /// paper's conditions alone (connected vertices of a cell, epsilon, the flip test of the
  /// related triangle set when a node is evaluated), so levels may change topology as vertex
  /// clustering does, and reach counts that those repairs keep far above on rough surfaces.
  bool PreserveTopology = true;
  /// Give clusters of zero error thresholds of their own, far below any error that matters
  /// (see UpdateThreshold), so that a search for a triangle count can stop part way through a
  /// flat region. Off, every epsilon merges them all, epsilon 0 included (a lossless reduction
  /// of flat parts); the filter turns it on for target counts only.
  bool OrderFlatClusters = false;
};

/// One level as produced by OctreeClustering; point ids refer to this level, "previous" ids to
/// the level it was built from.
struct VTKFILTERSMESHLOD_EXPORT ClusterLevel
{
  TriangleMesh Mesh;                 // compact; points at the cluster representatives
  std::vector<Id> PointNode;         // point -> tree node (vertex id for a single vertex)
  std::vector<Id> PointVertexCount;  // point -> number of input vertices it represents
  std::vector<Id> LevelZeroTriangle; // triangle -> input triangle it descends from
  std::vector<Id> Target;            // previous point -> point (every previous point)
  std::vector<Id> Rank;              // previous point -> collapse rank, -1: unchanged
  // Point -> previous points merged into it (CSR), with weights summing to one (vertex counts).
  std::vector<Id> SourceOffsets;
  std::vector<Id> SourceParents;
  std::vector<float> SourceWeights;
  double Epsilon = 0.0;        // the epsilon the level was cut at (world units)
  double EstimatedError = 0.0; // largest cluster error of the level (world units)
  Id ChangedClusters = 0;      // clusters that merged or moved
  Id FlippedTrianglesFixed = 0;
};

class VTKFILTERSMESHLOD_EXPORT OctreeClustering
{
public:
  /// `mesh` and `topology` must outlive this object. Locked vertices (non-manifold ones other
  /// than regular curve points) never merge.
  OctreeClustering(const TriangleMesh& mesh,
    const TriangleTopology& topology,
    const OctreeClusteringOptions& options);
  ~OctreeClustering();
  OctreeClustering(const OctreeClustering&) = delete;
  OctreeClustering& operator=(const OctreeClustering&) = delete;

  /// Build the cluster tree (data-parallel over the octree cells of a coarse depth).
  void BuildTree();

  /// The next level at error bound `epsilon` (world units, at least the previous level's).
  /// With PreserveTopology, an epsilon whose level would close a handle is lowered to the
  /// largest found below it that keeps every handle (level.Epsilon is the one used). Returns
  /// false when the level would have no triangle left.
  bool MakeLevel(double epsilon, ClusterLevel& level);

  /// The next level with about `targetTriangles` triangles (at most that many when reachable),
  /// found by a search over epsilon. Returns false when no triangle would be left.
  bool MakeLevelForTriangleCount(Id targetTriangles, ClusterLevel& level);

  /// Number of triangles of the current (last made) level.
  Id GetCurrentTriangleCount() const;

  /// Flip edges of `level`, made before, towards the input (see TriangulationFlips.h): the
  /// same points, counts and clusters, closer triangles, no longer all images of the previous
  /// level's triangles. `next` is the level made right after it (its Target gives where
  /// level's points go), or null for the last level (a `next` whose Target does not have one
  /// entry per point of `level` counts as null). With `next`, no flip makes two triangles that
  /// become one triangle twice in the next level. The next level is cut from `level`'s
  /// triangles as they were made, so a level is flipped once the next one exists (the images of
  /// the flipped triangles are known then) and flips change nothing the later levels are made
  /// from.
  void FlipEdges(ClusterLevel& level, const ClusterLevel* next) const;

  // Statistics, valid after BuildTree().
  Id GetNumberOfInternalNodes() const;
  Id GetNumberOfRoots() const;
  int GetTreeDepth() const;
  /// Nodes whose exact representative was computed so far.
  Id GetNumberOfEvaluatedNodes() const;
  /// For tests: recompute e1 of up to `count` evenly spread nodes from their related triangle
  /// sets directly and return the largest difference to the e1 the tree kept, divided by the
  /// edge of the bounding cube.
  double CheckNodeQuadrics(Id count) const;

  /// The cluster tree (valid after BuildTree()).
  const ClusterTree& GetTree() const;

private:
  struct Internals;
  Internals* Impl;
};

} // namespace meshlod

#endif
