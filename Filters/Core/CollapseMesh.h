// The mutable mesh that triangle (and edge) collapses run on.
//
// Ids never change during a run: a collapse merges two or three vertices into the lowest-id
// one (the survivor), marks the dying triangles dead, and rewrites the corners of the others.
// Vertex -> triangle rows are the compressed rows of the last rebuild; when vertices merge,
// their rows are chained together (ChainNext), so the triangles around a vertex are the live
// entries of its chain. Rows are rebuilt from scratch once enough triangles died, which keeps
// the chains short without patching rows per collapse.
//
//            p_ab
//            /  \            Triangle collapse of T = (a, b, c): T and its edge neighbours
//           / N  \           (N_ab, N_bc, N_ca, the "dying" triangles) disappear; every other
//          a------b          triangle around a, b or c (the "ring") gets the survivor in
//         / \ T  / \         place of its member. The apexes p_ab, p_bc, p_ca each lose one
//   p_ca /   \  /   \ p_bc   edge. The stencil of T is the dying triangles plus the ring.
//            c
#ifndef meshlod_CollapseMesh_h
#define meshlod_CollapseMesh_h

#include "CacheHint.h"
#include "Quadric.h"
#include "TriangleMesh.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace meshlod
{
/// Per-vertex flags.
enum VertexFlag : std::uint8_t
{
  FlagLocked = 1,   // never moves or merges (non-manifold vertices other than FlagCurve's)
  FlagBoundary = 2, // on a boundary edge
  // On a curve of non-manifold edges (where several sheets meet, as between the regions of a
  // segmented volume), at a regular point of it: exactly two of its edges have more than two
  // triangles, the same number k of them, every other edge two, and its triangles form k fans
  // each running from one of those edges to the other. Such a vertex may merge with its
  // neighbour along the curve or with a neighbour inside one of the sheets, by edge collapses
  // only (CollapseMesh::IsLegal); the curve keeps its sheets.
  FlagCurve = 4,
  // What is left of a small closed piece that vanished (TriangleCollapseOptions::
  // PreserveTopology off): a live vertex without triangles, kept in every later level as a
  // point of no cell, so that MorphTargetId maps the piece's points somewhere.
  FlagVanished = 8,
};

/// Around a vertex where more triangles than this meet (a fan, a cone's tip, a UV sphere's
/// pole) the work per collapse is bounded instead of following the fan:
/// - curvature method: a fit reads every k-th of them only, k the least that keeps at most this
///   many, and a collapse next to it leaves their costs as they are (with every triangle of the
///   fan read by every fit, and re-fitted after every collapse next to it, the work grew with
///   the cube of the valence: a fan of 2,000 triangles took 88 s);
/// - a star of more ring triangles is checked geometry first (CollapseMesh::IsLegal), a longer
///   row is hinted in part (CollapseMesh::Prefetch), and the solved spokes of such a survivor
///   are not kept (CostScratch::BeginSpokes);
/// - the parking lot looks at such a corner alone (ParkingLot::Release);
/// - with edges allowed, a triangle with one such corner is priced by its edge away from it,
///   so that the corner stays in place while it is one (CollapseCostModel::HubEdgesToSkip).
constexpr Id FanTriangleLimit = 64;

/// The largest connected piece that may vanish (TriangleCollapseOptions::PreserveTopology
/// off): a closed surface of genus 0 with at most this many triangles (it cannot shrink below
/// a tetrahedron, 4, and the triangle-collapse schedules, which keep paper 000's valence rule,
/// leave specks as octahedra, 8), and so at most VanishingPieceVertices vertices.
constexpr int VanishingPieceTriangles = 12;
constexpr int VanishingPieceVertices = 2 + VanishingPieceTriangles / 2;

/// What CollapseMesh::SmallPiece finds.
enum class PieceKind
{
  Other,    // a larger piece, or one that may not vanish
  Vanishing, // a piece that may vanish
  Foreign,  // it reaches a vertex another block owns: not known
};

/// Geometric and topological rules a collapse must pass.
struct CollapseRules
{
  /// Largest allowed angle between a ring triangle's normal before and after (radians, as its
  /// cosine).
  double MinimumNormalCosine = 0.5;
  /// Paper 000 (Gieng et al.) condition (2): an interior apex of valence 4 would become a
  /// valence-3 vertex, which blocks later collapses; refuse such collapses.
  bool ForbidValenceThree = true;
  /// The same for edge collapses. The rule serves triangle collapses (a triangle next to a
  /// valence-3 vertex has a stencil cycle and needs a swap first); an edge collapse removes
  /// such a vertex like any other, and without the rule edges follow vtkQuadricDecimation's
  /// manifold test (valence 3 allowed): on an extruded text at 1%, 1.0x its Hausdorff and RMS
  /// distances instead of 2.4x and 3x. The independent-set schedule keeps it, as paper 000.
  bool ForbidValenceThreeForEdges = true;
  /// Paper 000 condition (3): the stencil boundary polygon, projected on the collapsing
  /// triangle's plane, must be star-shaped around the projected collapse point.
  bool RequireStarShaped = true;
  /// For a mesh that is not consistently oriented (a non-orientable surface: Boy's surface, a
  /// Moebius strip), where a ring triangle across the seam winds the other way round the merged
  /// vertex, so that by its orientation alone it lies below the collapsing triangle's plane:
  /// condition (3) then asks instead that no new triangle changes side of that plane (or comes
  /// to lie edge-on). Refusing the seam's triangles stopped the curvature method on Boy's
  /// surface (13,804 triangles) at 944 triangles, asked for 138. Set for the whole mesh when
  /// any part of it cannot be oriented consistently.
  bool StarShapedBySide = false;
  /// Condition (3) relaxed: a ring triangle on the wrong side of the collapsing triangle's
  /// plane already may stay there (the others must still not cross it). Off at first; the
  /// collapser turns it on when a run would otherwise stop short of its target (not with
  /// StarShapedBySide, where no side is the wrong one). On a rough or noisy surface the strict
  /// test refuses most triangle collapses once triangles are large: the curvature method
  /// stopped on a noisy terrain at 36,211 triangles, asked for 1,555, and on a noisy sphere
  /// with holes at 14,759, asked for 781.
  bool LetWrongSideStay = false;
  /// No ring triangle may come to face away from the original surface its corners stand for
  /// (CollapseMesh::Facing); one that faces away already (noise) may stay so. The per-collapse
  /// normal test alone lets many small turns add up to a fold at coarse levels.
  bool KeepFacing = true;
};

/// Outcome of a legality check.
enum class Legality
{
  Legal,
  LowValenceApex, // only an apex's valence forbids it (see Star::BlockingApex)
  Illegal,
  Foreign, // the star reaches a vertex of another block (see Star::Owner); not a verdict
};

/// The triangles around a set of merging vertices (scratch storage reused between calls).
struct Star
{
  Id Members[VanishingPieceVertices] = { InvalidId, InvalidId, InvalidId }; // > 3: a piece
  int MemberCount = 0;
  std::vector<Id> Dying;      // triangles with two or three members
  std::vector<Id> Ring;       // triangles with exactly one member
  std::vector<std::int8_t> RingCorner; // the corner of the member in each ring triangle
  std::vector<Id> Apexes;     // the non-member vertex of each two-member dying triangle
  mutable Id BlockingApex = InvalidId; // set by IsLegal on LowValenceApex
  // Spatial blocks collapsing in parallel (see PartitionedGreedy.cxx): when Owner is set, a
  // star with a corner whose Owner is not Block is refused (GatherStar returns false with
  // Foreign set), so that a block never reads or writes what another block may change.
  const std::uint32_t* Owner = nullptr;
  std::uint32_t Block = 0;
  bool Foreign = false;
  mutable std::vector<Id> LinkScratch;
  mutable std::vector<std::pair<Id, Id>> PairScratch; // the checks' sorting space, one at a time
  mutable std::vector<Id> IdScratch; // the same, for ids
};

class VTKFILTERSMESHLOD_EXPORT CollapseMesh
{
public:
  TriangleMesh Mesh;             // positions and triangles; dead triangles have corner 0 invalid
  std::vector<Quadric> Quadrics; // per vertex: planes of the original triangles merged into it
  /// Per vertex: the weight of the original triangles' planes merged into it (their area, or
  /// planeWeight each; boundary planes left out): the surface it stands for.
  std::vector<double> SurfaceWeights;
  /// The mean of SurfaceWeights over the input's triangles (one plane each, counted once). The
  /// costs' order does not need it (a constant factor), but the weights over it are the same
  /// numbers, to the bit, for the input scaled by a power of two, and so is every power of
  /// them, pow included.
  double SurfaceWeightUnit = 1.0;
  /// Per vertex (x, y, z): the summed area vectors of the original triangles merged into it (a
  /// third of each around it), i.e. which way the original surface it stands for faces. In
  /// units of the squared diagonal (a power of two): only directions are read, and areas in
  /// world units overflow single precision for a mesh 1e20 across (vanish for one 1e-20).
  std::vector<float> Facing;
  std::vector<std::uint8_t> Flags;
  std::vector<Id> Survivor;      // vertex -> the vertex it merged into (itself while alive)
  Id AliveTriangles = 0;
  Id AliveAtLastRebuild = 0;

  /// Take over the mesh and its topology (both are moved from); classify vertices from the
  /// topology; accumulate plane quadrics, each weighted by its triangle's area, or by
  /// planeWeight (an area) for every plane when that is positive, plus, on boundary edges,
  /// planes through the edge perpendicular to its triangle weighted by boundaryWeight times the
  /// edge length times boundaryScale (a length: the boundary's planes weigh boundaryWeight *
  /// boundaryScale per unit of its length), or times the edge length again when boundaryScale
  /// is 0.
  void Initialize(TriangleMesh&& mesh, TriangleTopology&& topology, double boundaryWeight,
    double boundaryScale, double planeWeight = 0.0);

  bool IsAlive(Id t) const { return this->Mesh.Triangles[3 * static_cast<std::size_t>(t)] != InvalidId; }
  bool IsLocked(Id v) const { return (this->Flags[v] & FlagLocked) != 0; }
  bool IsBoundary(Id v) const { return (this->Flags[v] & FlagBoundary) != 0; }
  bool IsCurve(Id v) const { return (this->Flags[v] & FlagCurve) != 0; }

  /// False for an edge whose collapse the vertices' kinds alone forbid: a curve vertex (see
  /// FlagCurve) merges only along its curve (an edge of more than two triangles) or with a
  /// neighbour that is on no boundary and no curve. (Locked vertices are excluded earlier.)
  bool EdgeMayMerge(Id a, Id b) const
  {
    const bool ca = this->IsCurve(a), cb = this->IsCurve(b);
    if (!ca && !cb)
    {
      return true;
    }
    if (this->IsBoundary(a) || this->IsBoundary(b))
    {
      return false;
    }
    return !(ca && cb) || this->TrianglesOnEdge(a, b) > 2;
  }

  /// Live triangles containing both a and b.
  int TrianglesOnEdge(Id a, Id b) const
  {
    int count = 0;
    this->ForEachTriangle(a, [&](Id t) { count += CornerOf(this->Mesh.Triangle(t), b) >= 0 ? 1 : 0; });
    return count;
  }

  /// Call f(t) for every live triangle around live vertex v ...
  template <typename F>
  void ForEachTriangle(Id v, F&& f) const
  {
    this->ForEachTriangle(v, 1, std::forward<F>(f));
  }

  /// ... or until f(t) returns true, then true (false when it never does) ...
  template <typename F>
  bool AnyTriangle(Id v, F&& f) const
  {
    for (Id u = v; u != InvalidId; u = this->ChainNext[u])
    {
      for (Id i = this->Rows.Begin(u), end = this->Rows.End(u); i < end; ++i)
      {
        const Id t = this->Rows.Triangles[i];
        if (this->IsAlive(t) && CornerOf(this->Mesh.Triangle(t), v) >= 0 && f(t))
        {
          return true;
        }
      }
    }
    return false;
  }

  /// ... or, with every > 1, for those at every every-th place of its rows (about one in every,
  /// in time proportional to those: a fan's centre has thousands).
  template <typename F>
  void ForEachTriangle(Id v, Id every, F&& f) const
  {
    Id before = 0; // places in the rows before this one
    for (Id u = v; u != InvalidId; u = this->ChainNext[u])
    {
      const Id begin = this->Rows.Begin(u), end = this->Rows.End(u);
      for (Id i = begin + (every - before % every) % every; i < end; i += every)
      {
        const Id t = this->Rows.Triangles[i];
        if (this->IsAlive(t) && CornerOf(this->Mesh.Triangle(t), v) >= 0)
        {
          f(t);
        }
      }
      before += end - begin;
    }
  }

  /// Cache hints for the neighbourhood of live triangle t, which a check of its collapse reads
  /// (GatherStar, IsLegal) and the evaluations after it: most of a greedy step's time is spent
  /// waiting for these loads, one after the other, since each says where the next one is.
  /// Stage 0 reaches the corners' own data (position, quadric, flags, row offsets), stage 1
  /// their rows of triangles, stage 2 those triangles, stage 3 the triangles' other corners.
  /// Each stage reads what the one before brought into the cache, so the greedy loops issue
  /// them for the next candidate in turn while the current one is checked and made. Changes
  /// nothing; t may have died since it was listed.
  void Prefetch(Id t, int stage) const;

  /// Number of live triangles around v (kept up to date by Apply, so O(1)).
  Id TriangleCount(Id v) const { return this->TriangleCounts[v]; }

  /// Whether v has at least n distinct neighbours (n small: the walk stops at the n-th).
  bool HasValenceAtLeast(Id v, int n, std::vector<Id>& scratch) const;

  /// Collect dying and ring triangles for merging `members` (2: an edge, 3: a triangle or a path
  /// of two edges, more: the vertices of a SmallPiece, whose triangles all die); false
  /// when a member is locked or the configuration is not a manifold edge/triangle
  /// neighbourhood, or (star.Foreign) when a triangle of the star has a corner owned by another
  /// block.
  bool GatherStar(const Id* members, int count, Star& star) const;

  /// Label the connected pieces and count their live triangles (Apply keeps the counts), for
  /// SmallPiece. 4 bytes per vertex (8 while labelling), and 12 per piece.
  void TrackPieces();

  /// The live triangles' counts of every piece as they are now, which SmallPiece reads in a
  /// parallel round (where other blocks may be changing the live counts) instead of the live
  /// ones: its answers then do not depend on the order in which blocks run.
  void FreezePieceCounts();

  /// After a parallel round that began with FreezePieceCounts: into `vertices`, the lowest
  /// vertex (the survivor of every merge in its piece, so still live) of each piece that had
  /// more than VanishingPieceTriangles triangles then and has at most that many, and some, now.
  /// Its blocks judged it by the frozen count, and may have parked its triangles for good.
  void PiecesTurnedSmall(std::vector<Id>& vertices) const;

  /// The number of connected pieces of live triangles; without TrackPieces, found by a
  /// union-find in `scratch` (any vector not otherwise in use: its room is reused).
  Id CountLivePieces(std::vector<Id>& scratch) const;

  /// With TrackPieces: whether live triangle t belongs to a connected piece of at most
  /// VanishingPieceTriangles triangles that is a closed surface of genus 0 (no vertex locked,
  /// on a curve or on a boundary), and not the piece that had the most triangles at the start
  /// (the first of them), which stays so that no level is empty: then (Vanishing) `members`
  /// gets its vertices, increasing, and `count` their number. Such a piece may vanish whole
  /// (TriangleCollapseOptions::PreserveTopology off); the smallest, a tetrahedron, cannot lose
  /// a triangle otherwise. With `owner` (a parallel round: the counts of FreezePieceCounts), a
  /// piece reaching a vertex whose owner is not `block` is Foreign (another block may be
  /// changing it). O(1) for a triangle of a larger piece.
  PieceKind SmallPiece(
    Id t, const std::uint32_t* owner, std::uint32_t block, Id* members, int& count) const;

  /// Whether merging the star's members at x keeps a manifold mesh of the same topology with no
  /// flipped triangle (see CollapseRules); with a FlagCurve member, whether it keeps the same
  /// sheets meeting along the same curves (CurveMergeIsValid). The members need not form a
  /// triangle: three members joined by a path of two edges are the triangle collapse that
  /// follows an edge swap. `planeNormal` is the normal of the collapsing triangle (for the
  /// star-shape test); may be null for edge collapses.
  Legality IsLegal(
    const Star& star, const double x[3], const double* planeNormal, const CollapseRules& rules) const;

  /// IsLegal's rule on the apexes alone (paper 000's rule against new valence-3 vertices, see
  /// CollapseRules): an apex that m of star.Apexes name loses m edges and must keep at least 2
  /// (on a boundary), 4 or 3 (with or without the rule for the star's kind of collapse). The
  /// first apex of the list that would not is star.BlockingApex (LowValenceApex). Of the star
  /// it reads Apexes and MemberCount only (and uses its scratch), so a test may fill them by
  /// hand.
  Legality ApexValences(const Star& star, const CollapseRules& rules) const;

  /// Merge the members into the first one (the lowest id) at x and return it. Does not touch
  /// AliveTriangles (collapses applied in parallel sum their dying counts afterwards).
  Id Apply(const Star& star, const double x[3]);

  /// Rebuild the rows from the live triangles (resets the chains).
  void RebuildRows();

  /// Give live triangle t new corners (an edge flip: the same vertices, counted again around
  /// each). The rows still list it at its old corners: RebuildRows() before they are read.
  void SetCorners(Id t, const Id corners[3]);

private:
  // The other two parts of IsLegal (the third is ApexValences): the merged vertex's link is one
  // simple cycle or path (and, where that is not enough, the link condition holds); no ring
  // triangle folds, turns too far or degenerates, and the stencil stays star-shaped.
  bool LinkKeepsManifold(const Star& star, bool boundary, bool curve) const;
  bool GeometryKeepsShape(const Star& star, const double x[3], const double* planeNormal,
    const CollapseRules& rules, bool curve) const;
  /// The topology test of an edge collapse with a FlagCurve member (see IsLegal).
  bool CurveMergeIsValid(const Star& star) const;
  /// The link condition: the members joined to any other vertex are connected through dying
  /// triangles at it (for two members: one dying triangle has both), the edge that its edges
  /// to them become keeps a triangle, and no two ring triangles become one; with `alongCurve`,
  /// no apex is joined to both members by edges of more than two triangles.
  bool MergeKeepsLinks(const Star& star, bool alongCurve) const;
  /// Initialize's sums at vertex v: the quadric of the planes of its triangles (and of their
  /// boundary edges at v), the surface they stand for and which way they face (in units of
  /// areaUnit), into Quadrics, SurfaceWeights and Facing.
  void SumPlanes(Id v, const TriangleTopology& topology, double boundaryWeight,
    double boundaryScale, double planeWeight, double areaUnit);
  /// Every vertex's chain back to its own row alone.
  void ResetChains();
  /// `parent` as a union-find forest (FindRoot) joining the corners of every live triangle,
  /// each root the lowest vertex of its piece.
  void JoinLiveTriangles(std::vector<Id>& parent) const;

  VertexTriangleAdjacency Rows; // as of the last rebuild
  std::vector<Id> PieceOf;      // per vertex, its connected piece (TrackPieces), or empty
  // Per piece, its live triangles; collapses in parallel blocks may share a piece.
  std::unique_ptr<std::atomic<Id>[]> PieceTriangles;
  std::vector<Id> FrozenPieceTriangles; // FreezePieceCounts
  std::vector<Id> PieceVertex;          // per piece, its lowest vertex
  Id LargestPiece = InvalidId; // never vanishes
  Id Pieces = 0;
  std::vector<Id> TriangleCounts; // per vertex, live triangles around it
  std::vector<Id> ChainNext;
  std::vector<Id> ChainTail;
};

/// Whether all three corners of triangle `tri` belong to `block` (a cell of a parallel round).
inline bool CornersOwnedBy(const std::uint32_t* owner, const Id* tri, std::uint32_t block)
{
  return owner[tri[0]] == block && owner[tri[1]] == block && owner[tri[2]] == block;
}

/// Unit normal (and twice the area) of the triangle (p0, p1, p2).
double TriangleNormal(const double* p0, const double* p1, const double* p2, double normal[3]);

} // namespace meshlod

#endif
