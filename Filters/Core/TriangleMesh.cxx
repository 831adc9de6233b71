#include "TriangleMesh.h"

#include "FreshMemory.h"
#include "GroupByKey.h"
#include "ParallelCompact.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace meshlod
{
//------------------------------------------------------------------------------
void TriangleMesh::AreaVector(Id t, double n[3]) const
{
  const Id* tri = this->Triangle(t);
  const double* a = this->Point(tri[0]);
  const double* b = this->Point(tri[1]);
  const double* c = this->Point(tri[2]);
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
}

//------------------------------------------------------------------------------
void ListSidesByLowerPoint(const Id* triangles, Id count, Id points, const unsigned char* skip,
  std::vector<Id>& offsets, std::vector<std::uint64_t>& sides)
{
  auto ends = [triangles](std::int64_t k) {
    const Id a = triangles[k], b = triangles[NextCorner(static_cast<Id>(k))];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  GroupItemsByKey(
    static_cast<std::size_t>(points), 3 * static_cast<std::int64_t>(count),
    [&](std::int64_t k) { return skip && skip[k / 3] ? Id(-1) : ends(k).first; },
    [&](std::int64_t k) {
      return std::uint64_t(ends(k).second) << 32 | static_cast<std::uint32_t>(k);
    },
    offsets, sides);
  vtkSMPTools::For(0, points, [&](Id begin, Id end) {
    for (Id p = begin; p < end; ++p)
    {
      std::sort(sides.begin() + offsets[p], sides.begin() + offsets[p + 1]);
    }
  });
}

//------------------------------------------------------------------------------
void VertexTriangleAdjacency::Build(const Id* triangles, Id numberOfTriangles, Id numberOfPoints)
{
  // Each corner in its point's row, in triangle order: each row sorted.
  GroupItemsByKey(
    static_cast<std::size_t>(numberOfPoints), 3 * static_cast<std::int64_t>(numberOfTriangles),
    [triangles](std::int64_t k) { return triangles[k - k % 3] == InvalidId ? -1 : triangles[k]; },
    [](std::int64_t k) { return static_cast<Id>(k / 3); }, this->Offsets, this->Triangles);
}

namespace
{
// Index of the edge of `tri` joining a and b (edge k joins corner k and corner k+1), or -1.
int EdgeIndexOf(const Id* tri, Id a, Id b)
{
  const int ca = CornerOf(tri, a);
  const int cb = CornerOf(tri, b);
  if (ca < 0 || cb < 0)
  {
    return -1;
  }
  return (ca + 1) % 3 == cb ? ca : cb;
}

// Walk around vertex v from triangle `start`, leaving through the edge (v, first) and then
// always through the other edge at v, until the fan closes or hits a non-interior edge.
// Returns the number of triangles visited (start excluded).
Id WalkFan(const TriangleMesh& mesh, const std::vector<Id>& neighbors, Id v, Id start, Id first,
  bool& closed)
{
  closed = false;
  Id visited = 0;
  Id t = start;
  Id through = first; // the edge (v, through) is the one we leave t by
  for (;;)
  {
    const Id* tri = mesh.Triangle(t);
    const Id next = neighbors[3 * static_cast<size_t>(t) + EdgeIndexOf(tri, v, through)];
    if (next < 0)
    {
      return visited;
    }
    if (next == start)
    {
      closed = true;
      return visited;
    }
    const Id* ntri = mesh.Triangle(next);
    // The third vertex of `next` (neither v nor `through`) names the edge we leave it by.
    Id other = InvalidId;
    for (int k = 0; k < 3; ++k)
    {
      if (ntri[k] != v && ntri[k] != through)
      {
        other = ntri[k];
      }
    }
    through = other;
    t = next;
    if (++visited > mesh.GetNumberOfTriangles())
    {
      return visited; // cannot happen on valid input; guards against an endless walk
    }
  }
}
} // namespace

//------------------------------------------------------------------------------
void TriangleTopology::Build(const TriangleMesh& mesh)
{
  const Id nt = mesh.GetNumberOfTriangles();
  const Id nv = mesh.GetNumberOfPoints();
  this->VertexTriangles.Build(mesh);
  AssignFresh(this->EdgeNeighbors, 3 * static_cast<size_t>(nt), BoundaryEdge);
  std::vector<std::uint8_t>().swap(this->BoundaryFlags);

  // Edge neighbours from the sides of the triangles listed at their lower point: the sides of
  // an edge are consecutive in that row, so no other triangle is read. (Scanning the triangles
  // around a corner for the other end read about eighteen triangles per triangle, at random
  // places on a mesh whose ids are scattered: on a 611k-triangle gyroid isosurface with its ids
  // shuffled the whole build took 0.37 s then, 0.15 s now, and in the contouring filter's order
  // 0.048 s then, 0.040 s now, one thread.) And whether each manifold edge's two triangles run it
  // in opposite directions.
  std::vector<unsigned char> deleted;
  for (Id t = 0; t < nt; ++t)
  {
    if (mesh.Triangle(t)[0] == InvalidId)
    {
      deleted.assign(nt, 0);
      for (Id s = t; s < nt; ++s)
      {
        deleted[s] = mesh.Triangle(s)[0] == InvalidId ? 1 : 0;
      }
      break;
    }
  }
  std::vector<Id> rows;
  std::vector<std::uint64_t> sides;
  ListSidesByLowerPoint(mesh.Triangles.data(), nt, nv, deleted.empty() ? nullptr : deleted.data(),
    rows, sides);
  std::atomic<bool> inconsistent(false);
  vtkSMPTools::For(0, nv, [&](Id begin, Id end) {
    bool clash = false;
    for (Id p = begin; p < end; ++p)
    {
      for (Id i = rows[p], next; i < rows[p + 1]; i = next)
      {
        const Id higher = SideHigherPoint(sides[i]);
        for (next = i + 1; next < rows[p + 1] && SideHigherPoint(sides[next]) == higher; ++next)
        {
        }
        if (next - i == 2)
        {
          const Id k0 = SideCorner(sides[i]);
          const Id k1 = SideCorner(sides[i + 1]);
          this->EdgeNeighbors[k0] = k0 / 3 == k1 / 3 ? NonManifoldEdge : k1 / 3;
          this->EdgeNeighbors[k1] = k0 / 3 == k1 / 3 ? NonManifoldEdge : k0 / 3;
          // Side k runs from corner k to the next: from p, or towards it.
          clash = clash || (mesh.Triangles[k0] == p) == (mesh.Triangles[k1] == p);
        }
        else if (next - i > 2)
        {
          for (Id j = i; j < next; ++j)
          {
            this->EdgeNeighbors[SideCorner(sides[j])] = NonManifoldEdge;
          }
        }
      }
    }
    if (clash)
    {
      inconsistent.store(true, std::memory_order_relaxed);
    }
  });
  Release(rows);
  Release(sides);
  const VertexTriangleAdjacency& adj = this->VertexTriangles;
  this->OrientedWhenBuilt = !inconsistent.load();

  // Vertex kinds: walk the fan of the first incident triangle; any triangle not reached means
  // several fans meet at the vertex.
  AssignFresh(this->VertexKinds, nv, VertexKind::Unused);
  vtkSMPTools::For(0, nv, [&](Id begin, Id end) {
    for (Id v = begin; v < end; ++v)
    {
      const Id count = adj.Count(v);
      if (count == 0)
      {
        continue;
      }
      bool nonManifold = false;
      Id boundaryEdges = 0;
      for (Id i = adj.Begin(v); i < adj.End(v) && !nonManifold; ++i)
      {
        const Id t = adj.Triangles[i];
        const int c = CornerOf(mesh.Triangle(t), v);
        // The two edges of t at v: edge c (v -> next) and edge c-1 (prev -> v).
        for (const int e : { c, (c + 2) % 3 })
        {
          const Id nb = this->EdgeNeighbors[3 * static_cast<size_t>(t) + e];
          nonManifold = nonManifold || nb == NonManifoldEdge;
          boundaryEdges += (nb == BoundaryEdge) ? 1 : 0;
        }
      }
      if (!nonManifold)
      {
        const Id start = adj.Triangles[adj.Begin(v)];
        const Id* tri = mesh.Triangle(start);
        const int c = CornerOf(tri, v);
        bool closed = false;
        Id reached = 1 + WalkFan(mesh, this->EdgeNeighbors, v, start, tri[(c + 1) % 3], closed);
        if (!closed)
        {
          reached += WalkFan(mesh, this->EdgeNeighbors, v, start, tri[(c + 2) % 3], closed);
        }
        nonManifold = reached != count || boundaryEdges > 2;
      }
      this->VertexKinds[v] = nonManifold
        ? VertexKind::NonManifold
        : (boundaryEdges > 0 ? VertexKind::Boundary : VertexKind::Interior);
    }
  });
}

//------------------------------------------------------------------------------
void TriangleMesh::GetBounds(double lo[3], double hi[3]) const
{
  // Per fixed block of points, then over the blocks, as one pass from point 0 would take them: the
  // first block starts from point 0, the others from an empty box, so that a NaN coordinate is
  // passed over wherever it lies (std::min keeps its first argument when the second is NaN), as
  // it was by the pass, rather than emptying the rest of its block.
  const FixedBlocks blocks{ this->GetNumberOfPoints() };
  const Id count = blocks.Count();
  std::vector<double> boxes(6 * static_cast<std::size_t>(count));
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    for (Id b = begin; b < end; ++b)
    {
      double* box = boxes.data() + 6 * b;
      for (int c = 0; c < 3; ++c)
      {
        box[c] = b == 0 ? this->Point(0)[c] : infinity;
        box[c + 3] = b == 0 ? this->Point(0)[c] : -infinity;
      }
      for (Id v = b == 0 ? 1 : blocks.Begin(b); v < blocks.End(b); ++v)
      {
        for (int c = 0; c < 3; ++c)
        {
          box[c] = std::min(box[c], this->Point(v)[c]);
          box[c + 3] = std::max(box[c + 3], this->Point(v)[c]);
        }
      }
    }
  });
  for (int c = 0; c < 3; ++c)
  {
    lo[c] = count > 0 ? boxes[c] : 0.0;
    hi[c] = count > 0 ? boxes[c + 3] : 0.0;
    for (Id b = 1; b < count; ++b)
    {
      lo[c] = std::min(lo[c], boxes[6 * b + c]);
      hi[c] = std::max(hi[c], boxes[6 * b + c + 3]);
    }
  }
}

