#include "CollapseMesh.h"

#include "FreshMemory.h"
#include "Vector3.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace meshlod
{
namespace
{
int CountMembers(const Id* tri, const Id* members, int count)
{
  int n = 0;
  for (int k = 0; k < 3; ++k)
  {
    for (int m = 0; m < count; ++m)
    {
      n += tri[k] == members[m] ? 1 : 0;
    }
  }
  return n;
}
} // namespace

//------------------------------------------------------------------------------
double TriangleNormal(const double* p0, const double* p1, const double* p2, double normal[3])
{
  double e1[3], e2[3];
  Subtract(p1, p0, e1);
  Subtract(p2, p0, e2);
  Cross(e1, e2, normal);
  const double length = std::sqrt(Dot(normal, normal));
  if (length > 0.0)
  {
    normal[0] /= length;
    normal[1] /= length;
    normal[2] /= length;
  }
  return length;
}

//------------------------------------------------------------------------------
void CollapseMesh::Initialize(TriangleMesh&& input, TriangleTopology&& topology,
  double boundaryWeight, double boundaryScale, double planeWeight)
{
  this->Mesh = std::move(input);
  const TriangleMesh& mesh = this->Mesh;
  const Id nv = mesh.GetNumberOfPoints();
  const Id nt = mesh.GetNumberOfTriangles();
  AssignFresh(this->Flags, nv, 0);
  AssignFresh(this->Quadrics, nv, Quadric());
  AssignFresh(this->SurfaceWeights, nv, 0.0);
  AssignFresh(this->Facing, 3 * static_cast<std::size_t>(nv), 0.0f);
  const double areaUnit = SquaredLengthUnit(boundaryScale); // the diagonal (1 for one point)
  ResizeFresh(this->Survivor, nv);
  std::iota(this->Survivor.begin(), this->Survivor.end(), 0);
  this->AliveTriangles = nt;
  this->AliveAtLastRebuild = nt;

  const VertexTriangleAdjacency& adj = topology.VertexTriangles;
  vtkSMPTools::For(0, nv, [&](Id begin, Id end) {
    std::vector<std::pair<Id, Id>> ends;
    std::vector<Id> fan;
    for (Id v = begin; v < end; ++v)
    {
      const VertexKind kind = topology.VertexKinds[v];
      if (kind == VertexKind::NonManifold)
      {
        this->Flags[v] = IsRegularCurveVertex(mesh, adj, v, ends, fan) ? FlagCurve : FlagLocked;
      }
      else
      {
        this->Flags[v] = kind == VertexKind::Boundary ? FlagBoundary : 0;
      }
      this->SumPlanes(v, topology, boundaryWeight, boundaryScale, planeWeight, areaUnit);
    }
  });

  ResizeFresh(this->TriangleCounts, nv);
  double surface = 0.0; // in vertex order, for the same sum on any thread count
  for (Id v = 0; v < nv; ++v)
  {
    this->TriangleCounts[v] = adj.Count(v);
    surface += this->SurfaceWeights[v];
  }
  // (Each plane went to its triangle's three corners. A power-of-two scaling of the input
  // scales every weight and this unit alike, exactly.)
  this->SurfaceWeightUnit = surface > 0.0 && nt > 0 ? surface / (3.0 * nt) : 1.0;

  // The topology's vertex -> triangle rows are the first rows.
  this->Rows.Offsets.swap(topology.VertexTriangles.Offsets);
  this->Rows.Triangles.swap(topology.VertexTriangles.Triangles);
  topology = TriangleTopology();
  this->ResetChains();
}

//------------------------------------------------------------------------------
void CollapseMesh::SumPlanes(Id v, const TriangleTopology& topology, double boundaryWeight,
  double boundaryScale, double planeWeight, double areaUnit)
{
  const TriangleMesh& mesh = this->Mesh;
  const VertexTriangleAdjacency& adj = topology.VertexTriangles;
  Quadric q;
  double surface = 0.0;
  double facing[3] = { 0, 0, 0 };
  for (Id i = adj.Begin(v); i < adj.End(v); ++i)
  {
    const Id t = adj.Triangles[i];
    const Id* tri = mesh.Triangle(t);
    Quadric plane;
    double normal[3];
    if (!TriangleQuadric(
          mesh.Point(tri[0]), mesh.Point(tri[1]), mesh.Point(tri[2]), plane, normal))
    {
      continue; // degenerate triangle
    }
    if (planeWeight > 0.0)
    {
      // (TriangleQuadric weighs the plane by the area, half the normal's length.)
      q.Add(plane, 2.0 * planeWeight / std::sqrt(Dot(normal, normal)));
      surface += planeWeight;
    }
    else
    {
      q += plane;
      surface += plane.Weight();
    }
    for (int i = 0; i < 3; ++i)
    {
      facing[i] += normal[i] / 6.0; // a third of the area vector (normal is twice it)
    }
    // Boundary edges of t at v get a plane through the edge, perpendicular to t, so that
    // the boundary resists moving sideways. (A curve where sheets meet needs none: the
    // planes of the sheets, in different directions, hold a vertex to it; planes through
    // its edges as well would keep it at every wiggle of the input's curve: on a smoothed
    // segmentation, 1.7 times the RMS distance at the coarse levels.)
    const int c = CornerOf(tri, v);
    for (const int e : { c, (c + 2) % 3 })
    {
      if (topology.EdgeNeighbors[3 * static_cast<std::size_t>(t) + e] == BoundaryEdge)
      {
        Quadric side;
        BoundaryEdgeQuadric(mesh.Point(tri[e]), mesh.Point(tri[(e + 1) % 3]), normal,
          boundaryWeight, side, boundaryScale);
        q += side;
      }
    }
  }
  this->Quadrics[v] = q;
  this->SurfaceWeights[v] = surface;
  for (int i = 0; i < 3; ++i)
  {
    this->Facing[3 * static_cast<std::size_t>(v) + i] = static_cast<float>(facing[i] * areaUnit);
  }
}

//------------------------------------------------------------------------------
void CollapseMesh::ResetChains()
{
  const Id nv = this->Mesh.GetNumberOfPoints();
  AssignFresh(this->ChainNext, nv, InvalidId);
  ResizeFresh(this->ChainTail, nv);
  std::iota(this->ChainTail.begin(), this->ChainTail.end(), 0);
}

//------------------------------------------------------------------------------
void CollapseMesh::RebuildRows()
{
  this->Rows.Build(this->Mesh); // reuses the rows' memory
  this->ResetChains();
  this->AliveAtLastRebuild = this->AliveTriangles;
}

//------------------------------------------------------------------------------
void CollapseMesh::SetCorners(Id t, const Id corners[3])
{
  Id* tri = this->Mesh.Triangle(t);
  for (int k = 0; k < 3; ++k)
  {
    --this->TriangleCounts[tri[k]];
  }
  for (int k = 0; k < 3; ++k)
  {
    tri[k] = corners[k];
    ++this->TriangleCounts[tri[k]];
  }
}

//------------------------------------------------------------------------------
void CollapseMesh::Prefetch(Id t, int stage) const
{
  const Id* tri = this->Mesh.Triangle(t);
  if (tri[0] == InvalidId)
  {
    return; // died meanwhile: its other corners may be stale
  }
  const auto vertex = [&](Id v) {
    CacheHint(this->Mesh.Point(v));
    CacheHint(this->Quadrics[v].Q);
    CacheHint(this->Quadrics[v].Q + 9);
    CacheHint(this->SurfaceWeights.data() + v);
    CacheHint(this->Facing.data() + 3 * static_cast<std::size_t>(v));
    CacheHint(this->Flags.data() + v);
    CacheHint(this->TriangleCounts.data() + v);
  };
  for (int k = 0; k < 3; ++k)
  {
    const Id v = tri[k];
    if (stage == 0)
    {
      vertex(v);
      CacheHint(this->Survivor.data() + v);
      CacheHint(this->ChainNext.data() + v);
      CacheHint(this->Rows.Offsets.data() + v);
      continue;
    }
    // At most the first FanTriangleLimit entries of the row: hints for a whole fan of thousands of
    // triangles, asked for every candidate next to its centre, took 90% of the time of a flat
    // fan of 120,000 triangles (and help nothing there: they cannot all stay in the cache).
    const Id* row = this->Rows.Triangles.data() + this->Rows.Begin(v);
    const Id* rowEnd = std::min(this->Rows.Triangles.data() + this->Rows.End(v),
      row + static_cast<std::ptrdiff_t>(FanTriangleLimit));
    if (stage == 1)
    {
      for (const Id* entry = row; entry < rowEnd; entry += 16)
      {
        CacheHint(entry);
      }
      continue;
    }
    for (const Id* entry = row; entry < rowEnd; ++entry)
    {
      const Id* around = this->Mesh.Triangle(*entry);
      if (stage == 2)
      {
        CacheHint(around);
      }
      else if (around[0] != InvalidId)
      {
        vertex(around[0]);
        vertex(around[1]);
        vertex(around[2]);
      }
    }
  }
}

//------------------------------------------------------------------------------
bool CollapseMesh::HasValenceAtLeast(Id v, int n, std::vector<Id>& scratch) const
{
  if (!this->IsLocked(v) && !this->IsCurve(v))
  {
    // A manifold fan: as many neighbours as triangles, plus one when the fan is open.
    return this->TriangleCounts[v] + (this->IsBoundary(v) ? 1 : 0) >= n;
  }
  // Distinct neighbours, counted until there are n: a locked vertex can have thousands (cones
  // sharing their apex), and sorting all of them for every check next to it took nearly the
  // whole run.
  scratch.clear();
  return this->AnyTriangle(v, [&](Id t) {
    const Id* tri = this->Mesh.Triangle(t);
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] != v && std::find(scratch.begin(), scratch.end(), tri[k]) == scratch.end())
      {
        scratch.push_back(tri[k]);
      }
    }
    return static_cast<int>(scratch.size()) >= n;
  });
}

