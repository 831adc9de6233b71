#include "OctreeClustering.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>

namespace meshlod
{
namespace
{
// The e2 weight (original area / new area)^2 is capped where a new triangle nearly degenerates.
constexpr double MaximumCrossingWeight = 100.0;
// Fixed blocks for the deterministic parallel compactions (independent of the thread count).
constexpr Id BlockSize = 16384;
constexpr float Infinite = std::numeric_limits<float>::infinity();

void Cross(const double u[3], const double v[3], double out[3])
{
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}

double Dot(const double u[3], const double v[3])
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

// Normal (not normalised) of triangle (a, b, c).
void Normal(const double a[3], const double b[3], const double c[3], double n[3])
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  Cross(u, v, n);
}

// Keep the i in [0, n) for which keep(i) holds, in order, calling write(i, slot): counts per
// fixed block, a serial prefix sum, then the writes, so the result does not depend on how the
// blocks are spread over threads. Returns the number kept.
template<typename Keep, typename Write>
Id ParallelCompact(Id n, Keep keep, Write write)
{
  const Id blocks = (n + BlockSize - 1) / BlockSize;
  std::vector<Id> offsets(static_cast<size_t>(blocks) + 1, 0);
  vtkSMPTools::For(0,
    blocks,
    [&](Id begin, Id end)
    {
      for (Id b = begin; b < end; ++b)
      {
        Id count = 0;
        for (Id i = b * BlockSize; i < std::min(n, (b + 1) * BlockSize); ++i)
        {
          count += keep(i) ? 1 : 0;
        }
        offsets[b + 1] = count;
      }
    });
  for (Id b = 0; b < blocks; ++b)
  {
    offsets[b + 1] += offsets[b];
  }
  vtkSMPTools::For(0,
    blocks,
    [&](Id begin, Id end)
    {
      for (Id b = begin; b < end; ++b)
      {
        Id slot = offsets[b];
        for (Id i = b * BlockSize; i < std::min(n, (b + 1) * BlockSize); ++i)
        {
          if (keep(i))
          {
            write(i, slot++);
          }
        }
      }
    });
  return offsets[blocks];
}

enum class NodeState : std::uint8_t
{
  NotEvaluated = 0,
  Admissible = 1,
  Inadmissible = 2,
};

// The crossing triangles of a node (exactly one vertex inside) with their planes.
struct EvaluationScratch
{
  std::vector<Id> Crossing;      // 3 t + corner of the vertex inside
  std::vector<Quadric> Planes;   // area-weighted plane quadric of each
  std::vector<double> Normals;   // 3 per crossing triangle (twice the area in length)
  std::vector<Id> BoundaryEdges; // boundary edges with an end inside (3 t + k)
  std::vector<double> Related;   // planes of the related triangle set (unit normal, offset)
};

// A level being built: clusters (cut nodes) and the previous level's triangles re-indexed.
struct Synthesis
{
  std::vector<Id> Cut;          // cluster -> node, in depth-first order
  std::vector<double> Reps;     // 3 per cluster
  std::vector<Id> PointCluster; // previous point -> cluster
  std::vector<Id> Triangles;    // 3 clusters per kept triangle
  std::vector<Id> From;         // kept triangle -> previous triangle
  std::vector<unsigned char> Duplicate;
  std::vector<unsigned char> Changed; // cluster is not exactly one previous point

  /// Whether kept triangle j may have folded or pinched: not a duplicate, with a changed cluster.
  bool Involved(Id j) const
  {
    const Id* tri = this->Triangles.data() + 3 * j;
    return !this->Duplicate[j] &&
      (this->Changed[tri[0]] || this->Changed[tri[1]] || this->Changed[tri[2]]);
  }
};
} // namespace

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
  std::vector<NodeState> State;
  std::vector<float> Thr; // the smallest epsilon at which the node may be a cluster
  std::vector<Id> RepSlot;
  // Per evaluated node (RepSlot): representative, surface normal and error.
  static constexpr int SlotSize = 7;
  std::vector<double> Reps;
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
  void MovedNormal(Id item, const double v0[3], double moved[3]) const;
  void AddCrossingTerms(const double v0[3], const EvaluationScratch& crossing, Quadric& q) const;
  bool HasFlip(const double v0[3], const EvaluationScratch& crossing, int depth) const;
  void Evaluate(Id index, EvaluationScratch& scratch);
  void ProjectOnBoundary(const std::vector<Id>& edges, double v0[3]) const;
  void RepresentativeOf(Id node, double out[3]) const;
  double NodeError(Id node) const;
  void SurfaceNormal(Id node, double normal[3]) const;

  // --- cuts ------------------------------------------------------------------------------------
  void ComputeActivation(bool guess = false);
  void CollectCut(double epsilon, std::vector<Id>& cut) const;
  void CutAt(double epsilon, std::vector<Id>& cut, bool update = false);
  double EpsilonForCount(Id target) const;
  std::int64_t EstimateAt(double epsilon) const;
  double SearchEpsilon(Id target, Id tolerance);

  // --- levels ----------------------------------------------------------------------------------
  void AssignClusters(Synthesis& s);
  Id ReindexTriangles(Synthesis& s) const;
  void MarkDuplicates(Synthesis& s) const;
  Id MarkFolds(Synthesis& s);
  Id MarkPinches(Synthesis& s);
  // Mark the changed clusters among `clusters` as not mergeable; returns how many were.
  Id MarkChanged(Synthesis& s, const std::vector<Id>& clusters);
  Id TryLevel(double epsilon, ClusterLevel& level);
  void Finalize(Synthesis& s, ClusterLevel& level) const;
  void Commit(const ClusterLevel& level);
};

//------------------------------------------------------------------------------
bool OctreeClustering::Internals::CheapInadmissible(Id index) const
{
  const ClusterNode& n = this->Tree.Nodes[index];
  return n.Locked != 0 ||
    (this->Options.MaximumPointsPerCell > 0 && n.Count > this->Options.MaximumPointsPerCell) ||
    (this->Options.MaximumCellSize > 0.0 &&
      this->Tree.CellSize(n.Depth) > this->Options.MaximumCellSize);
}

// The smallest epsilon at which the node may be a cluster: its error once evaluated in full,
// before that e1 (a lower bound). The tree's e1 comes from quadrics summed with cancellations, so
// values at rounding level are taken as zero (the full evaluation recomputes the quadric
// directly and tells exact zeros, such as a flat part or a cube corner, from small errors).
void OctreeClustering::Internals::UpdateThreshold(Id index)
{
  float& thr = this->Thr[index];
  if (this->State[index] == NodeState::Inadmissible || this->CheapInadmissible(index))
  {
    thr = Infinite;
    return;
  }
  const float e1 = this->Tree.Nodes[index].E1;
  thr = this->State[index] == NodeState::Admissible
    ? static_cast<float>(this->Reps[SlotSize * static_cast<size_t>(this->RepSlot[index]) + 6])
    : (e1 < 1e-6 * this->Tree.Size ? 0.0f : e1);
}