//------------------------------------------------------------------------------
double TriangleMesh::BoundingDiagonal() const
{
  double lo[3], hi[3];
  this->GetBounds(lo, hi);
  return BoxDiagonal(lo, hi);
}

//------------------------------------------------------------------------------
double TriangleMesh::MeanTriangleArea() const
{
  constexpr Id Block = 8192;
  const Id triangles = this->GetNumberOfTriangles();
  const Id blocks = (triangles + Block - 1) / Block;
  std::vector<double> sums(2 * static_cast<std::size_t>(blocks), 0.0); // area, count per block
  vtkSMPTools::For(0, blocks, [&](Id begin, Id end) {
    for (Id b = begin; b < end; ++b)
    {
      for (Id t = b * Block; t < std::min(triangles, (b + 1) * Block); ++t)
      {
        double n[3];
        this->AreaVector(t, n);
        const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (area > 0.0)
        {
          sums[2 * b] += area;
          sums[2 * b + 1] += 1.0;
        }
      }
    }
  });
  double area = 0.0, count = 0.0;
  for (Id b = 0; b < blocks; ++b)
  {
    area += sums[2 * b];
    count += sums[2 * b + 1];
  }
  return count > 0.0 ? area / count : 0.0;
}

//------------------------------------------------------------------------------
double BoxDiagonal(const double lo[3], const double hi[3])
{
  // hypot: no overflow or underflow of the squares (a box of 1e-200 is not one of size 0).
  return std::hypot(hi[0] - lo[0], std::hypot(hi[1] - lo[1], hi[2] - lo[2]));
}

