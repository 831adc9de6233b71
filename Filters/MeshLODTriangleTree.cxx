#include "MeshLODTriangleTree.h"

#include "Core/TriangulationFlips.h"

#include "vtkPoints.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshlod
{
namespace
{
// Triangles per leaf at most: fewer makes more nodes (64 bytes each), more tests more
// triangles per leaf reached.
constexpr vtkIdType LeafTriangles = 8;
// Below the top of the tree, subtrees of at most this many triangles are built in parallel.
constexpr vtkIdType SubtreeTriangles = 16384;
// Pending nodes of a query: one per level at most (the farther child), and median splits of
// 2^63 triangles make 60 levels.
constexpr int StackSize = 96;
// The closest point that ClosestPointOnTriangle computes can lie a little outside the
// triangle's box through rounding (less than a unit in the last place of the coordinates, seen
// with coordinates large against the distance: 512 against 1.2), its distance then smaller than
// the box's. A box is passed over only when it is farther than the reach by more than this
// fraction of the largest coordinate (the tree's or the query point's): the nearest triangle of
// the search is then that of a search of every triangle.
constexpr double RoundingSlack = 1e-10;
} // namespace

//------------------------------------------------------------------------------
// A triangle while the tree is built: three times its centroid (only the order along an axis
// is used) next to its id, so that the splits read and move contiguous memory.
struct TriangleTree::Item
{
  double Centroid[3];
  vtkIdType Id;
};

//------------------------------------------------------------------------------
vtkIdType TriangleTree::NodesFor(vtkIdType count, NodeCounts& memo)
{
  if (count <= LeafTriangles)
  {
    return 1;
  }
  // A split's halves differ by at most one triangle, so each depth has at most two sizes.
  for (const auto& known : memo)
  {
    if (known.first == count)
    {
      return known.second;
    }
  }
  const vtkIdType nodes = 1 + NodesFor(count / 2, memo) + NodesFor(count - count / 2, memo);
  memo.emplace_back(count, nodes);
  return nodes;
}

//------------------------------------------------------------------------------
void TriangleTree::Build(const double* points, const vtkIdType* triangles, vtkIdType count)
{
  this->Points = points;
  this->Triangles = triangles;
  this->Nodes.clear();
  this->Order.clear();
  this->Corners.clear();
  this->Magnitude = 0.0;
  if (count == 0)
  {
    return;
  }
  std::vector<Item> items(count);
  this->Corners.resize(count);
  vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType t = begin; t < end; ++t)
    {
      const vtkIdType* ids = triangles + 3 * t;
      this->Corners[t] = static_cast<signed char>(ClosestPointCorner(
        points + 3 * ids[0], points + 3 * ids[1], points + 3 * ids[2]));
      for (int c = 0; c < 3; ++c)
      {
        items[t].Centroid[c] = points[3 * triangles[3 * t] + c] +
          points[3 * triangles[3 * t + 1] + c] + points[3 * triangles[3 * t + 2] + c];
      }
      items[t].Id = t;
    }
  });
  // Nodes in depth-first order, a node's first child right after it: the layout follows from
  // the triangle count alone, so subtrees can be built at once, each into its own place.
  NodeCounts memo;
  this->Nodes.resize(static_cast<std::size_t>(NodesFor(count, memo)));
  // The top of the tree is split here, one node after the other, down to subtrees of at most
  // SubtreeTriangles; those are built in parallel, then the top's boxes from its children's.
  std::vector<Subtree> subtrees, top;
  std::vector<Subtree> pending = { { 0, 0, count } };
  while (!pending.empty())
  {
    const Subtree part = pending.back();
    pending.pop_back();
    if (part.End - part.Begin <= SubtreeTriangles)
    {
      subtrees.push_back(part);
      continue;
    }
    top.push_back(part);
    const vtkIdType middle = this->Divide(part, items.data(), memo);
    const vtkIdType second = this->Nodes[part.Node].End;
    pending.push_back({ second, middle, part.End });
    pending.push_back({ part.Node + 1, part.Begin, middle });
  }
  const vtkIdType parts = static_cast<vtkIdType>(subtrees.size());
  vtkSMPTools::For(0, parts, [&](vtkIdType begin, vtkIdType end) {
    NodeCounts localMemo;
    for (vtkIdType i = begin; i < end; ++i)
    {
      this->Split(subtrees[i], items.data(), localMemo);
    }
  });
  for (auto part = top.rbegin(); part != top.rend(); ++part)
  {
    this->Enclose(part->Node);
  }
  this->Order.resize(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    this->Order[i] = items[i].Id;
  }
  for (const double bound : this->Nodes[0].Bounds)
  {
    this->Magnitude = std::max(this->Magnitude, std::abs(bound));
  }
}

