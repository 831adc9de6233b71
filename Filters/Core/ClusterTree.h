// MeshLOD core: the cluster tree of adaptive octree vertex clustering (see OctreeClustering.h).
//
// A node is a set of vertices that lie in one cell of a subdivision of the bounding cube and are
// connected by mesh edges inside that cell (up to islands, a few vertices that poke through a
// cell face: they count as lying in the cell of their nearest neighbour, see PlaceIslands).
// The subdivision is an octree whose every split is made as three binary splits (x, then y,
// then z): octree depth k is depth 3 k here, and the depths in between are halves and quarters
// of octree cells. Going up, the parts of the child cells merge where edges join them inside
// the parent cell; each merge is a node, so the tree has the vertices as leaves (ids [0, NV))
// and the internal nodes above them (ids NV + i, a parent always after its children). The
// vertices of a node occupy one contiguous range of a depth-first vertex order (Order / PosOf).
//
// Built bottom-up like Kruskal's algorithm: every half-edge is sorted by the depth at which its
// two ends part (the common prefix of their Morton codes), and a union-find merges the parts of
// each cell depth by depth. Cells of octree depth 4 are built in parallel, the few merges above
// them serially, so the tree does not depend on the thread count.
//
// While a node is built it carries the quadric of its related triangle set (every triangle with
// a vertex in it, counted once, plus the perpendicular planes of the boundary edges at its
// vertices): summed from its children, minus the triangles counted twice, which are those whose
// closest pair of vertices first meets in the node and those whose three vertices first meet in
// it (inclusion-exclusion). From it the node's e1 error is kept; the quadric itself is dropped,
// and RelatedQuadric() recomputes it when a node is evaluated in full.
#ifndef meshlod_ClusterTree_h
#define meshlod_ClusterTree_h

#include "Quadric.h"
#include "TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"

#include <cstdint>
#include <vector>

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT ClusterTreeOptions
{
  /// Weight of the boundary-edge planes: BoundaryWeight * squared edge length.
  double BoundaryWeight = 1.0;
  /// Eigenvalues below this fraction of the largest are treated as zero when placing.
  double PlacementTolerance = 1e-3;
};

/// The related triangle set of a node in detail (ClusterTree::RelatedQuadric).
struct RelatedTriangles
{
  std::vector<Id> Crossing;            // triangles with exactly one vertex inside: 3 t + its corner
  std::vector<Quadric> CrossingPlanes; // their area-weighted plane quadrics
  std::vector<double> CrossingNormals; // their normals, 3 numbers each (twice the area long)
  std::vector<double> CrossingEnds;    // their corners outside, relative to Centre: 6 numbers
  std::vector<Id> BoundaryEdges;       // boundary edges with an end inside: 3 t + k for edge k
  std::vector<double> Planes;          // every triangle's plane: unit normal and offset
};

/// An internal node of the tree.
struct ClusterNode
{
  Id Count = 0; // number of vertices
  Id Parent = InvalidId;
  Id Dies = 0;             // triangles that degenerate when this node (or an ancestor) is collapsed
  float E1 = 0.0f;         // e1 error: sqrt(min Q1 / weight of Q1)
  std::uint8_t Depth = 0;  // binary splits of the cell the node forms in
  std::uint8_t Locked = 0; // holds a locked vertex (non-manifold, not a regular curve point)
  std::uint8_t Curve = 0;  // holds a regular point of a curve where sheets meet
  std::uint8_t Seam = 0;   // holds a vertex of a seam of a part that cannot be oriented
};

class VTKFILTERSMESHLOD_EXPORT ClusterTree
{
public:
  static constexpr int AxisBits = 20;
  static constexpr int MaxDepth = 3 * AxisBits;

  /// `mesh` and `topology` must outlive the tree.
  void Build(const TriangleMesh& mesh,
    const TriangleTopology& topology,
    const ClusterTreeOptions& options);

  const TriangleMesh* Mesh = nullptr;
  const TriangleTopology* Topology = nullptr;
  ClusterTreeOptions Options;
  Id NV = 0;
  double Centre[3] = { 0.0, 0.0, 0.0 }; // positions in the tree are relative to this point
  double Corner[3] = { 0.0, 0.0, 0.0 }; // lowest corner of the bounding cube
  double Size = 1.0;                    // edge of the bounding cube
  double Extent = 0.0; // the largest extent of the points (0 when all lie at one place)

  std::vector<ClusterNode> Nodes; // internal node NV + i is Nodes[i]
  std::vector<Id> LeafParent;     // vertex -> parent node, InvalidId for a lone vertex
  std::vector<Id> Begin;          // internal node -> first position in Order
  std::vector<Id> Order;          // depth-first vertex order
  std::vector<Id> PosOf;          // vertex -> position in Order
  // The children of internal node NV + i, in depth-first order: Children[ChildOffsets[i] ..
  // ChildOffsets[i + 1]); and the roots (nodes without a parent) in depth-first order.
  std::vector<Id> ChildOffsets;
  std::vector<Id> Children;
  std::vector<Id> Roots;
  // The internal nodes built cell by cell (the bottom tier), Nodes[CellNodeOffsets[c] ..
  // CellNodeOffsets[c + 1]) for cell c; their parents lie in the same range or in the top tier,
  // Nodes[CellNodeOffsets.back() ..).
  std::vector<Id> CellNodeOffsets;
  int Depth = 0;                  // deepest node
  /// Per vertex, its curve neighbours and sheet count when it is a regular point of a curve
  /// where sheets meet (IsRegularCurveVertex; Sheets 0 otherwise). Empty when the mesh has no
  /// such vertex (a manifold mesh), so that it costs nothing there.
  std::vector<CurveVertex> Curves;
  /// The input's edges of more than two triangles whose two ends are both locked (a curve of a
  /// single edge between two junctions): ends, and the number of triangles on it.
  struct LockedEdge
  {
    Id A, B;
    int Sheets;
  };
  std::vector<LockedEdge> LockedEdges;