//------------------------------------------------------------------------------
bool CollapseMesh::GatherStar(const Id* members, int count, Star& star) const
{
  star.MemberCount = count;
  std::copy_n(members, count, star.Members);
  std::sort(star.Members, star.Members + count);
  star.Dying.clear();
  star.Ring.clear();
  star.RingCorner.clear();
  star.Apexes.clear();
  star.Foreign = false;
  for (int m = 0; m < count; ++m)
  {
    const Id v = star.Members[m];
    if (this->IsLocked(v) || this->Survivor[v] != v)
    {
      return false;
    }
  }
  for (int m = 0; m < count; ++m)
  {
    const Id v = star.Members[m];
    this->ForEachTriangle(v, [&](Id t) {
      const Id* tri = this->Mesh.Triangle(t);
      if (star.Owner != nullptr &&
        !CornersOwnedBy(star.Owner, tri, star.Block))
      {
        star.Foreign = true;
      }
      const int inside = CountMembers(tri, star.Members, count);
      if (inside == 1)
      {
        star.Ring.push_back(t);
        star.RingCorner.push_back(static_cast<std::int8_t>(CornerOf(tri, v)));
        return;
      }
      // A triangle with several members is seen from each of them: keep it once, from the
      // first member it contains.
      for (int earlier = 0; earlier < m; ++earlier)
      {
        if (CornerOf(tri, star.Members[earlier]) >= 0)
        {
          return;
        }
      }
      star.Dying.push_back(t);
      if (inside == 2)
      {
        for (int k = 0; k < 3; ++k)
        {
          if (std::find(star.Members, star.Members + count, tri[k]) == star.Members + count)
          {
            star.Apexes.push_back(tri[k]);
          }
        }
      }
    });
  }
  // Each edge between manifold members has at most two triangles, so a triangle collapse kills
  // at most 4 triangles and an edge collapse at most 2; an edge along a curve where sheets meet
  // kills one per sheet (IsLegal checks it is such an edge).
  bool curve = false;
  for (int m = 0; m < count; ++m)
  {
    curve = curve || this->IsCurve(star.Members[m]);
  }
  if (curve && count >= 3)
  {
    return false; // only edge collapses touch such a curve
  }
  if (count > 3) // a vanishing piece: all of its triangles die
  {
    return !star.Foreign && !star.Dying.empty() && star.Ring.empty();
  }
  const std::size_t most = count == 3 ? 4 : 2;
  return !star.Foreign && !star.Dying.empty() && (curve || star.Dying.size() <= most);
}