//------------------------------------------------------------------------------
// Normal (not normalised) of crossing triangle item / 3 with its corner item % 3 moved to v0.
void OctreeClustering::Internals::MovedNormal(Id item, const double v0[3], double moved[3]) const
{
  double p[3][3];
  this->Tree.RelativeTriangle(this->Mesh.Triangle(item / 3), p);
  std::copy_n(v0, 3, p[item % 3]);
  Normal(p[0], p[1], p[2], moved);
}

//------------------------------------------------------------------------------
// e2 (§3): the squared distance of the vertex inside a crossing triangle (v, a, b) to the new
// triangle (v0, a, b) is (area(v, a, b) / area(v0, a, b))^2 times the squared distance of v0 to
// the original plane, so e2 reweights the crossing triangles' planes.
void OctreeClustering::Internals::AddCrossingTerms(const double v0[3],
  const EvaluationScratch& crossing,
  Quadric& q) const
{
  for (size_t i = 0; i < crossing.Crossing.size(); ++i)
  {
    double moved[3];
    this->MovedNormal(crossing.Crossing[i], v0, moved);
    const double* n = crossing.Normals.data() + 3 * i;
    const double before = Dot(n, n);
    const double after = Dot(moved, moved);
    const double weight =
      after * MaximumCrossingWeight > before ? before / after : MaximumCrossingWeight;
    q.Add(crossing.Planes[i], weight);
  }
}

//------------------------------------------------------------------------------
// §2.4: clustering must not flip a triangle joining the cluster to the outside. A crossing
// triangle whose two outside vertices share a cell of the cluster's size will most likely fall
// into one neighbouring cluster and vanish, so it is not held against the cluster (otherwise the
// thin triangles of isosurfaces would forbid almost every cluster on a curved surface).
bool OctreeClustering::Internals::HasFlip(const double v0[3],
  const EvaluationScratch& crossing,
  int depth) const
{
  for (size_t i = 0; i < crossing.Crossing.size(); ++i)
  {
    const Id item = crossing.Crossing[i];
    const Id* tri = this->Mesh.Triangle(item / 3);
    const int c = static_cast<int>(item % 3);
    if (this->Tree.CommonDepth(tri[(c + 1) % 3], tri[(c + 2) % 3]) >= depth)
    {
      continue;
    }
    double moved[3];
    this->MovedNormal(item, v0, moved);
    if (!(Dot(crossing.Normals.data() + 3 * i, moved) > 0.0))
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
// Move v0 (relative coordinates) to the closest point of the given boundary edges.
void OctreeClustering::Internals::ProjectOnBoundary(const std::vector<Id>& edges,
  double v0[3]) const
{
  double best[3] = { v0[0], v0[1], v0[2] };
  double bestDistance = std::numeric_limits<double>::max();
  for (const Id item : edges)
  {
    const Id* tri = this->Mesh.Triangle(item / 3);
    const int k = static_cast<int>(item % 3);
    double a[3], b[3];
    this->Tree.RelativePoint(tri[k], a);
    this->Tree.RelativePoint(tri[(k + 1) % 3], b);
    const double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double w[3] = { v0[0] - a[0], v0[1] - a[1], v0[2] - a[2] };
    const double length = Dot(d, d);
    const double t = length > 0.0 ? std::min(1.0, std::max(0.0, Dot(w, d) / length)) : 0.0;
    const double p[3] = { a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2] };
    const double e[3] = { v0[0] - p[0], v0[1] - p[1], v0[2] - p[2] };
    const double distance = Dot(e, e);
    if (distance < bestDistance)
    {
      bestDistance = distance;
      std::copy_n(p, 3, best);
    }
  }
  std::copy_n(best, 3, v0);
}

//------------------------------------------------------------------------------
// The representative and error of a node (§2.3, §3), and whether it may be a cluster.
void OctreeClustering::Internals::Evaluate(Id index, EvaluationScratch& scratch)
{
  const Id node = this->NV + index;
  const ClusterNode& n = this->Tree.Nodes[index];
  Quadric q1, boundary;
  double* slot = this->Reps.data() + SlotSize * static_cast<size_t>(this->RepSlot[index]);
  this->Tree.RelatedQuadric(
    node, q1, &scratch.Crossing, slot + 3, &boundary, &scratch.BoundaryEdges, &scratch.Related);
  const size_t crossings = scratch.Crossing.size();
  scratch.Planes.resize(crossings);
  scratch.Normals.resize(3 * crossings);
  for (size_t i = 0; i < crossings; ++i)
  {
    const Id* tri = this->Mesh.Triangle(scratch.Crossing[i] / 3);
    double p[3][3];
    this->Tree.RelativeTriangle(tri, p);
    TriangleQuadric(p[0], p[1], p[2], scratch.Planes[i], scratch.Normals.data() + 3 * i);
  }
  const EvaluationScratch& crossing = scratch;

  double centre[3];
  this->Tree.Centroid(node, centre);
  const double tolerance = this->Options.PlacementTolerance;
  const double cell = this->Tree.CellSize(n.Depth);
  double v0[3];
  MinimizeQuadric(q1, centre, tolerance, v0);
  const int iterations = this->Options.RepresentativeIterations;
  for (int it = 0; it < iterations; ++it)
  {
    Quadric q = q1;
    this->AddCrossingTerms(v0, crossing, q);
    double v1[3];
    MinimizeQuadric(q, centre, tolerance, v1);
    const double d[3] = { v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2] };
    std::copy_n(v1, 3, v0);
    if (Dot(d, d) <= 1e-18 * cell * cell)
    {
      break;
    }
  }
  auto errorAt = [&](const double x[3])
  {
    Quadric q = q1;
    if (iterations > 0)
    {
      this->AddCrossingTerms(x, crossing, q);
    }
    return q.Evaluate(x);
  };

  // A placement far outside the cell means near-parallel planes met far away: fall back to the
  // best of the centroid and the cluster's vertices (§2.3).
  double low[3], extent[3];
  this->Tree.CellBox(this->FirstVertex(node), n.Depth, low, extent);
  bool outside = false;
  for (int c = 0; c < 3; ++c)
  {
    outside = outside || v0[c] < low[c] - 0.5 * extent[c] || v0[c] > low[c] + 1.5 * extent[c];
  }
  double value = 0.0;
  if (outside)
  {
    std::copy_n(centre, 3, v0);
    value = errorAt(v0);
    const Id first = this->Tree.Position(node);
    for (Id pos = first; pos < first + n.Count; ++pos)
    {
      double p[3];
      this->Tree.RelativePoint(this->Tree.Order[pos], p);
      const double e = errorAt(p);
      if (e < value)
      {
        value = e;
        std::copy_n(p, 3, v0);
      }
    }
  }
  else
  {
    value = errorAt(v0);
  }
  // A cluster on an open boundary keeps its representative on the input's boundary: the closest
  // point of its boundary edges (a small move, paid for in the error below).
  if (!scratch.BoundaryEdges.empty())
  {
    this->ProjectOnBoundary(scratch.BoundaryEdges, v0);
    value = errorAt(v0);
  }
  // The error: the root mean squared distance to the planes of the related triangle set, and
  // separately to the boundary-edge planes (few, so they would hardly count in the mean: an
  // open boundary is kept within epsilon too). No single plane may be farther than twice that:
  // a mean lets elongated or bent clusters stray far at their ends.
  const double weight = q1.Weight();
  double error = weight > 0.0 ? std::sqrt(value / weight) : 0.0;
  if (boundary.Weight() > 0.0)
  {
    error = std::max(error, std::sqrt(boundary.Evaluate(v0) / boundary.Weight()));
  }
  double farthest = 0.0;
  for (size_t i = 0; i < scratch.Related.size(); i += 4)
  {
    const double* plane = scratch.Related.data() + i;
    farthest = std::max(farthest, std::abs(Dot(plane, v0) + plane[3]));
  }
  error = std::max(error, 0.5 * farthest);
  std::copy_n(v0, 3, slot);
  slot[6] = static_cast<float>(error); // as a threshold, in single precision
  this->State[index] =
    this->HasFlip(v0, crossing, n.Depth) ? NodeState::Inadmissible : NodeState::Admissible;
  this->UpdateThreshold(index);
}

