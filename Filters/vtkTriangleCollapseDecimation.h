/**
 * @class   vtkTriangleCollapseDecimation
 * @brief   a hierarchy of levels of detail of a triangle mesh by triangle collapses
 *
 * vtkTriangleCollapseDecimation reduces a triangle mesh step by step by collapsing triangles: a
 * triangle and its (up to three) edge neighbours disappear and its three vertices merge into one
 * new vertex. With the default operator (SetOperator) a triangle whose cheapest edge collapse is
 * much cheaper collapses that edge instead (half a triangle collapse). The result is not one mesh
 * but a hierarchy: output port 0 is a vtkMultiBlockDataSet whose block i is level i as a
 * vtkPolyData named "Level i". Block 0 is the validated input; every next level has strictly fewer
 * triangles. Use GetHierarchy() to get it (the inherited GetOutput() is null for a composite
 * output).
 *
 * Two methods weight the triangles and place the collapse point (SetMethod):
 * - Quadric (the default; Pan, Zhou, Shi, "A New Mesh Simplification Algorithm Based on Triangle
 *   Collapses", J. Comput. Sci. Technol. 2002): each vertex carries the quadric of the planes of
 *   the original triangles around it (area weighted, or alike: PlaneWeights; plus planes through
 *   boundary edges perpendicular to their triangle, weighted by BoundaryWeight times the edge
 *   length times the bounding-box diagonal, so open boundaries stay in place). Collapsing a
 *   triangle costs the sum of its three quadrics at the point minimising it (divided by the surface
 *   its vertices stand for to the power AreaNormalization, by default); quadrics add up when
 *   vertices merge, so the cost of later collapses carries every original plane merged into them
 *   (error propagation). The minimiser is solved in the well-determined directions only (a
 *   Tikhonov-regularised solve around the centroid, close to a truncated pseudo-inverse), so that a
 *   nearly singular system (a flat or cylindrical patch) keeps the point near the centroid along
 *   its free directions and needs none of the paper's fixed fallback candidates. The paper's own
 *   rule (the minimiser where the system is solvable, else the best of the centroid, the vertices
 *   and the edge midpoints) is SetPlacementToPaperCandidates().
 * - Curvature (Gieng, Hamann, Joy, Schussman, Trotts, "Smooth Hierarchical Surface
 *   Triangulations", IEEE Visualization 1997): a least-squares quadratic height field
 *   f(u, v) is fitted over the triangle's stencil and its ancestral points (the original
 *   vertices merged into its corners, at most MaximumFitPoints of them as an evenly strided
 *   subset; an extended stencil when the fit is singular; around a vertex where more than 64
 *   triangles meet, such as a fan's centre, a cone's tip or a UV sphere's pole, a fit reads
 *   about 64 of them, each standing for its share, and a collapse next to it does not re-fit
 *   them all: otherwise the work grows with the cube of the valence, 88 s for a fan of 2,000
 *   triangles, against 0.06 s now with the default CurvatureCost; with CurvatureCost WEIGHT,
 *   whose valence term changes for every triangle at such a vertex with each collapse there,
 *   the work still grows with its square: 2.2 s for a fan of 2,000, 12 s for 4,000, where
 *   re-fitting the fan after every collapse at its centre took 9 s and 47 s).
 *   Collapses are ranked by CurvatureCost. By default
 *   (FIT_DEVIATION) a collapse costs the integral over the new triangles of their squared
 *   height above the fitted surface, or the merged planes'
 *   area-weighted squared distance at the collapse point where that is larger; the collapse
 *   point is on the normal through the centroid c at the height where that deviation is least,
 *   or the merged planes' minimiser when that costs less. With WEIGHT, paper 000's own ranking,
 *   the weight is W = A (wk kappa + wa alpha + wv V) with the absolute curvature kappa
 *   (normalised by the largest in the input), the shape measure alpha and the valence penalty
 *   V = |val - 6| / 12, weighted by CurvatureWeight, AngleWeight and ValenceWeight (which must
 *   sum to 1); the collapse point is on the normal through c, as in the paper, but not at the
 *   fitted surface (c + f(0, 0) n): at the height where the new triangles lie on the fitted
 *   surface on average (at f(0, 0) they are chords inside a convex surface; on the benchmark
 *   meshes this lowers the RMS error by about a third). The paper collapses only triangles with
 *   a complete stencil, none touching a boundary; here a triangle with a boundary vertex
 *   collapses to the minimiser of its merged planes, boundary planes included, so that open
 *   boundaries stay in place. The paper's weight is a curvature and shape heuristic, not an
 *   error: at equal triangle counts its error is several times that of the quadric method,
 *   and FIT_DEVIATION's is a seventh to a half of it (Benchmarks/RESULTS.md).
 *
 * A collapse is made only when it is legal (paper 000, section 3, generalised to open
 * meshes):
 * - no vertex involved is non-manifold, except on a curve where several sheets meet (as
 *   between the regions of a segmented volume): a vertex at a regular point of such a curve
 *   (two of its edges with the same number k > 2 of triangles, the others with two, its
 *   triangles in k fans from one of those edges to the other) may merge with its neighbour
 *   along the curve or absorb a neighbour inside a sheet, by edge collapses only, under the
 *   link condition (the members' common neighbours are only the apexes of the dying
 *   triangles), so that the sheets, the curve and every other edge's triangle count stay; its
 *   position minimises the merged planes of all its sheets, which hold it to the curve. Other
 *   non-manifold vertices (where curves meet or end, bow ties) are locked; the curvature
 *   method leaves every curve as it is unless it may collapse edges (FIT_DEVIATION with
 *   TRIANGLES_AND_EDGES, see SetOperator);
 * - the merged vertex's neighbourhood is one disk or half-disk (no pinch, no non-manifold
 *   edge, no duplicate triangle, same genus), tested without regard to winding, so that
 *   non-orientable surfaces such as a Moebius strip or Boy's surface simplify like any other;
 *   on a boundary and next to a non-manifold vertex, the link condition too (a hole of three
 *   edges stays open, a bow tie keeps both wings);
 * - no neighbour apex drops to valence 3 (paper 000's "no new cycle" rule; it holds for
 *   triangle collapses, and for edge collapses in the IndependentSets schedule only: an edge
 *   collapse removes a valence-3 vertex like any other, as in vtkQuadricDecimation);
 * - the stencil boundary polygon projected on the triangle's plane is star-shaped around the
 *   collapse point (on a mesh with a part that cannot be oriented consistently: no new
 *   triangle changes side of that plane, since across the seam a triangle's winding says
 *   nothing about it). On other meshes a run that finds no legal collapse left before its
 *   last target relaxes this test once: a ring triangle already on the wrong side may stay
 *   there (on noisy or rough input the strict test stops the curvature method far short of
 *   its target; runs that reach their targets under it are unchanged). When a run stalls with
 *   this test relaxed (or with nothing to relax), the curvature method with FIT_DEVIATION and
 *   TRIANGLES_AND_EDGES lets a refused triangle collapse its cheapest legal edge instead, as
 *   the quadric method always does (on the isosurface of a noisy volume, 25,344 triangles with
 *   PreserveTopology off, it had stopped at 542 triangles asked for 253; now 252, at 2.1 times
 *   vtkQuadricDecimation's Hausdorff distance);
 * - no triangle's normal turns by more than MaximumNormalDeviation, unless it ends within that
 *   angle of the input surface's facing (collapses that smooth a noisy scan turn its triangles
 *   towards the surface);
 * - no triangle comes to face away from the original surface its corners stand for (the
 *   summed area vectors of the input triangles merged into them; without this, many small
 *   turns can add up to a fold at coarse levels); one that faces away already, as many do on
 *   a very noisy scan, may stay so.
 * Zero-area input triangles (coincident points, as marching cubes makes where the surface
 * passes through a sample) are collapsed, not kept, where the topology allows: next to an
 * open attribute seam (coincident points that differ in point data are not stitched, see
 * below) some stay (VTK's Boy's surface with texture coordinates, 60 x 60: 120 of the 258
 * triangles of its coarsest level). A triangle refused only because a
 * neighbour apex has a low valence gets the edge swap of paper 000 (figure 3): the shared edge
 * is swapped and one of the two new triangles collapses; swap and collapse are made as one
 * merge of three vertices joined by two edges, which keeps every level's correspondence exact
 * (GetNumberOfSwaps()).
 *
 * Two schedules order the collapses (SetSchedule):
 * - Greedy (the default): one collapse at a time from a priority queue, cheapest first, with the
 *   costs around each collapse updated (paper 002, section 2.4). With the quadric method a
 *   triangle whose collapse is refused goes back into the queue at the cost of its cheapest
 *   legal other edge (the shortest of equal costs), so that a refused edge does not hold back
 *   a free one (on flat parts every edge costs nothing: a subdivided 3 x 1 x 1 box asked for
 *   12 triangles comes out exact, where triangles waiting on their refused edge left it 20% of
 *   its diagonal off). With PartitionedGreedy on (the default) the greedy order runs in
 *   parallel rounds: each round cuts space into the cells of a grid and runs the greedy loop in
 *   every cell at once, up to a cost threshold shared by all cells; a collapse that would reach
 *   into another cell waits for the next round, whose grid is shifted by half a cell. The
 *   curvature method re-fits the triangles one ring out from a collapse lazily, when they come
 *   to the top of the queue (exactly the same order wherever no cost falls below half its old
 *   value); in the rounds, those with a corner in another cell are marked for re-fitting at
 *   the end of the round, and a fit reads only its own cell's vertices' neighbourhoods.
 *   (Ranked by paper 000's weight, CurvatureCost WEIGHT, the greedy order stays serial: in
 *   rounds it lost much of its accuracy on a noisy surface.) For its whole hierarchy the
 *   curvature method takes 1.3-3.4x the time vtkQuadricDecimation needs for one 10% target on
 *   one thread (1.61-2.55x in Benchmarks/RESULTS.md's run), and 1.6-2.75x less on two (the
 *   quadric method: 0.29-0.57x over fifteen runs on AMD EPYC processors, 0.35-0.53x in
 *   RESULTS.md's, where the two runs before on the same output gave 0.40-0.51x and
 *   0.37-0.47x; 1.4-1.9x less on two, 1.63-1.80x in RESULTS.md's (1.65-1.73x and 1.67-1.74x
 *   the two runs before); the 154k-triangle
 *   mesh's one run of half a second swings most; the
 *   ratios move with the processor, the machine's load and what ran before in the same process:
 *   on an Intel Xeon the quadric method took 0.42-0.69x over three runs, its own times about as
 *   on the EPYC, vtkQuadricDecimation's 1.3-2.0x shorter; on one EPYC the 154k mesh's 0.54 was
 *   0.41 in the next run of the same build).
 * - IndependentSets (paper 000, section 6): each pass takes, cheapest first, triangles whose
 *   neighbourhoods share no vertex, until it removes 4 * LevelFraction of the live triangles,
 *   checks and collapses them all at once (in parallel), and re-weights only the triangles
 *   around what changed. Passes that stall hand the rest of a level to the greedy loop (see
 *   SetSchedule).
 * Either way, output levels are snapshots taken when the triangle count reaches each level's
 * target; the collapses between two levels are composed. (A collapse along a curve where k
 * sheets meet removes k triangles, so such a mesh's level may end up to k - 1 triangles below
 * its target.) On the benchmark meshes both reach
 * about the same error per triangle (RMS within 3%, Hausdorff distances within the few tens of
 * percent by which a maximum varies between runs; Benchmarks/RESULTS.md); Greedy is the
 * default because it is faster: 1.7-2.8x on one thread, 1.9-3.8x on two (its last three runs).
 * On CAD-like solids (flat faces, sharp rims) Greedy is also far more accurate: IndependentSets keeps paper 000's
 * valence rule for edge collapses too, and on the extruded text of the Python test (79,280
 * triangles) asked for 1% it stopped at 1.02% with about 40x vtkQuadricDecimation's Hausdorff
 * distance and 60x its RMS distance (Greedy: 1.3x and 1.0x).
 *
 * Levels: by default NumberOfLevels levels follow level 0 with triangle counts spaced
 * geometrically down to (1 - TargetReduction) times the input's (8 levels to 1% gives 56%, 32%,
 * 18%, 10%, 5.6%, 3.2%, 1.8% and 1%). AddLevelReduction() gives the reductions explicitly
 * instead. Targets that round to the same count, or that one collapse passes together (more
 * levels than a small mesh has collapses to spread them over), give one level. MaximumError
 * (world units) stops early when the next collapse's estimated error exceeds it; the coarsest
 * mesh reached is then the last level. By default every connected piece stays, each at least
 * a tetrahedron, with its genus: on the isosurface of a noisy volume (103,940 triangles, 328
 * specks around single noisy samples besides the main surface, 312 of them of 8 triangles) the
 * levels stopped at 2,016 triangles for a target of 1,039, most of them specks, and that level was
 * 5.2 times as far from the input (Hausdorff distance) as vtkQuadricDecimation's output of the
 * same count, which drops the specks. With PreserveTopology off small closed pieces vanish and the
 * levels reach their counts (Benchmarks/RESULTS.md, "Beyond isosurfaces"). A warning reports a
 * coarsest level short of its target,
 * and a level whose estimated error jumps far beyond what the fall in its triangle count
 * explains (more than 8 times, from level 2 on): on a broken input, such as a seam left open
 * and locked, the last collapses forced by the count can distort it.
 *
 * What every level carries (array names in MeshLODHierarchy.h):
 * - every input point-data array, with its component names and information (units, say);
 *   floating-point arrays interpolated with the barycentric weights of each collapse point
 *   (composed over the collapses between levels), integer arrays (ids, labels, categories)
 *   taking the value of the vertex with the largest weight.
 *   The weights are those of the collapse point's projection onto the merged edge or
 *   triangle, clamped to it: a point placed outside (a boundary point moved along the
 *   boundary) takes the data of the nearest point of the edge, never values beyond its
 *   vertices' (on a flat grid carrying x + 2y, such points differ from x + 2y by up to twice
 *   the grid step at coarse levels; with Placement PAPER_CANDIDATES, not at all);
 * - the cell data of the surviving input triangles;
 * - the GlobalIds attributes of the input's points and cells, unique on every level as in the
 *   input (a level's point takes the id of one of the input points merged into it, no two the
 *   same; a triangle keeps its input triangle's; where polygons or strips were triangulated,
 *   their triangles share the cell's id, in a plain array of that name, not the attribute);
 * - for every level but the last: MorphTarget (where each point goes in the next level),
 *   MorphTargetId (its point id there; chaining it maps any input point to its point in any
 *   coarser level) and CollapseRank (the order in which the points move when only part of the
 *   transition is applied, -1 for points that do not move);
 * - field data LevelIndex, NumberOfTriangles, EstimatedError and, with ComputeLevelError on,
 *   MeasuredHausdorff and MeasuredRMS, plus the input's field-data arrays (shared; one named like
 *   any of these, or TextureAtlasLevel, is left out, so a level of an unmeasured run never shows an
 *   input's MeasuredHausdorff). EstimatedError is the filter's own estimate: the largest RMS
 *   distance of a vertex to the original planes merged into it. It is not a bound. The measured
 *   values are symmetric surface distances to level 0 found by sampling; they are measurements from
 *   below: the true Hausdorff distance is at least as large.
 *
 * Input: triangles (polygons and strips are triangulated first; vertices and lines are
 * ignored with a warning). Empty input gives a hierarchy of one empty level, without error.
 * Composite data (a multiblock of surfaces) is an error: merge its blocks first, or run one
 * filter per block. Integer points give levels in double.
 * NaN or infinite coordinates (of points that triangles use: unused points are dropped), point
 * ids out of range and a bounding-box diagonal above 1e30 or
 * below 1e-30 but not 0 (the collapse costs hold squared areas) are an error (all points at one
 * place, a diagonal of 0, are simplified like any other mesh: every collapse is free); point- or
 * cell-data
 * arrays whose tuple count is not the number of points or cells are ignored with a warning.
 * Points on boundary or non-manifold edges that coincide up to rounding (1e-12 of the bounding
 * diagonal, or 64 double-precision epsilons of the largest coordinate where that is more, far
 * from the origin) and carry the same point data are merged, which stitches triangle soups and
 * duplicated seams (coincident points whose data differ, an attribute seam such as a cube's split
 * normals, stay apart, with a warning);
 * triangles wound against the rest of their connected part are flipped (each orientable part
 * keeps the orientation most of its triangles have; a warning gives the count); non-manifold
 * vertices that remain are kept but locked, except on curves where sheets meet (see the
 * collapse rules above). The computation runs about the centre of the
 * bounding box, so meshes far from the origin lose no accuracy.
 *
 * The data-parallel parts (initial weights, the greedy rounds' cells, re-weighting and legality
 * checks of a pass, collapsing an independent set, output arrays) run with vtkSMPTools; the
 * output is the same for every thread count.
 *
 * A mesh whose point ids are scattered in space (written from a hash map, merged from a point
 * set) is simplified on a copy renumbered in Morton order, and the levels are numbered back
 * (level 0 stays the input as it came): the collapses read per-point arrays around each
 * collapse, and on scattered ids nearly every read misses the cache. Such a mesh is told from a
 * contouring filter's, a parametric source's or a grid's by how far apart its triangles' corner
 * ids lie (Filters/Core/SpatialOrder.h); meshes of under 4,096 points are never renumbered. On
 * the 611k-triangle gyroid isosurface with its ids shuffled the whole hierarchy took 1.13-1.29
 * times as long as on the contoured mesh in two runs, against 1.80 without the renumbering
 * (vtkQuadricDecimation 1.37-1.54; Benchmarks/RESULTS.md, "Input order", has the 1.29 and 1.37;
 * the others from trial runs). The levels of a
 * renumbered mesh do not depend on how it was numbered, but for the centring (CenterOnInput),
 * which samples the input's triangles in their order.
 *
 * @sa vtkLODGeomorph vtkVertexClusterOctree vtkQuadricDecimation vtkDecimatePro
 */