//------------------------------------------------------------------------------
vtkIdType TriangleTree::Divide(const Subtree& part, Item* items, NodeCounts& memo)
{
  double low[3], high[3]; // of the centroids, to choose the axis
  for (int c = 0; c < 3; ++c)
  {
    low[c] = std::numeric_limits<double>::max();
    high[c] = std::numeric_limits<double>::lowest();
  }
  for (vtkIdType i = part.Begin; i < part.End; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      low[c] = std::min(low[c], items[i].Centroid[c]);
      high[c] = std::max(high[c], items[i].Centroid[c]);
    }
  }
  int axis = 0;
  for (int c = 1; c < 3; ++c)
  {
    axis = high[c] - low[c] > high[axis] - low[axis] ? c : axis;
  }
  // Half the triangles on each side (so the depth is log2 of the count whatever the shape),
  // ordered by centroid, then id: the same tree on every run.
  const vtkIdType middle = part.Begin + (part.End - part.Begin) / 2;
  std::nth_element(items + part.Begin, items + middle, items + part.End,
    [axis](const Item& a, const Item& b) {
      const double ca = a.Centroid[axis], cb = b.Centroid[axis];
      return ca < cb || (ca == cb && a.Id < b.Id);
    });
  Node& node = this->Nodes[part.Node];
  node.Begin = -1;
  node.End = part.Node + 1 + NodesFor(middle - part.Begin, memo); // the second child
  return middle;
}

//------------------------------------------------------------------------------
void TriangleTree::Split(const Subtree& part, Item* items, NodeCounts& memo)
{
  Node& node = this->Nodes[part.Node];
  if (part.End - part.Begin > LeafTriangles)
  {
    const vtkIdType middle = this->Divide(part, items, memo);
    this->Split({ part.Node + 1, part.Begin, middle }, items, memo);
    this->Split({ node.End, middle, part.End }, items, memo);
    this->Enclose(part.Node);
    return;
  }
  node.Begin = part.Begin;
  node.End = part.End;
  for (int c = 0; c < 3; ++c)
  {
    node.Bounds[2 * c] = std::numeric_limits<double>::max();
    node.Bounds[2 * c + 1] = std::numeric_limits<double>::lowest();
  }
  for (vtkIdType i = part.Begin; i < part.End; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double* x = this->Points + 3 * this->Triangles[3 * items[i].Id + k];
      for (int c = 0; c < 3; ++c)
      {
        node.Bounds[2 * c] = std::min(node.Bounds[2 * c], x[c]);
        node.Bounds[2 * c + 1] = std::max(node.Bounds[2 * c + 1], x[c]);
      }
    }
  }
}

//------------------------------------------------------------------------------
void TriangleTree::Enclose(vtkIdType index)
{
  Node& node = this->Nodes[index];
  const Node& a = this->Nodes[index + 1];
  const Node& b = this->Nodes[node.End];
  for (int c = 0; c < 3; ++c)
  {
    node.Bounds[2 * c] = std::min(a.Bounds[2 * c], b.Bounds[2 * c]);
    node.Bounds[2 * c + 1] = std::max(a.Bounds[2 * c + 1], b.Bounds[2 * c + 1]);
  }
}

//------------------------------------------------------------------------------
double TriangleTree::Distance2(const Node& node, const double p[3])
{
  double d2 = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    // (Plain comparisons: std::max of an initializer list cost more here, in the innermost
    // loop of every search.)
    const double below = node.Bounds[2 * c] - p[c], above = p[c] - node.Bounds[2 * c + 1];
    const double d = below > 0.0 ? below : (above > 0.0 ? above : 0.0);
    d2 += d * d;
  }
  return d2;
}

