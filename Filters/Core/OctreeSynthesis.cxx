// Octree clustering: a level from a cut of the cluster tree (see OctreeClusteringInternals.h).
#include "FreshMemory.h"
#include "GroupByKey.h"
#include "OctreeClusteringInternals.h"
#include "TriangulationFlips.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>

namespace meshlod
{
using namespace octree;

namespace
{
// The clusters of the kept triangles j for which flagged(j) holds, three per triangle.
template <typename Flagged>
std::vector<Id> ClustersOf(const Synthesis& s, Flagged flagged)
{
  std::vector<Id> clusters;
  const Id kept = static_cast<Id>(s.From.size());
  for (Id j = 0; j < kept; ++j)
  {
    if (flagged(j))
    {
      const auto first = s.Triangles.begin() + 3 * j;
      clusters.insert(clusters.end(), first, first + 3);
    }
  }
  return clusters;
}

// Union-find over 0..n-1 (FindRoot's forest; each root the smallest of its set).
struct Pieces
{
  std::vector<Id> Up;
  explicit Pieces(Id n)
    : Up(n)
  {
    std::iota(this->Up.begin(), this->Up.end(), Id(0));
  }
  Id Root(Id k) { return FindRoot(this->Up, k); }
  void JoinTriangle(const Id* tri)
  {
    for (int c = 1; c < 3; ++c)
    {
      const Id a = this->Root(tri[0]), b = this->Root(tri[c]);
      this->Up[std::max(a, b)] = std::min(a, b);
    }
  }
};

// A cluster's link (MarkPinchedVertices): the far edges of its kept triangles, two ends each,
// and room to join them, kept by each thread from one cluster to the next.
struct LinkScratch
{
  std::vector<Id> Ends, Vertices, Up;
};

// Whether the link in mine.Ends falls apart: two or more components.
bool LinkFallsApart(LinkScratch& mine)
{
  // Components of the link: union-find over its vertices, numbered by sorting.
  mine.Vertices = mine.Ends;
  std::sort(mine.Vertices.begin(), mine.Vertices.end());
  mine.Vertices.erase(
    std::unique(mine.Vertices.begin(), mine.Vertices.end()), mine.Vertices.end());
  const Id n = static_cast<Id>(mine.Vertices.size());
  mine.Up.resize(n);
  std::iota(mine.Up.begin(), mine.Up.end(), Id(0));
  auto local = [&](Id v)
  {
    return static_cast<Id>(
      std::lower_bound(mine.Vertices.begin(), mine.Vertices.end(), v) -
      mine.Vertices.begin());
  };
  Id components = n;
  for (std::size_t e = 0; e + 1 < mine.Ends.size(); e += 2)
  {
    const Id a = FindRoot(mine.Up, local(mine.Ends[e]));
    const Id b = FindRoot(mine.Up, local(mine.Ends[e + 1]));
    if (a != b)
    {
      mine.Up[std::max(a, b)] = std::min(a, b);
      --components;
    }
  }
  return components > 1;
}
} // namespace

//------------------------------------------------------------------------------
// The connected pieces of the current level (the previous one for the next trial), once per
// committed level; only MarkBreaks reads them, which runs with PreserveTopology alone.
void OctreeClustering::Internals::LabelPreviousPieces()
{
  if (!this->Options.PreserveTopology)
  {
    return;
  }
  const Id points = this->PreviousPoints();
  const Id triangles = this->PreviousTriangles();
  const Id* tri = this->PreviousTriangleData();
  Pieces pieces(points);
  for (Id t = 0; t < triangles; ++t)
  {
    pieces.JoinTriangle(tri + 3 * t);
  }
  // Numbered 0, 1, ... in the order of their smallest point (a root comes before the rest of
  // its piece), so that MarkBreaks needs one entry per piece, not per point.
  ResizeFresh(this->PreviousPiece, points);
  std::uint32_t count = 0;
  for (Id p = 0; p < points; ++p)
  {
    const Id root = pieces.Root(p);
    this->PreviousPiece[p] = root == p ? count++ : this->PreviousPiece[root];
  }
  this->PreviousPieces = count;
  if (count <= 1)
  {
    std::vector<std::uint32_t>().swap(this->PreviousPiece); // one piece: PieceOf says 0
  }
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
  ResizeFresh(s.PointCluster, previousPoints);
  vtkSMPTools::For(0,
    previousPoints,
    [&](Id begin, Id end)
    {
      for (Id p = begin; p < end; ++p)
      {
        s.PointCluster[p] = this->ClusterOfVertex[this->FirstVertex(this->NodeOfPoint(p))];
      }
    });
  ResizeFresh(s.Reps, 3 * static_cast<size_t>(clusters));
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
  std::vector<Id> count = FreshVector<Id>(clusters, 0);
  std::vector<Id> some = FreshVector<Id>(clusters, InvalidId);
  for (Id p = 0; p < previousPoints; ++p)
  {
    ++count[s.PointCluster[p]];
    some[s.PointCluster[p]] = p;
  }
  ResizeFresh(s.Changed, clusters);
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
  // Counted before written: From, which lives through the trial, gets only the room it needs.
  const ParallelCompaction survivors(previousTriangles, nonDegenerate);
  const Id kept = survivors.Count();
  ResizeFresh(s.From, kept);
  survivors.Write(nonDegenerate, [&](Id t, Id slot) { s.From[slot] = t; });
  ResizeFresh(s.Triangles, 3 * static_cast<size_t>(kept));
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
// Triangles with the same three clusters as an earlier one: SameDuplicate when an earlier one
// has the same orientation, else OppositeDuplicate (the first of its orientation). Triangles
// are grouped by their smallest cluster, then sorted within the group by the other two, then
// by their order: comparing every pair of a group was quadratic where one cluster keeps
// thousands of triangles (cones sharing their apex).
void OctreeClustering::Internals::MarkDuplicates(Synthesis& s) const
{
  const Id kept = static_cast<Id>(s.From.size());
  const Id clusters = static_cast<Id>(s.Cut.size());
  const std::vector<Id>& tris = s.Triangles;
  auto smallest = [&](Id j)
  { return std::min(tris[3 * j], std::min(tris[3 * j + 1], tris[3 * j + 2])); };
  std::vector<Id> offsets, grouped;
  GroupByKey(
    static_cast<size_t>(clusters),
    [&](auto&& emit) {
      for (Id j = 0; j < kept; ++j)
      {
        emit(smallest(j), j);
      }
    },
    offsets, grouped);
  AssignFresh(s.Duplicate, kept, 0);
  vtkSMPTools::For(0,
    clusters,
    [&](Id begin, Id end)
    {
      // Per triangle of the group: its other two clusters in turn from the smallest one (the
      // orientation: the second below the third or not), and the triangle.
      struct Entry
      {
        Id Second, Third, Triangle;
        Id Low() const { return std::min(this->Second, this->Third); }
        Id High() const { return std::max(this->Second, this->Third); }
      };
      std::vector<Entry> entries;
      for (Id k = begin; k < end; ++k)
      {
        entries.clear();
        for (Id x = offsets[k]; x < offsets[k + 1]; ++x)
        {
          const Id* a = tris.data() + 3 * grouped[x];
          const int c = a[0] == k ? 0 : (a[1] == k ? 1 : 2);
          entries.push_back({ a[(c + 1) % 3], a[(c + 2) % 3], grouped[x] });
        }
        std::sort(entries.begin(), entries.end(), [](const Entry& e, const Entry& f) {
          return std::make_tuple(e.Low(), e.High(), e.Triangle) <
            std::make_tuple(f.Low(), f.High(), f.Triangle);
        });
        bool seen[2] = { false, false }; // an earlier triangle of the run in each orientation
        for (std::size_t i = 0; i < entries.size(); ++i)
        {
          const Entry& e = entries[i];
          if (i == 0 || e.Low() != entries[i - 1].Low() || e.High() != entries[i - 1].High())
          {
            seen[0] = seen[1] = false;
          }
          const int turn = e.Second < e.Third ? 0 : 1;
          s.Duplicate[e.Triangle] =
            seen[turn] ? SameDuplicate : (seen[1 - turn] ? OppositeDuplicate : 0);
          seen[turn] = true;
        }
      }
    });
}

//------------------------------------------------------------------------------
// The normal (not normalised) of triangle t of the previous level, at its points' positions.
void OctreeClustering::Internals::PreviousNormal(Id t, double normal[3]) const
{
  const Id* tri = this->PreviousTriangleData() + 3 * t;
  double p[3][3];
  for (int c = 0; c < 3; ++c)
  {
    this->RepresentativeOf(this->NodeOfPoint(tri[c]), p[c]);
  }
  Normal(p[0], p[1], p[2], normal);
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
  std::vector<unsigned char> needed = FreshVector<unsigned char>(clusters, 0);
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
  std::vector<double> normals = FreshVector<double>(3 * static_cast<size_t>(clusters), 0.0);
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
  std::vector<unsigned char> folded = FreshVector<unsigned char>(kept, 0);
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
        bool ownSheet = false;
        for (int c = 0; c < 3; ++c)
        {
          ownSheet = ownSheet || this->Tree.HoldsCurve(s.Cut[tri[c]]) ||
            this->Tree.HoldsSeam(s.Cut[tri[c]]);
        }
        if (ownSheet)
        {
          // The surface normal at a curve point sums the sheets meeting there, which may
          // point anywhere, and so does the normal at a seam, where the windings on either side
          // disagree (on Boy's surface, 300 x 300, asked for 1%: 10,494 triangles, most of the
          // seam's triangles refused as folds; 4,708 comparing the own triangle): the
          // triangle's own sheet is compared, as the previous level had it.
          this->PreviousNormal(s.From[j], surface);
        }
        else
        {
          for (int c = 0; c < 3; ++c)
          {
            for (int i = 0; i < 3; ++i)
            {
              surface[i] += normals[3 * tri[c] + i];
            }
          }
        }
        Normal(s.Reps.data() + 3 * tri[0],
          s.Reps.data() + 3 * tri[1],
          s.Reps.data() + 3 * tri[2],
          after);
        folded[j] = Dot(surface, after) > 0.0 ? 0 : 1;
      }
    });
  return this->MarkChanged(s, ClustersOf(s, [&](Id j) { return folded[j] != 0; }), false);
}

