/**
 * @class   vtkVertexClusterOctree
 * @brief   levels of detail by adaptive octree vertex clustering with quadric error control,
 *          nested levels and colour/texture preservation
 *
 * Implements Zhou, Zhang, Shi and Pan, "A New Simplification Algorithm for Colored or Textured
 * Polygonal Models". The bounding cube of the input is subdivided as an octree; the vertices of
 * a cell that are connected to each other inside the cell (the paper's "related" vertices) are
 * clustered into one representative when
 * - the cell is no larger than MaximumCellSize and holds at most MaximumPointsPerCell vertices,
 * - no triangle joining the cluster to the rest of the mesh flips when its vertex moves to the
 *   representative (see below for the representative taken when the quadric's would flip one),
 * - and the cluster error is at most epsilon;
 * otherwise the cell is subdivided and its children are tried (§2.4, §2.5). A cell holding
 * several unconnected parts clusters each part on its own, so separate sheets that pass through
 * one cell never fuse. Each octree split is made as three binary splits (x, then y, then z), so
 * a cell slightly too coarse is tried in halves and quarters before its eighths. In the flip
 * test, a triangle whose two outside vertices share a cell of the cluster's size does not count:
 * it falls into one neighbouring cluster and vanishes; nor does one that still faces the way the
 * cluster's surface does (its area-weighted normal, when the cluster's triangles mostly face one
 * way): on a rough surface, such as a scan, the input triangles' own normals scatter. Where a
 * rough surface pokes through a cell face, a group of at most 4 vertices cut off from the rest
 * of its cell (cells at least twice its longest edge) counts as lying in the cell of its nearest
 * neighbour outside, instead of staying a tiny cluster of its own next to large ones. Without
 * these two, a noisy sphere (vertex noise a third of its edge length) asked for 1% of its
 * triangles kept 8,442 instead of 782 and a noisy height field 14,265 instead of 1,555 (now 877
 * and 1,938). A cluster whose triangles form two or more fans joined at it alone (a thin part
 * pinched there) is split again like one that folds (with PreserveTopology on, the default).
 *
 * The representative minimises the quadric e = e1 + e2 of §3: e1 sums the squared distances to
 * the planes of every triangle touching the cluster, plus planes through the boundary edges
 * perpendicular to their triangle (weighted by BoundaryWeight); e2 sums the squared distances of
 * the cluster's vertices to the new triangles around the representative, found by the paper's
 * fixed-point iteration (RepresentativeIterations passes from e2 = 0, stopping early on
 * convergence). Planes are weighted by triangle area and the placement is a pseudo-inverse
 * solve that stays at the vertex centroid along directions the planes do not determine (a flat
 * or cylindrical cluster); a cluster holding open-boundary vertices then moves to the closest
 * point of its boundary edges, so every boundary point of a level lies on the input's
 * boundary. Beyond the paper, which falls back to a vertex of the cluster where its 3x3 system
 * is ill-conditioned: where the minimiser would flip a triangle, the best of the cluster's own
 * vertices that flips none stands for it (every vertex of a cluster of up to 32, else 32 to 63
 * evenly spaced), at its own error, and the cluster is refused only when none is left. Refused
 * clusters are split down to small cells, and a search for a count made up for them with
 * coarser clusters elsewhere: on the 154k metaballs isosurface at 1% the Hausdorff and RMS
 * distances were 1.10 and 0.80 times vtkQuadricClustering's, now 0.73 and 0.59. Where the
 * minimiser has no error (planes meeting at a solid's corner or along its edge), only a vertex
 * without error may stand in, so that corners are not cut (a subdivided icosahedron asked for
 * 1% would get its count at 7.7% of its diagonal instead of 746 triangles at no error). On a
 * faceted cylinder (64 sides, 64,512 triangles) asked for 645 triangles the levels got worse,
 * 2,172 triangles at 4.5 times vtkQuadricClustering's distances (618 at 3.2 and 2.7 times
 * before). The cluster error is the largest of the root of the area-weighted mean squared
 * distance to all the planes, the largest distance to a boundary plane (so an open boundary,
 * corners included, stays within epsilon; not with BoundaryWeight 0), the distance to the
 * farthest boundary tip it holds, and half the distance to the farthest plane (a mean alone
 * lets elongated or bent clusters stray at their ends), in world units; it is what epsilon
 * bounds (the surface typically stays within 2-3 epsilon of the input). A boundary tip is a
 * vertex whose two boundary edges meet at under 30 degrees, where the boundary planes are
 * almost parallel and barely see the tip pulled back along them; a cluster holding one is
 * placed at it (the first, when it holds several). Without this, a sheet's 3-degree corner
 * lost 15% of the sheet's length at 1% of its triangles, and the spike of Dini's surface
 * (vtkParametricDini, 300 x 300, 178,802 triangles) 4.9% of the diagonal (Hausdorff distance
 * at 1%, 0.45% now; vtkQuadricDecimation's 0.35%).
 *
 * Levels. The output has NumberOfLevels simplified levels after level 0 (the input), chosen by
 * LevelMode:
 * - GeometricEpsilon (default): level i (1-based) uses epsilon Epsilon * EpsilonFactor^(i - 1);
 * - EpsilonList: one level per AddEpsilonValue() value (strictly increasing);
 * - TargetTriangleCounts: one level per AddTargetTriangleCount() value (strictly decreasing),
 *   epsilon found by a search; the count is met within 0.2% (or 2 triangles) where the cluster tree
 *   allows, and a miss by more than 2% (or 2 triangles) is reported by a warning naming the count
 *   reached and why: a count below what collapsing every mergeable cluster gives (clusters that
 *   would flip triangles, the vertices where curves of non-manifold edges meet or end, bow ties and
 *   separate components stop the merging; on a rough or noisy surface, splitting the clusters that
 *   fold adds back so many triangles that counts well above the target are all the search finds: a
 *   noisy terrain (height noise of 1.5 edges) asked for 10% and 1% got 13% and 1.25%, a noisy
 *   height field with noise of an edge 11.6% and 1.25%, a sphere of 158,400 triangles with its
 *   radii moved at random by up to two thirds of an edge 14% and 4.9%, by up to an edge 18% and
 *   3.7% (the 1% counts swing with the random numbers: over four seeds each, 0.2-11% and
 *   0.07-6.9%, either way far from the target, with the warning; the nearer in ratio is kept,
 *   even below it, where the smallest epsilon that merges enough merges far more at once; at
 *   such a level a large cluster that folds gives way to the topmost clusters below
 *   it that neither fold nor flip a triangle, and those are small; PreserveTopology off
 *   lifts those repairs and reaches such counts); a self-intersecting surface that cannot be
 *   oriented (vtkParametricBoy, 178,204 triangles) asked for 10% and 1% gets 10.4% and 2.6%, its
 *   clusters folding where it turns tightly (these counts, but for the last, were measured
 *   before a vertex of a cluster could stand in for a representative that flips a triangle,
 *   which lets more clusters merge: the self-intersecting surface stopped near 9% then, and
 *   near 6% after it, before the fold test compared the triangles at its seam with their own
 *   previous selves); when the trials miss, the one nearest the
 *   target in ratio is kept, never a level cut at the octree's roots because it is nearer in
 *   difference, and when that one keeps a quarter or more above the target, the epsilon backs off
 *   to the smallest that keeps at most a tenth more triangles than it, or at most half more at
 *   under a quarter of its error, or up to four times as many whose error times the square root
 *   of their count is under a tenth of the fewest's (giving back at most three quarters of what
 *   the level removes from the one before): the search's epsilon merges all that may merge, at an error far beyond
 *   what a few more triangles need; on the surfaces of a segmented volume asked for 1%, whose
 *   curves merge only so far, 3,245 triangles at 0.79% Hausdorff distance instead of 2,423 at
 *   4.6% when this rule was made (the segmented balls of Benchmarks/RESULTS.md now: 3,012 at
 *   0.69%); on a finely subdivided icosahedron asked for 10% and 1%, 746 triangles at no error
 *   at 1% instead of 390 at 8%, whose clusters across the edges cut the corners); a count
 *   between two that consecutive epsilons give (levels cut one cluster tree, so counts move in
 *   steps of whole clusters); a count at or above the previous level's (a level never refines).
 *   In this mode clusters of zero error (an exactly flat region, a faceted solid's facets)
 *   merge in order of size, the smallest first, at epsilons far below any error that matters
 *   (about 1e-7 of a cluster's cell), so counts are met there too: flat disks of about 120,000
 *   triangles (vtkDiskSource) asked for 12,000 got 11,988-12,000 at no error, where they all
 *   merged at once before (4,488); a fan of 40,000 inside a ring of 80,000 gets 10,154, with
 *   the warning. Errors under 1e-6 of the bounding cube count as zero: the planes of a facet
 *   of single-precision points differ by their rounding, and such errors (up to 7e-7) ordered
 *   the merges at random: a subdivided octagonal prism asked for 1% (1,146 triangles) got 1,252
 *   at 8% of its diagonal, its corner edges cut (now 2,172 at no error). In the epsilon modes
 *   every epsilon, 0 included, merges all clusters of exactly zero error, and rounding-size
 *   errors count as they are (a cluster stays within its level's epsilon).
 * A level that keeps exactly the triangles of the level before (an epsilon that merges nothing
 * more, or a small count met within its tolerance by the same cut) is kept, the same mesh again,
 * and said in a warning.
 * With RelativeUnits on (default) epsilon values and MaximumCellSize are fractions of the
 * input's bounding-box diagonal, otherwise world units. Levels nest: every cluster of a coarser
 * level is a union of clusters of the finer one (a coarser level cuts the same cluster tree
 * higher up), so MorphTargetId is exact and a geomorph between levels does not pop. A level
 * that would keep no triangle ends the hierarchy (with a warning). The octree halves the input's
 * bounding cube at most 20 times along each axis: where most edges are shorter than its finest
 * cells (2^-20 of the box's largest side; a small part beside a far outlier), vertices sharing
 * a cell cannot be clustered apart and those parts hardly simplify, with a warning.
 *
 * Synthesis. Triangles are re-indexed to the representatives, degenerate and duplicate
 * triangles removed (of two with the same three points in the same order, the first is kept),
 * orientation kept. A kept triangle whose normal opposes the input surface around its three
 * clusters (at a curve where sheets meet, or at the seam of a surface that cannot be oriented,
 * where the input's normals around a cluster sum to nothing meaningful: its own triangle in
 * the level before), two on the same three points in opposite order (a thin part folded onto itself),
 * an edge that three or more kept triangles share (clusters that folded the surface onto
 * itself), and a connected piece of the finer level that the kept triangles split into pieces
 * that each keep triangles (a tube or rod whose whole cross-section fell into one cluster)
 * mark the clusters that changed as not mergeable, and the level is cut again (unless
 * PreserveTopology is off: then the cut stands as the paper makes it). Vertex
 * clustering may still change topology: a spike swallowed by the cluster around it vanishes,
 * and so does a connected piece that keeps no triangle at all (a small closed surface merged
 * whole) when the level's triangles pass within twice the epsilon of all of it (its points then
 * lie about as close to the level as the other clusters' points do; a speck of a noisy volume
 * next to the surface); a piece farther away is cut again as for a fold, so that it stays. In
 * the same way a boundary loop (a hole) whose vertices fall into fewer than three clusters
 * closes only where each of its vertices lies within twice the epsilon of the level's triangles
 * around it. (Both with PreserveTopology on. The wavelet isosurface of Benchmarks/RESULTS.md,
 * open at the volume's faces, asked for 1%: its blobs vanished 5.3% of the diagonal away from
 * the level and the surface that capped a closed tube end lay 3.7% away, where its clusters
 * erred by 1.4% at most; when both rules came, its Hausdorff distance went from 1.63 to 0.42
 * times vtkQuadricClustering's at the same count, 4,413 triangles instead of 4,311 then.) A cluster
 * whose triangles all vanish sends its points to the nearest neighbouring cluster. Beyond the paper,
 * each finished level can flip the edges whose other diagonal lies closer to the input
 * (FlipEdges, off by default: it breaks the exact triangle correspondence a geomorph needs): the
 * clusters' connectivity comes from the input's and often crosses a curved quad of clusters the
 * wrong way; a flip moves no point.
 *
 * Input (port 0): a vtkPolyData surface, validated by the shared MeshLOD policy: composite data is
 * an error (merge the blocks first); empty input gives a hierarchy of one empty level, without
 * error; integer points give levels in double; polygons and strips are triangulated; vertex and
 * line cells are ignored with a warning; NaN or infinite points that triangles use (unused points
 * are dropped) and point ids out of range are an
 * error (no output), and so is a bounding-box diagonal above 1e30 or below 1e-30 but not 0
 * (cluster errors are kept in single precision; with all points at one place, a diagonal of 0,
 * every cluster merges at any epsilon, so level 1 would keep no triangle and the hierarchy is
 * level 0, with that warning); arrays whose tuple count is not the number of points or cells are
 * ignored with a warning; points on boundary or non-manifold edges that coincide up to rounding
 * (1e-12 of the bounding diagonal, or 64 double-precision epsilons of the largest coordinate
 * where that is more, far from the origin) and carry the same point data are stitched (an attribute
 * seam stays open, with a warning); triangles wound against the rest of their connected part are
 * flipped (each orientable part keeps its majority orientation). Where k > 2 sheets meet along a
 * curve of non-manifold edges (the surfaces between the regions of a segmented volume), a cluster
 * may hold one open piece of one curve, with the curve going on outside it at both ends, and
 * every level keeps each curve with k triangles on each of its edges: the curves shorten, no
 * sheet or curve vanishes and no two are joined (a trial level where one would is cut again
 * below the clusters concerned, as for folds; with PreserveTopology off a curve edge may lose
 * sheets). The other non-manifold vertices, where curves meet or end and bow ties, are locked:
 * they never move, and no cluster holds one with other points. (A wing of a bow tie, a triangle
 * hanging at it, still vanishes when its other corners fall into one cluster; that cluster's
 * points then go to the bow tie's, and the vertex is no longer a bow tie.)
 * Optional input (port 1): a vtkImageData texture for an input with texture coordinates: an
 * image in the XY, XZ or YZ plane (texture coordinate s along its first axis, t along its
 * second) with 1 to 4 component scalars (grey, grey-alpha, RGB, RGBA; 16-bit integers 0-65535,
 * other integer types 0-255, floating point 0-1), one tuple per image point.
 *
 * Output port 0: the shared MeshLOD hierarchy (see MeshLODHierarchy.h): a vtkMultiBlockDataSet
 * with block i = level i named "Level i"; every point-data array of the input is carried to
 * every level, with its component names and information (floating-point arrays averaged over
 * the cluster's input vertices, integer arrays from the dominant one: the GlobalIds attribute
 * stays unique, unless BakeTexture splits the points, see below), cell data from the input
 * triangle each triangle descends from (its GlobalIds included; as a plain array of that name
 * where polygons or strips were triangulated, since their triangles share the cell's id),
 * field data LevelIndex, NumberOfTriangles, EstimatedError (the largest cluster error of the level)
 * and, with MeasureLevelErrors, MeasuredHausdorff and MeasuredRMS, plus the input's field-data
 * arrays (shared; one named like any of these or TextureAtlasLevel is left out, so a level
 * of an unmeasured run never shows an input's MeasuredHausdorff); every level but the last
 * carries MorphTarget, MorphTargetId and CollapseRank (clusters ordered by error: the points of
 * one cluster share a rank; -1 for points whose cluster did not change).
 *
 * Output port 1 (with BakeTexture): a vtkMultiBlockDataSet of vtkImageData textures, block i
 * for level i. Block 0 is the input texture (or null, no block, when the colours come from a
 * point array). For each simplified level a texture atlas is built as in §4: every triangle gets a
 * half-square triangle in a TextureResolution^2 texture, sized by its area in power-of-two
 * steps; adjacent triangles are paired into squares that share their diagonal, and edge texels
 * are sampled at the same points from both sides wherever the two triangles got the same size.
 * Each texel takes the colour of the nearest point of the input surface: the colour array
 * interpolated there, or the input texture looked up at the interpolated texture coordinates.
 * The level's points are then split per texture square (so MorphTargetId refers to the first
 * copy of each point; the copies share their point data, so an input GlobalIds attribute, which
 * promises one point per id, stays there as a plain array of that name) and get texture
 * coordinates as their TCoords attribute; the level's field
 * data TextureAtlasLevel gives the index of the texture they address (vtkLODGeomorph keeps such
 * coordinates unblended, the finer level's, for the finer level's texture). Without
 * BakeTexture, colours and texture coordinates are averaged per vertex like any point array.
 *
 * The passes run with vtkSMPTools; the output is the same for every thread count.
 *
 * A mesh whose point ids are scattered in space (written from a hash map, merged from a point
 * set) is clustered on a copy renumbered in Morton order, and each level is numbered back (level
 * 0 stays the input as it came): the clustering reads its per-point arrays around every cluster,
 * and on scattered ids nearly every read misses the cache. Such a mesh is told from a contouring
 * filter's, a parametric source's or a grid's by how far apart its triangles' corner ids lie
 * (Filters/Core/SpatialOrder.h); meshes of under 4,096 points are never renumbered. On the
 * 611k-triangle gyroid isosurface with its ids shuffled the levels took 1.17-1.27 times as long
 * as on the contoured mesh in two runs, against 1.88 without the renumbering
 * (vtkQuadricClustering 1.21-1.93; Benchmarks/RESULTS.md, "Input order", has the 1.17 and 1.21;
 * the others from trial runs). The levels of a renumbered
 * mesh do not depend on how it was numbered, but for CenterOnInput's centring, which samples
 * the input's triangles in their order.
 *
 * @sa vtkQuadricClustering vtkTriangleCollapseDecimation vtkLODGeomorph
 */
