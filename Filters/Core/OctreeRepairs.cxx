// Octree clustering: the repairs of a trial level (see OctreeClusteringInternals.h): folds, fins,
// breaks, pinched edges and vertices; the clusters of a triangle that needs one are marked, and
// the trial is made again with them split.
#include "ConcurrentForest.h"
#include "FreshMemory.h"
#include "GroupByKey.h"
#include "OctreeClusteringInternals.h"
#include "PieceGenus.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>

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

// Joins the points of a triangle in a forest of points (the pieces of a level).
void JoinTriangle(ConcurrentForest& pieces, const Id* tri)
{
  pieces.Join(tri[0], tri[1]);
  pieces.Join(tri[0], tri[2]);
}

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
  ConcurrentForest pieces(points);
  vtkSMPTools::For(0, triangles, [&](Id begin, Id end) {
    for (Id t = begin; t < end; ++t)
    {
      JoinTriangle(pieces, tri + 3 * t);
    }
  });
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
  std::vector<Id> group(this->PreviousPiece.begin(), this->PreviousPiece.end());
  this->PreviousHandles =
    HandleMeasures(tri, triangles, group, count, &this->PreviousSides);
  if (count <= 1)
  {
    std::vector<std::uint32_t>().swap(this->PreviousPiece); // one piece: PieceOf says 0
  }
}

//------------------------------------------------------------------------------
Id OctreeClustering::Internals::MarkAnnuli(Synthesis& s)
{
  // A cluster whose previous points, with the previous edges and triangles among them, have an
  // Euler characteristic below 1 holds a loop of edges around no triangles of its own: around a
  // handle, or a tube's whole cross-section (a Boy surface's stitched seam: one cluster of 223
  // points, 506 edges and 283 triangles). Merged into one point, the loop is gone and the
  // handle with it, though the cluster's link is whole. Twice the characteristic per cluster:
  // two per point, two per triangle, and minus one per side inside it (two for a boundary side,
  // which no other triangle counts). Not judged: a cluster with a side of three triangles or
  // more inside (a curve where sheets meet), whose edges the sides do not count.
  const Id clusters = static_cast<Id>(s.Cut.size());
  std::vector<Id> twiceChi = FreshVector<Id>(clusters, 0);
  std::vector<unsigned char> judged = FreshVector<unsigned char>(clusters, 1);
  const Id previousPoints = this->PreviousPoints();
  for (Id p = 0; p < previousPoints; ++p)
  {
    twiceChi[s.PointCluster[p]] += 2;
  }
  const Id previousTriangles = this->PreviousTriangles();
  const Id* prev = this->PreviousTriangleData();
  for (Id t = 0; t < previousTriangles; ++t)
  {
    const Id k[3] = { s.PointCluster[prev[3 * t]], s.PointCluster[prev[3 * t + 1]],
      s.PointCluster[prev[3 * t + 2]] };
    for (int c = 0; c < 3; ++c)
    {
      if (k[c] == k[(c + 1) % 3])
      {
        const unsigned char flags = this->PreviousSides[t];
        twiceChi[k[c]] -= SideOnBoundary(flags, c) ? 2 : 1;
        judged[k[c]] &= SideNonManifold(flags, c) ? 0 : 1;
      }
    }
    twiceChi[k[0]] += k[0] == k[1] && k[1] == k[2] ? 2 : 0;
  }
  std::vector<Id> annuli;
  for (Id k = 0; k < clusters; ++k)
  {
    if (judged[k] && twiceChi[k] < 2)
    {
      annuli.push_back(k);
    }
  }
  return annuli.empty() ? 0 : this->MarkChanged(s, annuli, false);
}

//------------------------------------------------------------------------------
bool OctreeClustering::Internals::LosesHandle(const Synthesis& s) const
{
  // The trial's triangles grouped by the previous piece their clusters come from (a cluster's
  // previous points lie in one piece): each piece that keeps triangles must keep its measure.
  // (A piece that vanishes whole is the vanishing rules' business, not a lost handle.)
  std::vector<Id> group = FreshVector<Id>(s.Cut.size(), 0);
  const Id previousPoints = this->PreviousPoints();
  for (Id p = 0; p < previousPoints; ++p)
  {
    group[s.PointCluster[p]] = this->PieceOf(p);
  }
  std::vector<Id> kept; // the triangles the level would have (as Finalize takes them)
  for (const Id j : this->KeptTriangles(s))
  {
    kept.insert(kept.end(), s.Triangles.begin() + 3 * j, s.Triangles.begin() + 3 * j + 3);
  }
  const std::vector<PieceMeasure> now = HandleMeasures(
    kept.data(), static_cast<Id>(kept.size() / 3), group, this->PreviousPieces);
  for (std::uint32_t piece = 0; piece < this->PreviousPieces; ++piece)
  {
    // (A surface that touches itself at a point counts as its parts there: one of them that
    // vanishes into the point is lost too, as one of two tori sharing a vertex was.)
    if (now[piece].Measured && this->PreviousHandles[piece].Measured &&
      now[piece] != this->PreviousHandles[piece])
    {
      return true;
    }
  }
  return false;
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
  ConcurrentForest after(clusters); // the clusters joined by the kept triangles
  std::vector<unsigned char> alive = FreshVector<unsigned char>(clusters, 0);
  for (Id j = 0; j < kept; ++j)
  {
    if (!s.Duplicate[j])
    {
      const Id* tri = s.Triangles.data() + 3 * j;
      JoinTriangle(after, tri);
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
  // Each side listed at its smaller cluster, packed with the larger (ListSidesByLowerPoint):
  // sorting a cluster's entries brings the triangles of each of its edges together (n log n
  // even around a vertex with very many triangles).
  std::vector<Id> offsets;
  std::vector<std::uint64_t> entries;
  ListSidesByLowerPoint(s.Triangles.data(), kept, clusters, s.Duplicate.data(), offsets, entries);
  auto triangleOf = [&](std::size_t x) { return SideCorner(entries[x]) / 3; };
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
        for (std::size_t x = first; x < last;)
        {
          std::size_t y = x;
          bool watched = false;
          for (; y < last && SideHigherPoint(entries[y]) == SideHigherPoint(entries[x]); ++y)
          {
            watched = watched || s.Involved(triangleOf(y));
          }
          if (y - x > 2 && watched && !onCurve(k, SideHigherPoint(entries[x]), y - x))
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

} // namespace meshlod