//------------------------------------------------------------------------------
void CollapseMesh::TrackPieces()
{
  // Union-find over the triangles' edges, then pieces numbered by their lowest vertex.
  const Id nv = this->Mesh.GetNumberOfPoints();
  const Id nt = this->Mesh.GetNumberOfTriangles();
  std::vector<Id>& parent = this->PieceOf;
  ResizeFresh(parent, nv);
  this->JoinLiveTriangles(parent);
  Id pieces = 0;
  std::vector<Id> label(nv);
  this->PieceVertex.clear();
  for (Id v = 0; v < nv; ++v) // a root is the lowest vertex of its piece: labelled first
  {
    const Id r = FindRoot(parent, v);
    if (r == v)
    {
      this->PieceVertex.push_back(v);
      label[v] = pieces++;
    }
    else
    {
      label[v] = label[r];
    }
  }
  parent.swap(label);
  this->PieceTriangles.reset(new std::atomic<Id>[static_cast<std::size_t>(pieces)]);
  this->Pieces = pieces;
  std::vector<Id> triangles(static_cast<std::size_t>(pieces), 0);
  for (Id t = 0; t < nt; ++t)
  {
    if (this->IsAlive(t))
    {
      ++triangles[parent[this->Mesh.Triangle(t)[0]]];
    }
  }
  this->LargestPiece = InvalidId;
  for (Id p = 0; p < pieces; ++p)
  {
    this->PieceTriangles[p].store(triangles[p], std::memory_order_relaxed);
    if (this->LargestPiece == InvalidId || triangles[p] > triangles[this->LargestPiece])
    {
      this->LargestPiece = p;
    }
  }
}