//------------------------------------------------------------------------------
// Fins: two kept triangles on the same three clusters in opposite order, the two sides of a
// thin part folded onto each other. Removing the second as a duplicate left the first facing
// one side only: a hole, a non-manifold vertex or a triangle whose correspondence has the
// wrong orientation (a rough terrain and sphere had each). Like folds, the changed clusters
// of the second are refused.
Id OctreeClustering::Internals::MarkFins(Synthesis& s)
{
  const auto fin = [&](Id j) { return s.Duplicate[j] == OppositeDuplicate; };
  return this->MarkChanged(s, ClustersOf(s, fin), false);
}

//------------------------------------------------------------------------------
// Breaks: a connected piece of the previous level that the kept triangles split into two or
// more pieces that keep triangles. Where a thin part (a tube, a rod, a plate's rim) had its
// whole cross-section fall into one cluster, its triangles there degenerate: the part breaks in
// two, each piece capped, and the input around the gap is as far from the level as the gap is
// long (a tube of 0.7% of the diagonal in radius lost whole turns: 13.6% Hausdorff distance at
// an estimated error under 1%). The changed clusters of the previous triangles that straddle
// the kept pieces are marked, as for a fold. A piece that keeps no triangle at all (a small
// closed surface merged whole) is MarkFarVanishing's.
Id OctreeClustering::Internals::MarkBreaks(Synthesis& s)
{
  const Id kept = static_cast<Id>(s.From.size());
  const Id clusters = static_cast<Id>(s.Cut.size());
  Pieces after(clusters); // the clusters joined by the kept triangles
  std::vector<unsigned char> alive = FreshVector<unsigned char>(clusters, 0);
  for (Id j = 0; j < kept; ++j)
  {
    if (!s.Duplicate[j])
    {
      const Id* tri = s.Triangles.data() + 3 * j;
      after.JoinTriangle(tri);
      alive[tri[0]] = alive[tri[1]] = alive[tri[2]] = 1;
    }
  }
  // A previous piece is broken when its clusters that keep triangles lie in two kept pieces.
  // (A cluster's previous points are connected: they lie in one previous piece.)
  const Id previousPoints = this->PreviousPoints();
  std::vector<Id> keptPiece(this->PreviousPieces, InvalidId); // by previous piece
  std::vector<unsigned char> broken = FreshVector<unsigned char>(this->PreviousPieces, 0);
  bool any = false;
  for (Id p = 0; p < previousPoints; ++p)
  {
    const Id k = s.PointCluster[p];
    if (alive[k])
    {
      const Id piece = this->PieceOf(p), now = after.Root(k);
      if (keptPiece[piece] == InvalidId)
      {
        keptPiece[piece] = now;
      }
      else if (keptPiece[piece] != now)
      {
        broken[piece] = 1;
        any = true;
      }
    }
  }
  if (!any)
  {
    return 0;
  }
  const Id previousTriangles = this->PreviousTriangles();
  const Id* prev = this->PreviousTriangleData();
  std::vector<Id> straddling;
  for (Id t = 0; t < previousTriangles; ++t)
  {
    const Id* tri = prev + 3 * t;
    const Id k[3] = { s.PointCluster[tri[0]], s.PointCluster[tri[1]], s.PointCluster[tri[2]] };
    const Id now = after.Root(k[0]);
    if (broken[this->PieceOf(tri[0])] &&
      (after.Root(k[1]) != now || after.Root(k[2]) != now))
    {
      straddling.insert(straddling.end(), k, k + 3);
    }
  }
  return this->MarkChanged(s, straddling, false);
}