//------------------------------------------------------------------------------
void TriangleTopology::KeepBoundaryFlagsOnly()
{
  const Id nt = static_cast<Id>(this->EdgeNeighbors.size() / 3);
  AssignFresh(this->BoundaryFlags, nt, 0);
  for (Id t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (this->EdgeNeighbors[3 * static_cast<std::size_t>(t) + k] == BoundaryEdge)
      {
        this->BoundaryFlags[t] |= static_cast<std::uint8_t>(1u << k);
      }
    }
  }
  Release(this->EdgeNeighbors);
}

//------------------------------------------------------------------------------
Id TriangleTopology::Valence(const TriangleMesh& mesh, Id v) const
{
  std::vector<Id> neighbors;
  for (Id i = this->VertexTriangles.Begin(v); i < this->VertexTriangles.End(v); ++i)
  {
    const Id* tri = mesh.Triangle(this->VertexTriangles.Triangles[i]);
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] != v)
      {
        neighbors.push_back(tri[k]);
      }
    }
  }
  std::sort(neighbors.begin(), neighbors.end());
  return static_cast<Id>(std::unique(neighbors.begin(), neighbors.end()) - neighbors.begin());
}

//------------------------------------------------------------------------------
int TriangleTopology::TrianglesOnEdge(
  const TriangleMesh& mesh, Id a, Id b, Id* out, int maxCount) const
{
  if (this->VertexTriangles.Count(b) < this->VertexTriangles.Count(a))
  {
    std::swap(a, b); // scan the shorter row; both list their triangles in increasing order
  }
  int count = 0;
  for (Id i = this->VertexTriangles.Begin(a); i < this->VertexTriangles.End(a); ++i)
  {
    const Id t = this->VertexTriangles.Triangles[i];
    if (CornerOf(mesh.Triangle(t), b) >= 0)
    {
      if (count < maxCount)
      {
        out[count] = t;
      }
      ++count;
    }
  }
  return count;
}