//------------------------------------------------------------------------------
void OctreeClustering::Internals::RepresentativeOf(Id node, double out[3]) const
{
  if (this->Tree.IsLeaf(node))
  {
    std::copy_n(this->Mesh.Point(node), 3, out);
    return;
  }
  const double* r =
    this->Reps.data() + SlotSize * static_cast<size_t>(this->RepSlot[node - this->NV]);
  for (int c = 0; c < 3; ++c)
  {
    out[c] = r[c] + this->Tree.Centre[c];
  }
}

double OctreeClustering::Internals::NodeError(Id node) const
{
  return this->Tree.IsLeaf(node)
    ? 0.0
    : this->Reps[SlotSize * static_cast<size_t>(this->RepSlot[node - this->NV]) + 6];
}

// The area-weighted normal of the input surface at a node's vertices (not normalised); kept
// from the evaluation for internal nodes.
void OctreeClustering::Internals::SurfaceNormal(Id node, double normal[3]) const
{
  if (!this->Tree.IsLeaf(node))
  {
    std::copy_n(
      this->Reps.data() + SlotSize * static_cast<size_t>(this->RepSlot[node - this->NV]) + 3,
      3,
      normal);
    return;
  }
  normal[0] = normal[1] = normal[2] = 0.0;
  const VertexTriangleAdjacency& adj = this->Topology.VertexTriangles;
  const Id first = this->Tree.Position(node);
  for (Id pos = first; pos < first + this->Tree.Count(node); ++pos)
  {
    const Id v = this->Tree.Order[pos];
    for (Id i = adj.Begin(v); i < adj.End(v); ++i)
    {
      const Id* tri = this->Mesh.Triangle(adj.Triangles[i]);
      double n[3];
      Normal(this->Mesh.Point(tri[0]), this->Mesh.Point(tri[1]), this->Mesh.Point(tri[2]), n);
      for (int c = 0; c < 3; ++c)
      {
        normal[c] += n[c];
      }
    }
  }
}

//------------------------------------------------------------------------------
// Activation[i]: the smallest threshold on the path from node i to its root. A node is collapsed
// (it or an ancestor is a cluster) exactly when epsilon reaches it.
void OctreeClustering::Internals::ComputeActivation(bool guess)
{
  // To guess an epsilon (not to cut), unevaluated nodes count with e1 raised by the ratio the
  // evaluations showed so far (e2 typically adds some 10%).
  const float inflation = static_cast<float>(
    guess && this->RatioCount > 0 ? std::exp(this->LogRatioSum / this->RatioCount) : 1.0);
  const Id ni = this->Tree.NumberOfInternalNodes();
  this->Activation.resize(ni);
  for (Id i = ni - 1; i >= 0; --i)
  {
    const Id parent = this->Tree.Nodes[i].Parent;
    const float own =
      this->State[i] == NodeState::NotEvaluated ? this->Thr[i] * inflation : this->Thr[i];
    this->Activation[i] =
      parent == InvalidId ? own : std::min(own, this->Activation[parent - this->NV]);
  }
}

//------------------------------------------------------------------------------
// The clusters at `epsilon`: the topmost nodes whose threshold is at most epsilon (a vertex on
// its own always qualifies), in depth-first order. Needs ComputeActivation().
void OctreeClustering::Internals::CollectCut(double epsilon, std::vector<Id>& cut) const
{
  const Id ni = this->Tree.NumberOfInternalNodes();
  const Id nv = this->NV;
  auto parentOpen = [&](Id parent)
  { return parent == InvalidId || this->Activation[parent - nv] > epsilon; };
  auto isCluster = [&](Id node)
  {
    if (node < nv)
    {
      return parentOpen(this->Tree.LeafParent[node]);
    }
    const Id i = node - nv;
    return this->Thr[i] <= epsilon && parentOpen(this->Tree.Nodes[i].Parent);
  };
  cut.resize(static_cast<size_t>(nv) + ni);
  const Id count = ParallelCompact(nv + ni, isCluster, [&](Id node, Id slot) { cut[slot] = node; });
  cut.resize(count);
  std::sort(cut.begin(),
    cut.end(),
    [&](Id a, Id b) { return this->Tree.Position(a) < this->Tree.Position(b); });
}

