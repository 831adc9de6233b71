// The cluster tree (ClusterTree.h): cell geometry, Morton codes, islands, seams and curves, and
// the queries of a node's related triangle set; its construction is in ClusterTreeBuild.cxx.
#include "ClusterTree.h"

#include "CacheHint.h"
#include "FreshMemory.h"
#include "SpatialOrder.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace meshlod
{
namespace
{
// The inverse of SpreadBits (SpatialOrder.h): every third bit of x, from bit 0 up.
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
} // namespace

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
// Cells come from the points as they are. Where the noise is larger than the edges, neighbours
// fall into different cells and meet only high up (a sphere of 158,400 triangles with radii
// moved at random by up to 2.5 edges: 39% of the clusters of its first trial level were single
// vertices, each hanging below a node of 136 vertices on average), and with PreserveTopology
// the folds next to them keep target counts far out of reach. Codes from positions smoothed ten
// times (each point halfway to its neighbours' mean) were tried: that sphere then reached 19%
// and 6% of its triangles for 10% and 1% instead of 92% and 87%, but at 3.5 and 12 times
// vtkQuadricClustering's Hausdorff and RMS distances at 1%; and on clean meshes the distances
// grew by up to 15% (metaballs and gyroid isosurfaces), and a faceted cylinder asked for 1%
// kept 6,660 triangles instead of 1,276. Not done.
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

} // namespace meshlod