//------------------------------------------------------------------------------
// Calls f(t, k, neighbour) for edge k of every live triangle t until f returns false; returns
// whether every call returned true.
namespace
{
template <typename F>
bool ForEachLiveEdge(const TriangleMesh& mesh, const std::vector<Id>& edgeNeighbors, F&& f)
{
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    if (mesh.Triangle(t)[0] == InvalidId)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      if (!f(t, k, edgeNeighbors[3 * static_cast<size_t>(t) + k]))
      {
        return false;
      }
    }
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
TriangleTopology::EdgeCounts TriangleTopology::CountEdges(const TriangleMesh& mesh) const
{
  EdgeCounts counts;
  ForEachLiveEdge(mesh, this->EdgeNeighbors, [&](Id t, int k, Id nb) {
    if (nb == BoundaryEdge)
    {
      ++counts.Boundary;
    }
    else if (nb >= 0)
    {
      counts.Manifold += (t < nb) ? 1 : 0;
    }
    else
    {
      // Count a non-manifold edge once: from the lowest triangle id on it.
      const Id* tri = mesh.Triangle(t);
      Id first = InvalidId;
      this->TrianglesOnEdge(mesh, tri[k], tri[(k + 1) % 3], &first, 1);
      counts.NonManifold += (first == t) ? 1 : 0;
    }
    return true;
  });
  return counts;
}

//------------------------------------------------------------------------------
bool TriangleTopology::IsConsistentlyOriented(const TriangleMesh& mesh) const
{
  return ForEachLiveEdge(mesh, this->EdgeNeighbors, [&](Id t, int k, Id nb) {
    if (nb < 0)
    {
      return true;
    }
    // t runs a -> b, so the neighbour must run b -> a.
    const Id* tri = mesh.Triangle(t);
    const Id* ntri = mesh.Triangle(nb);
    const int cb = CornerOf(ntri, tri[(k + 1) % 3]);
    return ntri[(cb + 1) % 3] == tri[k];
  });
}

//------------------------------------------------------------------------------
std::int64_t TriangleTopology::CountVertices(VertexKind kind) const
{
  return std::count(this->VertexKinds.begin(), this->VertexKinds.end(), kind);
}

//------------------------------------------------------------------------------
std::int64_t TriangleTopology::EulerCharacteristic(const TriangleMesh& mesh) const
{
  std::int64_t faces = 0;
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    faces += mesh.Triangle(t)[0] == InvalidId ? 0 : 1;
  }
  const std::int64_t vertices =
    static_cast<std::int64_t>(this->VertexKinds.size()) - this->CountVertices(VertexKind::Unused);
  return vertices - this->CountEdges(mesh).Total() + faces;
}