void CollapseMesh::FreezePieceCounts()
{
  ResizeFresh(this->FrozenPieceTriangles, this->Pieces);
  for (Id p = 0; p < this->Pieces; ++p)
  {
    this->FrozenPieceTriangles[p] = this->PieceTriangles[p].load(std::memory_order_relaxed);
  }
}

void CollapseMesh::PiecesTurnedSmall(std::vector<Id>& vertices) const
{
  vertices.clear();
  for (Id p = 0; p < static_cast<Id>(this->FrozenPieceTriangles.size()); ++p)
  {
    const Id now = this->PieceTriangles[p].load(std::memory_order_relaxed);
    if (this->FrozenPieceTriangles[p] > VanishingPieceTriangles && now > 0 &&
      now <= VanishingPieceTriangles)
    {
      vertices.push_back(this->PieceVertex[p]);
    }
  }
}

Id CollapseMesh::CountLivePieces(std::vector<Id>& parent) const
{
  Id live = 0;
  if (!this->PieceOf.empty())
  {
    for (Id p = 0; p < this->Pieces; ++p)
    {
      live += this->PieceTriangles[p].load(std::memory_order_relaxed) > 0 ? 1 : 0;
    }
    return live;
  }
  const Id nv = this->Mesh.GetNumberOfPoints();
  parent.resize(static_cast<std::size_t>(nv));
  this->JoinLiveTriangles(parent);
  for (Id v = 0; v < nv; ++v)
  {
    live += this->TriangleCount(v) > 0 && FindRoot(parent, v) == v ? 1 : 0;
  }
  return live;
}

void CollapseMesh::JoinLiveTriangles(std::vector<Id>& parent) const
{
  std::iota(parent.begin(), parent.end(), 0);
  for (Id t = 0; t < this->Mesh.GetNumberOfTriangles(); ++t)
  {
    if (this->IsAlive(t))
    {
      const Id* tri = this->Mesh.Triangle(t);
      for (int k = 1; k < 3; ++k)
      {
        const Id a = FindRoot(parent, tri[0]), b = FindRoot(parent, tri[k]);
        parent[std::max(a, b)] = std::min(a, b);
      }
    }
  }
}