  /// Per vertex, 1 where an edge at it is traversed in the same direction by its two triangles
  /// (the seam of a part that cannot be oriented, such as a Moebius strip or Boy's surface):
  /// there the winding of the triangles on either side says nothing about their facing. Empty
  /// when the mesh is consistently oriented.
  std::vector<std::uint8_t> Seams;

  bool IsCurve(Id v) const { return !this->Curves.empty() && this->Curves[v].Sheets > 0; }
  bool IsSeam(Id v) const { return !this->Seams.empty() && this->Seams[v] != 0; }
  /// Whether a node (a vertex, or an internal node) holds a seam vertex.
  bool HoldsSeam(Id node) const
  {
    return this->IsLeaf(node) ? this->IsSeam(node) : this->Internal(node).Seam != 0;
  }
  /// Whether a node (a vertex, or an internal node) holds a regular curve point.
  bool HoldsCurve(Id node) const
  {
    return this->IsLeaf(node) ? this->IsCurve(node) : this->Internal(node).Curve != 0;
  }
  bool IsLocked(Id v) const
  {
    return this->Topology->VertexKinds[v] == VertexKind::NonManifold && !this->IsCurve(v);
  }

  Id NumberOfInternalNodes() const { return static_cast<Id>(this->Nodes.size()); }
  bool IsLeaf(Id node) const { return node < this->NV; }
  const ClusterNode& Internal(Id node) const { return this->Nodes[node - this->NV]; }
  Id Parent(Id node) const
  {
    return node < this->NV ? this->LeafParent[node] : this->Nodes[node - this->NV].Parent;
  }
  Id Count(Id node) const { return node < this->NV ? 1 : this->Nodes[node - this->NV].Count; }
  Id Position(Id node) const
  {
    return node < this->NV ? this->PosOf[node] : this->Begin[node - this->NV];
  }
  /// Whether vertex v belongs to `node`.
  bool Contains(Id node, Id v) const
  {
    const Id p = this->PosOf[v];
    return p >= this->Position(node) && p < this->Position(node) + this->Count(node);
  }

  /// Point of vertex v relative to Centre.
  void RelativePoint(Id v, double out[3]) const
  {
    const double* p = this->Mesh->Point(v);
    out[0] = p[0] - this->Centre[0];
    out[1] = p[1] - this->Centre[1];
    out[2] = p[2] - this->Centre[2];
  }
  /// The corners of triangle `tri` relative to Centre.
  void RelativeTriangle(const Id* tri, double p[3][3]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      this->RelativePoint(tri[k], p[k]);
    }
  }
  /// The longest edge of the cell of a node formed at `depth`.
  double CellSize(int depth) const;
  /// The cell of `depth` of vertex v's code (for an island's vertex, its neighbour's cell):
  /// lowest corner (relative to Centre) and edge lengths.
  void CellBox(Id v, int depth, double low[3], double extent[3]) const;
  /// Morton code of vertex v's finest cell (x bits highest within each level); an island's
  /// vertex has its outside neighbour's code (see PlaceIslands).
  std::uint64_t Morton(Id v) const { return this->Codes[v]; }
  std::vector<std::uint64_t> Codes; // per vertex
  /// The deepest depth at which two vertices share a cell.
  int CommonDepth(Id a, Id b) const { return CommonDepth(this->Morton(a), this->Morton(b)); }
  static int CommonDepth(std::uint64_t a, std::uint64_t b)
  {
    const std::uint64_t x = a ^ b;
#if defined(__GNUC__) || defined(__clang__)
    return MaxDepth - (x == 0 ? 0 : 64 - __builtin_clzll(x));
#else
    int bits = 0;
    for (std::uint64_t y = x; y != 0; y >>= 1)
    {
      ++bits;
    }
    return MaxDepth - bits;
#endif
  }
  /// The children of internal node `node`, in depth-first order.
  const Id* ChildrenBegin(Id node) const
  {
    return this->Children.data() + this->ChildOffsets[node - this->NV];
  }
  const Id* ChildrenEnd(Id node) const
  {
    return this->Children.data() + this->ChildOffsets[node - this->NV + 1];
  }
  /// The centroid of a node's vertices (relative to Centre).
  void Centroid(Id node, double out[3]) const;

  /// The quadric of the related triangle set of `node`, recomputed from its vertices, with
  /// `normal` (optional) the sum of the area-weighted normals of its triangles and `details`
  /// (optional) the lists of RelatedTriangles.
  void RelatedQuadric(
    Id node, Quadric& q, double normal[3], RelatedTriangles* details = nullptr) const;

  /// The quadric of the related triangle set of a single vertex.
  void VertexQuadric(Id v, Quadric& q, double normal[3]) const;

private:
  struct Builder;
  void HintRelated(Id pos, Id last) const;
  void ComputeFrame();
  void ComputeCodes();
  void PlaceIslands();
  void FindCurves();
  void FindSeams();
  // Build's steps after the codes: the vertices bucketed by their cell of the bottom tier, that
  // tier built cell by cell (in parallel, on provisional node ids), its nodes given their final
  // ids, and the top tier built over them (serially).
  struct BottomTier;
  void BucketVertices(BottomTier& tier) const;
  void BuildBottomTier(Builder& builder, BottomTier& tier);
  void RenumberBottomTier(Builder& builder, BottomTier& tier);
  void BuildTopTier(Builder& builder, BottomTier& tier);
  void ComputeOrder();
  void ComputeChildren();
};

} // namespace meshlod

#endif
