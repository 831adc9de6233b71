#include "MeshLODTriangleTree.h"

#include "Core/TriangulationFlips.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace meshlod
{
namespace
{
// Triangles per leaf at most: fewer makes more nodes (64 bytes each), more tests more
// triangles per leaf reached.
constexpr vtkIdType LeafTriangles = 8;
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
void TriangleTree::Build(const double* points, const vtkIdType* triangles, vtkIdType count)
{
  this->Points = points;
  this->Triangles = triangles;
  this->Nodes.clear();
  this->Magnitude = 0.0;
  this->Order.resize(count);
  std::iota(this->Order.begin(), this->Order.end(), vtkIdType(0));
  if (count == 0)
  {
    return;
  }
  std::vector<double> centroids(3 * static_cast<std::size_t>(count));
  for (vtkIdType t = 0; t < count; ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      // Three times the centroid: only the order along an axis is used.
      centroids[3 * t + c] = points[3 * triangles[3 * t] + c] +
        points[3 * triangles[3 * t + 1] + c] + points[3 * triangles[3 * t + 2] + c];
    }
  }
  this->Nodes.reserve(static_cast<std::size_t>(count / 2 + 2));
  this->Nodes.emplace_back();
  this->Split(0, 0, count, centroids);
  for (const double bound : this->Nodes[0].Bounds)
  {
    this->Magnitude = std::max(this->Magnitude, std::abs(bound));
  }
}

//------------------------------------------------------------------------------
void TriangleTree::Split(
  vtkIdType index, vtkIdType begin, vtkIdType end, const std::vector<double>& centroids)
{
  Node node;
  double low[3], high[3]; // of the centroids, to choose the axis
  for (int c = 0; c < 3; ++c)
  {
    node.Bounds[2 * c] = low[c] = std::numeric_limits<double>::max();
    node.Bounds[2 * c + 1] = high[c] = std::numeric_limits<double>::lowest();
  }
  for (vtkIdType i = begin; i < end; ++i)
  {
    const vtkIdType t = this->Order[i];
    for (int k = 0; k < 3; ++k)
    {
      const double* x = this->Points + 3 * this->Triangles[3 * t + k];
      for (int c = 0; c < 3; ++c)
      {
        node.Bounds[2 * c] = std::min(node.Bounds[2 * c], x[c]);
        node.Bounds[2 * c + 1] = std::max(node.Bounds[2 * c + 1], x[c]);
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      low[c] = std::min(low[c], centroids[3 * t + c]);
      high[c] = std::max(high[c], centroids[3 * t + c]);
    }
  }
  if (end - begin <= LeafTriangles)
  {
    node.Begin = begin;
    node.End = end;
    this->Nodes[index] = node;
    return;
  }
  int axis = 0;
  for (int c = 1; c < 3; ++c)
  {
    axis = high[c] - low[c] > high[axis] - low[axis] ? c : axis;
  }
  // Half the triangles on each side (so the depth is log2 of the count whatever the shape),
  // ordered by centroid, then id: the same tree on every run.
  const vtkIdType middle = begin + (end - begin) / 2;
  std::nth_element(this->Order.begin() + begin, this->Order.begin() + middle,
    this->Order.begin() + end, [&](vtkIdType a, vtkIdType b) {
      const double ca = centroids[3 * a + axis], cb = centroids[3 * b + axis];
      return ca < cb || (ca == cb && a < b);
    });
  const vtkIdType first = static_cast<vtkIdType>(this->Nodes.size());
  node.Begin = -1;
  node.End = first;
  this->Nodes[index] = node;
  this->Nodes.emplace_back();
  this->Nodes.emplace_back();
  this->Split(first, begin, middle, centroids);
  this->Split(first + 1, middle, end, centroids);
}

//------------------------------------------------------------------------------
double TriangleTree::Distance2(const Node& node, const double p[3])
{
  double d2 = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    const double d = std::max({ node.Bounds[2 * c] - p[c], p[c] - node.Bounds[2 * c + 1], 0.0 });
    d2 += d * d;
  }
  return d2;
}

//------------------------------------------------------------------------------
double TriangleTree::ToTriangle(vtkIdType t, const double p[3], double closest[3]) const
{
  const vtkIdType* ids = this->Triangles + 3 * t;
  return ClosestPointOnTriangle(
    p, this->Points + 3 * ids[0], this->Points + 3 * ids[1], this->Points + 3 * ids[2], closest);
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
  vtkIdType stack[StackSize];
  int pending = 0;
  stack[pending++] = 0;
  while (pending > 0)
  {
    const Node& node = this->Nodes[stack[--pending]];
    if (reach2 != reached)
    {
      reached = reach2;
      const double reach = std::sqrt(reach2) + slack;
      limit = reach * reach;
    }
    if (Distance2(node, p) > limit)
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
    const vtkIdType a = node.End, b = node.End + 1;
    const bool aNearer = Distance2(this->Nodes[a], p) <= Distance2(this->Nodes[b], p);
    stack[pending++] = aNearer ? b : a;
    stack[pending++] = aNearer ? a : b;
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
} // namespace meshlod