//------------------------------------------------------------------------------
// The cut at `epsilon` with every cluster evaluated in full. An evaluation can only raise a
// node's threshold: a cluster that fails is replaced by the topmost nodes below it that qualify,
// which are evaluated in turn. With `update`, `cut` is the cut at the same epsilon before some of
// its nodes were marked inadmissible: only those are replaced, which gives the same cut as
// starting afresh (the nodes above a cut node do not qualify, marked or not) without a pass
// over the whole tree.
void OctreeClustering::Internals::CutAt(double epsilon, std::vector<Id>& cut, bool update)
{
  if (!update)
  {
    this->ComputeActivation();
    this->CollectCut(epsilon, cut);
  }
  vtkSMPThreadLocal<EvaluationScratch> scratch;
  std::vector<Id> pending, failed, kept, stack;
  auto queue = [&](Id node)
  {
    if (node >= this->NV && this->State[node - this->NV] == NodeState::NotEvaluated)
    {
      const Id i = node - this->NV;
      pending.push_back(node);
      this->RepSlot[i] = static_cast<Id>(this->Reps.size() / SlotSize);
      this->Reps.resize(this->Reps.size() + SlotSize);
    }
    else if (node < this->NV || this->Thr[node - this->NV] <= epsilon)
    {
      kept.push_back(node);
    }
    else
    {
      failed.push_back(node); // evaluated before, since marked inadmissible (update only)
    }
  };
  // Replace a node that does not qualify by the topmost qualifying nodes below it.
  auto descend = [&](Id node, std::vector<Id>& into)
  {
    stack.assign(1, node);
    while (!stack.empty())
    {
      const Id parent = stack.back();
      stack.pop_back();
      // The children tile the parent's range of the depth-first order.
      const Id end = this->Tree.Position(parent) + this->Tree.Count(parent);
      for (Id pos = this->Tree.Position(parent); pos < end;)
      {
        const Id child = this->Tree.ChildAt(parent, pos);
        pos += this->Tree.Count(child);
        if (child < this->NV || this->Thr[child - this->NV] <= epsilon)
        {
          into.push_back(child);
        }
        else
        {
          stack.push_back(child);
        }
      }
    }
  };
  std::vector<Id> candidates;
  candidates.swap(cut);
  for (;;)
  {
    pending.clear();
    failed.clear();
    for (const Id node : candidates)
    {
      queue(node);
    }
    if (pending.empty() && failed.empty())
    {
      break;
    }
    vtkSMPTools::For(0,
      static_cast<Id>(pending.size()),
      [&](Id begin, Id end)
      {
        EvaluationScratch& local = scratch.Local();
        for (Id j = begin; j < end; ++j)
        {
          this->Evaluate(pending[j] - this->NV, local);
        }
      });
    this->Evaluated += static_cast<Id>(pending.size());
    for (const Id node : pending)
    {
      const Id i = node - this->NV;
      const float e1 = this->Tree.Nodes[i].E1;
      const double error = this->NodeError(node);
      if (this->State[i] == NodeState::Admissible && e1 > 0.0f && error > 0.0)
      {
        this->LogRatioSum += std::log(error / e1);
        ++this->RatioCount;
      }
    }
    candidates.clear();
    for (const Id node : pending)
    {
      if (this->Thr[node - this->NV] <= epsilon)
      {
        kept.push_back(node);
      }
      else
      {
        descend(node, candidates);
      }
    }
    for (const Id node : failed)
    {
      descend(node, candidates);
    }
  }
  cut.swap(kept);
  std::sort(cut.begin(),
    cut.end(),
    [&](Id a, Id b) { return this->Tree.Position(a) < this->Tree.Position(b); });
}

//------------------------------------------------------------------------------
// The smallest epsilon whose cut keeps at most `target` input triangles by the estimate
// NT - (triangles that degenerate in collapsed nodes), from a histogram of the activation
// epsilons (no sort of all nodes). Needs ComputeActivation(). Returns infinity when even
// collapsing every mergeable node keeps more.
double OctreeClustering::Internals::EpsilonForCount(Id target) const
{
  const Id ni = this->Tree.NumberOfInternalNodes();
  const std::int64_t need = static_cast<std::int64_t>(this->NT) - target;
  if (need <= 0)
  {
    return 0.0;
  }
  double lo = std::numeric_limits<double>::max(), hi = 0.0;
  std::int64_t total = 0;
  for (Id i = 0; i < ni; ++i)
  {
    const float a = this->Activation[i];
    if (this->Tree.Nodes[i].Dies > 0 && a < Infinite)
    {
      total += this->Tree.Nodes[i].Dies;
      if (a > 0.0f)
      {
        lo = std::min(lo, double(a));
        hi = std::max(hi, double(a));
      }
    }
  }
  if (total < need)
  {
    return std::numeric_limits<double>::infinity();
  }
  if (!(hi > 0.0))
  {
    return 0.0;
  }
  // Positive floats order like their bit patterns: bin by the leading bits above `lo`.
  constexpr int bins = 4096;
  auto bits = [](float a)
  {
    std::uint32_t u;
    std::memcpy(&u, &a, sizeof(u));
    return u;
  };
  const std::uint32_t base = bits(static_cast<float>(lo));
  const std::uint32_t range = bits(static_cast<float>(hi)) - base;
  int shift = 0;
  while ((range >> shift) >= static_cast<std::uint32_t>(bins - 1))
  {
    ++shift;
  }
  auto bin = [&](float a)
  { return a <= static_cast<float>(lo) ? 0 : 1 + static_cast<int>((bits(a) - base) >> shift); };
  std::vector<std::int64_t> histogram(bins, 0);
  for (Id i = 0; i < ni; ++i)
  {
    const float a = this->Activation[i];
    if (this->Tree.Nodes[i].Dies > 0 && a < Infinite)
    {
      histogram[bin(a)] += this->Tree.Nodes[i].Dies;
    }
  }
  std::int64_t before = 0;
  int b = 0;
  for (; b < bins && before + histogram[b] < need; ++b)
  {
    before += histogram[b];
  }
  std::vector<std::pair<float, Id>> inBin;
  for (Id i = 0; i < ni; ++i)
  {
    const float a = this->Activation[i];
    if (this->Tree.Nodes[i].Dies > 0 && a < Infinite && bin(a) == b)
    {
      inBin.emplace_back(a, this->Tree.Nodes[i].Dies);
    }
  }
  std::sort(inBin.begin(), inBin.end());
  for (const auto& entry : inBin)
  {
    before += entry.second;
    if (before >= need)
    {
      return entry.first;
    }
  }
  return hi;
}

//------------------------------------------------------------------------------
// NT minus the triangles that degenerate at `epsilon`. Needs ComputeActivation().
std::int64_t OctreeClustering::Internals::EstimateAt(double epsilon) const
{
  std::int64_t vanished = 0;
  for (Id i = 0; i < this->Tree.NumberOfInternalNodes(); ++i)
  {
    vanished += this->Activation[i] <= epsilon ? this->Tree.Nodes[i].Dies : 0;
  }
  return this->NT - vanished;
}