#ifndef vtkVertexClusterOctree_h
#define vtkVertexClusterOctree_h

#include "vtkFiltersMeshLODModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <vector> // For the level lists

class vtkAlgorithmOutput;
class vtkImageData;
class vtkMultiBlockDataSet;

class VTKFILTERSMESHLOD_EXPORT vtkVertexClusterOctree : public vtkPolyDataAlgorithm
{
public:
  static vtkVertexClusterOctree* New();
  vtkTypeMacro(vtkVertexClusterOctree, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum LevelModes
  {
    GEOMETRIC_EPSILON = 0,
    EPSILON_LIST = 1,
    TARGET_TRIANGLE_COUNTS = 2
  };

  ///@{
  /**
   * How the levels are chosen (see the class comment). Default GEOMETRIC_EPSILON.
   */
  vtkSetClampMacro(LevelMode, int, GEOMETRIC_EPSILON, TARGET_TRIANGLE_COUNTS);
  vtkGetMacro(LevelMode, int);
  void SetLevelModeToGeometricEpsilon() { this->SetLevelMode(GEOMETRIC_EPSILON); }
  void SetLevelModeToEpsilonList() { this->SetLevelMode(EPSILON_LIST); }
  void SetLevelModeToTargetTriangleCounts() { this->SetLevelMode(TARGET_TRIANGLE_COUNTS); }
  ///@}

  ///@{
  /**
   * Number of simplified levels in GEOMETRIC_EPSILON mode (the output has one more block, level
   * 0). Range [1, 32], default 3. The list modes make one level per list entry.
   */
  vtkSetClampMacro(NumberOfLevels, int, 1, 32);
  vtkGetMacro(NumberOfLevels, int);
  ///@}

  ///@{
  /**
   * Bound on the cluster error (not on the distance to the input: see the class docs) of the
   * first simplified level in GEOMETRIC_EPSILON mode, as a fraction of the
   * bounding-box diagonal (RelativeUnits on) or in world units. Range [0, VTK_DOUBLE_MAX],
   * default 0.002. A level's epsilon that overflows (Epsilon * EpsilonFactor^(i - 1) times the
   * diagonal, or an EpsilonList value times it) is taken as the largest double, which merges
   * every cluster that may merge.
   */
  vtkSetClampMacro(Epsilon, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Epsilon, double);
  ///@}

  ///@{
  /**
   * Ratio between the epsilons of consecutive levels in GEOMETRIC_EPSILON mode. Range
   * [1, 1000], default 3 (each level has roughly a third of the triangles of the one before on
   * smooth closed surfaces; about half on an open gyroid or wavelet isosurface).
   */
  vtkSetClampMacro(EpsilonFactor, double, 1.0, 1000.0);
  vtkGetMacro(EpsilonFactor, double);
  ///@}

  ///@{
  /**
   * The epsilon of each level in EPSILON_LIST mode, strictly increasing (same units as
   * Epsilon). Values must be finite and not negative. Empty by default.
   */
  void AddEpsilonValue(double epsilon);
  void RemoveAllEpsilonValues();
  int GetNumberOfEpsilonValues() const;
  double GetEpsilonValue(int i) const;
  ///@}

  ///@{
  /**
   * The triangle count of each level in TARGET_TRIANGLE_COUNTS mode, strictly decreasing, each
   * at least 1. Empty by default.
   */
  void AddTargetTriangleCount(vtkIdType count);
  void RemoveAllTargetTriangleCounts();
  int GetNumberOfTargetTriangleCounts() const;
  vtkIdType GetTargetTriangleCount(int i) const;
  ///@}

  ///@{
  /**
   * Whether epsilon values and MaximumCellSize are fractions of the input's bounding-box
   * diagonal (on) or world units (off). Default on.
   */
  vtkSetMacro(RelativeUnits, bool);
  vtkGetMacro(RelativeUnits, bool);
  vtkBooleanMacro(RelativeUnits, bool);
  ///@}

  ///@{
  /**
   * Largest octree cell a cluster may span (§2.4 case a), same units as Epsilon; 0 means no
   * limit. Range [0, VTK_DOUBLE_MAX], default 0. It bounds the cell, not quite the cluster: a
   * group of at most 4 vertices cut off at a cell face counts as lying in its neighbour's cell
   * (see the class docs), at every finer depth too, so a cluster may reach past its cell by
   * about the input's edge length there (on a UV sphere of radius 1 and 12,480 triangles, with
   * MaximumCellSize 0.05 in world units and epsilon 0.01, 32 of 5,400 clusters spanned more than
   * 0.05, the widest 0.115: 5 vertices over four cells of 0.031).
   */
  vtkSetClampMacro(MaximumCellSize, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumCellSize, double);
  ///@}

  ///@{
  /**
   * Most vertices one cluster may hold (§2.4 case b); 0 means no limit. Range [0, VTK_INT_MAX],
   * default 0.
   */
  vtkSetClampMacro(MaximumPointsPerCell, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumPointsPerCell, int);
  ///@}

  ///@{
  /**
   * Fixed-point iterations for the e2 term of the representative (§3); 0 uses e1 alone. Range
   * [0, 20], default 3 (the paper's choice; it stops earlier when the point stops moving).
   */
  vtkSetClampMacro(RepresentativeIterations, int, 0, 20);
  vtkGetMacro(RepresentativeIterations, int);
  ///@}

  ///@{
  /**
   * Weight of the planes through boundary edges (perpendicular to their triangle) relative to
   * the area-weighted face planes: an edge plane weighs BoundaryWeight * length^2. Higher keeps
   * open boundaries straighter at the cost of the surface. Range [0, 1e6], default 1.
   */
  vtkSetClampMacro(BoundaryWeight, double, 0.0, 1e6);
  vtkGetMacro(BoundaryWeight, double);
  ///@}

  ///@{
  /**
   * Keep the topology and orientation of the input on every level (default on). A trial level is
   * cut again below the clusters that fold a triangle against the surface around it, fold a thin
   * part onto itself, pinch an edge or a vertex, or break a connected piece, until none does: every
   * level of a closed manifold input is a closed manifold (up to small pieces that vanish whole
   * near the level's surface, see above; an open input may also lose a small hole that closes near
   * it) that faces the same way. Those repairs are local, and a handle can close between
   * clusters that each keep their link, so each trial level is also compared with the level
   * before, piece by piece: twice the genus of each piece (its cross-caps where it cannot be
   * oriented, with a point where the surface touches itself counted once per side) must stay.
   * Where it does not, the clusters that hold a loop of edges around no triangles of their own
   * are cut again; a level that still closes a handle is not taken: a target count then gets the
   * nearest level that keeps every handle (a 3,600-triangle torus asked for 24 triangles has 48,
   * where it became a sphere of 16 without the check; a Klein bottle of 9,600 asked for 64 has
   * 100, where it became a sphere of 76; VTK's wavelet isosurface, 25,624 triangles asked for 1%,
   * has 2,549 and keeps its 11 handles, where 1,264 kept 6), and an epsilon is lowered to the
   * largest found below it that keeps every handle, with a warning (on that isosurface epsilon
   * 0.3 of the diagonal gives 6,800 triangles at 0.99 of it, where 2,454 kept 9 handles; a
   * level refused at a large epsilon can keep more triangles than one at a smaller epsilon, as
   * 0.1 gives 4,745). Small closed pieces that vanish whole are not counted; two surfaces that
   * touch at a point count as two (one of two tori sharing a vertex is not lost into it). Far
   * below the counts a shape allows, large epsilons make clusters that the repairs split again,
   * so a smaller target can get more triangles (that Klein bottle asked for 28 has 372). On a rough surface (a
   * noisy scan, the isosurface of a noisy volume) those repairs add back so many triangles that
   * target counts are missed by far, and the search's level can then be far from the input: the
   * isosurface of a 120^3 volume with noise of one grid step (MeshLODTestMeshes'
   * MakeNoisyIsosurface, 103,940 triangles, full of small handles) asked for 10% and 1% got 18.0%
   * and 16.5%, at 0.93 and 0.98 times the Hausdorff distance of vtkQuadricClustering's output of
   * the same counts (before handles were compared: 15.8% and 6.0%, that last level with handles
   * closed and at 2.6 times that distance); with noise of 1.5 steps, 33% and 32% (measured before a vertex of a cluster could stand in for
   * a representative that flips a triangle). Thin parts keep many triangles too: a cluster that
   * holds a tube's whole cross-section breaks the tube, so along it the clusters stay narrower than
   * the tube; three tubes of 24 sides whose radius is 1% of the diagonal (57,588 triangles,
   * Benchmarks/OtherMeshesBenchmark.cxx) asked for 1% keep 4,622 (8%), where
   * vtkTriangleCollapseDecimation meets the count.
   *
   * Off: the paper's conditions alone (the connected vertices of a cell, epsilon, and the flip test
   * of the triangles joining a cluster to the rest of the mesh), as vertex clustering is meant to
   * work: a level may close holes and handles, join or drop thin parts and small pieces, have
   * non-manifold edges and vertices, and have triangles facing against their surroundings, as
   * vtkQuadricClustering's output does; a thin part folded flat keeps both its sides (two triangles
   * on the same points in opposite orders). The clusters' own rules for curves where sheets meet
   * (one open piece of one curve each) and for locked vertices stay, but a curve edge may lose
   * sheets. On that isosurface: 10,382 and 1,037 triangles, at 1.00 and 1.01 times
   * vtkQuadricClustering's Hausdorff distance and 0.94 and 0.92 times its RMS distance, in a
   * quarter of the time; on smooth isosurfaces, counts and distances as with it on. With noise far
   * above the edge length (a sphere whose radii moved by up to 2.5 edges) it reaches both counts,
   * at 0.67 and 0.71 times vtkQuadricClustering's Hausdorff distance and 0.96 and 0.53 times its
   * RMS distance (its 1% level crumpled, at about 5 and 10 times, before a vertex of a cluster
   * could stand in for a representative that flips a triangle), where the repairs keep 92% and 87%
   * of its triangles at the 10% and 1% targets; but the levels made with it off fold: on a sphere
   * like it, 14% of the triangles of both levels faced inwards (none of the input's, 0.03% and none
   * of vtkTriangleCollapseDecimation's levels of the same counts), so for a rough surface whose
   * levels must not fold over, vtkTriangleCollapseDecimation is the filter. Levels still nest, and
   * MorphTargetId maps every triangle onto one of the next level with its orientation.
   */
  vtkSetMacro(PreserveTopology, bool);
  vtkGetMacro(PreserveTopology, bool);
  vtkBooleanMacro(PreserveTopology, bool);
  ///@}

  ///@{
  /**
   * Flip edges of every simplified level where the other diagonal of the two triangles lies closer
   * to the input (judged by the local surface distance both ways). Triangle counts, clusters and
   * MorphTargetId stay as they are, and the next level is clustered from the unflipped
   * triangles; so do the points, but for CenterOnInput (default on), which centres the flipped
   * triangles on the input, so its shifts differ (on a UV sphere by up to a third of the
   * level's epsilon). On the benchmark isosurfaces it lowers the RMS distance by 8-21% and changes the
   * Hausdorff distance by -9% to +1%, for 1.3-1.5 times the time on one thread and 1.15-1.5 on
   * two (Benchmarks/RESULTS.md's runs; 1.34-1.46 and 1.16-1.44 in its last; the 2.3M gyroid's
   * one-thread run 1.89 in the run before;
   * 1.6-1.75 and 1.6-1.7 before edges whose far corners are sharp
   * were left unjudged, Core/TriangulationFlips.h). On a binary mask's terraced isosurface
   * (84,380 triangles) at 1%, where the input's connectivity joins many quads of clusters the
   * wrong way, the Hausdorff and RMS distances fall from 1.51 and 1.13 to 0.97 and 0.98 times
   * vtkQuadricClustering's. The price: a level's triangles are then no longer exactly what the
   * finer level's triangles become through MorphTargetId, so a geomorph from level i ends (as L
   * tends to i + 1) on those images, not on level i + 1, and jumps at L = i + 1 where quads were
   * flipped, by as much as the level's own error: between vtkLODGeomorph at L = i + 1 - 1e-7
   * and level i + 1 the Hausdorff distance was 0.5-1.9 times level i + 1's Hausdorff distance to
   * the input (the RMS distance 0.14-1.15 times the level's) over the three default levels of the
   * metaballs and 611k gyroid isosurfaces, whose levels are coarse and have many flips
   * (Benchmarks/RESULTS.md, "vtkLODGeomorph at the levels"). A level is flipped once the next
   * one is made, and a flip is refused where a triangle it makes would become, in the next level,
   * the same triangle as another one: where the next level merges the ends of the old diagonal
   * but not those of the new one, the two new triangles become one triangle twice, a fin that
   * the geomorph passed through on its way to the images (a gyroid isosurface of 22,550
   * triangles, eight levels of epsilon 0.002 times 2^i, had 10 such pairs between levels 1 and 2
   * and 16 in all, none now); a level that repeats the one before gets its flips. Holding a
   * level back keeps it in memory while the next is made (on the benchmark isosurfaces the peak
   * stayed within one byte per input triangle of the run without flips). For
   * discrete levels (no geomorph) turn it on; for geomorphs leave it off (then the geomorph at
   * L -> i + 1 is level i + 1 exactly). Default off.
   */
  vtkSetMacro(FlipEdges, bool);
  vtkGetMacro(FlipEdges, bool);
  vtkBooleanMacro(FlipEdges, bool);
  ///@}

  ///@{
  /**
   * Move every coarse level onto the middle of the input surface (Core/LevelCentering.h):
   * representatives minimising a quadric lie on a curved surface's outer side, and each
   * changed interior point of a level with at most a quarter of the input's triangles moves
   * along its normal by the area-weighted mean signed distance of the input around it, as far
   * as the largest deviation around the point does not grow and at most a quarter of its
   * shortest edge. On the metaballs isosurface (154k triangles) this lowers the RMS distance
   * by 8% at 10% of the triangles and 26% at 1%, the Hausdorff distance by 7% and 12%. Not
   * moved: boundary and non-manifold points, creases and corners, planar facets, and clusters
   * that stay the same between two levels. Clusters, counts and MorphTargetId are those of the
   * run without it (a baked texture follows the moved points). Default on.
   */
  vtkSetMacro(CenterOnInput, bool);
  vtkGetMacro(CenterOnInput, bool);
  vtkBooleanMacro(CenterOnInput, bool);
  ///@}

  ///@{
  /**
   * Recompute point normals (the Normals attribute) on every simplified level from its
   * triangles, replacing interpolated input normals: named as the input's Normals attribute,
   * "Normals" when the input has none. Default off.
   */
  vtkSetMacro(ComputeNormals, bool);
  vtkGetMacro(ComputeNormals, bool);
  vtkBooleanMacro(ComputeNormals, bool);
  ///@}

  ///@{
  /**
   * Type of every level's points (level 0 included), as vtkAlgorithm::DesiredOutputPrecision:
   * DEFAULT_PRECISION (the default) keeps the input's when it is float or double and gives
   * double for integer points; SINGLE_PRECISION gives float, DOUBLE_PRECISION double. The
   * simplification itself runs in double precision either way; with SINGLE_PRECISION on double
   * input, level 0 is float too, and the passes that read level 0 (centring, edge flips,
   * measured errors) see its rounded points. vtkLODGeomorph's output keeps the levels' type.
   */
  vtkSetClampMacro(OutputPointsPrecision, int, SINGLE_PRECISION, DEFAULT_PRECISION);
  vtkGetMacro(OutputPointsPrecision, int);
  ///@}

  ///@{
  /**
   * Measure every level's surface distance to level 0 (MeasuredHausdorff, MeasuredRMS field
   * data). Costs about half the simplification's time (0.5 s on top of 1.0 s for the
   * levels of a 977,200-triangle UV sphere, one thread). Default off.
   */
  vtkSetMacro(MeasureLevelErrors, bool);
  vtkGetMacro(MeasureLevelErrors, bool);
  vtkBooleanMacro(MeasureLevelErrors, bool);
  ///@}

  ///@{
  /**
   * Bake a texture atlas per simplified level (output port 1) from the colour array or from the
   * texture on input port 1. Default off: colours and texture coordinates are averaged per
   * vertex.
   */
  vtkSetMacro(BakeTexture, bool);
  vtkGetMacro(BakeTexture, bool);
  vtkBooleanMacro(BakeTexture, bool);
  ///@}

  ///@{
  /**
   * Edge of each baked texture in texels, rounded up to a power of two (raised, with a warning,
   * when a level has too many triangles to fit). Range [16, 16384], default 1024. Each texel
   * takes a closest-point query on the input: 16384 (268M texels, 1 GB of RGBA per level) takes
   * minutes; the baking reports progress and honours an abort as it goes.
   */
  vtkSetClampMacro(TextureResolution, int, 16, 16384);
  vtkGetMacro(TextureResolution, int);
  ///@}

  ///@{
  /**
   * Point array holding the colours to bake: 3 or 4 components, 16-bit integers (0-65535), other
   * integer types such as unsigned char (0-255) or floating point (0-1); values outside are
   * clamped. Default none: the active scalars when they are such an array. Ignored when a
   * texture is connected to port 1 and the input has texture coordinates.
   */
  vtkSetStringMacro(ColorArrayName);
  vtkGetStringMacro(ColorArrayName);
  ///@}

  /**
   * Connect the optional texture (port 1).
   */
  void SetTextureConnection(vtkAlgorithmOutput* output);
  void SetTextureData(vtkImageData* texture);

  /**
   * The hierarchy (output port 0); the inherited GetOutput() is null for a composite output.
   */
  vtkMultiBlockDataSet* GetHierarchy();

  /**
   * The baked textures (output port 1), one block per level.
   */
  vtkMultiBlockDataSet* GetTextures();

  /**
   * Epsilon actually used for simplified level `level` (1-based) in world units, valid after
   * execution (0 for level 0 or out of range).
   */
  double GetLevelEpsilon(int level) const;

protected:
  vtkVertexClusterOctree();
  ~vtkVertexClusterOctree() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  // The texture (port 1) is needed whole whatever piece of the mesh is asked for.
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int LevelMode = GEOMETRIC_EPSILON;
  int NumberOfLevels = 3;
  double Epsilon = 0.002;
  double EpsilonFactor = 3.0;
  std::vector<double> EpsilonValues;
  std::vector<vtkIdType> TargetTriangleCounts;
  bool RelativeUnits = true;
  double MaximumCellSize = 0.0;
  int MaximumPointsPerCell = 0;
  int RepresentativeIterations = 3;
  bool PreserveTopology = true;
  bool FlipEdges = false;
  bool CenterOnInput = true;
  double BoundaryWeight = 1.0;
  bool ComputeNormals = false;
  bool MeasureLevelErrors = false;
  int OutputPointsPrecision = DEFAULT_PRECISION;
  bool BakeTexture = false;
  int TextureResolution = 1024;
  char* ColorArrayName = nullptr;
  std::vector<double> LevelEpsilons;

private:
  vtkVertexClusterOctree(const vtkVertexClusterOctree&) = delete;
  void operator=(const vtkVertexClusterOctree&) = delete;

  bool CheckSettings();
  void WarnIfCountMissed(int level, vtkIdType asked, vtkIdType reached, vtkIdType previous);
  // RequestData's levels after level 0 (defined in the .cxx).
  struct LevelMaker;
};

#endif