//------------------------------------------------------------------------------
Id OctreeClustering::Internals::MarkChanged(Synthesis& s,
  const std::vector<Id>& clusters,
  bool lasting)
{
  Id marked = 0;
  auto mark = [&](Id node)
  {
    const Id i = node - this->NV;
    if (node < this->NV || this->State[i] == NodeState::Inadmissible)
    {
      return;
    }
    // A fold refusal is counted once; a pinch on a refused node still makes it lasting.
    marked += this->Refused[i] ? 0 : 1;
    if (lasting)
    {
      this->State[i] = NodeState::Inadmissible;
    }
    else if (!this->Refused[i])
    {
      this->Refused[i] = 1;
      this->RefusedNodes.push_back(i);
    }
    this->UpdateThreshold(i);
  };
  std::vector<unsigned char> split = FreshVector<unsigned char>(this->SplitFully ? s.Cut.size() : 0, 0);
  for (const Id k : clusters)
  {
    if (s.Changed[k])
    {
      mark(s.Cut[k]);
      if (this->SplitFully)
      {
        split[k] = 1;
      }
    }
  }
  if (this->SplitFully)
  {
    // Every node from a previous point of a split cluster up to the cluster: the next cut
    // descends to those points (which qualify: they were clusters at the previous epsilon).
    const Id previousPoints = this->PreviousPoints();
    for (Id p = 0; p < previousPoints; ++p)
    {
      const Id k = s.PointCluster[p];
      if (!split[k])
      {
        continue;
      }
      for (Id node = this->NodeOfPoint(p); node != s.Cut[k];)
      {
        node = this->Tree.Parent(node);
        mark(node);
      }
    }
  }
  return marked;
}

