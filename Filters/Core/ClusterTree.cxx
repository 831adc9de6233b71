#include "ClusterTree.h"

#include "CacheHint.h"
#include "FreshMemory.h"
#include "GroupByKey.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace meshlod
{
namespace
{
// The tree below this depth (octree depth 4, at most 4096 cells) is built cell by cell in
// parallel, the merges above it serially.
constexpr int TierDepth = 12;

std::uint64_t SpreadBits(std::uint32_t x)
{
  std::uint64_t v = x & 0x1fffffu;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// The inverse of SpreadBits: every third bit of x, from bit 0 up.
std::uint32_t CompactBits(std::uint64_t x)
{
  std::uint64_t v = x & 0x1249249249249249ULL;
  v = (v | v >> 2) & 0x10c30c30c30c30c3ULL;
  v = (v | v >> 4) & 0x100f00f00f00f00fULL;
  v = (v | v >> 8) & 0x1f0000ff0000ffULL;
  v = (v | v >> 16) & 0x1f00000000ffffULL;
  v = (v | v >> 32) & 0x1fffffULL;
  return static_cast<std::uint32_t>(v);
}

// Number of splits of axis c (0 = x, split first) among the first `depth` binary splits.
int AxisSplits(int depth, int c)
{
  return (depth + 2 - c) / 3;
}

// A half-edge (triangle t, edge k from corner k to corner k + 1) at the depth its ends part.
struct HalfEdge
{
  std::int64_t Item; // 3 t + k
  int Depth;
};

// Stable counting sort of half-edges by decreasing depth.
void SortByDepth(std::vector<HalfEdge>& items, std::vector<HalfEdge>& scratch)
{
  constexpr int buckets = ClusterTree::MaxDepth + 1;
  Id counts[buckets + 1] = {};
  for (const HalfEdge& h : items)
  {
    ++counts[ClusterTree::MaxDepth - h.Depth + 1];
  }
  for (int d = 1; d <= buckets; ++d)
  {
    counts[d] += counts[d - 1];
  }
  scratch.resize(items.size());
  for (const HalfEdge& h : items)
  {
    scratch[counts[ClusterTree::MaxDepth - h.Depth]++] = h;
  }
  items.swap(scratch);
}

void ComputeE1(ClusterNode& node, const Quadric& q, const double sum[3], double tolerance)
{
  const double centre[3] = { sum[0] / node.Count, sum[1] / node.Count, sum[2] / node.Count };
  double rep[3];
  MinimizeQuadric(q, centre, tolerance, rep);
  const double weight = q.Weight();
  node.E1 = weight > 0.0 ? static_cast<float>(std::sqrt(q.Evaluate(rep) / weight)) : 0.0f;
}

// What a node needs only while it is built: its quadric and the sum of its vertex positions.
struct Building
{
  Quadric Q;
  double Sum[3] = { 0.0, 0.0, 0.0 };
};

// A node of a finished cell, with its quadric, that the top tier still merges.
using FinishedNode = std::pair<Id, Building>;

// Nodes being created, with their quadrics. The tree's node array has room for every node from
// the start (a node joins two or more parts, so there are fewer than NV): the node with id
// Base + i is written in place, at Tree->Nodes[Base - NV + i], and its quadric is Work[i].
// Lower ids are nodes of the finished cells: only the serial top tier refers to them, and only
// to the cells' top components, whose quadrics are in Finished.
struct NodeStore
{
  Id Base = 0;
  Id Created = 0;
  std::vector<Building> Work;
  ClusterTree* Tree = nullptr;
  const std::vector<FinishedNode>* Finished = nullptr; // by increasing id

  ClusterNode& Record(Id id) { return this->Tree->Nodes[id - this->Tree->NV]; }
  const Building& WorkOf(Id id) const
  {
    if (id >= this->Base)
    {
      return this->Work[id - this->Base];
    }
    // (Always there: a node below Base that the top tier merges is a finished cell's top
    // component, and Finished lists all of them.)
    const auto found = std::lower_bound(this->Finished->begin(), this->Finished->end(), id,
      [](const FinishedNode& node, Id value) { return node.first < value; });
    return found->second;
  }
  Id Create(int depth)
  {
    ClusterNode& node = this->Record(this->Base + this->Created);
    node = ClusterNode();
    node.Depth = static_cast<std::uint8_t>(depth);
    this->Work.emplace_back();
    return this->Base + this->Created++;
  }
  /// Start on the nodes from id `base` on, reusing the room of the quadrics.
  void Restart(Id base)
  {
    this->Base = base;
    this->Created = 0;
    this->Work.clear();
  }
};

// The e1 errors of the nodes `store` created, from their quadrics.
void ComputeCreatedE1(NodeStore& store, double tolerance)
{
  for (Id i = 0; i < store.Created; ++i)
  {
    ComputeE1(store.Record(store.Base + i), store.Work[i].Q, store.Work[i].Sum, tolerance);
  }
}
} // namespace

//------------------------------------------------------------------------------
// Union-find over the vertices, with the node each component currently is.
struct ClusterTree::Builder
{
  ClusterTree& Tree;
  std::vector<Id> UF, UFSize, NodeOf, StampOld, StampNew, NewNode;

  int CommonDepth(Id a, Id b) const
  {
    return ClusterTree::CommonDepth(this->Tree.Codes[a], this->Tree.Codes[b]);
  }

  explicit Builder(ClusterTree& tree)
    : Tree(tree)
  {
    const Id nv = tree.NV;
    ResizeFresh(this->UF, nv);
    std::iota(this->UF.begin(), this->UF.end(), 0);
    AssignFresh(this->UFSize, nv, 1);
    ResizeFresh(this->NodeOf, nv);
    std::iota(this->NodeOf.begin(), this->NodeOf.end(), 0);
    AssignFresh(this->StampOld, nv, -1);
    AssignFresh(this->StampNew, nv, -1);
    AssignFresh(this->NewNode, nv, InvalidId);
  }

  Id Find(Id v) { return FindRoot(this->UF, v); }

  void Attach(Id child, Id parent, NodeStore& store);
  void DesignatedEdges(const Id* tri, int& deep, int& shallow) const;
  void MergeGroup(const HalfEdge* items,
    size_t count,
    int depth,
    Id stamp,
    NodeStore& store,
    std::vector<Id>& touched);
  void MergeSorted(const std::vector<HalfEdge>& items, Id stampBase, NodeStore& store);
};

//------------------------------------------------------------------------------
void ClusterTree::Builder::Attach(Id child, Id parent, NodeStore& store)
{
  const ClusterTree& tree = this->Tree;
  Building leaf;
  const Building* from = &leaf;
  Id count = 1;
  std::uint8_t locked = 0, curve = 0, seam = 0;
  if (child < tree.NV)
  {
    this->Tree.LeafParent[child] = parent;
    double normal[3];
    tree.VertexQuadric(child, leaf.Q, normal);
    tree.RelativePoint(child, leaf.Sum);
    locked = tree.IsLocked(child) ? 1 : 0;
    curve = tree.IsCurve(child) ? 1 : 0;
    seam = tree.IsSeam(child) ? 1 : 0;
  }
  else
  {
    ClusterNode& record = store.Record(child);
    record.Parent = parent;
    from = &store.WorkOf(child);
    count = record.Count;
    locked = record.Locked;
    curve = record.Curve;
    seam = record.Seam;
  }
  ClusterNode& node = store.Record(parent);
  Building& work = store.Work[parent - store.Base];
  work.Q.Add(from->Q);
  for (int c = 0; c < 3; ++c)
  {
    work.Sum[c] += from->Sum[c];
  }
  node.Count += count;
  node.Locked |= locked;
  node.Curve |= curve;
  node.Seam |= seam;
}

//------------------------------------------------------------------------------
// A triangle's vertex pairs first meet, going up the tree, at two nodes: the closest pair at
// the "deep" node, the other two pairs together at the "shallow" node (the node of all three).
// The triangle's plane is counted once per vertex at the leaves, so inclusion-exclusion removes
// it once at each of these nodes; `deep` and `shallow` name the edges whose half-edges do it.
void ClusterTree::Builder::DesignatedEdges(const Id* tri, int& deep, int& shallow) const
{
  int depth[3];
  for (int k = 0; k < 3; ++k)
  {
    depth[k] = this->CommonDepth(tri[k], tri[(k + 1) % 3]);
  }
  deep = 0;
  shallow = 2;
  for (int k = 1; k < 3; ++k)
  {
    deep = depth[k] > depth[deep] ? k : deep;
  }
  for (int k = 1; k >= 0; --k)
  {
    shallow = depth[k] < depth[shallow] ? k : shallow;
  }
  if (shallow == deep)
  {
    shallow = (deep + 1) % 3; // all three pairs meet at one node
  }
}

//------------------------------------------------------------------------------
// All half-edges whose ends first share a cell at `depth`: the components they join become the
// new nodes of that depth, one per connected part of each cell.
void ClusterTree::Builder::MergeGroup(const HalfEdge* items,
  size_t count,
  int depth,
  Id stamp,
  NodeStore& store,
  std::vector<Id>& touched)
{
  const TriangleMesh& mesh = *this->Tree.Mesh;
  touched.clear();
  for (size_t i = 0; i < count; ++i)
  {
    const Id* tri = mesh.Triangle(static_cast<Id>(items[i].Item / 3));
    const int k = static_cast<int>(items[i].Item % 3);
    Id ra = this->Find(tri[k]);
    Id rb = this->Find(tri[(k + 1) % 3]);
    if (ra == rb)
    {
      continue;
    }
    touched.push_back(ra);
    touched.push_back(rb);
    if (this->UFSize[ra] < this->UFSize[rb])
    {
      std::swap(ra, rb);
    }
    this->UF[rb] = ra;
    this->UFSize[ra] += this->UFSize[rb];
  }
  // One new node per merged component, in order of first appearance; its children are the
  // components that merged into it.
  size_t unique = 0;
  for (size_t i = 0; i < touched.size(); ++i)
  {
    const Id r = touched[i];
    if (this->StampOld[r] == stamp)
    {
      continue;
    }
    this->StampOld[r] = stamp;
    touched[unique++] = r;
    const Id root = this->Find(r);
    if (this->StampNew[root] != stamp)
    {
      this->StampNew[root] = stamp;
      this->NewNode[root] = store.Create(depth);
    }
    this->Attach(this->NodeOf[r], this->NewNode[root], store);
  }
  touched.resize(unique);
  for (const Id r : touched)
  {
    const Id root = this->Find(r);
    this->NodeOf[root] = this->NewNode[root];
  }
  // Inclusion-exclusion, and the triangles that degenerate in each node.
  const TriangleTopology& topology = *this->Tree.Topology;
  for (size_t i = 0; i < count; ++i)
  {
    const Id t = static_cast<Id>(items[i].Item / 3);
    const int k = static_cast<int>(items[i].Item % 3);
    const Id* tri = mesh.Triangle(t);
    const bool boundary = topology.IsBoundaryEdge(t, k);
    int deep, shallow;
    this->DesignatedEdges(tri, deep, shallow);
    if (k != deep && k != shallow && !boundary)
    {
      continue;
    }
    const Id node = this->NodeOf[this->Find(tri[k])];
    Quadric& q = store.Work[node - store.Base].Q;
    double p[3][3];
    this->Tree.RelativeTriangle(tri, p);
    Quadric face;
    double n[3];
    TriangleQuadric(p[0], p[1], p[2], face, n);
    if (k == deep || k == shallow)
    {
      q.Add(face, -1.0);
    }
    if (k == deep)
    {
      ++store.Record(node).Dies;
    }
    if (boundary)
    {
      Quadric edge;
      BoundaryEdgeQuadric(p[k], p[(k + 1) % 3], n, this->Tree.Options.BoundaryWeight, edge);
      q.Add(edge, -1.0);
    }
  }
}

//------------------------------------------------------------------------------
void ClusterTree::Builder::MergeSorted(const std::vector<HalfEdge>& items,
  Id stampBase,
  NodeStore& store)
{
  std::vector<Id> touched;
  size_t first = 0;
  while (first < items.size())
  {
    size_t last = first;
    const int depth = items[first].Depth;
    while (last < items.size() && items[last].Depth == depth)
    {
      ++last;
    }
    this->MergeGroup(
      items.data() + first, last - first, depth, stampBase + depth + 1, store, touched);
    first = last;
  }
}

//------------------------------------------------------------------------------
double ClusterTree::CellSize(int depth) const
{
  return std::ldexp(this->Size, -(depth / 3));
}

void ClusterTree::CellBox(Id v, int depth, double low[3], double extent[3]) const
{
  const std::uint64_t code = this->Codes[v];
  for (int c = 0; c < 3; ++c)
  {
    const std::uint32_t q = CompactBits(code >> (2 - c));
    const int splits = AxisSplits(depth, c);
    extent[c] = std::ldexp(this->Size, -splits);
    const std::uint32_t cell = splits > 0 ? q >> (AxisBits - splits) : 0u;
    low[c] = this->Corner[c] - this->Centre[c] + cell * extent[c];
  }
}

//------------------------------------------------------------------------------
void ClusterTree::ComputeFrame()
{
  double lo[3], hi[3];
  this->Mesh->GetBounds(lo, hi);
  double size = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    this->Centre[c] = 0.5 * (lo[c] + hi[c]);
    size = std::max(size, hi[c] - lo[c]);
  }
  // A hair larger than the extent, so that the highest coordinate falls inside the last cell.
  this->Size = size > 0.0 ? size * (1.0 + 1e-9) : 1.0;
  this->Extent = size;
  for (int c = 0; c < 3; ++c)
  {
    this->Corner[c] = this->Centre[c] - 0.5 * this->Size;
  }
}

//------------------------------------------------------------------------------
void ClusterTree::ComputeCodes()
{
  const Id nv = this->NV;
  const TriangleMesh& mesh = *this->Mesh;
  const double scale = std::ldexp(1.0, AxisBits) / this->Size;
  const double top = std::ldexp(1.0, AxisBits) - 1.0;
  ResizeFresh(this->Codes, nv);
  vtkSMPTools::For(0, nv, [&](Id begin, Id end) {
    for (Id v = begin; v < end; ++v)
    {
      const double* p = mesh.Point(v);
      std::uint64_t code = 0;
      for (int c = 0; c < 3; ++c)
      {
        const double q = std::min(top, std::max(0.0, std::floor((p[c] - this->Corner[c]) * scale)));
        code |= SpreadBits(static_cast<std::uint32_t>(q)) << (2 - c);
      }
      this->Codes[v] = code;
    }
  });
  this->PlaceIslands();
}

//------------------------------------------------------------------------------
// Where a rough surface (a scan, noisy or jagged data) crosses a cell face, single vertices and
// small groups poke through it: they lie in the cell beyond, cut off from the rest of that cell.
// Left there they would be clusters of their own (joined to the rest only far up the tree),
// single vertices next to clusters of hundreds: on a noisy sphere asked for 1% of its triangles
// the first cut (783 triangles, 134 of its 428 clusters of 1 to 4 vertices) had 70 clusters to
// split for folds and 64 for fins and pinched edges, and splitting them again, pass after pass,
// left ten times the triangles asked for. So a group of at most IslandVertices vertices that is a
// whole connected part of a cell at least IslandCellEdges times as long as the longest edge at
// the vertex the group is found from takes the code of its nearest neighbour outside (the longest
// common prefix, ties to the lowest id): it joins the part it pokes out of at the bottom of the
// tree. The tree stays a tree, so levels still nest; a node's vertices may then lie a few edges
// outside its cell. (Decided for every vertex from the codes before any change, so the result
// does not depend on the order or the threads. Two islands facing each other across a cell face
// may take each other's codes and stay islands; passing over neighbours in islands, or taking
// only the prefix of the neighbour's cell at the island's depth, came out no better on the
// noisy meshes tried, and the latter clearly worse: a noisy sphere asked for 1% kept 1,425
// triangles for 782 instead of 877, at three times the RMS distance.)
void ClusterTree::PlaceIslands()
{
  constexpr int IslandVertices = 4;
  constexpr double IslandCellEdges = 2.0;
  const Id nv = this->NV;
  const TriangleMesh& mesh = *this->Mesh;
  const VertexTriangleAdjacency& adj = this->Topology->VertexTriangles;
  // The depth of the cells at least IslandCellEdges times the longest edge at v: where they are
  // smaller, every vertex would be alone in its cell.
  auto islandDepth = [&](Id v) {
    double longest = 0.0;
    const double* p = mesh.Point(v);
    for (Id i = adj.Begin(v); i < adj.End(v); ++i)
    {
      const Id* tri = mesh.Triangle(adj.Triangles[i]);
      for (int k = 0; k < 3; ++k)
      {
        const double* q = mesh.Point(tri[k]);
        longest = std::max(longest,
          (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
            (p[2] - q[2]) * (p[2] - q[2]));
      }
    }
    longest = IslandCellEdges * std::sqrt(longest);
    if (!(longest > 0.0) || !(this->Size > longest))
    {
      return -1;
    }
    const double octreeDepth = std::floor(std::log2(this->Size / longest));
    return 3 * static_cast<int>(std::min<double>(AxisBits, octreeDepth));
  };
  const std::vector<std::uint64_t>& codes = this->Codes;
  std::vector<std::uint64_t> placed = FreshCopy(codes.begin(), codes.end());
  vtkSMPTools::For(0, nv, [&](Id begin, Id end) {
    std::vector<Id> island;
    auto inIsland = [&](Id w)
    { return std::find(island.begin(), island.end(), w) != island.end(); };
    for (Id v = begin; v < end; ++v)
    {
      // v's connected part of its cell, unless it has more than IslandVertices vertices.
      const int depth = islandDepth(v);
      if (depth < 0)
      {
        continue;
      }
      island.assign(1, v);
      bool large = false;
      for (std::size_t m = 0; m < island.size() && !large; ++m)
      {
        const Id u = island[m];
        for (Id i = adj.Begin(u); i < adj.End(u) && !large; ++i)
        {
          const Id* tri = mesh.Triangle(adj.Triangles[i]);
          for (int k = 0; k < 3 && !large; ++k)
          {
            const Id w = tri[k];
            if (CommonDepth(codes[u], codes[w]) >= depth && !inIsland(w))
            {
              island.push_back(w);
              large = island.size() > static_cast<std::size_t>(IslandVertices);
            }
          }
        }
      }
      if (large)
      {
        continue;
      }
      int nearest = -1;
      Id outside = InvalidId;
      for (const Id u : island)
      {
        for (Id i = adj.Begin(u); i < adj.End(u); ++i)
        {
          const Id* tri = mesh.Triangle(adj.Triangles[i]);
          for (int k = 0; k < 3; ++k)
          {
            const Id w = tri[k];
            const int common = inIsland(w) ? -1 : CommonDepth(codes[u], codes[w]);
            if (common > nearest || (common == nearest && common >= 0 && w < outside))
            {
              nearest = common;
              outside = w;
            }
          }
        }
      }
      if (outside != InvalidId)
      {
        placed[v] = codes[outside];
      }
    }
  });
  this->Codes.swap(placed);
}

//------------------------------------------------------------------------------
void ClusterTree::Centroid(Id node, double out[3]) const
{
  out[0] = out[1] = out[2] = 0.0;
  const Id first = this->Position(node), count = this->Count(node);
  for (Id pos = first; pos < first + count; ++pos)
  {
    const double* p = this->Mesh->Point(this->Order[pos]);
    for (int c = 0; c < 3; ++c)
    {
      out[c] += p[c];
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    out[c] = out[c] / count - this->Centre[c];
  }
}

//------------------------------------------------------------------------------
void ClusterTree::VertexQuadric(Id v, Quadric& q, double normal[3]) const
{
  q.Clear();
  normal[0] = normal[1] = normal[2] = 0.0;
  const VertexTriangleAdjacency& adj = this->Topology->VertexTriangles;
  for (Id i = adj.Begin(v); i < adj.End(v); ++i)
  {
    const Id t = adj.Triangles[i];
    const Id* tri = this->Mesh->Triangle(t);
    double p[3][3];
    this->RelativeTriangle(tri, p);
    Quadric face;
    double n[3];
    TriangleQuadric(p[0], p[1], p[2], face, n);
    q.Add(face);
    for (int c = 0; c < 3; ++c)
    {
      normal[c] += n[c];
    }
    const int c = CornerOf(tri, v);
    for (const int e : { c, (c + 2) % 3 })
    {
      if (this->Topology->IsBoundaryEdge(t, e))
      {
        Quadric edge;
        BoundaryEdgeQuadric(p[e], p[(e + 1) % 3], n, this->Options.BoundaryWeight, edge);
        q.Add(edge);
      }
    }
  }
}

//------------------------------------------------------------------------------
// The walk over a node's related triangles reads, vertex after vertex, the vertex's row of
// triangles, the triangles and their corners' positions and points: reads scattered over memory,
// each address known only from the one before, which took most of the walk's time. They are
// hinted in stages for the vertices a few places ahead, so that they overlap with the work.
void ClusterTree::HintRelated(Id pos, Id last) const
{
  const VertexTriangleAdjacency& adj = this->Topology->VertexTriangles;
  if (pos + 6 < last)
  {
    CacheHint(adj.Offsets.data() + this->Order[pos + 6]);
  }
  if (pos + 4 < last)
  {
    CacheHint(adj.Of(this->Order[pos + 4]));
  }
  if (pos + 2 < last)
  {
    const Id v = this->Order[pos + 2];
    for (Id i = adj.Begin(v); i < adj.End(v); ++i)
    {
      CacheHint(this->Mesh->Triangle(adj.Triangles[i]));
    }
  }
  if (pos + 1 < last)
  {
    const Id v = this->Order[pos + 1];
    for (Id i = adj.Begin(v); i < adj.End(v); ++i)
    {
      const Id* tri = this->Mesh->Triangle(adj.Triangles[i]);
      for (int k = 0; k < 3; ++k)
      {
        CacheHint(this->PosOf.data() + tri[k]);
        CacheHint(this->Mesh->Point(tri[k]));
      }
    }
  }
}

//------------------------------------------------------------------------------
void ClusterTree::RelatedQuadric(
  Id node, Quadric& q, double normal[3], RelatedTriangles* details) const
{
  q.Clear();
  if (details)
  {
    details->Crossing.clear();
    details->CrossingPlanes.clear();
    details->CrossingNormals.clear();
    details->CrossingEnds.clear();
    details->BoundaryEdges.clear();
    details->Planes.clear();
  }
  double unused[3];
  normal = normal ? normal : unused;
  normal[0] = normal[1] = normal[2] = 0.0;
  const Id first = this->Position(node);
  const Id last = first + this->Count(node);
  const VertexTriangleAdjacency& adj = this->Topology->VertexTriangles;
  for (Id pos = first; pos < last; ++pos)
  {
    this->HintRelated(pos, last);
    const Id v = this->Order[pos];
    for (Id i = adj.Begin(v); i < adj.End(v); ++i)
    {
      const Id t = adj.Triangles[i];
      const Id* tri = this->Mesh->Triangle(t);
      bool inside[3];
      int insideCount = 0;
      for (int k = 0; k < 3; ++k)
      {
        const Id p = this->PosOf[tri[k]];
        inside[k] = p >= first && p < last;
        insideCount += inside[k] ? 1 : 0;
      }
      const int c = CornerOf(tri, v);
      // Each triangle once, from its first vertex inside; each boundary edge once, from its
      // first end inside.
      const int firstInside = inside[0] ? 0 : (inside[1] ? 1 : 2);
      bool boundary[2] = { false, false };
      for (int j = 0; j < 2; ++j)
      {
        const int e = j == 0 ? c : (c + 2) % 3;
        const int from = inside[e] ? e : (e + 1) % 3;
        boundary[j] = from == c && this->Topology->IsBoundaryEdge(t, e);
      }
      if (firstInside != c && !boundary[0] && !boundary[1])
      {
        continue;
      }
      double p[3][3];
      this->RelativeTriangle(tri, p);
      Quadric face;
      double n[3], plane[4];
      const bool hasPlane = TriangleQuadric(p[0], p[1], p[2], face, n, plane);
      if (firstInside == c)
      {
        q.Add(face);
        for (int k = 0; k < 3; ++k)
        {
          normal[k] += n[k];
        }
        if (details)
        {
          if (insideCount == 1)
          {
            details->Crossing.push_back(3 * t + c);
            details->CrossingPlanes.push_back(face);
            details->CrossingNormals.insert(details->CrossingNormals.end(), n, n + 3);
            for (const int k : { (c + 1) % 3, (c + 2) % 3 })
            {
              details->CrossingEnds.insert(details->CrossingEnds.end(), p[k], p[k] + 3);
            }
          }
          if (hasPlane)
          {
            details->Planes.insert(details->Planes.end(), plane, plane + 4);
          }
        }
      }
      for (int j = 0; j < 2; ++j)
      {
        if (boundary[j])
        {
          const int e = j == 0 ? c : (c + 2) % 3;
          Quadric edge;
          BoundaryEdgeQuadric(p[e], p[(e + 1) % 3], n, this->Options.BoundaryWeight, edge);
          q.Add(edge);
          if (details)
          {
            details->BoundaryEdges.push_back(3 * t + e);
          }
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
void ClusterTree::FindSeams()
{
  this->Seams.clear();
  const TriangleTopology& topology = *this->Topology;
  if (topology.OrientedWhenBuilt)
  {
    return;
  }
  // A seam edge (a, b) runs from a to b in both its triangles: around a, two triangles have b
  // as the corner after a; around b, two have a as the corner before b. Each vertex looks at
  // its own triangles only, so both ends are found without writes to another vertex's flag.
  ResizeFresh(this->Seams, this->NV);
  const VertexTriangleAdjacency& adj = topology.VertexTriangles;
  const TriangleMesh& mesh = *this->Mesh;
  vtkSMPTools::For(0,
    this->NV,
    [&](Id begin, Id end)
    {
      for (Id v = begin; v < end; ++v)
      {
        std::uint8_t seam = 0;
        for (Id i = adj.Begin(v); i < adj.End(v) && !seam; ++i)
        {
          const Id* tri = mesh.Triangle(adj.Triangles[i]);
          const int c = CornerOf(tri, v);
          for (Id j = i + 1; j < adj.End(v) && !seam; ++j)
          {
            const Id* other = mesh.Triangle(adj.Triangles[j]);
            const int d = CornerOf(other, v);
            seam = (tri[(c + 1) % 3] == other[(d + 1) % 3] ||
                     tri[(c + 2) % 3] == other[(d + 2) % 3])
              ? 1
              : 0;
          }
        }
        this->Seams[v] = seam;
      }
    });
}

//------------------------------------------------------------------------------
void ClusterTree::FindCurves()
{
  this->Curves.clear();
  this->LockedEdges.clear();
  const TriangleTopology& topology = *this->Topology;
  if (topology.CountVertices(VertexKind::NonManifold) == 0)
  {
    return;
  }
  ResizeFresh(this->Curves, this->NV);
  vtkSMPTools::For(0,
    this->NV,
    [&](Id begin, Id end)
    {
      std::vector<std::pair<Id, Id>> ends;
      std::vector<Id> fan;
      for (Id v = begin; v < end; ++v)
      {
        if (topology.VertexKinds[v] == VertexKind::NonManifold)
        {
          IsRegularCurveVertex(
            *this->Mesh, topology.VertexTriangles, v, ends, fan, &this->Curves[v]);
        }
      }
    });
  // Edges of more than two triangles between two locked vertices, each listed from its lower
  // end (serial: few vertices are locked).
  const VertexTriangleAdjacency& adj = topology.VertexTriangles;
  std::vector<Id> others;
  for (Id v = 0; v < this->NV; ++v)
  {
    if (!this->IsLocked(v))
    {
      continue;
    }
    others.clear();
    for (Id i = adj.Begin(v); i < adj.End(v); ++i)
    {
      const Id* tri = this->Mesh->Triangle(adj.Triangles[i]);
      for (int c = 0; c < 3; ++c)
      {
        if (tri[c] > v && this->IsLocked(tri[c]))
        {
          others.push_back(tri[c]);
        }
      }
    }
    std::sort(others.begin(), others.end());
    for (std::size_t i = 0; i < others.size();)
    {
      std::size_t run = 1;
      while (i + run < others.size() && others[i + run] == others[i])
      {
        ++run;
      }
      if (run > 2)
      {
        this->LockedEdges.push_back(LockedEdge{ v, others[i], static_cast<int>(run) });
      }
      i += run;
    }
  }
}

//------------------------------------------------------------------------------
// The bottom tier: the vertices bucketed by their cell at TierDepth (KeyOffsets, CellVertices;
// Cells lists the keys of the cells that hold some), and what building each cell leaves for
// the top tier: its number of nodes, its top components with their quadrics and its half-edges
// to other cells.
struct ClusterTree::BottomTier
{
  std::vector<Id> KeyOffsets, CellVertices;
  std::vector<Id> Cells;
  std::vector<Id> CellCounts;
  std::vector<std::vector<FinishedNode>> CellRoots;
  std::vector<std::vector<HalfEdge>> CellTop;
};

//------------------------------------------------------------------------------
void ClusterTree::Build(const TriangleMesh& mesh,
  const TriangleTopology& topology,
  const ClusterTreeOptions& options)
{
  this->Mesh = &mesh;
  this->Topology = &topology;
  this->Options = options;
  this->NV = mesh.GetNumberOfPoints();
  this->Nodes.clear();
  AssignFresh(this->LeafParent, this->NV, InvalidId);
  this->ComputeFrame();
  this->FindCurves();
  this->FindSeams();
  Builder builder(*this);
  this->ComputeCodes();

  BottomTier tier;
  this->BucketVertices(tier);
  this->BuildBottomTier(builder, tier);
  this->RenumberBottomTier(builder, tier);
  this->BuildTopTier(builder, tier);
  this->ComputeOrder();
}

//------------------------------------------------------------------------------
void ClusterTree::BucketVertices(BottomTier& tier) const
{
  const Id nv = this->NV;
  std::vector<Id>& keyOffsets = tier.KeyOffsets;
  std::vector<Id>& cellVertices = tier.CellVertices;
  std::vector<Id>& cells = tier.Cells;
  // Vertices bucketed by their cell at TierDepth (stable: each cell lists its vertices by id).
  const int shift = MaxDepth - TierDepth;
  const Id numberOfKeys = Id(1) << TierDepth;
  GroupByKey(
    static_cast<size_t>(numberOfKeys),
    [&](auto&& emit) {
      for (Id v = 0; v < nv; ++v)
      {
        emit(static_cast<size_t>(this->Codes[v] >> shift), v);
      }
    },
    keyOffsets, cellVertices);
  for (Id key = 0; key < numberOfKeys; ++key)
  {
    if (keyOffsets[key + 1] > keyOffsets[key])
    {
      cells.push_back(key);
    }
  }
}

//------------------------------------------------------------------------------
void ClusterTree::BuildBottomTier(Builder& builder, BottomTier& tier)
{
  const Id nv = this->NV;
  const TriangleMesh& mesh = *this->Mesh;
  const std::vector<Id>& keyOffsets = tier.KeyOffsets;
  const std::vector<Id>& cellVertices = tier.CellVertices;
  const std::vector<Id>& cells = tier.Cells;
  // Bottom tier, cell by cell. Node ids are provisional, NV + (first slot of the cell in
  // cellVertices) + local index: a cell of n vertices makes at most n - 1 nodes, so the ranges
  // never overlap, and each cell writes its nodes straight into the node array, sized for all
  // nodes of the tree from the start. The quadrics of a cell's nodes live only while the cell is
  // built, except those of its top components, which the top tier still needs.
  const Id numberOfCells = static_cast<Id>(cells.size());
  ResizeFresh(this->Nodes, nv);
  std::vector<Id>& cellCounts = tier.CellCounts;
  std::vector<std::vector<FinishedNode>>& cellRoots = tier.CellRoots;
  std::vector<std::vector<HalfEdge>>& cellTop = tier.CellTop;
  cellCounts.assign(numberOfCells, 0);
  cellRoots.resize(numberOfCells);
  cellTop.resize(numberOfCells);
  const VertexTriangleAdjacency& adj = this->Topology->VertexTriangles;
  vtkSMPTools::For(0,
    numberOfCells,
    [&](Id begin, Id end)
    {
      std::vector<HalfEdge> items, scratch;
      NodeStore store;
      store.Tree = this;
      for (Id c = begin; c < end; ++c)
      {
        const Id key = cells[c];
        items.clear();
        for (Id i = keyOffsets[key]; i < keyOffsets[key + 1]; ++i)
        {
          const Id v = cellVertices[i];
          for (Id j = adj.Begin(v); j < adj.End(v); ++j)
          {
            const Id t = adj.Triangles[j];
            const Id* tri = mesh.Triangle(t);
            const int k = CornerOf(tri, v);
            const int depth = builder.CommonDepth(v, tri[(k + 1) % 3]);
            const HalfEdge h{ 3 * static_cast<std::int64_t>(t) + k, depth };
            (depth >= TierDepth ? items : cellTop[c]).push_back(h);
          }
        }
        SortByDepth(items, scratch);
        store.Restart(nv + keyOffsets[key]);
        builder.MergeSorted(items, c * (MaxDepth + 2), store);
        ComputeCreatedE1(store, this->Options.PlacementTolerance);
        for (Id i = keyOffsets[key]; i < keyOffsets[key + 1]; ++i)
        {
          const Id v = cellVertices[i];
          if (builder.UF[v] == v && builder.NodeOf[v] >= nv)
          {
            cellRoots[c].emplace_back(
              builder.NodeOf[v], store.Work[builder.NodeOf[v] - store.Base]);
          }
        }
        cellCounts[c] = store.Created;
      }
    });
}

//------------------------------------------------------------------------------
void ClusterTree::RenumberBottomTier(Builder& builder, BottomTier& tier)
{
  const Id nv = this->NV;
  const std::vector<Id>& keyOffsets = tier.KeyOffsets;
  const std::vector<Id>& cellVertices = tier.CellVertices;
  const std::vector<Id>& cells = tier.Cells;
  const std::vector<Id>& cellCounts = tier.CellCounts;
  std::vector<std::vector<FinishedNode>>& cellRoots = tier.CellRoots;
  const Id numberOfCells = static_cast<Id>(cells.size());
  // Final ids: the cells' nodes in cell order, then the top tier's.
  std::vector<Id>& nodeOffsets = this->CellNodeOffsets;
  nodeOffsets.assign(static_cast<size_t>(numberOfCells) + 1, 0);
  for (Id c = 0; c < numberOfCells; ++c)
  {
    nodeOffsets[c + 1] = nodeOffsets[c] + cellCounts[c];
  }
  vtkSMPTools::For(0,
    numberOfCells,
    [&](Id begin, Id end)
    {
      for (Id c = begin; c < end; ++c)
      {
        const Id key = cells[c];
        const Id provisional = nv + keyOffsets[key];
        const Id shiftBy = nodeOffsets[c] - keyOffsets[key];
        auto fix = [&](Id& id)
        {
          if (id != InvalidId && id >= provisional)
          {
            id += shiftBy;
          }
        };
        for (Id i = 0; i < cellCounts[c]; ++i)
        {
          fix(this->Nodes[keyOffsets[key] + i].Parent);
        }
        for (Id i = keyOffsets[key]; i < keyOffsets[key + 1]; ++i)
        {
          const Id v = cellVertices[i];
          fix(this->LeafParent[v]);
          if (builder.UF[v] == v)
          {
            fix(builder.NodeOf[v]);
          }
        }
        for (auto& root : cellRoots[c])
        {
          fix(root.first);
        }
        std::sort(cellRoots[c].begin(), cellRoots[c].end(),
          [](const FinishedNode& a, const FinishedNode& b) { return a.first < b.first; });
      }
    });
  // Close the gaps, in cell order: a cell's nodes only ever move down (its final offset is at
  // most its provisional one), onto slots of earlier cells already moved.
  for (Id c = 0; c < numberOfCells; ++c)
  {
    if (nodeOffsets[c] != keyOffsets[cells[c]])
    {
      const auto from = this->Nodes.begin() + keyOffsets[cells[c]];
      std::copy(from, from + cellCounts[c], this->Nodes.begin() + nodeOffsets[c]);
    }
  }
}

//------------------------------------------------------------------------------
void ClusterTree::BuildTopTier(Builder& builder, BottomTier& tier)
{
  const Id nv = this->NV;
  const std::vector<Id>& nodeOffsets = this->CellNodeOffsets;
  std::vector<std::vector<FinishedNode>>& cellRoots = tier.CellRoots;
  std::vector<std::vector<HalfEdge>>& cellTop = tier.CellTop;
  const Id numberOfCells = static_cast<Id>(tier.Cells.size());
  // Top tier, serially.
  // The cells' top components with their quadrics, by id (each cell's list is sorted, and its
  // ids lie above the previous cell's), and the half-edges between cells.
  std::vector<FinishedNode> finished;
  std::vector<HalfEdge> top;
  std::size_t topItems = 0, rootCount = 0;
  for (Id c = 0; c < numberOfCells; ++c)
  {
    topItems += cellTop[c].size();
    rootCount += cellRoots[c].size();
  }
  ReserveFresh(top, topItems);
  ReserveFresh(finished, rootCount);
  for (Id c = 0; c < numberOfCells; ++c)
  {
    finished.insert(finished.end(), cellRoots[c].begin(), cellRoots[c].end());
    Release(cellRoots[c]);
    top.insert(top.end(), cellTop[c].begin(), cellTop[c].end());
    Release(cellTop[c]);
  }
  {
    std::vector<HalfEdge> scratch;
    SortByDepth(top, scratch);
  }
  NodeStore store;
  store.Tree = this;
  store.Finished = &finished;
  store.Restart(nv + nodeOffsets[numberOfCells]);
  builder.MergeSorted(top, numberOfCells * (MaxDepth + 2), store);
  ComputeCreatedE1(store, this->Options.PlacementTolerance);
  // (The room of the NV - 1 nodes a tree can have stays: shrinking would copy the array.)
  this->Nodes.resize(nodeOffsets[numberOfCells] + store.Created);
}

//------------------------------------------------------------------------------
// Depth-first ranges. A parent has a larger id than its children, so walking the internal
// nodes downwards reaches every parent before its children.
void ClusterTree::ComputeOrder()
{
  const Id nv = this->NV;
  const Id ni = static_cast<Id>(this->Nodes.size());
  AssignFresh(this->Begin, ni, 0);
  ResizeFresh(this->Order, nv);
  ResizeFresh(this->PosOf, nv);
  std::vector<Id> cursor = FreshVector<Id>(ni, 0);
  Id next = 0;
  for (Id v = 0; v < nv; ++v)
  {
    if (this->LeafParent[v] == InvalidId)
    {
      this->PosOf[v] = next;
      this->Order[next++] = v;
    }
  }
  this->Depth = 0;
  for (Id i = ni - 1; i >= 0; --i)
  {
    const ClusterNode& n = this->Nodes[i];
    if (n.Parent == InvalidId)
    {
      this->Begin[i] = next;
      next += n.Count;
    }
    else
    {
      Id& parentCursor = cursor[n.Parent - nv];
      this->Begin[i] = parentCursor;
      parentCursor += n.Count;
    }
    cursor[i] = this->Begin[i];
    this->Depth = std::max(this->Depth, int(n.Depth));
  }
  for (Id v = 0; v < nv; ++v)
  {
    if (this->LeafParent[v] != InvalidId)
    {
      const Id pos = cursor[this->LeafParent[v] - nv]++;
      this->PosOf[v] = pos;
      this->Order[pos] = v;
    }
  }
  this->ComputeChildren();
}

//------------------------------------------------------------------------------
// The nodes that start at a position are the vertex there and those of its ancestors that start
// there too: taking the positions in order lists every node's children, and the roots, in
// depth-first order.
void ClusterTree::ComputeChildren()
{
  const Id nv = this->NV;
  const Id ni = this->NumberOfInternalNodes();
  AssignFresh(this->ChildOffsets, static_cast<size_t>(ni) + 1, 0);
  for (Id node = 0; node < nv + ni; ++node)
  {
    const Id parent = this->Parent(node);
    if (parent != InvalidId)
    {
      ++this->ChildOffsets[parent - nv + 1];
    }
  }
  for (Id i = 0; i < ni; ++i)
  {
    this->ChildOffsets[i + 1] += this->ChildOffsets[i];
  }
  ResizeFresh(this->Children, this->ChildOffsets[ni]);
  this->Roots.clear();
  std::vector<Id> cursor = FreshCopy(this->ChildOffsets.begin(), this->ChildOffsets.end() - 1);
  for (Id pos = 0; pos < nv; ++pos)
  {
    for (Id node = this->Order[pos];;)
    {
      const Id parent = this->Parent(node);
      if (parent == InvalidId)
      {
        this->Roots.push_back(node);
        break;
      }
      this->Children[cursor[parent - nv]++] = node;
      if (this->Position(parent) != pos)
      {
        break;
      }
      node = parent;
    }
  }
}

} // namespace meshlod