//------------------------------------------------------------------------------
double TriangleTree::ToTriangle(vtkIdType t, const double p[3], double closest[3]) const
{
  const vtkIdType* ids = this->Triangles + 3 * t;
  const double* a = this->Points + 3 * ids[0];
  const double* b = this->Points + 3 * ids[1];
  const double* c = this->Points + 3 * ids[2];
  const int corner = this->Corners[t];
  return corner >= 0 ? ClosestPointFromCorner(p, a, b, c, corner, closest)
                     : ClosestPointOnTriangle(p, a, b, c, closest);
}

//------------------------------------------------------------------------------
template <typename Visit>
void TriangleTree::Descend(const double p[3], const double& reach2, Visit&& visit) const
{
  if (this->Nodes.empty())
  {
    return;
  }
  const double slack = RoundingSlack *
    std::max({ this->Magnitude, std::abs(p[0]), std::abs(p[1]), std::abs(p[2]) });
  double reached = -1.0, limit = 0.0; // limit: reach2 widened by the slack
  // Pending nodes with their boxes' distances (measured when pushed, for the order).
  std::pair<vtkIdType, double> stack[StackSize];
  int pending = 0;
  stack[pending++] = { 0, Distance2(this->Nodes[0], p) };
  while (pending > 0)
  {
    const auto [index, distance2] = stack[--pending];
    const Node& node = this->Nodes[index];
    if (reach2 != reached)
    {
      reached = reach2;
      const double reach = std::sqrt(reach2) + slack;
      limit = reach * reach;
    }
    if (distance2 > limit)
    {
      continue;
    }
    if (node.Begin >= 0)
    {
      for (vtkIdType i = node.Begin; i < node.End; ++i)
      {
        visit(this->Order[i]);
      }
      continue;
    }
    // The nearer child is searched first (pushed last): the reach shrinks sooner.
    const vtkIdType a = index + 1, b = node.End;
    const double da = Distance2(this->Nodes[a], p), db = Distance2(this->Nodes[b], p);
    if (da <= db)
    {
      stack[pending++] = { b, db };
      stack[pending++] = { a, da };
    }
    else
    {
      stack[pending++] = { a, da };
      stack[pending++] = { b, db };
    }
  }
}

//------------------------------------------------------------------------------
vtkIdType TriangleTree::FindClosest(const double p[3], double closest[3], double& distance2) const
{
  vtkIdType best = -1;
  distance2 = std::numeric_limits<double>::infinity();
  this->Descend(p, distance2, [&](vtkIdType t) {
    double x[3];
    const double d2 = this->ToTriangle(t, p, x);
    if (d2 < distance2 || (d2 == distance2 && t < best))
    {
      best = t;
      distance2 = d2;
      std::copy_n(x, 3, closest);
    }
  });
  return best;
}

//------------------------------------------------------------------------------
vtkIdType TriangleTree::FindLowestWithin(
  const double p[3], double limit2, double closest[3]) const
{
  vtkIdType best = -1;
  this->Descend(p, limit2, [&](vtkIdType t) {
    if (best >= 0 && t > best)
    {
      return;
    }
    double x[3];
    if (this->ToTriangle(t, p, x) <= limit2)
    {
      best = t;
      std::copy_n(x, 3, closest);
    }
  });
  return best;
}

//------------------------------------------------------------------------------
void SurfaceTriangles::Build(vtkPoints* points, std::vector<vtkIdType> triangles)
{
  const vtkIdType np = points ? points->GetNumberOfPoints() : 0;
  this->Points.resize(3 * static_cast<std::size_t>(np));
  vtkSMPTools::For(0, np, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      points->GetPoint(i, this->Points.data() + 3 * i);
    }
  });
  this->Triangles = std::move(triangles);
  this->Tree.Build(this->Points.data(), this->Triangles.data(),
    static_cast<vtkIdType>(this->Triangles.size() / 3));
}
} // namespace meshlod
