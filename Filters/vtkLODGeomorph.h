/**
 * @class   vtkLODGeomorph
 * @brief   continuous level of detail between the levels of a LOD hierarchy (geomorphs)
 *
 * vtkLODGeomorph takes a LOD hierarchy and produces one triangle mesh at a continuous level of
 * detail L in [0, n - 1], n being the number of levels: L = i + t (i = floor(L), 0 <= t < 1)
 * is level i's connectivity with every point moved the fraction t of the way to where it goes
 * in level i + 1. L = n - 1 is the coarsest level itself. The level of detail comes from the
 * pipeline time (animating time walks smoothly through the levels) or from LevelOfDetail; or
 * TargetNumberOfTriangles asks for an exact triangle count.
 *
 * @par Input
 * A vtkMultiBlockDataSet of vtkPolyData levels, block 0 the finest (the layout of
 * MeshLODHierarchy.h, produced by vtkTriangleCollapseDecimation and vtkVertexClusterOctree).
 * Any list of LOD meshes works too, e.g. several outputs of vtkQuadricDecimation gathered in a
 * multiblock: see Correspondence.
 *
 * @par With morph data (Correspondence MorphArrays)
 * The levels carry the point arrays MorphTarget, MorphTargetId and CollapseRank. The output at
 * L = i + t is the partial collapse M_i(t) of Gieng, Hamann, Joy, Schussman and Trotts, "Smooth
 * Hierarchical Surface Triangulations" (section 6): level i's triangles, every point p at
 * (1 - t) p + t MorphTarget(p). It shares level i's cell arrays (the connectivity does not
 * change within a level) and computes only the points, in one vtkSMPTools loop. At t = 0 the
 * output equals level i (its arrays are shared); as t -> 1 its geometry tends to level i + 1's
 * (the collapsing triangles shrink to their collapse points and are kept, with vanishing area:
 * the output stays a valid mesh with fixed connectivity). DropDegenerateTriangles removes the
 * triangles whose corners coincide in the output up to rounding. With FlipEdges off (both
 * filters' default) the output at L -> i + 1 is level i + 1 (Benchmarks/RESULTS.md,
 * "vtkLODGeomorph at the levels").
 *
 * @par Edge flips between levels
 * A hierarchy made with FlipEdges on has levels whose triangles are not all the images of the
 * finer level's: some quads' diagonals are flipped. Where every such difference between level
 * i + 1 and the images of level i's triangles is a lone quad, no two sharing a point
 * (vtkTriangleCollapseDecimation's FlipEdges), the transition is made in two parts: the
 * collapses above, at t / 0.75, for t < 0.75; then, on level i + 1's points, each flipped quad
 * turns its diagonal about a point in its middle that moves from the middle of the old
 * diagonal to the middle of the new one (four triangles around it: two more per quad), so that
 * the output is continuous at t = 0.75 and tends to level i + 1 as t -> 1 (its point arrays are
 * level i + 1's, the midpoints' blended from the quad's corners, and so is its cell data; since
 * a midpoint's ids are a corner's and the triangles split at it repeat their source's, the
 * GlobalIds of points and cells are plain arrays of that name in this part, not attributes; the
 * rules of "Point and cell data" below hold in the first part for its own fraction t / 0.75, so
 * an integer array switches at t = 0.375, and an array level i + 1 lacks ends at t = 0.75).
 * The quads are found once per level (kept until the input changes). The exact-count mode has
 * no such second part: between a flipped level's last counts and its own, the quads' diagonals
 * turn at once (by 1.7% of the diagonal on a gyroid's coarse level). A level that differs in any other way (as
 * with vtkVertexClusterOctree's FlipEdges, whose next level is cut from the unflipped clusters)
 * is left as it was: as t -> 1 the output tends to the images (no flip makes two of them the
 * same triangle: the octree refuses such flips), and at L = i + 1 it jumps to
 * level i + 1 where quads were flipped, by 0.5-1.9 times the level's own Hausdorff distance to the input on the
 * benchmark isosurfaces (see the octree's FlipEdges).
 *
 * @par Without morph data (Correspondence NearestVertices)
 * The correspondence between level i and level i + 1 is built by nearest vertices, as in Pan,
 * Zhou and Shi, "A New Mesh Simplification Algorithm Based on Triangle Collapses" (section 4):
 * every coarse point takes its nearest fine point, then every fine point left alone takes its
 * nearest coarse point (vtkStaticPointLocator; a fine point wanted by several coarse points
 * goes to the nearest, the others take their nearest free fine point). Each fine point p of
 * level i goes to (1 - t) p + t partner(p); then the points joined by an edge of level i that
 * are closer than MergeTolerance are merged (into the lowest id of each group, at its
 * position) and the triangles that degenerate are removed. The correspondence of a pair of
 * levels is built once and kept until the input changes (GetNumberOfCorrespondenceBuilds()
 * counts the builds); changing L only recomputes the points and the merge. Levels far apart
 * (each coarse point's nearest fine point taken by another) take seconds to correspond (about
 * 3 s for 100,000 and 75,000 points); an abort stops the build, which is then made again at the
 * next update.
 *
 * @par Texture coordinates of baked atlases
 * A level whose field data has TextureAtlasLevel (vtkVertexClusterOctree with BakeTexture) has
 * TCoords that address a texture of its own: between levels i and i + 1 the output keeps level
 * i's coordinates, unblended (blending two atlases gives meaningless ones), to be shown with
 * level i's texture (block floor(L) of the octree's texture output, ActualLevelOfDetail).
 *
 * @par Exact triangle count (TargetNumberOfTriangles >= 0, needs the morph arrays)
 * The output has exactly TargetNumberOfTriangles triangles when that count is reachable. A
 * count equal to a level's own gives that level itself, and so does one that only the whole
 * transition into that level reaches, where that transition ends on the level's count (then L
 * is that level, and a baked level's TCoords are its own, for its texture block floor(L); where
 * it ends above it, as between levels with PreserveTopology off whose triangles do not all
 * merge, the output is that end with L just below the level); otherwise the transition from the
 * coarsest level with more triangles (level i) to the next one is used, and level i's
 * collapses are applied in CollapseRank order, one point at a time (Core/CollapseSchedule.h):
 * a point that reaches its MorphTarget merges with the points already there, and a triangle
 * disappears as soon as two of its corners have merged. A point joining a collapse is an edge
 * collapse: it removes the two triangles of that edge (one on a boundary; a large cluster may
 * remove more at once), so a closed manifold only reaches counts of its levels' parity. The
 * points of a cluster join in an order that keeps every intermediate mesh manifold (each join
 * is checked; where k sheets meet along a curve, as on a segmented volume's surfaces, the
 * merged point must keep k fans, and a join along the curve removes k triangles) and, where it
 * can, folds no triangle over: as the first points of a cluster settle while the others have
 * not moved yet, a triangle between them can face against its orientation both before and
 * after the transition, or lose its area; and a whole cluster that would fold a triangle
 * towards a neighbour not merged yet waits for that neighbour, as long as the waiting keeps
 * 98% of the transition's counts reachable (else the rank order holds and such folds may
 * show). On a UV sphere's triangle-collapse and vertex-clustering hierarchies, 1 count in
 * 2,400 has such a triangle. A cluster
 * whose merge is valid only after a neighbour's (a level composes many collapses per point)
 * waits for that neighbour; a join that no order can make valid is passed through and its
 * count is not reachable. (Between levels that are not manifold themselves, as
 * vtkVertexClusterOctree's with PreserveTopology off where sheets meet, a point whose target has
 * no single fan in the next level joins unchecked, and the mesh between may hold what neither
 * level has: on four sheets meeting along a closed curve, 146 of the 385 counts between two
 * such levels held one triangle twice.) When the count is not reachable, the output has the
 * largest
 * reachable count below it, with a warning when it is more than 2% (and 3 triangles) below
 * (on the smooth meshes tried, a Moebius strip, UV spheres and isosurfaces, every count of
 * levels even 97% apart is reached within parity; on a flat-faced solid, the extruded text of
 * 79,280 triangles of the Python test, whose thin strokes shrink into single points, the
 * default 8 levels miss 6 of 26,163 counts by more, by up to 7 triangles (310, by up to 471,
 * before the points of collapses that wait for each other joined interleaved), and levels at
 * 75% and 95% of it miss 15 of 8,495 counts of their first transition, by up to 49 (1,482, by
 * up to 1,475, before); on a faceted cylinder of 48,128 triangles with levels at 90% and 99%,
 * whose flat caps each merge into one point (5,032 points), 2.3% of the first transition's
 * counts are out of reach, and of 99 counts asked for in each transition 3 miss by more, by up
 * to 303 (23%, and 17 by up to 1,517, before the joins of such a merge were tried more widely
 * at each step and the collapses waiting for it made during it). A single level made straight
 * from the input can block
 * most: between a Moebius strip's 7,080 and 240 triangles, every count from 6,472 down to 400
 * gave 400; hierarchies of the default 8 levels reach them. Merged on its own, most clusters
 * of such a level are not one fan: a jagged rim touches a neighbouring point twice, a pinch
 * until that neighbour's cluster merges too, so the clusters wait for each other and go
 * together at the end; on a UV sphere's 0.1% level, 161 of the 220 merges tried whole were
 * not one fan). A level
 * whose TCoords address a texture of its own (TextureAtlasLevel: vtkVertexClusterOctree's levels
 * with BakeTexture, and its level 0 when the input comes with a texture) keeps its points apart
 * in the output, each with its own coordinates, as between levels: the points that settle on
 * one target coincide instead of merging, and points left without a triangle are dropped.
 * Baked levels have their points split per texture square; the schedule joins each point's
 * copies (same position, target and rank) as one point, so their counts are as reachable as
 * without BakeTexture (joined one copy at a time, 8 of the 489 counts between a UV sphere's
 * levels of 986 and 496 triangles were reached within one triangle, the step of a closed
 * surface; welded, all of them). Counts
 * above the finest level's or below the coarsest level's are clamped to them, with a warning.
 * CollapseFraction geomorphs the next collapse: the points of the next step that removes triangles
 * (with the steps before it that remove none) are moved that fraction of the way to their targets
 * (at a level's own count, the first collapse after it), so that raising CollapseFraction from 0 to
 * 1 and then lowering the count moves continuously. The output has the triangle count asked for
 * whatever the fraction.
 * The first count asked on a transition builds its order, once (kept until the input
 * changes): 0.7 s for the first level of vtkTriangleCollapseDecimation's defaults on 672,716
 * triangles, 1.3 s from vtkVertexClusterOctree's first default level of the same mesh (16,719
 * triangles), 0.9 s for a UV sphere's 636,800 -> 540, 3.6 s for a single level of 0.1% made
 * straight from a 610,880-triangle isosurface (of whose counts most cannot be stopped at, as
 * above: asked for 310,745 triangles, it gives 14,865; from a single level of 1%, whose
 * waiting groups are smaller, 310,744); later counts take milliseconds. An abort stops the
 * build (the output is empty), which is then made again at the next update.
 *
 * @par Point and cell data
 * Every point-data array of level i is carried to the output, with its component names and
 * information (so is every cell array). Floating-point arrays are blended like the points:
 * (1 - t) a(p) + t a'(MorphTargetId(p)), a' being the array of the same name in level i + 1 (the
 * partner point's value without morph data); the Normals attribute is renormalised. Integer and
 * string arrays (ids, labels, categories) are not interpolated: a point takes level i + 1's value
 * from t >= 0.5 on, level i's before (in the exact-count mode: once it has settled, or moved at
 * least half way). An array level i + 1 lacks keeps level i's values, and so does the GlobalIds attribute
 * (switched, the points that merge would share one id; global ids must stay unique). The morph
 * arrays themselves are not passed. Cell data: level i's, for the triangles kept (global ids
 * included). Field data: LevelOfDetail (double), the L produced (for an exact count: i + the
 * fraction of level i's steps applied, just below i + 1 when all are), and the field data of the
 * level whose point data the output has (level floor(L), or i + 1 while flips turn): the
 * input's metadata, shared, and TextureAtlasLevel, the texture its TCoords address; not
 * LevelIndex, NumberOfTriangles, EstimatedError, MeasuredHausdorff and MeasuredRMS, which
 * describe a level alone.
 *
 * @par Time
 * With UsePipelineTime on (the default), RequestInformation publishes TIME_STEPS = {0, s, 2s, ...,
 * (n - 1) s} and TIME_RANGE = [0, (n - 1) s], s = TimeScale, and a requested UPDATE_TIME_STEP u
 * gives L = u / s (clamped to [0, n - 1] silently, as readers clamp time; within 1e-9 of a whole
 * number, that number: a published step i * s gives level i exactly although i * s / s may round
 * below i); the output's DATA_TIME_STEP is u. ParaView then shows one time step per level; to see
 * the continuous transitions, animate in Sequence mode rather than Snap To TimeSteps. Without a
 * time request LevelOfDetail rules. The number of levels is a property of the data, so
 * RequestInformation brings the input up to date first (the upstream runs then rather than in the
 * data pass). The time request is not passed upstream: the hierarchy is taken to be independent of
 * time and is never recomputed because time changes (an upstream with time steps of its own is
 * asked for its first one, or the start of its time range, whatever was asked of it before).
 *
 * @par Pieces
 * The blend needs the whole hierarchy: the input is always asked for piece 0 of 1 without
 * ghost levels (a reader of a saved hierarchy gives all its levels), and a request for pieces
 * gets the whole mesh as piece 0 and empty pieces otherwise, so that the pieces together hold
 * it once. (A hierarchy per piece of a distributed mesh is not blended piece by piece.)
 * With UsePipelineTime off, LevelOfDetail always rules and the filter is transparent to time:
 * the input's time steps, if any, are passed on and time requests go upstream, so a
 * hierarchy that changes with time can be animated at a fixed level of detail.
 *
 * @par Errors
 * An input that is not a multiblock of vtkPolyData blocks, a hierarchy without levels,
 * incomplete or out-of-range morph arrays (meshlod::CheckHierarchyLayout: MorphTarget with 3
 * components, MorphTargetId and CollapseRank with 1, MorphTargetId a point of the next level,
 * CollapseRank -1 or an integer from 0 to 2^53), a cell array with invalid
 * offsets or a cell referring to a point a level does not have, a NaN or infinite point or
 * MorphTarget, a NaN setting (whether or not the mode uses it, but for LevelOfDetail where the
 * pipeline time or an exact count overrides it), an exact count on a hierarchy with a level
 * that has vertex, line or strip cells (levels are told apart by their counts), an exact
 * count, NearestVertices or DropDegenerateTriangles made from the triangles of a level of
 * other polygons than triangles (a whole level, at an integer L, or an exact count's at its
 * own count, is passed as it is; so is the coarser level of a NearestVertices blend, of which
 * only the points are read): an error and an empty output. Point or
 * cell arrays of the wrong length are left out with a warning. A level without points gives an
 * empty output without error.
 *
 * @sa vtkTriangleCollapseDecimation vtkVertexClusterOctree vtkQuadricDecimation
 */