//------------------------------------------------------------------------------
// Pinched vertices: a cluster whose kept triangles form two or more fans that share no edge
// (their far edges, the cluster's link, fall apart), where one of those triangles is involved.
// A thin part whose cross-section fell into a cluster can pinch there instead of breaking:
// the pieces on either side stay joined at that one cluster, so MarkBreaks, which joins pieces
// at their clusters, does not see the break (a thin tube came out as a chain of 12 closed
// pieces). Clusters holding curve points or locked vertices have several fans by nature and
// are left alone. Like folds, the changed clusters of the triangles around it are marked.
Id OctreeClustering::Internals::MarkPinchedVertices(Synthesis& s)
{
  const Id kept = static_cast<Id>(s.From.size());
  const Id clusters = static_cast<Id>(s.Cut.size());
  // The kept triangles around each cluster (counting sort by cluster).
  std::vector<Id> offsets, around;
  GroupByKey(
    static_cast<size_t>(clusters),
    [&](auto&& emit) {
      for (Id j = 0; j < kept; ++j)
      {
        for (int c = 0; c < 3 && !s.Duplicate[j]; ++c)
        {
          emit(s.Triangles[3 * j + c], j);
        }
      }
    },
    offsets, around);
  std::vector<unsigned char> pinched = FreshVector<unsigned char>(clusters, 0);
  vtkSMPThreadLocal<LinkScratch> scratch;
  vtkSMPTools::For(0,
    clusters,
    [&](Id begin, Id end)
    {
      LinkScratch& mine = scratch.Local();
      for (Id k = begin; k < end; ++k)
      {
        const Id first = offsets[k], last = offsets[k + 1];
        const Id node = s.Cut[k];
        const bool locked =
          this->Tree.IsLeaf(node) ? this->Tree.IsLocked(node) : this->Tree.Internal(node).Locked;
        if (last - first < 2 || locked || this->Tree.HoldsCurve(node))
        {
          continue;
        }
        bool involved = false;
        mine.Ends.clear();
        for (Id x = first; x < last; ++x)
        {
          const Id j = around[x];
          involved = involved || s.Involved(j);
          const Id* tri = s.Triangles.data() + 3 * j;
          for (int c = 0; c < 3; ++c)
          {
            if (tri[c] != k)
            {
              mine.Ends.push_back(tri[c]);
            }
          }
        }
        if (!involved)
        {
          continue;
        }
        pinched[k] = LinkFallsApart(mine) ? 1 : 0;
      }
    });
  std::vector<Id> marks;
  for (Id k = 0; k < clusters; ++k)
  {
    if (pinched[k])
    {
      for (Id x = offsets[k]; x < offsets[k + 1]; ++x)
      {
        const auto corners = s.Triangles.begin() + 3 * around[x];
        marks.insert(marks.end(), corners, corners + 3);
      }
    }
  }
  return this->MarkChanged(s, marks, false);
}

