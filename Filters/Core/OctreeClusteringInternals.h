// Private to the octree clustering (OctreeClustering.h): the state shared by its sources,
// - OctreeNodes.cxx: evaluating a node (representative, error, admissibility; paper 001 §2-3);
// - OctreeCuts.cxx: the cut of the cluster tree at an epsilon and the search for an epsilon;
// - OctreeSynthesis.cxx: a level from a cut (re-indexed triangles, the trial made again until
//   no repair is needed, the level's arrays);
// - OctreeRepairs.cxx: the repairs of a trial level (folds, fins, breaks, pinched edges and
//   vertices: the clusters of the triangles concerned marked to split);
// - OctreeVanishing.cxx: what a level would make vanish: small closed pieces far from its
//   surface, holes closed up;
// - OctreeClustering.cxx: the public class.
#ifndef meshlod_OctreeClusteringInternals_h
#define meshlod_OctreeClusteringInternals_h

#include "OctreeClustering.h"
#include "ParallelCompact.h"
#include "PieceGenus.h"
#include "Vector3.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace meshlod
{
namespace octree
{
// The e2 weight (original area / new area)^2 is capped where a new triangle nearly degenerates.
constexpr double MaximumCrossingWeight = 100.0;
constexpr float Infinite = std::numeric_limits<float>::infinity();

enum class NodeState : std::uint8_t
{
  NotEvaluated = 0,
  Admissible = 1,
  Inadmissible = 2,
};

// The related triangle set of the node being evaluated: its crossing triangles (exactly one
// vertex inside) with their planes, its boundary edges and all its planes.
using EvaluationScratch = RelatedTriangles;

// Synthesis::Duplicate: the same clusters as an earlier kept triangle, in the same order (up to
// rotation) or in the opposite order.
constexpr unsigned char SameDuplicate = 1;
constexpr unsigned char OppositeDuplicate = 2;

// An edge between two clusters on a curve where Sheets sheets meet.
struct CurveEdge
{
  Id Low, High;
  int Sheets;
  bool operator<(const CurveEdge& o) const
  {
    if (this->Low != o.Low)
    {
      return this->Low < o.Low;
    }
    return this->High != o.High ? this->High < o.High : this->Sheets < o.Sheets;
  }
  bool operator==(const CurveEdge& o) const
  {
    return this->Low == o.Low && this->High == o.High && this->Sheets == o.Sheets;
  }
};

// A level being built: clusters (cut nodes) and the previous level's triangles re-indexed.
struct Synthesis
{
  std::vector<Id> Cut;          // cluster -> node, in depth-first order
  std::vector<double> Reps;     // 3 per cluster
  std::vector<Id> PointCluster; // previous point -> cluster
  std::vector<Id> Triangles;    // 3 clusters per kept triangle
  std::vector<Id> From;         // kept triangle -> previous triangle
  std::vector<unsigned char> Duplicate; // 0, or Same/OppositeDuplicate of an earlier triangle
  std::vector<unsigned char> Changed; // cluster is not exactly one previous point

  /// Whether kept triangle j may have folded or pinched: not a duplicate, with a changed cluster.
  bool Involved(Id j) const
  {
    const Id* tri = this->Triangles.data() + 3 * j;
    return !this->Duplicate[j] &&
      (this->Changed[tri[0]] || this->Changed[tri[1]] || this->Changed[tri[2]]);
  }
};
} // namespace octree

//------------------------------------------------------------------------------
struct OctreeClustering::Internals
{
  const TriangleMesh& Mesh;
  const TriangleTopology& Topology;
  OctreeClusteringOptions Options;
  ClusterTree Tree;
  Id NV = 0;
  Id NT = 0;

  // Per internal node: the full evaluation, and the epsilon from which the node or an ancestor
  // is a cluster (Activation).
  std::vector<octree::NodeState> State;
  // Per internal node: refused as a cluster because it folded a level (MarkFolds, MarkFins).
  // Unlike pinches (State Inadmissible for good), a fold refusal can be lifted (ClearRefusals)
  // when a later level finds almost nothing left to merge: on a rough surface the refusals can
  // leave only the octree's roots, while the coarser clusters around a refused node at the
  // later epsilon may no longer fold it. Nesting holds either way: a refused node lies above
  // the cut it was refused for (and Commit lifts every mark from the clusters of the level it
  // keeps, which a later trial may have marked).
  std::vector<unsigned char> Refused;
  std::vector<Id> RefusedNodes;
  // Refusals that hold for one trial level only (MarkFarVanishing: they depend on its epsilon).
  std::vector<Id> TrialRefusals;
  // The input's boundary loops (holes) with PreserveTopology: the vertices of loop i are
  // HoleVertices[HoleOffsets[i] .. HoleOffsets[i + 1]); empty without boundary (LabelHoles).
  std::vector<Id> HoleOffsets;
  std::vector<Id> HoleVertices;
  std::vector<double> HoleRadius; // half the diagonal of each loop's bounding box
  // Per input vertex: whether it is a tip of the open boundary (LabelTips); empty without one.
  std::vector<unsigned char> Tip;
  std::vector<float> Thr; // the smallest epsilon at which the node may be a cluster
  std::vector<Id> RepSlot;
  // Per evaluated node (RepSlot): representative, surface normal and error, in blocks that
  // never move, so that they grow without a copy and without the spare half of a doubling.
  static constexpr int SlotSize = 7;
  static constexpr Id SlotsPerBlock = 4096;
  std::vector<std::vector<double>> RepBlocks;
  Id RepCount = 0;
  /// The slot of internal node `index` (node NV + index), evaluated or queued.
  const double* Slot(Id index) const
  {
    const Id s = this->RepSlot[index];
    return this->RepBlocks[s / SlotsPerBlock].data() +
      SlotSize * static_cast<size_t>(s % SlotsPerBlock);
  }
  double* Slot(Id index)
  {
    return const_cast<double*>(static_cast<const Internals*>(this)->Slot(index));
  }
  /// Give internal node `index` a slot (serially).
  void NewSlot(Id index)
  {
    if (this->RepCount % SlotsPerBlock == 0)
    {
      this->RepBlocks.emplace_back(SlotSize * static_cast<size_t>(SlotsPerBlock));
    }
    this->RepSlot[index] = this->RepCount++;
  }
  std::vector<float> Activation;
  double LogRatioSum = 0.0; // log(full error / e1) summed over the evaluated nodes
  Id RatioCount = 0;
  Id Evaluated = 0;

  // The current level.
  // Level 0 is the input itself: empty vectors stand for the input's triangles and identity
  // maps, so that no copy of the input is kept.
  std::vector<Id> CurrentTriangles;
  std::vector<Id> CurrentLevelZero;
  std::vector<Id> PointNode;
  std::vector<Id> PointVertexCount;
  double CurrentEpsilon = 0.0;
  std::vector<Id> ClusterOfVertex;
  // Per point of the current level: its connected piece (0 .. PreviousPieces - 1), for
  // MarkBreaks; empty when there is one piece.
  std::vector<std::uint32_t> PreviousPiece;
  std::uint32_t PreviousPieces = 0;
  // Per piece of the current level: HandleMeasures (its parts and twice their genus), which a
  // level made from it must keep (LosesHandle).
  std::vector<PieceMeasure> PreviousHandles;
  // Per triangle of the current level: HandleMeasures' side flags (MarkAnnuli).
  std::vector<unsigned char> PreviousSides;
  // How many trial levels TryLevel refused for a lost handle (returning 0 for them).
  Id HandleRefusals = 0;
  Id PieceOf(Id p) const { return this->PreviousPiece.empty() ? 0 : this->PreviousPiece[p]; }

  Internals(const TriangleMesh& mesh,
    const TriangleTopology& topology,
    const OctreeClusteringOptions& options)
    : Mesh(mesh)
    , Topology(topology)
    , Options(options)
    , NV(mesh.GetNumberOfPoints())
    , NT(mesh.GetNumberOfTriangles())
  {
  }

  Id FirstVertex(Id node) const { return this->Tree.Order[this->Tree.Position(node)]; }
  bool AtInput() const { return this->PointNode.empty(); }
  Id PreviousPoints() const
  {
    return this->AtInput() ? this->NV : static_cast<Id>(this->PointNode.size());
  }
  Id PreviousTriangles() const
  {
    return this->AtInput() ? this->NT : static_cast<Id>(this->CurrentTriangles.size() / 3);
  }
  const Id* PreviousTriangleData() const
  {
    return this->AtInput() ? this->Mesh.Triangles.data() : this->CurrentTriangles.data();
  }
  Id NodeOfPoint(Id p) const { return this->AtInput() ? p : this->PointNode[p]; }
  Id VertexCountOfPoint(Id p) const { return this->AtInput() ? 1 : this->PointVertexCount[p]; }
  Id LevelZeroOf(Id t) const { return this->AtInput() ? t : this->CurrentLevelZero[t]; }

  // --- nodes -----------------------------------------------------------------------------------
  bool CheapInadmissible(Id index) const;
  void UpdateThreshold(Id index);
  void MovedNormal(
    const octree::EvaluationScratch& crossing, size_t i, const double v0[3], double moved[3]) const;
  void AddCrossingTerms(const double v0[3], const octree::EvaluationScratch& crossing, Quadric& q) const;
  bool HasFlip(const double v0[3],
    const octree::EvaluationScratch& crossing,
    int depth,
    const double* surface) const;
  bool CurveMayMerge(Id node) const;
  void Evaluate(Id index, octree::EvaluationScratch& scratch);
  // Evaluate's steps: the representative placed (into v0) and kept near its cell, a vertex
  // standing in for one that flips a triangle (returns whether it still flips), and the error.
  void PlaceRepresentative(const Quadric& q1,
    const octree::EvaluationScratch& crossing,
    const double centre[3],
    double cell,
    double v0[3]) const;
  double PlacementError(
    const Quadric& q1, const octree::EvaluationScratch& crossing, const double x[3]) const;
  double KeepInsideCell(Id node,
    const Quadric& q1,
    const octree::EvaluationScratch& crossing,
    const double centre[3],
    double v0[3]) const;
  bool StandInVertex(Id node,
    const Quadric& q1,
    const octree::EvaluationScratch& crossing,
    const double* surface,
    double weight,
    double& value,
    double v0[3]) const;
  double ClusterError(const octree::EvaluationScratch& scratch,
    double value,
    double weight,
    const double v0[3],
    double tipDistance) const;
  double BoundaryDistance(const std::vector<Id>& edges, const double v0[3]) const;
  void ProjectOnBoundary(const std::vector<Id>& edges, double v0[3]) const;
  void LabelTips();
  // f(a, b) for each boundary edge of the input, from a to b in its triangle's winding.
  template <typename F>
  void ForEachBoundaryEdge(F&& f) const
  {
    for (Id t = 0; t < this->NT; ++t)
    {
      const Id* tri = this->Mesh.Triangle(t);
      for (int k = 0; k < 3; ++k)
      {
        if (this->Topology.IsBoundaryEdge(t, k))
        {
          f(tri[k], tri[(k + 1) % 3]);
        }
      }
    }
  }
  double PlaceAtTip(Id node, const std::vector<Id>& edges, double v0[3]) const;
  void RepresentativeOf(Id node, double out[3]) const;
  double NodeError(Id node) const;
  void SurfaceNormal(Id node, double normal[3]) const;

  // --- cuts ------------------------------------------------------------------------------------
  void ComputeActivation(bool guess = false);
  // Whether node may be a cluster at epsilon: a vertex always, an internal node from its
  // threshold on.
  bool Qualifies(Id node, double epsilon) const
  {
    return node < this->NV || this->Thr[node - this->NV] <= epsilon;
  }
  void CollectCut(double epsilon, std::vector<Id>& cut) const;
  void CutAt(double epsilon, std::vector<Id>& cut, bool update = false);
  // CutAt's steps: the candidates sorted into those to evaluate, those that qualify and those
  // that fail; the count and error ratios of the evaluated; a node replaced by the topmost
  // qualifying nodes below it.
  void TriageCandidates(const std::vector<Id>& candidates,
    double epsilon,
    std::vector<Id>& pending,
    std::vector<Id>& kept,
    std::vector<Id>& failed);
  void RecordEvaluations(const std::vector<Id>& evaluated);
  void DescendToQualifying(
    Id node, double epsilon, std::vector<Id>& stack, std::vector<Id>& into) const;
  double EpsilonForCount(Id target) const;
  // EpsilonForCount's steps: the nodes that count, the span and histogram of their activations
  // (binned by ActivationBins), and the epsilon found among the nodes of one bin.
  struct ActivationBins;
  bool CountsForEstimate(Id i) const;
  void ActivationSpan(double& lo, double& hi, std::int64_t& total) const;
  std::vector<std::int64_t> ActivationHistogram(const ActivationBins& bin) const;
  double EpsilonInBin(const ActivationBins& bin,
    int b,
    std::int64_t before,
    std::int64_t need,
    double hi) const;
  std::int64_t EstimateAt(double epsilon) const;
  double SearchEpsilon(Id target, Id tolerance);

  // --- levels ----------------------------------------------------------------------------------
  void AssignClusters(octree::Synthesis& s);
  Id ReindexTriangles(octree::Synthesis& s) const;
  void MarkDuplicates(octree::Synthesis& s) const;
  void PreviousNormal(Id t, double normal[3]) const;
  Id MarkFolds(octree::Synthesis& s);
  Id MarkFins(octree::Synthesis& s);
  Id MarkPinches(octree::Synthesis& s);
  Id MarkBreaks(octree::Synthesis& s);
  Id MarkAnnuli(octree::Synthesis& s);
  Id MarkFarVanishing(octree::Synthesis& s, double epsilon);
  // MarkFarVanishing's steps. `alive` flags the clusters that keep a triangle, `slot` maps a
  // previous piece to its place among the vanishing ones (InvalidId for the others); the grid
  // holds the kept surface near which a piece may vanish.
  struct KeptSurfaceGrid;
  std::vector<std::uint32_t> VanishingPieces(const octree::Synthesis& s,
    const std::vector<unsigned char>& alive,
    std::vector<Id>& slot) const;
  std::vector<double> VanishingBoxes(const std::vector<Id>& slot, std::size_t count) const;
  void FillKeptSurfaceGrid(const octree::Synthesis& s,
    const std::vector<unsigned char>& alive,
    KeptSurfaceGrid& grid) const;
  bool NearKeptSurface(const octree::Synthesis& s,
    const KeptSurfaceGrid& grid,
    const double centre[3],
    double radius) const;
  std::vector<Id> ClustersOfRefusedPieces(const octree::Synthesis& s,
    const std::vector<Id>& slot,
    const std::vector<unsigned char>& refused) const;
  Id MarkClosedHoles(octree::Synthesis& s, double epsilon);
  void LabelHoles();
  /// MarkChanged for refusals that hold for the current trial level only (TrialRefusals).
  Id MarkForTrial(octree::Synthesis& s, const std::vector<Id>& clusters);
  Id MarkPinchedVertices(octree::Synthesis& s);
  void LabelPreviousPieces();
  std::vector<octree::CurveEdge> CurveEdgesOf(std::vector<Id>& shrunk) const;
  // Mark the changed clusters among `clusters` as not mergeable; returns how many were. With
  // SplitFully, also every node between them and the previous level's points inside them.
  // `lasting`: for good (pinches), otherwise as a fold refusal (Refused).
  Id MarkChanged(octree::Synthesis& s, const std::vector<Id>& clusters, bool lasting);
  // Lift the fold refusals; false when there were none.
  bool ClearRefusals();
  // Lift the refusals of `nodes` (RefusedNodes or TrialRefusals) and empty the list.
  void LiftRefusals(std::vector<Id>& nodes);
  bool SplitFully = false;
  Id TryLevel(double epsilon, ClusterLevel& level);
  // With PreserveTopology: whether a finished trial level changed the genus of a piece of the
  // previous level (closed a handle), which the local repairs cannot see: a handle can close
  // between clusters that each keep their link. The trial is then refused as a whole.
  bool LosesHandle(const octree::Synthesis& s) const;
  // The current level again (for a level that cannot merge more).
  Id RepeatCurrentLevel(ClusterLevel& level);
  // The best of a few trial levels for a target count (see MakeLevelForTriangleCount); returns
  // its count, 0 when none has a triangle.
  Id SearchLevel(Id targetTriangles, ClusterLevel& best);
  // The smallest epsilon at which a SearchLevel trial kept no triangle (infinity when none).
  double EmptyEpsilon = 0.0;
  /// When every trial of the search kept no triangle (a small target on a closed surface whose
  /// folds keep many triangles below the epsilon that merges it whole): the largest epsilon
  /// below EmptyEpsilon that keeps some, into best; returns its count (0 when none does). Also
  /// for trials refused for a lost handle (TryLevel returns 0 for those too).
  Id LastNonEmpty(ClusterLevel& best);
  /// When the search's best level keeps `count` triangles, a quarter or more above what was
  /// asked (a target the surface cannot reach): the smallest epsilon (between the current
  /// level's and best's) that keeps at most a tenth more, giving back at most three quarters of
  /// what the level removes; replaces best with that trial and returns its count.
  Id BackOff(Id count, ClusterLevel& best);
  void Finalize(octree::Synthesis& s, ClusterLevel& level) const;
  // Finalize's steps. `final` lists the kept triangles that make the level, `newId` maps a
  // cluster to the level's point (InvalidId for a cluster no such triangle uses) and `redirect`
  // a vanished cluster to the kept cluster that takes its previous points.
  std::vector<Id> KeptTriangles(const octree::Synthesis& s) const;
  Id SetLevelPoints(const octree::Synthesis& s,
    const std::vector<Id>& final,
    std::vector<Id>& newId,
    ClusterLevel& level) const;
  void SetLevelTriangles(const octree::Synthesis& s,
    const std::vector<Id>& final,
    const std::vector<Id>& newId,
    ClusterLevel& level) const;
  std::vector<Id> RedirectVanished(const octree::Synthesis& s, const std::vector<Id>& newId) const;
  void SetTargetsAndRanks(const octree::Synthesis& s,
    const std::vector<Id>& newId,
    const std::vector<Id>& redirect,
    Id points,
    ClusterLevel& level) const;
  void SetSources(
    const octree::Synthesis& s, const std::vector<Id>& newId, Id points, ClusterLevel& level) const;
  // Makes the chosen level the current one.
  void Commit(ClusterLevel& level);
  // OctreeClustering::FlipEdges; `nextTarget`: per point of the level, its point in the next
  // level, or null.
  void FlipLevelEdges(ClusterLevel& level, const Id* nextTarget) const;
};

} // namespace meshlod

#endif