//------------------------------------------------------------------------------
// An epsilon (at least the current one) whose cut keeps about `target` triangles by the
// estimate. The estimate from e1 alone is a first guess (thresholds only rise when nodes are
// evaluated); then a bisection in log scale on the estimate with the cut evaluated.
double OctreeClustering::Internals::SearchEpsilon(Id target, Id tolerance)
{
  std::vector<Id> cut;
  auto estimate = [&](double epsilon)
  {
    this->CutAt(epsilon, cut);
    this->ComputeActivation();
    return this->EstimateAt(epsilon);
  };
  const double floor = this->CurrentEpsilon;
  double low = floor, high = 0.0;
  std::int64_t lowCount = this->NT, highCount = 0;
  for (int guess = 0; guess < 3; ++guess)
  {
    this->ComputeActivation(true);
    const double epsilon = std::max(floor, this->EpsilonForCount(target));
    if (!std::isfinite(epsilon))
    {
      return std::numeric_limits<float>::max(); // unreachable: collapse all that may collapse
    }
    const std::int64_t count = estimate(epsilon);
    if (std::abs(count - target) <= tolerance)
    {
      return epsilon;
    }
    if (count < target)
    {
      high = epsilon;
      highCount = count;
      break;
    }
    low = epsilon;
    lowCount = count;
  }
  if (!(high > 0.0))
  {
    // Grow until the estimate falls below the target.
    high = std::max(low, 1e-12 * this->Tree.Size);
    for (int it = 0; it < 60; ++it)
    {
      high *= 1.25;
      highCount = estimate(high);
      if (highCount <= target)
      {
        break;
      }
      low = high;
      lowCount = highCount;
    }
  }
  // The count falls about like a power of epsilon: interpolate in log-log (regula falsi), with a
  // bisection whenever the same end moved twice.
  int lastMoved = 0;
  for (int it = 0; it < 20 && high > low * (1.0 + 1e-7); ++it)
  {
    double next = low > 0.0 ? std::sqrt(low * high) : 0.5 * high;
    if (low > 0.0 && lastMoved != 2 && lastMoved != -2)
    {
      const double a = std::log(static_cast<double>(std::max<std::int64_t>(1, lowCount)));
      const double b = std::log(static_cast<double>(std::max<std::int64_t>(1, highCount)));
      const double t = a > b ? (a - std::log(static_cast<double>(target))) / (a - b) : 0.5;
      next = std::exp(
        std::log(low) + std::min(0.95, std::max(0.05, t)) * (std::log(high) - std::log(low)));
    }
    const std::int64_t count = estimate(next);
    if (std::abs(count - target) <= tolerance)
    {
      return next;
    }
    if (count > target)
    {
      low = next;
      lowCount = count;
      lastMoved = lastMoved < 0 ? lastMoved - 1 : -1;
    }
    else
    {
      high = next;
      highCount = count;
      lastMoved = lastMoved > 0 ? lastMoved + 1 : 1;
    }
    if (lastMoved == 3 || lastMoved == -3)
    {
      lastMoved = 0;
    }
  }
  return high;
}

//------------------------------------------------------------------------------
// Clusters of every vertex and previous point, and the representatives.
void OctreeClustering::Internals::AssignClusters(Synthesis& s)
{
  const Id clusters = static_cast<Id>(s.Cut.size());
  vtkSMPTools::For(0,
    clusters,
    [&](Id begin, Id end)
    {
      for (Id k = begin; k < end; ++k)
      {
        const Id first = this->Tree.Position(s.Cut[k]);
        const Id last = first + this->Tree.Count(s.Cut[k]);
        for (Id pos = first; pos < last; ++pos)
        {
          this->ClusterOfVertex[this->Tree.Order[pos]] = k;
        }
      }
    });
  const Id previousPoints = this->PreviousPoints();
  s.PointCluster.resize(previousPoints);
  vtkSMPTools::For(0,
    previousPoints,
    [&](Id begin, Id end)
    {
      for (Id p = begin; p < end; ++p)
      {
        s.PointCluster[p] = this->ClusterOfVertex[this->FirstVertex(this->NodeOfPoint(p))];
      }
    });
  s.Reps.resize(3 * static_cast<size_t>(clusters));
  vtkSMPTools::For(0,
    clusters,
    [&](Id begin, Id end)
    {
      for (Id k = begin; k < end; ++k)
      {
        this->RepresentativeOf(s.Cut[k], s.Reps.data() + 3 * k);
      }
    });
  // A cluster is unchanged when it is exactly one previous point.
  std::vector<Id> count(clusters, 0), some(clusters, InvalidId);
  for (Id p = 0; p < previousPoints; ++p)
  {
    ++count[s.PointCluster[p]];
    some[s.PointCluster[p]] = p;
  }
  s.Changed.resize(clusters);
  for (Id k = 0; k < clusters; ++k)
  {
    s.Changed[k] = (count[k] == 1 && this->NodeOfPoint(some[k]) == s.Cut[k]) ? 0 : 1;
  }
}

//------------------------------------------------------------------------------
// The previous triangles re-indexed to clusters, without those that degenerate.
Id OctreeClustering::Internals::ReindexTriangles(Synthesis& s) const
{
  const Id previousTriangles = this->PreviousTriangles();
  const Id* prev = this->PreviousTriangleData();
  const std::vector<Id>& pc = s.PointCluster;
  auto nonDegenerate = [&](Id t)
  {
    const Id a = pc[prev[3 * t]], b = pc[prev[3 * t + 1]], c = pc[prev[3 * t + 2]];
    return a != b && b != c && c != a;
  };
  s.From.resize(previousTriangles);
  const Id kept =
    ParallelCompact(previousTriangles, nonDegenerate, [&](Id t, Id slot) { s.From[slot] = t; });
  s.From.resize(kept);
  s.Triangles.resize(3 * static_cast<size_t>(kept));
  vtkSMPTools::For(0,
    kept,
    [&](Id begin, Id end)
    {
      for (Id j = begin; j < end; ++j)
      {
        for (int k = 0; k < 3; ++k)
        {
          s.Triangles[3 * j + k] = pc[prev[3 * s.From[j] + k]];
        }
      }
    });
  return kept;
}

//------------------------------------------------------------------------------
// Triangles with the same three clusters as an earlier one (either orientation), grouped by
// their smallest cluster with the triangle order kept inside each group.
void OctreeClustering::Internals::MarkDuplicates(Synthesis& s) const
{
  const Id kept = static_cast<Id>(s.From.size());
  const Id clusters = static_cast<Id>(s.Cut.size());
  const std::vector<Id>& tris = s.Triangles;
  auto smallest = [&](Id j)
  { return std::min(tris[3 * j], std::min(tris[3 * j + 1], tris[3 * j + 2])); };
  std::vector<Id> offsets(static_cast<size_t>(clusters) + 1, 0);
  for (Id j = 0; j < kept; ++j)
  {
    ++offsets[smallest(j) + 1];
  }
  for (Id k = 0; k < clusters; ++k)
  {
    offsets[k + 1] += offsets[k];
  }
  std::vector<Id> grouped(kept);
  {
    std::vector<Id> cursor(offsets.begin(), offsets.end() - 1);
    for (Id j = 0; j < kept; ++j)
    {
      grouped[cursor[smallest(j)]++] = j;
    }
  }
  s.Duplicate.assign(kept, 0);
  vtkSMPTools::For(0,
    clusters,
    [&](Id begin, Id end)
    {
      for (Id k = begin; k < end; ++k)
      {
        for (Id x = offsets[k]; x < offsets[k + 1]; ++x)
        {
          const Id* a = tris.data() + 3 * grouped[x];
          const Id amax = std::max(a[0], std::max(a[1], a[2]));
          const std::int64_t amid = std::int64_t(a[0]) + a[1] + a[2] - k - amax;
          for (Id y = offsets[k]; y < x; ++y)
          {
            const Id* b = tris.data() + 3 * grouped[y];
            const Id bmax = std::max(b[0], std::max(b[1], b[2]));
            if (bmax == amax && std::int64_t(b[0]) + b[1] + b[2] - k - bmax == amid)
            {
              s.Duplicate[grouped[x]] = 1;
              break;
            }
          }
        }
      }
    });
}