//------------------------------------------------------------------------------
// The edges between clusters that curve edges of the input join (a curve where sheets meet,
// and the edges of more than two triangles between two locked vertices), with the number of
// triangles each must keep, sorted; empty on a mesh without such curves. `shrunk` receives
// the clusters whose two curve edges lead to the same cluster: a closed curve down to two
// clusters, which its sheets no longer keep apart (a sheet inside it would vanish, and the
// curve with it, without an edge of unusual count to tell).
std::vector<CurveEdge> OctreeClustering::Internals::CurveEdgesOf(std::vector<Id>& shrunk) const
{
  std::vector<CurveEdge> edges;
  shrunk.clear();
  const ClusterTree& tree = this->Tree;
  if (tree.Curves.empty())
  {
    return edges;
  }
  for (Id v = 0; v < this->NV; ++v)
  {
    if (!tree.IsCurve(v))
    {
      continue;
    }
    for (const Id w : tree.Curves[v].Neighbours)
    {
      const Id a = this->ClusterOfVertex[v], b = this->ClusterOfVertex[w];
      if (a != b)
      {
        edges.push_back(CurveEdge{ a, b, tree.Curves[v].Sheets });
      }
    }
  }
  // Each curve cluster has two curve edges leading out (CurveMayMerge), both listed from it.
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i + 1 < edges.size(); ++i)
  {
    if (edges[i] == edges[i + 1])
    {
      shrunk.push_back(edges[i].Low);
      shrunk.push_back(edges[i].High);
    }
  }
  for (CurveEdge& e : edges)
  {
    if (e.High < e.Low)
    {
      std::swap(e.Low, e.High);
    }
  }
  // A curve of one edge between two junctions: both ends stay (locked), the edge must keep
  // its triangles too (two sheets' clusters merged across it would leave it looking manifold).
  for (const ClusterTree::LockedEdge& e : tree.LockedEdges)
  {
    const Id a = this->ClusterOfVertex[e.A], b = this->ClusterOfVertex[e.B];
    edges.push_back(CurveEdge{ std::min(a, b), std::max(a, b), e.Sheets });
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
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
  // Each entry packs the larger cluster (high bits) and the triangle, so that sorting a
  // cluster's entries brings the triangles of each of its edges together (n log n even around a
  // vertex with very many triangles).
  std::vector<Id> offsets;
  std::vector<std::uint64_t> entries;
  GroupByKey(
    static_cast<size_t>(clusters),
    [&](auto&& emit) {
      for (Id j = 0; j < kept; ++j)
      {
        for (int c = 0; c < 3 && !s.Duplicate[j]; ++c)
        {
          const Id a = s.Triangles[3 * j + c], b = s.Triangles[3 * j + (c + 1) % 3];
          emit(std::min(a, b),
            (static_cast<std::uint64_t>(std::max(a, b)) << 32) | static_cast<std::uint32_t>(j));
        }
      }
    },
    offsets, entries);
  auto triangleOf = [&](std::size_t x) { return static_cast<Id>(entries[x] & 0xffffffffu); };
  std::vector<Id> marks; // the clusters of the triangles on pinched edges, and shrunk curves
  const std::vector<CurveEdge> curveEdges = this->CurveEdgesOf(marks);
  // An edge that is the image of curve edges keeps the curve's k triangles: not a pinch.
  auto onCurve = [&](Id low, Id high, std::size_t run)
  {
    const CurveEdge key{ low, high, 0 };
    const auto it = std::lower_bound(curveEdges.begin(), curveEdges.end(), key);
    return it != curveEdges.end() && it->Low == low && it->High == high &&
      static_cast<std::size_t>(it->Sheets) == run;
  };
  // pinched[x]: entry x is on an edge with three or more triangles, one of them involved.
  std::vector<unsigned char> pinched = FreshVector<unsigned char>(entries.size(), 0);
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
          if (y - x > 2 && watched && !onCurve(k, static_cast<Id>(entries[x] >> 32), y - x))
          {
            std::fill(pinched.begin() + x, pinched.begin() + y, 1);
          }
          x = y;
        }
      }
    });
  // A curve edge that kept fewer triangles than its curve has sheets: the curve was cut open
  // there (a sheet along it vanished, or two of its triangles became one).
  for (const CurveEdge& e : curveEdges)
  {
    const auto first = entries.begin() + offsets[e.Low];
    const auto last = entries.begin() + offsets[e.Low + 1];
    const std::uint64_t key = static_cast<std::uint64_t>(e.High) << 32;
    const auto from = std::lower_bound(first, last, key);
    const auto to = std::lower_bound(from, last, key + (std::uint64_t(1) << 32));
    if (to - from != e.Sheets)
    {
      marks.push_back(e.Low);
      marks.push_back(e.High);
      std::fill(
        pinched.begin() + (from - entries.begin()), pinched.begin() + (to - entries.begin()), 1);
    }
  }
  for (std::size_t x = 0; x < pinched.size(); ++x)
  {
    if (pinched[x])
    {
      const Id j = triangleOf(x);
      marks.insert(marks.end(), s.Triangles.begin() + 3 * j, s.Triangles.begin() + 3 * j + 3);
    }
  }
  return this->MarkChanged(s, marks, true);
}

