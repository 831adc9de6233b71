// MeshLOD core: the edge flips of vtkTriangleCollapseDecimation's FlipEdges, level by level.
//
// Collapses leave the connectivity of what they did not touch, and on a saddle-shaped surface
// the greedy order sometimes ends with a long edge across the saddle whose two triangles bend
// sharply against each other: on the 611k-triangle gyroid isosurface at 1% the level's farthest
// point from the input is the middle of such an edge (triangles 85 degrees apart), 0.24% of the
// diagonal, while the quad's other diagonal lies within 0.08%. The flips of TriangulationFlips.h,
// judged on the input surface itself, replace such diagonals; they move no point and change no
// count, so MorphTargetId stays as it is.
//
// Each level is flipped as it is emitted (after its centring), in one sweep that flips at most
// one edge per point, and the collapses towards the next level go on from the flipped
// triangles (TriangleCollapseCallbacks, LevelRetriangulation): the next level's triangles then
// differ from the images of this level's by lone quads, which vtkLODGeomorph turns continuously
// (MeshLODGeomorphFlips.cxx). (Flipped on a copy, with the collapses going on from the
// unflipped triangles, the images of a flipped level ended on neither the next level nor its
// flips, and the geomorph jumped there by about the level's own error.) The walks over the
// input start at the input vertex nearest each level point among those it stands for (the
// chained MorphTargetId correspondence; ties: the lowest id). The judge's scale is twice the
// level's estimated error (the largest RMS distance of a vertex to its merged planes, which on
// the benchmark isosurfaces is a third to a quarter of the level's Hausdorff distance), and a
// quad farther than twice that from the input is taken for a lost walk.
//
// Which edges are judged: only edges whose facing angles add up to 150 degrees or more (the long
// diagonals) whose quads bend by at least MinimumSeparation (1.5) of the error scale, the sharp
// saddle edges that set the Hausdorff distance. From 0.3 of the scale (and up to four sweeps)
// the flips took a quarter to a third of the hierarchy's time (0.11 s of 0.45 s on the 154k
// metaballs, one thread, for 190 flips that left its Hausdorff distances as they were) and
// lowered RMS distances by 1-3%; from 1.5 the metaballs get no flip, the hierarchy takes about
// as long (0.98-1.06 times on the benchmark's isosurfaces) and the gyroids' Hausdorff distances
// at 1% fall as much as before (611k: 0.243% -> 0.188% of the diagonal), but at 10% no longer
// (2.3M: 0.0056%, where 0.3 gave 0.0050%). Levels with more than LargestFraction of the input's
// triangles are not flipped: on the 611k gyroid the two finest of eight levels (56% and 32%)
// took most of the flips' time (all eight flipped: 6.2 s for the run, against 3.8 s) and their
// distances are small.
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
  static constexpr double MinimumSeparation = 1.5;

  /// The input (level 0) and where its points have gone (it must outlive this object, and be
  /// advanced to each level before Apply): the level's points must be in the same coordinates.
  void SetLevelZero(const LevelZeroCorrespondence& levelZero);

  /// Flip the edges of the next level, after advancing the correspondence to it;
  /// `estimatedError` is the level's estimated error in world units. Returns the number of
  /// flips made; `flipped`, when given, gets the two triangles of each (no triangle is flipped
  /// twice: one sweep, at most one flip per vertex).
  Id Apply(TriangleMesh& level, double estimatedError, std::vector<Id>* flipped = nullptr);

private:
  const LevelZeroCorrespondence* LevelZero = nullptr;
  VertexTriangleAdjacency InputTriangles;
};
} // namespace meshlod

#endif
