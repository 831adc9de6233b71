// MeshLOD core: the edge flips of vtkTriangleCollapseDecimation's FlipEdges, level by level.
//
// Collapses leave the connectivity of what they did not touch, and on a saddle-shaped surface
// the greedy order sometimes ends with a long edge across the saddle whose two triangles bend
// sharply against each other: on the 611k-triangle gyroid isosurface at 1% the level's farthest
// point from the input is the middle of such an edge (triangles 85 degrees apart), 0.24% of the
// diagonal, while the quad's other diagonal lies within 0.08%. The flips of TriangulationFlips.h,
// judged on the input surface itself, replace such diagonals; they move no point and change no
// count, so MorphTargetId and CollapseRank stay as they are.
//
// Each level is flipped as it is emitted (after its centring), on a copy: the collapses go on
// from the unflipped triangles, so the next level is what it would be without flips. The walks
// over the input start at the input vertex nearest each level point among those it stands for
// (the chained MorphTargetId correspondence; ties: the lowest id). The judge's scale is twice
// the level's estimated error (the largest RMS distance of a vertex to its merged planes, which
// on the benchmark isosurfaces is a third to a quarter of the level's Hausdorff distance): flips
// whose configurations differ by less than a tenth of that are not judged, and a quad farther
// than twice that from the input is taken for a lost walk.
//
// Which edges are judged: the collapses leave well-shaped triangles, and judging only edges whose
// facing angles add up to 150 degrees or more (the long diagonals) whose quads bend by at least
// 0.3 of the error scale took 0.8 s instead of 1.4 s on the 611k gyroid (one thread, the
// hierarchy's own time 2.0 s) for the same Hausdorff distances, the RMS distances about 1%
// higher than when judging as vtkVertexClusterOctree does (from 120 degrees and 0.1). Levels
// with more than LargestFraction of the input's triangles are not flipped: on the 611k gyroid
// the two finest of eight levels (56% and 32%) took most of the flips' time (all eight flipped:
// 6.2 s for the run, against 3.8 s) and their distances are small.
//
// Memory: the input is read in place, as the hierarchy's level 0 holds it (LevelZeroView.h); its
// vertex-to-triangle adjacency is kept for the whole run (about 14 bytes per input triangle),
// and so is one id per input point (LevelZeroCorrespondence), which the centring shares (about
// 2 more when CenterOnInput is off). A copy of the input's points and triangles took 24 more: on
// the 2.3M-triangle gyroid the run grew by 241 bytes per input triangle instead of 217 (0.51
// times vtkQuadricDecimation's growth), measured while each pass still kept its own ids.
#ifndef meshlod_LevelEdgeFlips_h
#define meshlod_LevelEdgeFlips_h

#include "LevelZeroCorrespondence.h"
#include "TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"

#include <vector>

namespace meshlod
{
class VTKFILTERSMESHLOD_EXPORT LevelEdgeFlips
{
public:
  /// Levels with more than this fraction of the input's triangles are not flipped.
  static constexpr double LargestFraction = 0.25;
  /// The flips' error scale is this multiple of a level's estimated error.
  static constexpr double ErrorScale = 2.0;
  /// Only edges whose facing angles add up to this many degrees or more are judged, and only
  /// where the quad's two configurations lie this fraction of the error scale apart or more
  /// (TriangulationFlipOptions; vtkVertexClusterOctree judges from 120 degrees and 0.1).
  static constexpr double MinimumOppositeAngles = 150.0;
  static constexpr double MinimumSeparation = 0.3;

  /// The input (level 0) and where its points have gone (it must outlive this object, and be
  /// advanced to each level before Apply): the level's points must be in the same coordinates.
  void SetLevelZero(const LevelZeroCorrespondence& levelZero);

  /// Flip the edges of the next level, after advancing the correspondence to it;
  /// `estimatedError` is the level's estimated error in world units. Returns the number of
  /// flips made.
  Id Apply(TriangleMesh& level, double estimatedError);

private:
  const LevelZeroCorrespondence* LevelZero = nullptr;
  VertexTriangleAdjacency InputTriangles;
};
} // namespace meshlod

#endif