#ifndef vtkTriangleCollapseDecimation_h
#define vtkTriangleCollapseDecimation_h

#include "vtkFiltersMeshLODModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <vector> // For the level reductions

class vtkMultiBlockDataSet;
namespace meshlod
{
struct TriangleCollapseOptions;
struct TriangleCollapseResult;
} // namespace meshlod

class VTKFILTERSMESHLOD_EXPORT vtkTriangleCollapseDecimation : public vtkPolyDataAlgorithm
{
public:
  static vtkTriangleCollapseDecimation* New();
  vtkTypeMacro(vtkTriangleCollapseDecimation, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Methods
  {
    QUADRIC = 0,
    CURVATURE = 1
  };
  enum CurvatureCosts
  {
    WEIGHT = 0,
    FIT_DEVIATION = 1
  };
  enum Schedules
  {
    INDEPENDENT_SETS = 0,
    GREEDY = 1
  };
  enum Operators
  {
    TRIANGLES = 0,
    TRIANGLES_AND_EDGES = 1
  };
  enum Placements
  {
    REGULARIZED = 0,
    PAPER_CANDIDATES = 1
  };
  enum PlaneWeightings
  {
    AREA_WEIGHTS = 0,
    UNIFORM_WEIGHTS = 1
  };

  /// The hierarchy (output port 0).
  vtkMultiBlockDataSet* GetHierarchy();

  ///@{
  /**
   * How triangles are weighted and where they collapse to: QUADRIC (default) or CURVATURE.
   */
  vtkSetClampMacro(Method, int, QUADRIC, CURVATURE);
  vtkGetMacro(Method, int);
  void SetMethodToQuadric() { this->SetMethod(QUADRIC); }
  void SetMethodToCurvature() { this->SetMethod(CURVATURE); }
  const char* GetMethodAsString() const;
  ///@}

  ///@{
  /**
   * Order of the collapses: GREEDY (default, one at a time, cheapest first) or
   * INDEPENDENT_SETS (passes of many simultaneous collapses with disjoint stencils). Passes
   * stall where few candidates can be taken at once: around a vertex of very high valence,
   * whose every stencil holds it (one collapse there per pass), or where most collapses are
   * refused (long thin triangles with the TRIANGLES operator). After 64 passes in a row that
   * each removed under 1% of their budget, the greedy loop makes the rest of the level, and the
   * passes take up the next one. With it, on one thread, a fan of 30,000 triangles around one
   * point takes 0.2 s with the quadric method and 1.0 s with the curvature method (GREEDY:
   * 0.07 s and 0.8 s; 12 s and 13 s before the fallback), a UV sphere of 384,000 triangles with
   * poles of valence 4,000 3.7 s and 18 s (GREEDY: 1.1 s and 10.5 s; on two threads 3.4 s and
   * 11 s, GREEDY 0.6 s and 6 s), and a UV sphere of 116,000 long thin triangles (theta
   * resolution 1,000, phi 60) with the TRIANGLES operator 4.8 s where it had not finished after
   * five minutes (GREEDY: 1.7 s). With the TRIANGLES operator a fan of 3,000 takes 1.3 s either
   * way. GREEDY is the better choice for such meshes.
   */
  vtkSetClampMacro(Schedule, int, INDEPENDENT_SETS, GREEDY);
  vtkGetMacro(Schedule, int);
  void SetScheduleToGreedy() { this->SetSchedule(GREEDY); }
  void SetScheduleToIndependentSets() { this->SetSchedule(INDEPENDENT_SETS); }
  const char* GetScheduleAsString() const;
  ///@}

  ///@{
  /**
   * Greedy schedule: make the greedy order's collapses in parallel, in rounds over the cells of
   * a spatial grid (on, the default), or strictly one after the other (off: the order of paper
   * 002, on one thread). The curvature method ranked by paper 000's weight (CurvatureCost
   * WEIGHT) always takes the strict order. Each round takes the cheapest collapses up to a
   * cost threshold shared by all cells; the last collapses before each level are serial, so the
   * levels land on their triangle counts either way. The output does not depend on the number
   * of threads.
   */
  vtkSetMacro(PartitionedGreedy, bool);
  vtkGetMacro(PartitionedGreedy, bool);
  vtkBooleanMacro(PartitionedGreedy, bool);
  ///@}

  ///@{
  /**
   * Quadric method: what one collapse merges. TRIANGLES: always a triangle's three vertices (the
   * papers' operator). TRIANGLES_AND_EDGES (default): a triangle collapses whole when that costs at
   * most TriangleCostFactor times its cheapest edge collapse, otherwise that edge collapses (an
   * edge collapse is half a triangle collapse: two vertices merge, two triangles disappear).
   * Forcing three vertices to one point costs accuracy (on the benchmark meshes TRIANGLES had
   * 1.0-1.3 times the RMS distance of vtkQuadricDecimation at equal triangle counts, 1.14-1.15 at
   * 10%, with the IndependentSets schedule: the "triangles only" rows of Benchmarks/RESULTS.md;
   * TRIANGLES_AND_EDGES matches it), which the default avoids. Curvature method, ranked by
   * FIT_DEVIATION: TRIANGLES collapses triangles only (paper 000); TRIANGLES_AND_EDGES (default)
   * collapses a triangle's cheapest edge instead only where the triangle collapse would cost more
   * than a million times that edge's merged planes (a crease, such as the rim of a faceted solid,
   * where the edge runs along the rim and the triangle would cut across it, or a flat face) or
   * cannot collapse (a corner on a curve where sheets meet). On the isosurfaces and the other
   * smooth or noisy meshes of the benchmark the levels are those of triangle collapses (within the
   * benchmark's noise); a faceted cylinder at 1% keeps its shape exactly instead of losing its rims
   * (4.4% of the diagonal with TRIANGLES), and the surfaces of a segmented volume reach 1% instead
   * of stopping at 3.3%. With WEIGHT, triangles only.
   * With TRIANGLES_AND_EDGES, a triangle with one corner where more than 64 triangles meet (a
   * hub: a fan's centre, a cone's tip, a UV sphere's pole) is priced by its edge away from the
   * hub alone, as its collapse and its fallback edge (quadric method; the curvature method's
   * fallback edge likewise): the hub keeps its place while it is one. A collapse that moves a
   * hub changes every triangle around it, and re-weighing and re-checking all of them after
   * each such move made a flat fan of 16,000 triangles inside a ring of 32,000 take 4.8 s and
   * one of 20,000 in 40,000 36 s; now 0.41 s and 0.69 s (one thread).
   */
  vtkSetClampMacro(Operator, int, TRIANGLES, TRIANGLES_AND_EDGES);
  vtkGetMacro(Operator, int);
  void SetOperatorToTriangles() { this->SetOperator(TRIANGLES); }
  void SetOperatorToTrianglesAndEdges() { this->SetOperator(TRIANGLES_AND_EDGES); }
  const char* GetOperatorAsString() const;
  ///@}

  ///@{
  /**
   * Quadric method: where a collapse puts the merged vertex. REGULARIZED (default): the point
   * minimising the merged quadric in its well-determined directions and at the centroid of the
   * merging vertices along the others (see the class docs). PAPER_CANDIDATES, paper 002's rule:
   * the minimiser when the quadric's 3x3 system is solvable (every eigenvalue above 1e-6 times
   * the largest), otherwise the cheapest of the triangle's centroid, its three vertices and its
   * three edge midpoints (for an edge collapse: the midpoint and the two ends; ties go to the
   * centroid, then the vertices). On the benchmark isosurfaces (Benchmarks/RESULTS.md, the
   * "paper placement" rows, one thread): the same RMS distance to within 1%; at 10% of the
   * triangles the same Hausdorff distance on the metaballs and the 611k gyroid, less on the
   * 2.3M gyroid (0.92x vtkQuadricDecimation's against 1.03x); at 1% the candidates' was 0.98,
   * 0.82 and 1.05x vtkQuadricDecimation's against the default's 0.92, 1.02 and 0.99x: more on
   * the metaballs and the 2.3M gyroid, less on the 611k gyroid (each is the distance at one
   * spot, which moves by chance: see AreaNormalization), and the whole hierarchy took 1.3-1.65
   * times as long (1.49-1.65 in the last run; an
   * eigendecomposition per solve, against one L D L^T factorisation). On faceted solids both
   * keep the faces exactly. Curvature method: not used (its collapse point comes from the fit).
   */
  vtkSetClampMacro(Placement, int, REGULARIZED, PAPER_CANDIDATES);
  vtkGetMacro(Placement, int);
  void SetPlacementToRegularized() { this->SetPlacement(REGULARIZED); }
  void SetPlacementToPaperCandidates() { this->SetPlacement(PAPER_CANDIDATES); }
  const char* GetPlacementAsString() const;
  ///@}

  ///@{
  /**
   * TRIANGLES_AND_EDGES: how much more a triangle collapse may cost than the triangle's
   * cheapest edge collapse and still be preferred, in [1, 1e6], default 1.5. It removes twice
   * the triangles, so 2 would compare the two per removed triangle, but forcing three vertices
   * to one point costs more than its quadric says where the surface bends: on 14 isosurfaces
   * of 150k-2.3M triangles (metaballs, gyroids, wavelet sheets) at 1%, the Hausdorff distance
   * was 1.06x vtkQuadricDecimation's (geometric mean) at 2 and 1.00x at 1.5, RMS 1.00x
   * at both, the 10% levels the same, the time the same. At 1 a triangle collapses only when it
   * costs no more than an edge (flat regions, where all costs are 0); 1 and 1.5 gave the same
   * figures. Larger values make more triangle collapses at some cost in accuracy. Both costs
   * are divided by their surface's scale (AreaNormalization), a triangle's by more than an
   * edge's: at 0.25 that favours triangles by about a tenth, at 1 by about half.
   */
  vtkSetClampMacro(TriangleCostFactor, double, 1.0, 1.0e6);
  vtkGetMacro(TriangleCostFactor, double);
  ///@}

  ///@{
  /**
   * Fraction of the input triangles removed by the coarsest level, in [0, 1). Default 0.99.
   */
  vtkSetClampMacro(TargetReduction, double, 0.0, 0.999999);
  vtkGetMacro(TargetReduction, double);
  ///@}

  ///@{
  /**
   * Number of levels after level 0 when no explicit reductions are given, in [1, 1000].
   * Their triangle counts are spaced geometrically from the input's down to the coarsest.
   * Default 8.
   */
  vtkSetClampMacro(NumberOfLevels, int, 1, 1000);
  vtkGetMacro(NumberOfLevels, int);
  ///@}

  ///@{
  /**
   * Explicit reductions, one per level after level 0 (each in (0, 1), strictly increasing):
   * level k keeps (1 - reduction_k) of the input triangles. When any is given, NumberOfLevels
   * and TargetReduction are ignored. None by default.
   */
  void AddLevelReduction(double reduction);
  void RemoveAllLevelReductions();
  int GetNumberOfLevelReductions() const { return static_cast<int>(this->LevelReductions.size()); }
  double GetLevelReduction(int i) const;
  ///@}

  ///@{
  /**
   * IndependentSets schedule: the fraction of the live triangles selected for collapse per
   * pass in the paper's terms, in [0.001, 0.25]: a pass removes up to 4 * LevelFraction of the
   * live triangles (a triangle collapse removes 4, an edge collapse 2). Default 0.025 (2.5%, as
   * in paper 000).
   */
  vtkSetClampMacro(LevelFraction, double, 0.001, 0.25);
  vtkGetMacro(LevelFraction, double);
  ///@}

  ///@{
  /**
   * Stop when the next collapse's estimated error (RMS distance to its merged planes, world
   * units) exceeds this. 0 (the default) or negative: no limit.
   */
  vtkSetMacro(MaximumError, double);
  vtkGetMacro(MaximumError, double);
  ///@}

  ///@{
  /**
   * Curvature method: weights of the curvature, shape and valence terms, each in [0, 1]; they
   * must sum to 1 (an error otherwise). Default 1/3 each.
   */
  vtkSetClampMacro(CurvatureWeight, double, 0.0, 1.0);
  vtkGetMacro(CurvatureWeight, double);
  vtkSetClampMacro(AngleWeight, double, 0.0, 1.0);
  vtkGetMacro(AngleWeight, double);
  vtkSetClampMacro(ValenceWeight, double, 0.0, 1.0);
  vtkGetMacro(ValenceWeight, double);
  ///@}

  ///@{
  /**
   * Curvature method: how collapses are ranked. FIT_DEVIATION (the default) ranks by the integral
   * over the new triangles of their squared height above the fitted surface (the fit includes the
   * ancestral points, so this is a deviation from the input surface, what earlier collapses cost
   * included), or by the merged planes' area-weighted squared distance at the collapse point where
   * that is larger (the planes see what a quadratic smooths over: a crease, a stencil grown around
   * much of a small sphere). Two collapse points compete: the point on the normal through the
   * centroid where the deviation is least, and the merged planes' minimiser; the one of lower cost
   * is taken. The three weights are not used. WEIGHT is paper 000's weight W = A (wk kappa + wa
   * alpha + wv V) from the three weights above, at the collapse point described in the class docs.
   * The fit and the legality rules are the same for both. On the benchmark isosurfaces
   * FIT_DEVIATION's Hausdorff distance is 1.01-1.38x and its RMS distance 0.94-1.19x
   * vtkQuadricDecimation's, against 4.7-8.6x and 2.4-2.8x for WEIGHT (Benchmarks/RESULTS.md,
   * where WEIGHT runs with the INDEPENDENT_SETS schedule; with GREEDY its RMS distance on the
   * metaballs at 10% is 3.05x vtkQuadricDecimation's): the
   * paper's weight is dominated by the area, so it evens out the triangles' sizes instead of
   * keeping small ones where the surface bends. On the other meshes of the benchmark (a torus,
   * noisy spheres, Boy's surface, a superquadric, a faceted cylinder and the surfaces of a
   * segmented volume, with the default operator: see SetOperator) FIT_DEVIATION is at 0.84-1.54x
   * and 0.82-1.16x (the faceted cylinder aside, where both methods are within float rounding of its
   * faces); on a terrain and a sphere with holes at 1.21-1.55x and 1.06-1.35x, on the wavelet and
   * noisy isosurfaces up to 3.3x and 4.3x at 1%. Where it falls short: a very rough input with
   * high-valence poles (a UV sphere with radial noise of an edge) gets long triangles across it at
   * coarse levels (at 1% 4x vtkQuadricDecimation's Hausdorff distance, WEIGHT 2x); so does a
   * smooth UV sphere of long thin triangles, whose stencils fit a quadratic badly along them
   * (at 10%, 49x vtkQuadricDecimation's Hausdorff distance on a 600 x 16 sphere and 3.2x on
   * 200 x 30; on 600 x 8, 100-150x the quadric method's at coarse levels). The quadric method
   * has no such weakness.
   */
  vtkSetClampMacro(CurvatureCost, int, WEIGHT, FIT_DEVIATION);
  vtkGetMacro(CurvatureCost, int);
  void SetCurvatureCostToWeight() { this->SetCurvatureCost(WEIGHT); }
  void SetCurvatureCostToFitDeviation() { this->SetCurvatureCost(FIT_DEVIATION); }
  const char* GetCurvatureCostAsString() const;
  ///@}

  ///@{
  /**
   * Weight of the planes through boundary edges relative to the surface planes, in
   * [0, 10]: an edge of length l adds a plane weighted BoundaryWeight * l * D, D the input's
   * bounding-box diagonal (the surface planes weigh their triangle's area, or the mean
   * triangle area with PlaneWeights UNIFORM_WEIGHTS). Per unit of
   * boundary length the weight is the same whatever the input's resolution, and scaling the
   * input scales every weight alike. 0 lets boundaries move freely. Default 0.3: at 1% of
   * open isosurfaces, scan-like spheres with holes and a terrain, the levels then keep about
   * as many boundary edges as vtkQuadricDecimation at the same count (0.9-1.05x; it weighs
   * a boundary plane by l in world units). The weight before, 10 * l^2, kept 0.7-0.8x of them
   * on those inputs, and there their largest distances to the input lay on the boundary.
   * Larger values spend triangles on slivers along the boundary and hold it no better, and
   * beyond about 10 they hold it worse: the boundary planes then outweigh the surface planes
   * so far that the placement's regularisation (relative to all the planes' weight) takes the
   * surface planes' directions for undetermined, and a collapse point slides towards the
   * centroid of its vertices, off a curved rim. On a 4,802-triangle terrain whose rim is not
   * flat, the coarsest level's (48 triangles) Hausdorff distance was 0.04 at 0.3, 3 and 10, 0.08
   * at 100, 0.13 at 1,000 and 0.31 at 1e6, as at 0 (a boundary free to move); the range ended
   * at 1e6 before.
   */
  vtkSetClampMacro(BoundaryWeight, double, 0.0, 10.0);
  vtkGetMacro(BoundaryWeight, double);
  ///@}

  ///@{
  /**
   * How much each input triangle's plane weighs in the quadrics: the quadric method's costs
   * and placements; for the curvature method, its merged planes (which FIT_DEVIATION compares
   * with the fit's deviation, area-weighted either way), its placement of boundary triangles
   * and its error estimates. AREA_WEIGHTS
   * (default): its area, so that a quadric measures the squared distance integrated over the
   * surface, whatever the input's tessellation; levels then spend their vertices where that
   * integral asks, the least RMS distance per triangle. UNIFORM_WEIGHTS: every plane weighs
   * the same, the input's mean triangle area (vtkQuadricDecimation's weighting, made
   * scale-invariant), so regions tessellated finely in the input keep more of the error budget's
   * attention. Measured at 1% against vtkQuadricDecimation (Benchmarks/RESULTS.md, Beyond
   * isosurfaces; Hausdorff distance ratio, AREA_WEIGHTS -> UNIFORM_WEIGHTS, with the default
   * AreaNormalization): lower on some rough meshes and some with graded triangle sizes (very
   * noisy sphere 1.02 -> 0.75, superquadric 1.07 -> 0.86, terrain 1.11 -> 1.04, Boy's surface
   * 0.78 -> 0.73, one of three noisy UV spheres 0.93 -> 0.62), about the same on another
   * (0.93 -> 0.94), higher on the third (0.79 -> 0.83), the parametric torus (0.70 -> 0.76)
   * and the sphere with holes (1.11 -> 1.32); the RMS distance rises on most (superquadric
   * 0.72 -> 1.13, noisy UV spheres 0.80-0.83 -> 0.85-0.88). On the benchmark's
   * marching-cubes isosurfaces UNIFORM_WEIGHTS has the larger Hausdorff distance at all six
   * targets (metaballs at 1%: 0.92 -> 1.09) and the larger RMS distance at five (equal at the
   * sixth). Keep AREA_WEIGHTS for isosurfaces and for the least RMS distance; try
   * UNIFORM_WEIGHTS for rough or graded tessellations when the largest distance matters.
   */
  vtkSetClampMacro(PlaneWeights, int, AREA_WEIGHTS, UNIFORM_WEIGHTS);
  vtkGetMacro(PlaneWeights, int);
  void SetPlaneWeightsToArea() { this->SetPlaneWeights(AREA_WEIGHTS); }
  void SetPlaneWeightsToUniform() { this->SetPlaneWeights(UNIFORM_WEIGHTS); }
  const char* GetPlaneWeightsAsString() const;
  ///@}

  ///@{
  /**
   * Quadric method: how much the surface a collapse stands for lowers its cost, in [0, 1]. Default
   * 0.25. A collapse's quadric value (the weighted sum of squared distances from the collapse point
   * to the original planes merged into its vertices) is divided by the weight of the original
   * triangles' planes merged into them (their area, or their count with UNIFORM_WEIGHTS; boundary
   * planes left out), in units of the input's mean triangle, to this power. 0: the quadric value
   * itself, paper 002's cost, under which a collapse standing for much surface costs more than one
   * as far from its planes standing for little; 1: the mean squared distance alone, whatever the
   * area. Between, levels spend fewer vertices on large smooth regions and more where few original
   * triangles are far from their planes, which lowers the largest distance on most meshes: against
   * vtkQuadricDecimation at the same count (Benchmarks/RESULTS.md, the first and the
   * AreaNormalization 0 tables of "Beyond isosurfaces"; Hausdorff distance ratio, 0 -> 0.25), on
   * the 12 meshes there that are not at rounding level or topology-bound, the geometric mean went
   * from 0.97 to 0.89 at 10% and from 0.91 to 0.90 at 1%, the RMS distance unchanged (0.91 and
   * 0.85). At 1% lower on 5 of the 12 (parametric torus 0.91 -> 0.70, Boy's surface 1.07 ->
   * 0.78, a noisy UV sphere 0.98 -> 0.79), higher on 7 (segmented balls 0.94 -> 1.43, the very
   * noisy sphere 0.91 -> 1.02, terrain 1.03 -> 1.11, superquadric 1.03 -> 1.07). On the
   * benchmark isosurfaces ("paper cost" rows), at 10% / 1%: metaballs 0.93 / 0.98 -> 0.87 /
   * 0.92, gyroid (611k) 1.01 / 0.84 -> 0.95 / 1.02, gyroid (2.3M) 0.95 / 1.15 -> 1.03 / 0.99.
   * The largest distance at 1% is one spot and moves by chance: over nine targets from 6,107 to
   * 6,302 triangles the 611k gyroid's ratio was 0.81-1.02, median 0.85 (the benchmark's
   * target's 1.02), with the RMS distance 0.97-0.99x at each (Benchmarks/RESULTS.md, "One
   * target or nine"). Not in Benchmarks/RESULTS.md, from trial runs: the segmented balls'
   * ratio over nine targets from 900 to 1,060 triangles was 0.93-1.61, geometric mean 1.17
   * (0.90-1.76 and 1.23 before the greedy schedule retried refused triangles' other edges); on
   * the 611k gyroid at 1%, powers of 0.5 and 0.75 gave 1.11 and 1.12; 0.5
   * lowered the 10% ratios a little more than 0.25 and raised RMS by about 1%; 1 raised RMS by
   * 7-12%. The power also shifts TRIANGLES_AND_EDGES towards whole triangles, whose three vertices
   * stand for more surface than an edge's two (see TriangleCostFactor). (The accuracy figures given
   * for TriangleCostFactor and MaximumNormalDeviation were measured with 0.) Ignored by the
   * curvature method. Costs 8 bytes per input point (allocated for either method).
   */
  vtkSetClampMacro(AreaNormalization, double, 0.0, 1.0);
  vtkGetMacro(AreaNormalization, double);
  ///@}

  ///@{
  /**
   * Largest angle in degrees by which a triangle's normal may turn in one collapse, in
   * [0, 180], unless it ends within that angle of the input surface it stands for (no
   * triangle may face away from that surface in any case). Default 90, vtkQuadricDecimation's
   * bound too. Smaller values refuse more
   * collapses: at 60 (and without the exception for turns towards the input surface), a
   * sphere with 1% radial noise stopped at 3.7% of its triangles asked for 1%, with 13x
   * vtkQuadricDecimation's RMS distance; on isosurfaces 60 and 90 differ within noise.
   */
  vtkSetClampMacro(MaximumNormalDeviation, double, 0.0, 180.0);
  vtkGetMacro(MaximumNormalDeviation, double);
  ///@}

  ///@{
  /**
   * Whether every connected piece of the input stays to the coarsest level. Default on: each
   * closed piece keeps at least a tetrahedron (four triangles; no collapse that keeps a closed
   * manifold makes it smaller), each open one at least a triangle, and every level has the
   * input's Euler characteristic. Off: a closed piece of genus 0 with at most 12 triangles left
   * (a tetrahedron, or the octahedron the triangle-collapse schedules stop at under paper 000's
   * valence rule) vanishes when its cost comes up in the order of the collapses: its points
   * merge into one at the minimiser of their merged quadric, at that quadric's cost. That point
   * stays in this and every later level as a point of no cell, so that MorphTargetId still maps
   * the piece's points (a geomorph shrinks the piece to it); its point data are the mean of
   * theirs, and its error (the RMS distance to the piece's planes) counts in EstimatedError.
   * Open pieces stay (besides debris, they may be the faces of a flat-shaded model that its
   * normals keep apart), and so does the input's largest piece, so that no level is empty.
   * Genus is kept either way, and so is every piece with a handle. Where a vanishing removes
   * more triangles than are left to a level's count, the level lands below it by fewer than
   * the piece had (specks are cheap, so they mostly vanish long before the coarse levels). With
   * CurvatureCost WEIGHT, whose weights are not distances, a vanishing still ranks by its
   * quadric error among them. For the isosurface of a noisy volume, as of a scan, whose specks
   * around single noisy samples otherwise fill the coarse levels: on one of 103,940 triangles
   * with 328 specks, asked for 1%, 1,038 triangles at 1.2 times vtkQuadricDecimation's
   * Hausdorff distance instead of 2,016 at 5.2 times (Benchmarks/RESULTS.md, "Beyond
   * isosurfaces"; the largest distances left are from vanished specks to the surface, for
   * vtkQuadricDecimation's output too). Costs 4 bytes per input point and 12 per piece (8 per
   * point while the pieces are labelled).
   */
  vtkSetMacro(PreserveTopology, bool);
  vtkGetMacro(PreserveTopology, bool);
  vtkBooleanMacro(PreserveTopology, bool);
  ///@}

  ///@{
  /**
   * Curvature method: at most this many ancestral points per surface fit, in [6, 100000].
   * Default 48.
   */
  vtkSetClampMacro(MaximumFitPoints, int, 6, 100000);
  vtkGetMacro(MaximumFitPoints, int);
  ///@}

  ///@{
  /**
   * Move every coarse level onto the middle of the input surface (Core/LevelCentering.h):
   * quadric placement leaves a curved surface's levels to its outer side (the tangent planes of
   * a convex patch meet above it), and each changed interior point of a level with at most a
   * quarter of the input's triangles moves along its normal by the area-weighted mean signed
   * distance of the input around it, as far as the largest deviation around the point does
   * not grow and at most a quarter of its shortest edge. On the metaballs isosurface (154k
   * triangles) this lowers the RMS distance by 9% at 10% of the triangles and 22% at 1%, the
   * Hausdorff distance by about 16% and 7%; on a gyroid, which curves as much one way as the other,
   * by 2-3%. Not moved: boundary and non-manifold points, creases and corners (a triangle more
   * than 35 degrees from the point's normal), planar facets (which stay exact), and points that
   * keep their place between two levels (CollapseRank -1 holds). The triangles, counts and
   * correspondence are those of the run without it. Costs up to a tenth of the run's time.
   * Default on.
   */
  vtkSetMacro(CenterOnInput, bool);
  vtkGetMacro(CenterOnInput, bool);
  vtkBooleanMacro(CenterOnInput, bool);
  ///@}

  ///@{
  /**
   * Flip the edges of every level with at most a quarter of the input's triangles where the
   * quad's other diagonal lies closer to the input, judged on the input surface both ways
   * (Core/LevelEdgeFlips.h, the judge of vtkVertexClusterOctree's FlipEdges), at most one flip
   * per point, and only for quads bent by at least 1.5 times the judge's error scale (twice the
   * level's estimated error): the long edges across a saddle that the collapses sometimes
   * leave, whose two triangles bend sharply against each other. A flip moves no point and
   * changes no count and no MorphTargetId of its level; the collapses towards the next level go
   * on from the flipped triangles, so the coarser levels are not those made without flips (their
   * counts may differ by a triangle or two). On the gyroid isosurfaces of Benchmarks/RESULTS.md
   * the Hausdorff distance at 1% of the triangles falls from 0.243% to 0.185% of the diagonal
   * (611k triangles; 1.02 to 0.77 times vtkQuadricDecimation's) and from 0.0627% to 0.0510%
   * (2.3M; 0.99 to 0.81 times); at 10% it stays (0.95 and 1.03 times), and the RMS distances
   * fall by 0.4-0.6%. The whole hierarchy took 1.0-1.25 times as long on one thread in most of
   * the benchmark's runs: 1.00-1.23 times in RESULTS.md's (0.53, 0.44 and 0.43 times
   * vtkQuadricDecimation's time for 10% on the metaballs, the 611k and the 2.3M gyroid, against
   * 0.53, 0.41 and 0.35 without flips), 1.10-1.17 and 1.01-1.24 times in two before; in one
   * whose times swung with the machine's load, 0.93-1.58 times (the 2.3M gyroid's flipped
   * hierarchy was 2.42 times faster on two threads there, where 1.7-1.9 is usual, so its
   * one-thread runs met a slow phase).
   * On the metaballs isosurface, with hardly a saddle, no quad is bent that much and the levels
   * are those without flips. Judging every quad bent by 0.3 times the scale (with several
   * flips per point, on a copy the collapses did not go on from) took 1.35-1.5 times as long
   * for RMS distances 1-3% lower and also brought the 2.3M gyroid's 10% level to 0.92 times
   * vtkQuadricDecimation's Hausdorff distance, but the geomorph jumped at the flipped levels.
   *
   * The geomorph stays continuous: level i + 1's triangles differ from the images of level
   * i's (what its collapses make of them) by lone flipped quads, no two sharing a point, which
   * vtkLODGeomorph turns in the last quarter of the transition, each about a point in its
   * middle (two triangles more per quad meanwhile), so that at L -> i + 1 it is level i + 1
   * (Benchmarks/RESULTS.md, "vtkLODGeomorph at the levels"). What changes: the triangles of
   * level i + 1 are not all images of level i's (the flipped quads' are not), and
   * vtkLODGeomorph's exact-count mode, which applies level i's collapses in CollapseRank order,
   * ends the transition on the images and steps to level i + 1's flipped quads at its count.
   * Memory: the input is read in place (the output's level 0), and its adjacency is kept for the
   * run, 18-20 bytes more per input triangle (219 instead of 199 on the 2.3M gyroid, 0.47 times
   * vtkQuadricDecimation's growth; 14-15 before a level's topology was built from a list of its
   * triangles' sides, 24 bytes per triangle of the level while it is built). Default off.
   */
  vtkSetMacro(FlipEdges, bool);
  vtkGetMacro(FlipEdges, bool);
  vtkBooleanMacro(FlipEdges, bool);
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
   * Measure every level's symmetric Hausdorff and RMS surface distance to level 0 and store them as
   * MeasuredHausdorff and MeasuredRMS field data (10,000 area samples per surface plus up to 10,000
   * vertices, and from the 128 samples farthest from the other surface a search for the farthest
   * point near each; level 0 is sampled once). Default off: it adds about two fifths to the run
   * on one thread, two fifths to a half on two (8 levels of a 977,200-triangle UV sphere: 1.2 s
   * on top of 2.8 s on one thread, 0.74 s on top of 1.6 s on two; a search tree over level 0 is
   * much of it). For a
   * finer measurement use MeasureSurfaceDistance (MeshLODSurfaceDistance.h) with more samples.
   */
  vtkSetMacro(ComputeLevelError, bool);
  vtkGetMacro(ComputeLevelError, bool);
  vtkBooleanMacro(ComputeLevelError, bool);
  ///@}

  /// After execution: the number of levels produced (level 0 included).
  vtkGetMacro(NumberOfLevelsProduced, int);
  /// After execution: the fraction of the input triangles removed by the coarsest level.
  vtkGetMacro(ActualReduction, double);
  /// After execution: how many collapses followed an edge swap (paper 000, figure 3): a
  /// triangle blocked by a neighbour apex of low valence collapses with that apex instead.
  vtkGetMacro(NumberOfSwaps, vtkIdType);
  /// After execution: how many edges FlipEdges flipped, over all levels.
  vtkGetMacro(NumberOfFlips, vtkIdType);

protected:
  vtkTriangleCollapseDecimation();
  ~vtkTriangleCollapseDecimation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Method = QUADRIC;
  int Schedule = GREEDY;
  int Operator = TRIANGLES_AND_EDGES;
  bool PartitionedGreedy = true;
  int Placement = REGULARIZED;
  int PlaneWeights = AREA_WEIGHTS;
  double AreaNormalization = 0.25;
  double TriangleCostFactor = 1.5;
  double TargetReduction = 0.99;
  int NumberOfLevels = 8;
  std::vector<double> LevelReductions;
  double LevelFraction = 0.025;
  double MaximumError = 0.0;
  double CurvatureWeight = 1.0 / 3.0;
  double AngleWeight = 1.0 / 3.0;
  double ValenceWeight = 1.0 / 3.0;
  int CurvatureCost = FIT_DEVIATION;
  double BoundaryWeight = 0.3;
  double MaximumNormalDeviation = 90.0;
  int MaximumFitPoints = 48;
  bool PreserveTopology = true;
  bool ComputeLevelError = false;
  int OutputPointsPrecision = DEFAULT_PRECISION;
  bool CenterOnInput = true;
  bool FlipEdges = false;
  int NumberOfLevelsProduced = 0;
  double ActualReduction = 0.0;
  vtkIdType NumberOfSwaps = 0;
  vtkIdType NumberOfFlips = 0;

private:
  vtkTriangleCollapseDecimation(const vtkTriangleCollapseDecimation&) = delete;
  void operator=(const vtkTriangleCollapseDecimation&) = delete;

  bool CheckSettings();
  // LevelReductions, or else NumberOfLevels reductions up to TargetReduction.
  std::vector<double> LevelReductionsToMake() const;
  // The engine's options from the settings (without the level targets).
  meshlod::TriangleCollapseOptions CollapseOptions() const;
  void WarnIfTargetMissed(
    const meshlod::TriangleCollapseOptions& options, const meshlod::TriangleCollapseResult& result);
};

#endif