//------------------------------------------------------------------------------
// Folds: a kept triangle whose normal opposes the input surface around its three clusters.
// The clusters of such a triangle that changed are marked as not mergeable (they lie above the
// previous cut, so the levels still nest). Returns the number of nodes marked.
Id OctreeClustering::Internals::MarkFolds(Synthesis& s)
{
  const Id kept = static_cast<Id>(s.From.size());
  const Id clusters = static_cast<Id>(s.Cut.size());
  // Surface normals only for the clusters of triangles that can have folded.
  std::vector<unsigned char> needed(clusters, 0);
  for (Id j = 0; j < kept; ++j)
  {
    if (s.Involved(j))
    {
      for (int c = 0; c < 3; ++c)
      {
        needed[s.Triangles[3 * j + c]] = 1;
      }
    }
  }
  std::vector<double> normals(3 * static_cast<size_t>(clusters), 0.0);
  vtkSMPTools::For(0,
    clusters,
    [&](Id begin, Id end)
    {
      for (Id k = begin; k < end; ++k)
      {
        if (needed[k])
        {
          this->SurfaceNormal(s.Cut[k], normals.data() + 3 * k);
        }
      }
    });
  std::vector<unsigned char> folded(kept, 0);
  vtkSMPTools::For(0,
    kept,
    [&](Id begin, Id end)
    {
      for (Id j = begin; j < end; ++j)
      {
        if (!s.Involved(j))
        {
          continue;
        }
        const Id* tri = s.Triangles.data() + 3 * j;
        double surface[3] = { 0.0, 0.0, 0.0 }, after[3];
        for (int c = 0; c < 3; ++c)
        {
          for (int i = 0; i < 3; ++i)
          {
            surface[i] += normals[3 * tri[c] + i];
          }
        }
        Normal(s.Reps.data() + 3 * tri[0],
          s.Reps.data() + 3 * tri[1],
          s.Reps.data() + 3 * tri[2],
          after);
        folded[j] = Dot(surface, after) > 0.0 ? 0 : 1;
      }
    });
  std::vector<Id> marks; // the clusters of the folded triangles
  for (Id j = 0; j < kept; ++j)
  {
    if (folded[j])
    {
      marks.insert(marks.end(), s.Triangles.begin() + 3 * j, s.Triangles.begin() + 3 * j + 3);
    }
  }
  return this->MarkChanged(s, marks);
}

//------------------------------------------------------------------------------
Id OctreeClustering::Internals::MarkChanged(Synthesis& s, const std::vector<Id>& clusters)
{
  Id marked = 0;
  for (const Id k : clusters)
  {
    const Id node = s.Cut[k];
    if (s.Changed[k] && node >= this->NV &&
      this->State[node - this->NV] != NodeState::Inadmissible)
    {
      this->State[node - this->NV] = NodeState::Inadmissible;
      this->UpdateThreshold(node - this->NV);
      ++marked;
    }
  }
  return marked;
}

//------------------------------------------------------------------------------
// Pinches: an edge that three or more kept triangles share, where one of them has a changed
// cluster (clusters that merged folded part of the surface onto itself). Like folds, the changed
// clusters of the triangles on such an edge are marked as not mergeable. The edges are grouped
// by their smaller cluster (a counting sort, as for duplicates), so that each edge's triangles
// are found among the few edges of one cluster.
Id OctreeClustering::Internals::MarkPinches(Synthesis& s)
{
  const Id kept = static_cast<Id>(s.From.size());
  const Id clusters = static_cast<Id>(s.Cut.size());
  std::vector<Id> offsets(static_cast<size_t>(clusters) + 1, 0);
  auto forEachEdge = [&](auto visit)
  {
    for (Id j = 0; j < kept; ++j)
    {
      for (int c = 0; c < 3 && !s.Duplicate[j]; ++c)
      {
        const Id a = s.Triangles[3 * j + c], b = s.Triangles[3 * j + (c + 1) % 3];
        visit(std::min(a, b), std::max(a, b), j);
      }
    }
  };
  forEachEdge([&](Id low, Id, Id) { ++offsets[low + 1]; });
  for (Id k = 0; k < clusters; ++k)
  {
    offsets[k + 1] += offsets[k];
  }
  // Each entry packs the larger cluster (high bits) and the triangle, so that sorting a
  // cluster's entries brings the triangles of each of its edges together (n log n even around a
  // vertex with very many triangles).
  std::vector<std::uint64_t> entries(offsets[clusters]);
  {
    std::vector<Id> cursor(offsets.begin(), offsets.end() - 1);
    forEachEdge([&](Id low, Id other, Id j) {
      entries[cursor[low]++] =
        (static_cast<std::uint64_t>(other) << 32) | static_cast<std::uint32_t>(j);
    });
  }
  auto triangleOf = [&](std::size_t x) { return static_cast<Id>(entries[x] & 0xffffffffu); };
  // pinched[x]: entry x is on an edge with three or more triangles, one of them involved.
  std::vector<unsigned char> pinched(entries.size(), 0);
  vtkSMPTools::For(0,
    clusters,
    [&](Id begin, Id end)
    {
      for (Id k = begin; k < end; ++k)
      {
        const std::size_t first = offsets[k], last = offsets[k + 1];
        std::sort(entries.begin() + first, entries.begin() + last);
        for (std::size_t x = first; x < last;)
        {
          std::size_t y = x;
          bool watched = false;
          for (; y < last && (entries[y] >> 32) == (entries[x] >> 32); ++y)
          {
            watched = watched || s.Involved(triangleOf(y));
          }
          if (y - x > 2 && watched)
          {
            std::fill(pinched.begin() + x, pinched.begin() + y, 1);
          }
          x = y;
        }
      }
    });
  std::vector<Id> marks; // the clusters of the triangles on pinched edges
  for (std::size_t x = 0; x < pinched.size(); ++x)
  {
    if (pinched[x])
    {
      const Id j = triangleOf(x);
      marks.insert(marks.end(), s.Triangles.begin() + 3 * j, s.Triangles.begin() + 3 * j + 3);
    }
  }
  return this->MarkChanged(s, marks);
}

