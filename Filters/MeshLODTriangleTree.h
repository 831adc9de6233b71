// A bounding-box tree over the triangles of a surface, for the nearest triangle to a point.
//
// The texture baker asks it for every texel. vtkStaticCellLocator, which it replaces there,
// puts each triangle in every bin its box touches and searches bins: around a vertex of high
// valence (cones sharing an apex, a UV sphere's pole, a cylinder cap's fan) one bin holds
// thousands of long triangles and every query near it tested them all, and its search within
// bounds deduplicated its answers one by one (vtkIdList::InsertUniqueId, quadratic). Here a
// long triangle is one box, and a query descends only into boxes nearer than the best triangle
// found so far.
//
// The tree is built once, deterministically (median splits along the longest axis of the
// centroids, ties by triangle id; the same tree for every thread count), its subtrees in
// parallel; queries are const and may run on any number of threads.
#ifndef MeshLODTriangleTree_h
#define MeshLODTriangleTree_h

#include "vtkFiltersMeshLODModule.h"
#include "vtkType.h"

#include <utility>
#include <vector>

class vtkPoints;

namespace meshlod
{
class VTKFILTERSMESHLOD_EXPORT TriangleTree
{
public:
  /// Index `count` triangles (3 point ids each in `triangles`) over `points` (x, y, z each).
  /// Both arrays are read by the queries: they must outlive the tree, unchanged.
  void Build(const double* points, const vtkIdType* triangles, vtkIdType count);

  /// The triangle nearest to p (of those at the same distance, to the bit, the lowest id), its
  /// closest point and squared distance; -1 when there are no triangles.
  vtkIdType FindClosest(const double p[3], double closest[3], double& distance2) const;

  /// Of the triangles within squared distance `limit2` of p, the one with the lowest id and
  /// its closest point; -1 when there is none.
  vtkIdType FindLowestWithin(const double p[3], double limit2, double closest[3]) const;

private:
  struct Node
  {
    double Bounds[6]; // of the triangles' points: xmin, xmax, ymin, ymax, zmin, zmax
    vtkIdType Begin;  // leaf: its triangles are Order[Begin, End); inner node: -1
    vtkIdType End;    // leaf: see Begin; inner node: the second child (the first follows it)
  };
  struct Item;
  // Node counts of subtrees by their triangle count, as found so far.
  using NodeCounts = std::vector<std::pair<vtkIdType, vtkIdType>>;
  struct Subtree
  {
    vtkIdType Node, Begin, End; // the node, and its triangles' range of the items
  };
  // The number of nodes of a tree of `count` triangles.
  static vtkIdType NodesFor(vtkIdType count, NodeCounts& memo);
  // Order the part's items about their median along the longest axis of their centroids, and
  // make its node an inner node; returns the middle.
  vtkIdType Divide(const Subtree& part, Item* items, NodeCounts& memo);
  // Build the part's subtree whole (its boxes included).
  void Split(const Subtree& part, Item* items, NodeCounts& memo);
  // An inner node's box from its children's.
  void Enclose(vtkIdType index);
  static double Distance2(const Node& node, const double p[3]);
  // Call visit(t) for the triangles of every leaf whose box is within squared distance reach2
  // of p (and a rounding slack), nearer boxes first; reach2 is read again at every node (the
  // caller may shrink it).
  template <typename Visit>
  void Descend(const double p[3], const double& reach2, Visit&& visit) const;
  double ToTriangle(vtkIdType t, const double p[3], double closest[3]) const;

  std::vector<Node> Nodes; // the root first
  std::vector<vtkIdType> Order;
  std::vector<signed char> Corners; // per triangle its ClosestPointCorner, found once
  double Magnitude = 0.0; // the largest coordinate of the triangles, in absolute value
  const double* Points = nullptr;
  const vtkIdType* Triangles = nullptr;
};

/// A TriangleTree with the arrays it reads, for a vtkPolyData's surface (whose points may be
/// float): the points as double and the triangles. Not copyable: the tree points into them.
struct VTKFILTERSMESHLOD_EXPORT SurfaceTriangles
{
  std::vector<double> Points;        // x, y, z per point
  std::vector<vtkIdType> Triangles;  // 3 point ids per triangle
  TriangleTree Tree;                 // over the two

  SurfaceTriangles() = default;
  SurfaceTriangles(const SurfaceTriangles&) = delete;
  SurfaceTriangles& operator=(const SurfaceTriangles&) = delete;

  /// Copy `points` (none when null), take `triangles` and build the tree over them.
  void Build(vtkPoints* points, std::vector<vtkIdType> triangles);
};
} // namespace meshlod

#endif