//------------------------------------------------------------------------------
// Points, triangles, targets, ranks and sources of a level from its synthesis.
void OctreeClustering::Internals::Finalize(Synthesis& s, ClusterLevel& level) const
{
  const std::vector<Id> final = this->KeptTriangles(s);
  const Id count = static_cast<Id>(final.size());
  if (count == 0)
  {
    return; // everything collapsed: no level
  }
  std::vector<Id> newId;
  const Id points = this->SetLevelPoints(s, final, newId, level);
  this->SetLevelTriangles(s, final, newId, level);
  const std::vector<Id> redirect = this->RedirectVanished(s, newId);
  this->SetTargetsAndRanks(s, newId, redirect, points, level);
  this->SetSources(s, newId, points, level);
}

//------------------------------------------------------------------------------
// The kept triangles that go into the level: those that repeat no earlier one, and without the
// topology repairs those that repeat one in the opposite order.
std::vector<Id> OctreeClustering::Internals::KeptTriangles(const Synthesis& s) const
{
  // Without the topology repairs two triangles on the same clusters in opposite orders (a
  // thin part folded flat) both stay: each is the image of its finer triangles, so MorphTargetId
  // keeps every triangle's orientation (dropping one left finer triangles mapped onto the
  // reverse of a kept one).
  const bool free = !this->Options.PreserveTopology;
  std::vector<Id> final;
  ResizeFresh(final, s.From.size());
  const Id count = ParallelCompact(
    static_cast<Id>(s.From.size()),
    [&](Id j) { return s.Duplicate[j] == 0 || (free && s.Duplicate[j] == OppositeDuplicate); },
    [&](Id j, Id slot) { final[slot] = j; });
  final.resize(count);
  return final;
}

//------------------------------------------------------------------------------
// The level's points and its estimated error; newId maps a cluster to its point (InvalidId for
// a cluster that no triangle of `final` uses). Returns the number of points.
Id OctreeClustering::Internals::SetLevelPoints(const Synthesis& s,
  const std::vector<Id>& final,
  std::vector<Id>& newId,
  ClusterLevel& level) const
{
  const Id clusters = static_cast<Id>(s.Cut.size());
  // Points: the clusters some triangle uses, in depth-first order.
  newId = FreshVector<Id>(clusters, InvalidId);
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
  ResizeFresh(level.Mesh.Points, 3 * static_cast<size_t>(points));
  ResizeFresh(level.PointNode, points);
  ResizeFresh(level.PointVertexCount, points);
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
  return points;
}