//------------------------------------------------------------------------------
// Points, triangles, targets, ranks and sources of a level from its synthesis.
void OctreeClustering::Internals::Finalize(Synthesis& s, ClusterLevel& level) const
{
  const Id clusters = static_cast<Id>(s.Cut.size());
  const Id previousPoints = this->PreviousPoints();
  const Id previousTriangles = this->PreviousTriangles();
  const Id* prev = this->PreviousTriangleData();
  std::vector<Id> final;
  final.resize(s.From.size());
  const Id count = ParallelCompact(
    static_cast<Id>(s.From.size()),
    [&](Id j) { return s.Duplicate[j] == 0; },
    [&](Id j, Id slot) { final[slot] = j; });
  final.resize(count);
  if (count == 0)
  {
    return; // everything collapsed: no level
  }

  // Points: the clusters some triangle uses, in depth-first order.
  std::vector<Id> newId(clusters, InvalidId);
  for (const Id j : final)
  {
    for (int c = 0; c < 3; ++c)
    {
      newId[s.Triangles[3 * j + c]] = 0;
    }
  }
  Id points = 0;
  for (Id k = 0; k < clusters; ++k)
  {
    newId[k] = newId[k] == 0 ? points++ : InvalidId;
  }
  level.Mesh.Points.resize(3 * static_cast<size_t>(points));
  level.PointNode.resize(points);
  level.PointVertexCount.resize(points);
  double worst = 0.0;
  for (Id k = 0; k < clusters; ++k)
  {
    if (newId[k] != InvalidId)
    {
      std::copy_n(s.Reps.data() + 3 * k, 3, level.Mesh.Point(newId[k]));
      level.PointNode[newId[k]] = s.Cut[k];
      level.PointVertexCount[newId[k]] = this->Tree.Count(s.Cut[k]);
      worst = std::max(worst, this->NodeError(s.Cut[k]));
    }
  }
  level.EstimatedError = worst;
  level.Mesh.Triangles.resize(3 * static_cast<size_t>(count));
  level.LevelZeroTriangle.resize(count);
  vtkSMPTools::For(0,
    count,
    [&](Id begin, Id end)
    {
      for (Id i = begin; i < end; ++i)
      {
        const Id j = final[i];
        for (int c = 0; c < 3; ++c)
        {
          level.Mesh.Triangles[3 * i + c] = newId[s.Triangles[3 * j + c]];
        }
        level.LevelZeroTriangle[i] = this->LevelZeroOf(s.From[j]);
      }
    });

  // Clusters that lost all their triangles send their previous points to the nearest cluster
  // joined to them by a previous triangle, else to the nearer kept cluster before or after them
  // in depth-first order.
  std::vector<Id> redirect(clusters, InvalidId);
  std::vector<double> distance(clusters, std::numeric_limits<double>::max());
  auto offer = [&](Id k, Id candidate)
  {
    const double* x = s.Reps.data() + 3 * k;
    const double* y = s.Reps.data() + 3 * candidate;
    const double d =
      (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]);
    if (d < distance[k] || (d == distance[k] && candidate < redirect[k]))
    {
      redirect[k] = candidate;
      distance[k] = d;
    }
  };
  bool anyVanished = false;
  for (Id p = 0; p < previousPoints && !anyVanished; ++p)
  {
    anyVanished = newId[s.PointCluster[p]] == InvalidId;
  }
  if (anyVanished)
  {
    for (Id t = 0; t < previousTriangles; ++t)
    {
      for (int c = 0; c < 3; ++c)
      {
        const Id k = s.PointCluster[prev[3 * t + c]];
        for (int o = 1; o < 3 && newId[k] == InvalidId; ++o)
        {
          const Id other = s.PointCluster[prev[3 * t + (c + o) % 3]];
          if (newId[other] != InvalidId)
          {
            offer(k, other);
          }
        }
      }
    }
    std::vector<Id> before(clusters, InvalidId);
    Id lastKept = InvalidId;
    for (Id k = 0; k < clusters; ++k)
    {
      before[k] = lastKept;
      lastKept = newId[k] != InvalidId ? k : lastKept;
    }
    Id nextKept = InvalidId;
    for (Id k = clusters - 1; k >= 0; --k)
    {
      if (newId[k] == InvalidId && redirect[k] == InvalidId)
      {
        for (const Id candidate : { before[k], nextKept })
        {
          if (candidate != InvalidId)
          {
            offer(k, candidate);
          }
        }
      }
      nextKept = newId[k] != InvalidId ? k : nextKept;
    }
  }

  // Targets; collapse ranks: the clusters that changed, by increasing error.
  level.Target.resize(previousPoints);
  std::vector<unsigned char> receives(clusters, 0);
  for (Id p = 0; p < previousPoints; ++p)
  {
    Id k = s.PointCluster[p];
    if (newId[k] == InvalidId)
    {
      k = redirect[k];
      receives[k] = 1;
    }
    level.Target[p] = newId[k];
  }
  std::vector<Id> ranked;
  for (Id k = 0; k < clusters; ++k)
  {
    if (newId[k] != InvalidId && (s.Changed[k] || receives[k]))
    {
      ranked.push_back(k);
    }
  }
  std::sort(ranked.begin(),
    ranked.end(),
    [&](Id a, Id b)
    {
      const double ea = this->NodeError(s.Cut[a]), eb = this->NodeError(s.Cut[b]);
      return ea < eb || (ea == eb && s.Cut[a] < s.Cut[b]);
    });
  std::vector<Id> rankOfPoint(points, -1);
  for (size_t r = 0; r < ranked.size(); ++r)
  {
    rankOfPoint[newId[ranked[r]]] = static_cast<Id>(r);
  }
  level.Rank.resize(previousPoints);
  for (Id p = 0; p < previousPoints; ++p)
  {
    level.Rank[p] = rankOfPoint[level.Target[p]];
  }
  level.ChangedClusters = static_cast<Id>(ranked.size());

  // Sources: the previous points of each cluster, weighted by the input vertices they stand for.
  level.SourceOffsets.assign(static_cast<size_t>(points) + 1, 0);
  for (Id p = 0; p < previousPoints; ++p)
  {
    const Id j = newId[s.PointCluster[p]];
    if (j != InvalidId)
    {
      ++level.SourceOffsets[j + 1];
    }
  }
  for (Id j = 0; j < points; ++j)
  {
    level.SourceOffsets[j + 1] += level.SourceOffsets[j];
  }
  level.SourceParents.resize(level.SourceOffsets[points]);
  level.SourceWeights.resize(level.SourceOffsets[points]);
  std::vector<Id> cursor(level.SourceOffsets.begin(), level.SourceOffsets.end() - 1);
  for (Id p = 0; p < previousPoints; ++p)
  {
    const Id j = newId[s.PointCluster[p]];
    if (j != InvalidId)
    {
      level.SourceParents[cursor[j]] = p;
      level.SourceWeights[cursor[j]++] = static_cast<float>(
        static_cast<double>(this->VertexCountOfPoint(p)) / level.PointVertexCount[j]);
    }
  }
}