PieceKind CollapseMesh::SmallPiece(
  Id t, const std::uint32_t* owner, std::uint32_t block, Id* members, int& count) const
{
  const Id* tri = this->Mesh.Triangle(t);
  if (this->PieceOf.empty())
  {
    return PieceKind::Other;
  }
  const Id piece = this->PieceOf[tri[0]];
  const Id triangles = owner != nullptr
    ? this->FrozenPieceTriangles[piece]
    : this->PieceTriangles[piece].load(std::memory_order_relaxed);
  if (triangles > VanishingPieceTriangles || piece == this->LargestPiece)
  {
    return PieceKind::Other;
  }
  // Its vertices and triangles, from t's corners outwards (another block's vertex stops the
  // walk before anything of it is read: that block may be changing it).
  count = 0;
  for (int k = 0; k < 3; ++k)
  {
    members[count++] = tri[k];
  }
  Id faces[VanishingPieceTriangles];
  int faceCount = 0;
  bool small = true;
  for (int m = 0; m < count && small; ++m)
  {
    const Id v = members[m];
    if (owner != nullptr && owner[v] != block)
    {
      return PieceKind::Foreign;
    }
    if ((this->Flags[v] & (FlagLocked | FlagCurve | FlagBoundary)) != 0)
    {
      return PieceKind::Other;
    }
    this->ForEachTriangle(v, [&](Id s) {
      if (!small || std::find(faces, faces + faceCount, s) != faces + faceCount)
      {
        return;
      }
      small = faceCount < VanishingPieceTriangles;
      if (small)
      {
        faces[faceCount++] = s;
      }
      const Id* st = this->Mesh.Triangle(s);
      for (int k = 0; k < 3 && small; ++k)
      {
        if (std::find(members, members + count, st[k]) == members + count)
        {
          small = count < VanishingPieceVertices;
          if (small)
          {
            members[count++] = st[k];
          }
        }
      }
    });
  }
  if (!small || faceCount != triangles)
  {
    return PieceKind::Other;
  }
  // A closed surface of genus 0: Euler characteristic V - E + F = 2, no boundary edge. (Open
  // pieces stay: besides debris they are the faces of a flat-shaded model whose normals keep
  // them apart.)
  std::pair<Id, Id> edges[3 * VanishingPieceTriangles];
  int edgeCount = 0;
  for (int f = 0; f < faceCount; ++f)
  {
    const Id* ft = this->Mesh.Triangle(faces[f]);
    for (int k = 0; k < 3; ++k)
    {
      edges[edgeCount++] = std::minmax(ft[k], ft[(k + 1) % 3]);
    }
  }
  std::sort(edges, edges + edgeCount);
  const int distinct = static_cast<int>(std::unique(edges, edges + edgeCount) - edges);
  const int euler = count - distinct + faceCount;
  const int boundaryEdges = 2 * distinct - 3 * faceCount;
  if (euler != 2 || boundaryEdges != 0)
  {
    return PieceKind::Other;
  }
  std::sort(members, members + count);
  return PieceKind::Vanishing;
}

//------------------------------------------------------------------------------
Id CollapseMesh::Apply(const Star& star, const double x[3])
{
  const Id survivor = star.Members[0];
  for (const Id t : star.Dying)
  {
    Id* tri = this->Mesh.Triangle(t);
    for (int k = 0; k < 3; ++k)
    {
      --this->TriangleCounts[tri[k]];
    }
    tri[0] = InvalidId;
  }
  for (std::size_t i = 0; i < star.Ring.size(); ++i)
  {
    this->Mesh.Triangle(star.Ring[i])[star.RingCorner[i]] = survivor;
  }
  std::copy_n(x, 3, this->Mesh.Point(survivor));
  for (int m = 1; m < star.MemberCount; ++m)
  {
    const Id v = star.Members[m];
    this->Quadrics[survivor] += this->Quadrics[v];
    this->SurfaceWeights[survivor] += this->SurfaceWeights[v];
    for (int i = 0; i < 3; ++i)
    {
      this->Facing[3 * static_cast<std::size_t>(survivor) + i] +=
        this->Facing[3 * static_cast<std::size_t>(v) + i];
    }
    this->Flags[survivor] |= this->Flags[v];
    this->Survivor[v] = survivor;
    this->TriangleCounts[survivor] += this->TriangleCounts[v];
    this->TriangleCounts[v] = 0;
    this->ChainNext[this->ChainTail[survivor]] = v;
    this->ChainTail[survivor] = this->ChainTail[v];
  }
  if (!this->PieceOf.empty())
  {
    this->PieceTriangles[this->PieceOf[survivor]].fetch_sub(
      static_cast<Id>(star.Dying.size()), std::memory_order_relaxed);
  }
  if (this->TriangleCounts[survivor] == 0)
  {
    this->Flags[survivor] |= FlagVanished; // a closed piece merged whole
  }
  return survivor;
}

} // namespace meshlod