#ifndef vtkLODGeomorph_h
#define vtkLODGeomorph_h

#include "vtkFiltersMeshLODModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory>

class VTKFILTERSMESHLOD_EXPORT vtkLODGeomorph : public vtkPolyDataAlgorithm
{
public:
  static vtkLODGeomorph* New();
  vtkTypeMacro(vtkLODGeomorph, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum CorrespondenceModes
  {
    AUTOMATIC = 0, // MORPH_ARRAYS with two levels or more, level 0 with any morph array;
                   // else NEAREST_VERTICES
    MORPH_ARRAYS = 1,    // MorphTarget / MorphTargetId / CollapseRank (an error when missing)
    NEAREST_VERTICES = 2 // nearest-vertex correspondence, morph arrays ignored
  };

  ///@{
  /**
   * The level of detail L, used when no pipeline time rules (see UsePipelineTime). Range
   * [0, n - 1]: larger values are clamped to the coarsest level with a warning. Default 0.
   */
  vtkSetClampMacro(LevelOfDetail, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(LevelOfDetail, double);
  ///@}

  ///@{
  /**
   * When on, a requested pipeline time u gives the level of detail L = u / TimeScale and the
   * filter publishes one time step per level; when off, LevelOfDetail always rules and the
   * filter passes the input's time through. Default on.
   */
  vtkSetMacro(UsePipelineTime, bool);
  vtkGetMacro(UsePipelineTime, bool);
  vtkBooleanMacro(UsePipelineTime, bool);
  ///@}

  ///@{
  /**
   * Pipeline time per level: level i is at time i * TimeScale. Range (0, inf), default 1.
   */
  vtkSetClampMacro(TimeScale, double, VTK_DBL_MIN, VTK_DOUBLE_MAX);
  vtkGetMacro(TimeScale, double);
  ///@}

  ///@{
  /**
   * Exact number of triangles wanted; negative turns the exact-count mode off. When on, it
   * overrides the level of detail (time and LevelOfDetail). Needs the morph arrays: without
   * them, the level with the largest count not above it is produced, with a warning. Range
   * [-1, VTK_ID_MAX], default -1 (off).
   */
  vtkSetClampMacro(TargetNumberOfTriangles, vtkIdType, -1, VTK_ID_MAX);
  vtkGetMacro(TargetNumberOfTriangles, vtkIdType);
  ///@}

  ///@{
  /**
   * Exact-count mode only: how far the points of the next collapse have moved toward their
   * targets. At 1 they have arrived, but the triangles they remove are still there (with zero
   * area). Range [0, 1], default 0.
   */
  vtkSetClampMacro(CollapseFraction, double, 0.0, 1.0);
  vtkGetMacro(CollapseFraction, double);
  ///@}

  ///@{
  /**
   * With morph data, remove the triangles that are degenerate in the output: two corners
   * closer than 4 units in the last place of the point type at the scale of the level (4
   * epsilon times the diagonal of its bounding box), or exactly zero area. Collapsing triangles
   * become such near t = 1 (float coordinates round onto the collapse points). Level i itself
   * (t = 0) is never touched. Off keeps level i's connectivity (shared). Default off.
   */
  vtkSetMacro(DropDegenerateTriangles, bool);
  vtkGetMacro(DropDegenerateTriangles, bool);
  vtkBooleanMacro(DropDegenerateTriangles, bool);
  ///@}

  ///@{
  /**
   * How points of level i correspond to points of level i + 1 (CorrespondenceModes). Default
   * AUTOMATIC.
   */
  vtkSetClampMacro(Correspondence, int, AUTOMATIC, NEAREST_VERTICES);
  vtkGetMacro(Correspondence, int);
  void SetCorrespondenceToAutomatic() { this->SetCorrespondence(AUTOMATIC); }
  void SetCorrespondenceToMorphArrays() { this->SetCorrespondence(MORPH_ARRAYS); }
  void SetCorrespondenceToNearestVertices() { this->SetCorrespondence(NEAREST_VERTICES); }
  ///@}

  ///@{
  /**
   * NearestVertices only: points joined by an edge and closer than MergeTolerance times the
   * diagonal of level i's bounding box are merged. The default 1e-4 is well below a pixel when
   * the mesh fills a 4K screen (1 / 3840 = 2.6e-4), so merging is invisible; 0 merges only
   * coincident points (which always happens at t = 1). A tolerance that merges the blend to
   * under half the coarser level's triangles is too large for the mesh: a warning says so.
   * Range [0, 1], default 1e-4.
   */
  vtkSetClampMacro(MergeTolerance, double, 0.0, 1.0);
  vtkGetMacro(MergeTolerance, double);
  ///@}

  ///@{
  /**
   * Results of the last execution: number of levels of the input, level of detail produced
   * (-1 when the execution failed or was aborted, and for a piece other than 0, which is empty:
   * see Pieces), triangles in the output, correspondence used
   * (MORPH_ARRAYS or NEAREST_VERTICES).
   */
  vtkGetMacro(NumberOfLevels, int);
  vtkGetMacro(ActualLevelOfDetail, double);
  vtkGetMacro(ActualNumberOfTriangles, vtkIdType);
  vtkGetMacro(ActualCorrespondence, int);
  ///@}

  /**
   * How many nearest-vertex correspondences (one per pair of levels) have been built since the
   * filter was created. Stays put when only the level of detail changes.
   */
  vtkGetMacro(NumberOfCorrespondenceBuilds, int);

protected:
  vtkLODGeomorph();
  ~vtkLODGeomorph() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double LevelOfDetail = 0.0;
  bool UsePipelineTime = true;
  double TimeScale = 1.0;
  vtkIdType TargetNumberOfTriangles = -1;
  double CollapseFraction = 0.0;
  bool DropDegenerateTriangles = false;
  int Correspondence = AUTOMATIC;
  double MergeTolerance = 1e-4;

  int NumberOfLevels = 0;
  double ActualLevelOfDetail = -1.0;
  vtkIdType ActualNumberOfTriangles = 0;
  int ActualCorrespondence = AUTOMATIC;
  int NumberOfCorrespondenceBuilds = 0;

private:
  vtkLODGeomorph(const vtkLODGeomorph&) = delete;
  void operator=(const vtkLODGeomorph&) = delete;

  // The mesh at `lod` (or at TargetNumberOfTriangles) into `output`; `lod` becomes the level of
  // detail produced and `dataLevel` the level whose point data (and baked texture) it carries.
  bool Produce(double& lod, vtkPolyData* output, int& dataLevel);

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