//------------------------------------------------------------------------------
// Build (without committing) the level at `epsilon` from the current one; returns its number of
// triangles.
Id OctreeClustering::Internals::TryLevel(double epsilon, ClusterLevel& level)
{
  level = ClusterLevel();
  level.Epsilon = epsilon;
  Synthesis s;
  for (int pass = 0;; ++pass)
  {
    this->CutAt(epsilon, s.Cut, pass > 0); // later passes replace only the marked clusters
    this->AssignClusters(s);
    this->ReindexTriangles(s);
    this->MarkDuplicates(s);
    const Id marked =
      pass < this->Options.FlipPasses ? this->MarkFolds(s) + this->MarkPinches(s) : 0;
    if (marked == 0)
    {
      break;
    }
    level.FlippedTrianglesFixed += marked;
  }
  this->Finalize(s, level);
  return level.Mesh.GetNumberOfTriangles();
}

//------------------------------------------------------------------------------
void OctreeClustering::Internals::Commit(const ClusterLevel& level)
{
  this->CurrentTriangles = level.Mesh.Triangles;
  this->CurrentLevelZero = level.LevelZeroTriangle;
  this->PointNode = level.PointNode;
  this->PointVertexCount = level.PointVertexCount;
  this->CurrentEpsilon = level.Epsilon;
}

//------------------------------------------------------------------------------
OctreeClustering::OctreeClustering(const TriangleMesh& mesh,
  const TriangleTopology& topology,
  const OctreeClusteringOptions& options)
  : Impl(new Internals(mesh, topology, options))
{
}

OctreeClustering::~OctreeClustering()
{
  delete this->Impl;
}

void OctreeClustering::BuildTree()
{
  Internals& impl = *this->Impl;
  ClusterTreeOptions options;
  options.BoundaryWeight = impl.Options.BoundaryWeight;
  options.PlacementTolerance = impl.Options.PlacementTolerance;
  impl.Tree.Build(impl.Mesh, impl.Topology, options);
  const Id ni = impl.Tree.NumberOfInternalNodes();
  impl.State.assign(ni, NodeState::NotEvaluated);
  impl.RepSlot.assign(ni, InvalidId);
  impl.Reps.clear();
  impl.Thr.resize(ni);
  vtkSMPTools::For(0,
    ni,
    [&](Id begin, Id end)
    {
      for (Id i = begin; i < end; ++i)
      {
        impl.UpdateThreshold(i);
      }
    });

  // Level 0 is the input itself.
  impl.CurrentTriangles.clear();
  impl.CurrentLevelZero.clear();
  impl.PointNode.clear();
  impl.PointVertexCount.clear();
  impl.ClusterOfVertex.assign(impl.NV, InvalidId);
  impl.CurrentEpsilon = 0.0;
}

bool OctreeClustering::MakeLevel(double epsilon, ClusterLevel& level)
{
  epsilon = std::max(epsilon, this->Impl->CurrentEpsilon);
  if (this->Impl->TryLevel(epsilon, level) == 0)
  {
    return false;
  }
  this->Impl->Commit(level);
  return true;
}

bool OctreeClustering::MakeLevelForTriangleCount(Id targetTriangles, ClusterLevel& level)
{
  Internals& impl = *this->Impl;
  if (targetTriangles >= impl.PreviousTriangles())
  {
    // A level never refines: asked for at least what the current level has, it is the current
    // level again. At the input, even epsilon 0 would merge clusters of zero error (an exactly
    // flat region): a negative epsilon merges nothing.
    const double epsilon = impl.AtInput() ? -1.0 : impl.CurrentEpsilon;
    if (impl.TryLevel(epsilon, level) == 0)
    {
      return false;
    }
    level.Epsilon = std::max(0.0, epsilon); // the next searches start from it
    impl.Commit(level);
    return true;
  }
  const Id tolerance = std::max<Id>(2, targetTriangles / 500);
  // The estimate NT - (triangles that degenerate in collapsed nodes) ignores duplicates: aim off
  // by the difference a trial level shows, a few times.
  Id aim = targetTriangles;
  ClusterLevel best, trial;
  Id bestCount = 0;
  bool haveBest = false;
  for (int round = 0; round < 3; ++round)
  {
    const double epsilon = impl.SearchEpsilon(aim, std::max<Id>(1, tolerance / 2));
    const Id count = impl.TryLevel(epsilon, trial);
    if (count > 0)
    {
      const Id error = std::abs(count - targetTriangles);
      const Id bestError = std::abs(bestCount - targetTriangles);
      if (!haveBest || error < bestError)
      {
        best = std::move(trial);
        bestCount = count;
        haveBest = true;
      }
    }
    if (std::abs(count - targetTriangles) <= tolerance || count == 0 ||
      epsilon >= std::numeric_limits<float>::max())
    {
      break;
    }
    impl.ComputeActivation();
    aim = static_cast<Id>(
      std::max<std::int64_t>(1, targetTriangles + (impl.EstimateAt(epsilon) - count)));
  }
  if (!haveBest)
  {
    return false;
  }
  level = std::move(best);
  impl.Commit(level);
  return true;
}

Id OctreeClustering::GetCurrentTriangleCount() const
{
  return this->Impl->PreviousTriangles();
}

Id OctreeClustering::GetNumberOfInternalNodes() const
{
  return this->Impl->Tree.NumberOfInternalNodes();
}

Id OctreeClustering::GetNumberOfRoots() const
{
  const ClusterTree& tree = this->Impl->Tree;
  Id roots = 0;
  for (Id node = 0; node < tree.NV + tree.NumberOfInternalNodes(); ++node)
  {
    roots += tree.Parent(node) == InvalidId ? 1 : 0;
  }
  return roots;
}

int OctreeClustering::GetTreeDepth() const
{
  return this->Impl->Tree.Depth;
}

Id OctreeClustering::GetNumberOfEvaluatedNodes() const
{
  return this->Impl->Evaluated;
}

const ClusterTree& OctreeClustering::GetTree() const
{
  return this->Impl->Tree;
}

//------------------------------------------------------------------------------
double OctreeClustering::CheckNodeQuadrics(Id count) const
{
  // The tree keeps e1 only: recompute it from the related triangle set of a few nodes and
  // compare (a wrong inclusion-exclusion would show as a different e1).
  const Internals& impl = *this->Impl;
  const ClusterTree& tree = impl.Tree;
  const Id ni = tree.NumberOfInternalNodes();
  const Id stride = std::max<Id>(1, ni / std::max<Id>(1, count));
  double worst = 0.0;
  for (Id i = 0; i < ni; i += stride)
  {
    const ClusterNode& n = tree.Nodes[i];
    Quadric q;
    tree.RelatedQuadric(tree.NV + i, q, nullptr, nullptr);
    double centre[3];
    tree.Centroid(tree.NV + i, centre);
    double rep[3];
    MinimizeQuadric(q, centre, impl.Options.PlacementTolerance, rep);
    const double weight = q.Weight();
    const double e1 = weight > 0.0 ? std::sqrt(q.Evaluate(rep) / weight) : 0.0;
    worst = std::max(worst, std::abs(e1 - n.E1) / tree.Size);
  }
  return worst;
}

} // namespace meshlod
