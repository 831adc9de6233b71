// MeshLOD core: edge flips that fit a simplified level's triangles closer to its input surface.
//
// Vertex clustering fixes the points of a level (the cluster representatives) but takes the
// triangles between them from the input's connectivity, which often joins a quad of clusters
// across the diagonal that cuts a curved surface instead of following it. Flipping such a
// diagonal changes no point, no count and no cluster, so a level keeps its nesting and its
// correspondence (MorphTargetId) while lying closer to the input.
//
// vtkTriangleCollapseDecimation's FlipEdges applies the same flips to its levels (LevelEdgeFlips.h),
// where the greedy collapses sometimes leave a long edge across a saddle: one sweep there, so
// that no triangle is flipped twice and the geomorph can turn each flip on its own.
//
// A flip of the edge (a, b) between triangles (a, b, c) and (b, a, d) to (c, a, d), (d, b, c) is
// judged on the input surface itself, locally: points on the four triangles (their centroids and
// the two diagonals' quarter points and midpoints) are projected onto the input by a walk over its
// triangles from a vertex of a's cluster; a configuration's error is the largest of its own points'
// distances to the input and of the projected points' distances to it (both directions of a
// Hausdorff distance). The flip is made when it lowers that error to RequiredGain of the old one or
// less and the sum of the points' errors does not grow (on a sphere with noise of over an edge the
// largest alone traded the mean for it: 1.16 times vtkQuadricClustering's RMS distance instead of
// 0.97 unflipped; with the sum, 1.03). It is refused when it would fold (a new triangle turned more
// than 60 degrees from the pair's summed normal), create an edge that exists, or touch a boundary
// or non-manifold edge; and when the old error is at rounding level (nothing to gain) or beyond
// twice the level's largest cluster error (the walk is lost: on an extruded text it found points of
// a neighbouring letter's wall), or when the two configurations lie within a tenth of that error of
// each other (too close to matter); and, given the next level's targets, when a new triangle would
// become there the same triangle as another one (TriangulationFlipOptions::NextTarget).
//
// Only edges whose two facing angles (at c and d) add up to MinimumOppositeAngles or more are
// judged: below that the flip would make an obtuse triangle (in a flat quad the angles at a and
// b, which the flip leaves whole, add up to over 240 degrees). Judging every edge found few such
// flips worth making (8% of the flips on the 154k metaballs isosurface at 10% and 1%, whose RMS
// distances stayed the same to 3 digits; within 0.5% on the 611k gyroid) for over half the
// judging: the flips took 0.12 s there instead of 0.21 s and 0.54 s instead of 0.80 s on the
// 611k gyroid (one thread; the octree's own time 0.27 s and 1.34 s).
//
// Each sweep evaluates every interior edge in parallel against the sweep's triangles, then makes
// the flips in the order of their gain, at most one per vertex (so that every flip made was
// judged on the triangles it replaces); the result does not depend on the thread count.
#ifndef meshlod_TriangulationFlips_h
#define meshlod_TriangulationFlips_h

#include "LevelZeroView.h"
#include "TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"

#include <vector>

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT TriangulationFlipOptions
{
  /// Passes over the edges; a pass that flips nothing ends the loop early.
  int MaximumSweeps = 4;
  /// A flip must bring the local error to at most this fraction of the old one.
  double RequiredGain = 0.8;
  /// An edge is judged only when the two angles facing it add up to this many degrees or more.
  double MinimumOppositeAngles = 120.0;
  /// An edge is judged only when its quad's two configurations lie at least this fraction of
  /// the error bound apart: a flip between closer ones changes the error by less (on a
  /// 611k-triangle gyroid a tenth less time for the same flips).
  double MinimumSeparation = 0.1;
  /// When given: per point of the level, the point of the next level it becomes (the next
  /// level cut from the level's triangles as they were before the flips). A flip is then also
  /// refused when a triangle it makes would have the image, in the next level, of another
  /// triangle of the level (its three points merged onto the same three points: one triangle
  /// twice, a fin a geomorph towards the next level would pass through). Where the next level
  /// merges the ends of the old diagonal but not those of the new one, the two new triangles
  /// are such a pair; on a small closed piece that the next level makes a tetrahedron, a flip
  /// can give two faces each twice.
  const Id* NextTarget = nullptr;
};

/// Flip edges of `level` towards `input` (see above; read in place, LevelZeroView.h).
/// `startVertex[p]` is an input vertex near level point p (of the input part p represents);
/// `errorBound` is the level's largest cluster error in world units. Returns the number of
/// flips made; `flipped`, when given, gets the two triangles of each flip (a triangle flipped
/// again in a later sweep is listed again).
VTKFILTERSMESHLOD_EXPORT Id ImproveTriangulation(const LevelZeroView& input,
  const VertexTriangleAdjacency& inputTriangles,
  const std::vector<Id>& startVertex,
  double errorBound,
  TriangleMesh& level,
  const TriangulationFlipOptions& options = TriangulationFlipOptions(),
  std::vector<Id>* flipped = nullptr);

/// Closest point of triangle (a, b, c) to p; returns the squared distance. Exact to rounding
/// on triangles of any shape, thin caps, needles, segments (two corners equal) and points
/// included; a triangle whose edges meet at a sine below 1e-10 is measured by its edges, to
/// within its height.
VTKFILTERSMESHLOD_EXPORT double ClosestPointOnTriangle(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3],
  double closest[3]);
/// The same, also telling whether the closest point lies inside the triangle (not on an edge).
VTKFILTERSMESHLOD_EXPORT double ClosestPointOnTriangle(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3],
  double closest[3],
  bool& inside);
/// For a search that measures the same triangles again and again: the corner (0, 1, 2 for a,
/// b, c) from which ClosestPointOnTriangle measures triangle (a, b, c) when its shape allows the
/// fast region tests, else -1 ...
VTKFILTERSMESHLOD_EXPORT int ClosestPointCorner(const double a[3], const double b[3], const double c[3]);
/// ... and, for a triangle whose corner that is, ClosestPointOnTriangle's result to the bit
/// without looking at its shape again (a third of a query's time on a tree search where
/// hundreds of triangles are about as near).
VTKFILTERSMESHLOD_EXPORT double ClosestPointFromCorner(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3],
  int corner,
  double closest[3]);

} // namespace meshlod

#endif
