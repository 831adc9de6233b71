// MeshLOD core: moving each simplified level onto the middle of the input surface.
//
// Both algorithms place a level's vertices at quadric minimisers, and on a curved surface
// those lie on its outer side: the tangent planes of a convex patch meet above it. The flat
// triangles between such vertices cut back under the surface, but less than the vertices stand
// out, so a coarse level sits as a whole to one side of its input (on the metaballs isosurface
// at 1% the input's mean signed distance to the level was -0.6 times its RMS distance, for
// vtkQuadricDecimation's output as for ours). A level centred on the input has a smaller mean
// squared distance to it.
//
// For a level, the input triangles' centroids (every stride-th: every second, or fewer so that
// there are SamplesPerPoint per point of the level on average) are projected onto the triangles
// around the point the triangle's first corner became (the chained MorphTargetId correspondence),
// into the nearest of those whose interior they project into. Each signed distance, weighted by
// the input triangle's area, is spread over that triangle's corners with the barycentric weights
// of the projection; each point's weighted mean is the shift along its normal that zeroes it (the
// first step of a least-squares fit of per-point offsets: a uniform offset is removed exactly, a
// varying one smoothed over each point's triangles). The shift is then limited so that the largest
// distance of the projections near the point (barycentric weight at least a third) does not grow,
// and to a quarter of the point's shortest edge.
//
// Not moved: points that did not change between the previous level and this one (their own
// single parent with weight 1): they keep the shift they had there, added in the same rounding,
// so they are exactly where the previous level has them (CollapseRank -1 stays true); points
// on a boundary or non-manifold edge (an open boundary stays on the input's boundary), of a
// valence above MaximumValence, or with a triangle more than 35 degrees from their normal
// (a crease or corner, which the normal does not describe); points whose projections mostly lie
// on their triangles (a planar facet: such parts stay exact); and every point of a level with
// more than LargestFraction of the input's triangles. Shifts that turn a triangle by more than
// 60 degrees are undone around it, until none does.
//
// Cost: per level a pass over the input points' correspondence, and for a centred level the
// projection of at most max(input triangles / 2, 8 x points) centroids, in parallel over the
// points, with the sums in a fixed order, so the result does not depend on the thread count
// (about a tenth of vtkTriangleCollapseDecimation's time on the benchmark isosurfaces). Memory:
// one id per input point for the whole run, and per level arrays of the level's size (the input
// is read in place).
#ifndef meshlod_LevelCentering_h
#define meshlod_LevelCentering_h

#include "LevelZeroCorrespondence.h"
#include "TriangleMesh.h"
#include "Vector3.h"
#include "vtkFiltersMeshLODModule.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace meshlod
{
class VTKFILTERSMESHLOD_EXPORT LevelCentering
{
public:
  /// Input triangles (their centroids) sampled per point of a level, on average, when the
  /// level has fewer than a sixteenth as many points as the input has triangles (every second
  /// triangle otherwise).
  static constexpr Id SamplesPerPoint = 8;
  /// Levels with more than this fraction of the input's triangles are not moved: on the
  /// metaballs isosurface centring lowered the RMS distance of its levels of 56% and 32% of the
  /// input by 0% and 5%, for most of its time and memory (the finest levels are the largest).
  static constexpr double LargestFraction = 0.25;
  /// Samples on a point's triangles weighing less than this in all (barycentric weights): it
  /// is not moved (its mean is noise).
  static constexpr double MinimumSamples = 1.0;
  /// Points of a higher valence are not moved.
  static constexpr int MaximumValence = 32;

  /// Level 0 as the hierarchy holds it and where its points have gone (it must outlive this
  /// object, and be advanced to each level before Apply).
  void SetLevelZero(const LevelZeroCorrespondence& levelZero);

  /// Moves the points of `level`, whose points come from the previous level's as
  /// `sourceOffsets`, `sourceParents` and `sourceWeights` say (the PointSources layout: point p's
  /// parents are entries [offsets[p], offsets[p + 1])). Call once per level, coarsening, after
  /// advancing the correspondence to it.
  void Apply(TriangleMesh& level,
    const std::vector<Id>& sourceOffsets,
    const std::vector<Id>& sourceParents,
    const std::vector<float>& sourceWeights);

private:
  // Per point, what its samples' projections say; a triangle set up for projections; one
  // sample's projection (LevelCentering.cxx).
  struct PointSums;
  struct ProjectionFrame;
  struct Projection;

  // The samples' projections summed per point, and each point's own distance to the input.
  void SumProjections(const TriangleMesh& level, const VertexTriangleAdjacency& around,
    std::vector<PointSums>& sums, std::vector<float>& pointDistance) const;
  // Point p's samples projected into its triangles.
  void ProjectSamples(const TriangleMesh& level, const VertexTriangleAdjacency& around, Id p,
    const Id* samples, Id count, double areaUnit, ProjectionFrame* frames,
    Projection* projections, float& distance) const;
  // Point p's shift from its sums.
  static void PointShift(const TriangleMesh& level, const VertexTriangleAdjacency& around, Id p,
    const PointSums& sum, double itself, float* shift);

  // Centroid, unit normal (0 when degenerate) and area of input triangle t.
  double InputCentroid(Id t, double centroid[3], double unit[3]) const
  {
    double p[3][3];
    for (int c = 0; c < 3; ++c)
    {
      this->LevelZero->Input.Point(this->LevelZero->Input.Corner(t, c), p[c]);
    }
    double n[3];
    Normal(p[0], p[1], p[2], n);
    for (int k = 0; k < 3; ++k)
    {
      centroid[k] = (p[0][k] + p[1][k] + p[2][k]) / 3.0;
    }
    const double length = std::sqrt(Dot(n, n));
    for (int k = 0; k < 3; ++k)
    {
      unit[k] = length > 0.0 ? n[k] / length : 0.0;
    }
    return 0.5 * length;
  }

  // Level 0, and per input point the point of the last level it became.
  const LevelZeroCorrespondence* LevelZero = nullptr;
  // The point of the last level that sample i (input triangle i) belongs to: that of its first
  // corner.
  Id SamplePoint(Id i) const { return (*this->LevelZero)[this->LevelZero->Input.Corner(i, 0)]; }
  std::vector<float> Shifts; // last level's points: x, y, z of their shift
};

} // namespace meshlod

#endif