//------------------------------------------------------------------------------
// The level's triangles (the kept triangles `final` on their points) and the input triangle each
// comes from.
void OctreeClustering::Internals::SetLevelTriangles(const Synthesis& s,
  const std::vector<Id>& final,
  const std::vector<Id>& newId,
  ClusterLevel& level) const
{
  const Id count = static_cast<Id>(final.size());
  ResizeFresh(level.Mesh.Triangles, 3 * static_cast<size_t>(count));
  ResizeFresh(level.LevelZeroTriangle, count);
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
}

//------------------------------------------------------------------------------
// Per cluster without a point (newId InvalidId), the kept cluster that takes its previous points
// (InvalidId for the others).
std::vector<Id> OctreeClustering::Internals::RedirectVanished(
  const Synthesis& s, const std::vector<Id>& newId) const
{
  const Id clusters = static_cast<Id>(s.Cut.size());
  const Id previousPoints = this->PreviousPoints();
  const Id previousTriangles = this->PreviousTriangles();
  const Id* prev = this->PreviousTriangleData();
  // Clusters that lost all their triangles send their previous points to the nearest cluster
  // joined to them by a previous triangle, else to the nearer kept cluster before or after them
  // in depth-first order.
  std::vector<Id> redirect = FreshVector<Id>(clusters, InvalidId);
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
    std::vector<Id> before = FreshVector<Id>(clusters, InvalidId);
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
  return redirect;
}

//------------------------------------------------------------------------------
// Each previous point's target (the point of its cluster, or of the cluster its vanished cluster
// is redirected to) and collapse rank.
void OctreeClustering::Internals::SetTargetsAndRanks(const Synthesis& s,
  const std::vector<Id>& newId,
  const std::vector<Id>& redirect,
  Id points,
  ClusterLevel& level) const
{
  const Id clusters = static_cast<Id>(s.Cut.size());
  const Id previousPoints = this->PreviousPoints();
  // Targets; collapse ranks: the clusters that changed, by increasing error.
  ResizeFresh(level.Target, previousPoints);
  std::vector<unsigned char> receives = FreshVector<unsigned char>(clusters, 0);
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
  vtkSMPTools::Sort(ranked.begin(),
    ranked.end(),
    [&](Id a, Id b)
    {
      const double ea = this->NodeError(s.Cut[a]), eb = this->NodeError(s.Cut[b]);
      return ea < eb || (ea == eb && s.Cut[a] < s.Cut[b]);
    });
  std::vector<Id> rankOfPoint = FreshVector<Id>(points, -1);
  for (size_t r = 0; r < ranked.size(); ++r)
  {
    rankOfPoint[newId[ranked[r]]] = static_cast<Id>(r);
  }
  ResizeFresh(level.Rank, previousPoints);
  for (Id p = 0; p < previousPoints; ++p)
  {
    level.Rank[p] = rankOfPoint[level.Target[p]];
  }
  level.ChangedClusters = static_cast<Id>(ranked.size());
}

