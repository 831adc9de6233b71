// MeshLOD core: a flat triangle mesh and its topology.
//
// Everything here is plain arrays and integer ids (no pointers, no per-element heap objects), so
// that every pass over a mesh is a loop over contiguous memory and can be split across threads.
// The VTK filters convert a vtkPolyData into a TriangleMesh once, run the algorithm on it, and
// convert the results back in one go.
#ifndef meshlod_TriangleMesh_h
#define meshlod_TriangleMesh_h

#include "vtkFiltersMeshLODModule.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace meshlod
{
/// Vertex and triangle ids of the core. 32 bits halve the memory of the topology compared with
/// vtkIdType; meshes are limited to 2^31 - 1 vertices and triangles (checked on input).
using Id = std::int32_t;
constexpr Id InvalidId = -1;

/// Points (x, y, z per vertex) and triangles (three vertex ids each).
struct VTKFILTERSMESHLOD_EXPORT TriangleMesh
{
  std::vector<double> Points;
  std::vector<Id> Triangles;

  Id GetNumberOfPoints() const { return static_cast<Id>(this->Points.size() / 3); }
  Id GetNumberOfTriangles() const { return static_cast<Id>(this->Triangles.size() / 3); }
  const double* Point(Id v) const { return this->Points.data() + 3 * static_cast<std::size_t>(v); }
  double* Point(Id v) { return this->Points.data() + 3 * static_cast<std::size_t>(v); }
  const Id* Triangle(Id t) const { return this->Triangles.data() + 3 * static_cast<std::size_t>(t); }
  Id* Triangle(Id t) { return this->Triangles.data() + 3 * static_cast<std::size_t>(t); }

  /// (p1 - p0) x (p2 - p0) of triangle t: its normal, twice its area in length.
  void AreaVector(Id t, double n[3]) const;

  /// Lowest and highest coordinates of the points (all 0 without points).
  void GetBounds(double lo[3], double hi[3]) const;

  /// Length of the diagonal of the points' axis-aligned bounding box (0 without points).
  double BoundingDiagonal() const;

  /// Mean area of the triangles of positive area (0 without any), summed in blocks of a fixed
  /// size: the same number for any thread count.
  double MeanTriangleArea() const;
};

/// Length of the diagonal of the box [lo, hi] (TriangleMesh::GetBounds' box).
double BoxDiagonal(const double lo[3], const double hi[3]);

/// Root of v in a union-find forest stored as parent links (a root is its own parent), halving
/// the path on the way.
inline Id FindRoot(std::vector<Id>& parent, Id v)
{
  while (parent[v] != v)
  {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

/// The corner after and before corner k = 3t + c in triangle t (corners in a flat list of
/// triangles, three per triangle).
inline Id NextCorner(Id k)
{
  return k % 3 == 2 ? k - 2 : k + 1;
}
inline Id PreviousCorner(Id k)
{
  return k % 3 == 0 ? k + 2 : k - 1;
}

/// Each side of each triangle (from corner k = 3t + c to the next corner of t) listed at its
/// lower point, packed as its higher point (high 32 bits) and k (low 32 bits), each row sorted:
/// the sides of one edge are consecutive, in corner order, as many as the edge's triangles.
/// Triangles t with skip[t] nonzero (when `skip` is given) are left out. Built with
/// vtkSMPTools, the same rows for any thread count.
VTKFILTERSMESHLOD_EXPORT void ListSidesByLowerPoint(const Id* triangles, Id count, Id points,
  const unsigned char* skip, std::vector<Id>& offsets, std::vector<std::uint64_t>& sides);
/// A side as ListSidesByLowerPoint packs it: its higher point, and its corner.
inline Id SideHigherPoint(std::uint64_t side)
{
  return static_cast<Id>(side >> 32);
}
inline Id SideCorner(std::uint64_t side)
{
  return static_cast<Id>(side & 0xffffffffu);
}

/// Vertex -> incident triangles, as offsets into one flat list (compressed rows). The triangles
/// of each vertex are listed in increasing id order, which makes every later pass deterministic.
struct VTKFILTERSMESHLOD_EXPORT VertexTriangleAdjacency
{
  std::vector<Id> Offsets;   // NumberOfPoints + 1 entries
  std::vector<Id> Triangles; // 3 * NumberOfTriangles entries

  /// Build from `numberOfTriangles` triangles (3 ids each). Triangles whose first id is
  /// InvalidId are treated as deleted and skipped.
  void Build(const Id* triangles, Id numberOfTriangles, Id numberOfPoints);
  void Build(const TriangleMesh& mesh)
  {
    this->Build(mesh.Triangles.data(), mesh.GetNumberOfTriangles(), mesh.GetNumberOfPoints());
  }

  Id Begin(Id v) const { return this->Offsets[v]; }
  Id End(Id v) const { return this->Offsets[v + 1]; }
  Id Count(Id v) const { return this->Offsets[v + 1] - this->Offsets[v]; }
  const Id* Of(Id v) const { return this->Triangles.data() + this->Offsets[v]; }
};

/// Kind of a vertex, from the edges and triangle fans around it.
enum class VertexKind : std::uint8_t
{
  Unused = 0,      // no triangle uses the vertex
  Interior = 1,    // one closed fan of triangles, every edge shared by exactly two triangles
  Boundary = 2,    // one open fan: exactly two of its edges are boundary edges
  NonManifold = 3, // several fans (a "bow tie"), or on an edge with more than two triangles
};

/// Marker values in TriangleTopology::EdgeNeighbors.
constexpr Id BoundaryEdge = -1;
constexpr Id NonManifoldEdge = -2;

/// Topology of a triangle mesh: adjacency, edge neighbours, vertex kinds.
///
/// Edge k of triangle t runs from corner k to corner (k + 1) % 3. EdgeNeighbors[3 t + k] is the
/// triangle on the other side of that edge, BoundaryEdge when there is none, NonManifoldEdge
/// when more than two triangles share it.
struct VTKFILTERSMESHLOD_EXPORT TriangleTopology
{
  VertexTriangleAdjacency VertexTriangles;
  std::vector<Id> EdgeNeighbors;
  std::vector<VertexKind> VertexKinds;
  /// Per triangle, bit k set when edge k is a boundary edge; filled only by
  /// KeepBoundaryFlagsOnly().
  std::vector<std::uint8_t> BoundaryFlags;
  /// IsConsistentlyOriented() of the mesh given to Build(), found on the way: valid while the
  /// mesh's triangles are those it was built from.
  bool OrientedWhenBuilt = true;

  /// Build everything (data-parallel over triangles and vertices).
  void Build(const TriangleMesh& mesh);

  /// Replace EdgeNeighbors (an id per half-edge) by BoundaryFlags (a byte per triangle), for a
  /// user that asks only IsBoundaryEdge(): 11 bytes less per triangle.
  void KeepBoundaryFlagsOnly();

  /// Whether edge k of triangle t is a boundary edge (no triangle on its other side).
  bool IsBoundaryEdge(Id t, int k) const
  {
    return this->EdgeNeighbors.empty()
      ? ((this->BoundaryFlags[t] >> k) & 1) != 0
      : this->EdgeNeighbors[3 * static_cast<std::size_t>(t) + k] == BoundaryEdge;
  }

  /// Number of distinct vertices joined to v by an edge.
  Id Valence(const TriangleMesh& mesh, Id v) const;

  /// Triangles that contain both a and b, in increasing id order; returns how many there are
  /// (writes at most maxCount of them).
  int TrianglesOnEdge(const TriangleMesh& mesh, Id a, Id b, Id* out, int maxCount) const;

  struct EdgeCounts
  {
    std::int64_t Boundary = 0;
    std::int64_t Manifold = 0;
    std::int64_t NonManifold = 0; // distinct edges with more than two triangles
    std::int64_t Total() const { return this->Boundary + this->Manifold + this->NonManifold; }
  };
  EdgeCounts CountEdges(const TriangleMesh& mesh) const;

  /// True when every manifold edge is traversed in opposite directions by its two triangles.
  bool IsConsistentlyOriented(const TriangleMesh& mesh) const;

  /// V - E + F over the used vertices.
  std::int64_t EulerCharacteristic(const TriangleMesh& mesh) const;

  std::int64_t CountVertices(VertexKind kind) const;
};

/// Index of vertex v in triangle tri (0, 1, 2), or -1.
inline int CornerOf(const Id* tri, Id v)
{
  return tri[0] == v ? 0 : (tri[1] == v ? 1 : (tri[2] == v ? 2 : -1));
}

/// A regular point of a curve where k > 2 sheets meet (see IsRegularCurveVertex).
struct CurveVertex
{
  Id Neighbours[2] = { InvalidId, InvalidId }; // the two vertices joined to it along the curve
  int Sheets = 0;                              // k: the triangles on each of its two curve edges
};

/// Whether non-manifold vertex v is a regular point of a curve of non-manifold edges: two edges
/// with the same k > 2 triangles, every other edge with two, and k fans of triangles (joined
/// across v's manifold edges) each running from one of the two to the other. The surfaces
/// between the regions of a segmented volume are made of such curves, the vertices where they
/// meet or end excepted. `ends` and `fan` are scratch; `curveVertex`, when given, receives the
/// curve neighbours and k.
VTKFILTERSMESHLOD_EXPORT bool IsRegularCurveVertex(const TriangleMesh& mesh,
  const VertexTriangleAdjacency& adj,
  Id v,
  std::vector<std::pair<Id, Id>>& ends,
  std::vector<Id>& fan,
  CurveVertex* curveVertex = nullptr);

/// Result of a compaction: the kept mesh and the maps from old to new ids.
struct VTKFILTERSMESHLOD_EXPORT CompactionMaps
{
  std::vector<Id> PointMap;    // old vertex -> new vertex, InvalidId when dropped
  std::vector<Id> TriangleMap; // old triangle -> new triangle, InvalidId when dropped
  std::vector<Id> KeptPoints;  // new vertex -> old vertex
  std::vector<Id> KeptTriangles; // new triangle -> old triangle
};

/// Remove deleted triangles (first id InvalidId) and the vertices no triangle uses any more,
/// preserving the relative order of everything kept. `out` may not alias `in`.
VTKFILTERSMESHLOD_EXPORT void CompactMesh(
  const TriangleMesh& in, TriangleMesh& out, CompactionMaps& maps);

} // namespace meshlod

#endif