//------------------------------------------------------------------------------
void CompactMesh(const TriangleMesh& in, TriangleMesh& out, CompactionMaps& maps)
{
  const Id nt = in.GetNumberOfTriangles();
  const Id nv = in.GetNumberOfPoints();
  AssignFresh(maps.PointMap, nv, InvalidId);
  AssignFresh(maps.TriangleMap, nt, InvalidId);
  maps.KeptTriangles.clear();
  maps.KeptPoints.clear();

  std::vector<unsigned char> used(nv, 0);
  for (Id t = 0; t < nt; ++t)
  {
    const Id* tri = in.Triangle(t);
    if (tri[0] == InvalidId)
    {
      continue;
    }
    maps.TriangleMap[t] = static_cast<Id>(maps.KeptTriangles.size());
    maps.KeptTriangles.push_back(t);
    used[tri[0]] = used[tri[1]] = used[tri[2]] = 1;
  }
  for (Id v = 0; v < nv; ++v)
  {
    if (used[v])
    {
      maps.PointMap[v] = static_cast<Id>(maps.KeptPoints.size());
      maps.KeptPoints.push_back(v);
    }
  }

  const Id keptTriangles = static_cast<Id>(maps.KeptTriangles.size());
  const Id keptPoints = static_cast<Id>(maps.KeptPoints.size());
  ResizeFresh(out.Points, 3 * static_cast<size_t>(keptPoints));
  ResizeFresh(out.Triangles, 3 * static_cast<size_t>(keptTriangles));
  vtkSMPTools::For(0, keptPoints, [&](Id begin, Id end) {
    for (Id v = begin; v < end; ++v)
    {
      std::copy_n(in.Point(maps.KeptPoints[v]), 3, out.Point(v));
    }
  });
  vtkSMPTools::For(0, keptTriangles, [&](Id begin, Id end) {
    for (Id t = begin; t < end; ++t)
    {
      const Id* tri = in.Triangle(maps.KeptTriangles[t]);
      Id* dst = out.Triangle(t);
      for (int k = 0; k < 3; ++k)
      {
        dst[k] = maps.PointMap[tri[k]];
      }
    }
  });
}

//------------------------------------------------------------------------------
bool IsRegularCurveVertex(const TriangleMesh& mesh,
  const VertexTriangleAdjacency& adj,
  Id v,
  std::vector<std::pair<Id, Id>>& ends,
  std::vector<Id>& fan,
  CurveVertex* curveVertex)
{
  const Id first = adj.Begin(v);
  const Id count = adj.Count(v);
  ends.clear(); // (neighbour, index of the triangle in v's row), for both edges of it at v
  for (Id i = 0; i < count; ++i)
  {
    const Id* tri = mesh.Triangle(adj.Triangles[first + i]);
    const int c = CornerOf(tri, v);
    ends.emplace_back(tri[(c + 1) % 3], i);
    ends.emplace_back(tri[(c + 2) % 3], i);
  }
  std::sort(ends.begin(), ends.end());
  // Union of the triangles across each manifold edge (two triangles on it); the two curve
  // edges by their neighbour.
  fan.resize(static_cast<std::size_t>(count));
  std::iota(fan.begin(), fan.end(), 0);
  const auto root = [&](Id i) { return FindRoot(fan, i); };
  Id curve[2] = { InvalidId, InvalidId };
  std::size_t sheets = 0;
  int curves = 0;
  for (std::size_t i = 0; i < ends.size();)
  {
    std::size_t run = 1;
    while (i + run < ends.size() && ends[i + run].first == ends[i].first)
    {
      ++run;
    }
    if (run == 2)
    {
      fan[root(ends[i].second)] = root(ends[i + 1].second);
    }
    else if (run < 2 || curves == 2 || (curves == 1 && run != sheets))
    {
      return false; // a boundary edge, a third curve edge, or curve edges of unequal counts
    }
    else
    {
      curve[curves++] = ends[i].first;
      sheets = run;
    }
    i += run;
  }
  if (curves != 2)
  {
    return false;
  }
  // Each fan must hold exactly one triangle on each curve edge; then there are k fans.
  std::vector<std::pair<Id, Id>>& touches = ends; // reused: (fan root, which curve edge)
  touches.clear();
  for (Id i = 0; i < count; ++i)
  {
    const Id* tri = mesh.Triangle(adj.Triangles[first + i]);
    for (int e = 0; e < 2; ++e)
    {
      if (CornerOf(tri, curve[e]) >= 0)
      {
        touches.emplace_back(root(i), e);
      }
    }
  }
  std::sort(touches.begin(), touches.end());
  if (touches.size() != 2 * sheets)
  {
    return false;
  }
  for (std::size_t i = 0; i < touches.size(); i += 2)
  {
    if (touches[i].first != touches[i + 1].first || touches[i].second != 0 ||
      touches[i + 1].second != 1)
    {
      return false; // a fan from one curve edge back to it, or one reaching neither
    }
  }
  // Every triangle is in a fan that touches the curve: no closed fan (bow tie) besides.
  for (Id i = 0; i < count; ++i)
  {
    if (!std::binary_search(touches.begin(), touches.end(), std::make_pair(root(i), Id(0))))
    {
      return false;
    }
  }
  if (curveVertex)
  {
    curveVertex->Neighbours[0] = curve[0];
    curveVertex->Neighbours[1] = curve[1];
    curveVertex->Sheets = static_cast<int>(sheets);
  }
  return true;
}

} // namespace meshlod
