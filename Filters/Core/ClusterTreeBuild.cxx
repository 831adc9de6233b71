// The cluster tree's construction (see ClusterTree.h): bottom-up like Kruskal's algorithm over the
// half-edges sorted by the depth at which their ends part, the cells below TierDepth in parallel
// and the merges above them serially; then the depth-first vertex order and the children.
// ClusterTree.cxx holds the codes, seams, curves and islands it starts from, and the queries.
#include "ClusterTree.h"

#include "FreshMemory.h"
#include "GroupByKey.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace meshlod
{
namespace
{
// The tree below this depth (octree depth 4, at most 4096 cells) is built cell by cell in
// parallel, the merges above it serially.
constexpr int TierDepth = 12;

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
// Each node listed under its parent (by ranges of parents in parallel), then each parent's
// children, and the roots, sorted by position: depth-first order, as the ranges of two
// children of one node do not overlap.
void ClusterTree::ComputeChildren()
{
  const Id nv = this->NV;
  const Id ni = this->NumberOfInternalNodes();
  GroupItemsByKey(
    static_cast<size_t>(ni), std::int64_t(nv) + ni,
    [&](std::int64_t node) {
      const Id parent = this->Parent(static_cast<Id>(node));
      return parent == InvalidId ? Id(-1) : parent - nv;
    },
    [](std::int64_t node) { return static_cast<Id>(node); }, this->ChildOffsets, this->Children);
  auto byPosition = [&](Id a, Id b) { return this->Position(a) < this->Position(b); };
  vtkSMPTools::For(0, ni, [&](Id begin, Id end) {
    for (Id i = begin; i < end; ++i)
    {
      std::sort(this->Children.begin() + this->ChildOffsets[i],
        this->Children.begin() + this->ChildOffsets[i + 1], byPosition);
    }
  });
  this->Roots.clear();
  for (Id node = 0; node < nv + ni; ++node)
  {
    if (this->Parent(node) == InvalidId)
    {
      this->Roots.push_back(node);
    }
  }
  std::sort(this->Roots.begin(), this->Roots.end(), byPosition);
}

} // namespace meshlod