//------------------------------------------------------------------------------
void OctreeClustering::Internals::SetSources(
  const Synthesis& s, const std::vector<Id>& newId, Id points, ClusterLevel& level) const
{
  const Id previousPoints = this->PreviousPoints();
  // Sources: the previous points of each cluster, weighted by the input vertices they stand for.
  GroupByKey(
    static_cast<size_t>(points),
    [&](auto&& emit) {
      for (Id p = 0; p < previousPoints; ++p)
      {
        const Id j = newId[s.PointCluster[p]];
        if (j != InvalidId)
        {
          emit(j, p);
        }
      }
    },
    level.SourceOffsets, level.SourceParents);
  ResizeFresh(level.SourceWeights, level.SourceParents.size());
  for (Id j = 0; j < points; ++j)
  {
    for (Id x = level.SourceOffsets[j]; x < level.SourceOffsets[j + 1]; ++x)
    {
      level.SourceWeights[x] = static_cast<float>(
        static_cast<double>(this->VertexCountOfPoint(level.SourceParents[x])) /
        level.PointVertexCount[j]);
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
    if (!this->Options.PreserveTopology)
    {
      break; // the paper's vertex clustering: whatever the cut makes
    }
    // After FlipPasses, a cluster that folds or pinches goes back to the previous level's
    // points at once: each pass then leaves fewer changed clusters, so the loop ends. (A noisy
    // terrain kept 40 non-manifold edges when the passes simply stopped after 16; it needs 31
    // passes of the gradual kind.)
    this->SplitFully = pass >= this->Options.FlipPasses;
    const Id folds = this->MarkFolds(s); // before the pinches, which may make marks lasting
    Id marked = folds + this->MarkFins(s) + this->MarkPinches(s);
    if (marked == 0)
    {
      // Breaks and pinched vertices last, once the level is otherwise clean (passes over the
      // triangles: once or twice per trial instead of on every pass).
      marked = this->MarkBreaks(s);
      marked = marked > 0 ? marked : this->MarkClosedHoles(s, epsilon);
      marked = marked > 0 ? marked : this->MarkFarVanishing(s, epsilon);
      marked = marked > 0 ? marked : this->MarkPinchedVertices(s);
    }
    if (marked == 0)
    {
      break;
    }
    level.FlippedTrianglesFixed += marked;
  }
  this->SplitFully = false;
  this->LiftRefusals(this->TrialRefusals);
  this->Finalize(s, level);
  return level.Mesh.GetNumberOfTriangles();
}

//------------------------------------------------------------------------------
bool OctreeClustering::Internals::ClearRefusals()
{
  const bool any = !this->RefusedNodes.empty();
  this->LiftRefusals(this->RefusedNodes);
  return any;
}

//------------------------------------------------------------------------------
void OctreeClustering::Internals::LiftRefusals(std::vector<Id>& nodes)
{
  for (const Id i : nodes)
  {
    this->Refused[i] = 0;
    this->UpdateThreshold(i);
  }
  nodes.clear();
}

//------------------------------------------------------------------------------
void OctreeClustering::Internals::FlipLevelEdges(ClusterLevel& level) const
{
  // The walks over the input start at the vertex of each cluster nearest its representative.
  const Id points = level.Mesh.GetNumberOfPoints();
  std::vector<Id> start = FreshVector<Id>(points);
  vtkSMPTools::For(0,
    points,
    [&](Id begin, Id end)
    {
      for (Id p = begin; p < end; ++p)
      {
        const Id node = level.PointNode[p];
        const Id first = this->Tree.Position(node);
        double nearest = std::numeric_limits<double>::infinity();
        for (Id pos = first; pos < first + this->Tree.Count(node); ++pos)
        {
          const Id v = this->Tree.Order[pos];
          const double* x = this->Mesh.Point(v);
          const double* r = level.Mesh.Point(p);
          const double d[3] = { x[0] - r[0], x[1] - r[1], x[2] - r[2] };
          if (Dot(d, d) < nearest)
          {
            nearest = Dot(d, d);
            start[p] = v;
          }
        }
      }
    });
  ImproveTriangulation(
    this->Mesh, this->Topology.VertexTriangles, start, level.EstimatedError, level.Mesh);
}

//------------------------------------------------------------------------------
void OctreeClustering::Internals::Commit(ClusterLevel& level)
{
  // The level's clusters qualify again: a trial made after this level's (and not kept) may
  // have marked some of them, and the next level's cut would then go below them and break the
  // nesting. Each was a cluster, so evaluated, admissible and within its epsilon.
  for (const Id node : level.PointNode)
  {
    if (node >= this->NV)
    {
      const Id i = node - this->NV;
      this->Refused[i] = 0;
      if (this->State[i] == NodeState::Inadmissible)
      {
        this->State[i] = NodeState::Admissible;
      }
      this->UpdateThreshold(i);
    }
  }
  this->CurrentTriangles = level.Mesh.Triangles;
  this->CurrentLevelZero = level.LevelZeroTriangle;
  this->PointNode = level.PointNode;
  this->PointVertexCount = level.PointVertexCount;
  this->CurrentEpsilon = level.Epsilon;
  this->LabelPreviousPieces();
  // The next level is built from the triangles as clustered: flipped ones fed forward made the
  // next level's folds worse (metaballs 1%: 0.16% -> 0.18% epsilon for the same count).
  if (this->Options.FlipEdges)
  {
    this->FlipLevelEdges(level);
  }
}

} // namespace meshlod
