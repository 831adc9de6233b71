#include "SpatialOrder.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>

namespace meshlod
{
namespace
{
// Number of bits of x (0 for 0).
int BitCount(std::uint32_t x)
{
  int bits = 0;
  for (; x != 0; x >>= 1)
  {
    ++bits;
  }
  return bits;
}
} // namespace

//------------------------------------------------------------------------------
double MeanCornerSpreadBits(const TriangleMesh& mesh)
{
  const Id count = mesh.GetNumberOfTriangles();
  if (count == 0)
  {
    return 0.0;
  }
  std::atomic<std::int64_t> total{ 0 }; // an integer sum: the same in any order
  vtkSMPTools::For(0, count, [&](Id begin, Id end) {
    std::int64_t bits = 0;
    for (Id t = begin; t < end; ++t)
    {
      const Id* tri = mesh.Triangle(t);
      const Id low = std::min({ tri[0], tri[1], tri[2] });
      const Id high = std::max({ tri[0], tri[1], tri[2] });
      bits += BitCount(static_cast<std::uint32_t>(high - low));
    }
    total += bits;
  });
  return static_cast<double>(total.load()) / count;
}

//------------------------------------------------------------------------------
bool IsOrderScattered(const TriangleMesh& mesh)
{
  const Id vertices = mesh.GetNumberOfPoints();
  // Below a few thousand vertices everything stays in cache whatever the order.
  constexpr Id SmallestScattered = 1 << 12;
  return vertices >= SmallestScattered &&
    MeanCornerSpreadBits(mesh) >=
    BitCount(static_cast<std::uint32_t>(vertices)) - ScatteredMarginBits;
}

//------------------------------------------------------------------------------
void SpatialRenumbering::Apply(TriangleMesh& mesh)
{
  const Id nv = mesh.GetNumberOfPoints();
  const Id nt = mesh.GetNumberOfTriangles();
  double lo[3], hi[3];
  mesh.GetBounds(lo, hi);
  constexpr double Cells = 2097151.0; // 2^21 - 1: the largest cell coordinate
  double scale[3];
  for (int c = 0; c < 3; ++c)
  {
    scale[c] = hi[c] > lo[c] ? Cells / (hi[c] - lo[c]) : 0.0;
  }

  // Vertices by (Morton code, old id): a strict order, so any sort gives the same result.
  struct Keyed
  {
    std::uint64_t Code;
    Id Old;
    bool operator<(const Keyed& other) const
    {
      return this->Code != other.Code ? this->Code < other.Code : this->Old < other.Old;
    }
  };
  std::vector<Keyed> vertices(static_cast<std::size_t>(nv));
  vtkSMPTools::For(0, nv, [&](Id begin, Id end) {
    for (Id v = begin; v < end; ++v)
    {
      const double* p = mesh.Point(v);
      std::uint64_t code = 0;
      for (int c = 0; c < 3; ++c)
      {
        const double q = std::min(Cells, std::max(0.0, std::floor((p[c] - lo[c]) * scale[c])));
        code |= SpreadBits(static_cast<std::uint32_t>(q)) << (2 - c);
      }
      vertices[v] = { code, v };
    }
  });
  vtkSMPTools::Sort(vertices.begin(), vertices.end());
  this->OldVertex.resize(nv);
  this->NewVertex.resize(nv);
  std::vector<double> points(mesh.Points.size());
  vtkSMPTools::For(0, nv, [&](Id begin, Id end) {
    for (Id v = begin; v < end; ++v)
    {
      const Id old = vertices[v].Old;
      this->OldVertex[v] = old;
      this->NewVertex[old] = v;
      std::copy_n(mesh.Point(old), 3, points.data() + 3 * static_cast<std::size_t>(v));
    }
  });
  std::vector<Keyed>().swap(vertices);
  mesh.Points.swap(points);
  std::vector<double>().swap(points);

  // Triangles by their corners' new ids, sorted: distinct for distinct triangles (a validated
  // mesh has no two with the same corners), so again a strict order.
  // Each triangle's new corners, and the same sorted as its key.
  std::vector<Id> corners(mesh.Triangles.size());
  std::vector<Id> keys(corners.size());
  vtkSMPTools::For(0, nt, [&](Id begin, Id end) {
    for (Id t = begin; t < end; ++t)
    {
      Id* tri = corners.data() + 3 * static_cast<std::size_t>(t);
      for (int k = 0; k < 3; ++k)
      {
        tri[k] = this->NewVertex[mesh.Triangle(t)[k]];
      }
      Id* key = keys.data() + 3 * static_cast<std::size_t>(t);
      std::copy_n(tri, 3, key);
      std::sort(key, key + 3);
    }
  });
  this->OldTriangle.resize(nt);
  for (Id t = 0; t < nt; ++t)
  {
    this->OldTriangle[t] = t;
  }
  vtkSMPTools::Sort(this->OldTriangle.begin(), this->OldTriangle.end(), [&](Id a, Id b) {
    const Id* ka = keys.data() + 3 * static_cast<std::size_t>(a);
    const Id* kb = keys.data() + 3 * static_cast<std::size_t>(b);
    for (int k = 0; k < 3; ++k)
    {
      if (ka[k] != kb[k])
      {
        return ka[k] < kb[k];
      }
    }
    return a < b; // (not on a validated mesh: kept strict all the same)
  });
  std::vector<Id>().swap(keys);
  this->NewTriangle.resize(nt);
  vtkSMPTools::For(0, nt, [&](Id begin, Id end) {
    for (Id t = begin; t < end; ++t)
    {
      const Id old = this->OldTriangle[t];
      this->NewTriangle[old] = t;
      std::copy_n(corners.data() + 3 * static_cast<std::size_t>(old), 3, mesh.Triangle(t));
    }
  });
}

//------------------------------------------------------------------------------
bool SpatialRenumbering::ApplyIfScattered(TriangleMesh& mesh, TriangleTopology& topology)
{
  if (!IsOrderScattered(mesh))
  {
    return false;
  }
  this->Apply(mesh);
  topology.Build(mesh);
  return true;
}

//------------------------------------------------------------------------------
void SpatialRenumbering::NumberBack(std::vector<Id>& levelZeroTriangles,
  std::vector<Id>& parents, std::vector<Id>& target, std::vector<Id>& rank)
{
  if (this->OldVertex.empty())
  {
    return;
  }
  for (Id& t : levelZeroTriangles)
  {
    t = this->OldTriangle[t];
  }
  if (this->FirstLevelNumberedBack)
  {
    return;
  }
  this->FirstLevelNumberedBack = true;
  for (Id& p : parents)
  {
    p = this->OldVertex[p];
  }
  for (std::vector<Id>* row : { &target, &rank })
  {
    if (row->empty())
    {
      continue;
    }
    std::vector<Id> old(row->size());
    for (std::size_t v = 0; v < old.size(); ++v)
    {
      old[v] = (*row)[this->NewVertex[v]];
    }
    row->swap(old);
  }
}

} // namespace meshlod
