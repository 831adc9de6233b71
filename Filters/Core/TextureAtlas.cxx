#include "TextureAtlas.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace meshlod
{
namespace
{
double Length2(const double* a, const double* b)
{
  const double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

double Area(const TriangleMesh& mesh, Id t)
{
  double n[3];
  mesh.AreaVector(t, n);
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

Id NextPowerOfTwo(Id x)
{
  Id p = 1;
  while (p < x)
  {
    p *= 2;
  }
  return p;
}

// The nearest power of two (in ratio) to x, clamped to [2, maximum].
Id RoundToPowerOfTwo(double x, Id maximum)
{
  if (!(x > 2.0))
  {
    return 2;
  }
  const double exponent = std::round(std::log2(x));
  if (exponent >= std::log2(static_cast<double>(maximum)))
  {
    return maximum;
  }
  return static_cast<Id>(1) << static_cast<int>(exponent);
}

// Every other bit of a Morton offset.
Id CompactBits(std::int64_t x)
{
  Id result = 0;
  for (int b = 0; b < 31; ++b)
  {
    result |= static_cast<Id>((x >> (2 * b)) & 1) << b;
  }
  return result;
}

// One block to place: a pair of triangles sharing `edge` of `first`, or a single triangle.
struct Unit
{
  Id First = InvalidId;
  Id Second = InvalidId;
  int Edge = 0; // edge of First mapped to the diagonal
  double Area = 0.0;
  Id Size = 2;
};

// The blocks to place: each triangle, in id order, paired with an unpaired neighbour across its
// longest such edge.
std::vector<Unit> PairTriangles(const TriangleMesh& mesh)
{
  const Id nt = mesh.GetNumberOfTriangles();
  TriangleTopology topology;
  topology.Build(mesh);
  std::vector<Unit> units;
  std::vector<unsigned char> paired(nt, 0);
  for (Id t = 0; t < nt; ++t)
  {
    if (paired[t])
    {
      continue;
    }
    const Id* tri = mesh.Triangle(t);
    Unit unit;
    unit.First = t;
    double longestFree = -1.0, longest = -1.0;
    for (int k = 0; k < 3; ++k)
    {
      const double length = Length2(mesh.Point(tri[k]), mesh.Point(tri[(k + 1) % 3]));
      const Id neighbor = topology.EdgeNeighbors[3 * static_cast<size_t>(t) + k];
      if (neighbor >= 0 && !paired[neighbor] && length > longestFree)
      {
        longestFree = length;
        unit.Second = neighbor;
        unit.Edge = k;
      }
      if (unit.Second == InvalidId && length > longest)
      {
        longest = length;
        unit.Edge = k;
      }
    }
    paired[t] = 1;
    unit.Area = 2.0 * Area(mesh, t);
    if (unit.Second != InvalidId)
    {
      paired[unit.Second] = 1;
      unit.Area = Area(mesh, t) + Area(mesh, unit.Second);
    }
    units.push_back(unit);
  }
  return units;
}

// Block sizes at one texel density for all blocks: the largest whose power-of-two blocks fit the
// texture. Returns the texture's side (`side`, a power of two, or larger when there are more
// blocks than it holds at two texels).
Id SizeBlocks(std::vector<Unit>& units, Id side)
{
  const std::int64_t unitCount = static_cast<std::int64_t>(units.size());
  while (4 * unitCount > static_cast<std::int64_t>(side) * side)
  {
    side *= 2;
  }
  auto layout = [&](double density)
  {
    std::int64_t total = 0;
    for (Unit& u : units)
    {
      u.Size = RoundToPowerOfTwo(density * std::sqrt(u.Area) + 1.0, side);
      total += static_cast<std::int64_t>(u.Size) * u.Size;
    }
    return total;
  };
  const double totalArea = std::accumulate(
    units.begin(), units.end(), 0.0, [](double s, const Unit& u) { return s + u.Area; });
  double low = 0.0;
  double high = totalArea > 0.0 ? 4.0 * side / std::sqrt(totalArea) : 1.0;
  const std::int64_t capacity = static_cast<std::int64_t>(side) * side;
  while (layout(high) <= capacity && high < 1e30)
  {
    low = high;
    high *= 2.0;
  }
  for (int it = 0; it < 60; ++it)
  {
    const double middle = 0.5 * (low + high);
    (layout(middle) <= capacity ? low : high) = middle;
  }
  layout(low);
  return side;
}

// The blocks placed, largest first, in Morton order: each block starts at a multiple of its own
// area.
void PlaceBlocks(const std::vector<Unit>& units, TextureAtlas& atlas)
{
  std::vector<Id> order(units.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&](Id a, Id b) { return units[a].Size > units[b].Size; });
  atlas.Blocks.resize(units.size());
  std::int64_t offset = 0;
  for (const Id u : order)
  {
    TextureAtlas::Block& block = atlas.Blocks[u];
    block.Size = units[u].Size;
    block.X = CompactBits(offset);
    block.Y = CompactBits(offset >> 1);
    block.Lower = units[u].First;
    block.Upper = units[u].Second;
    offset += static_cast<std::int64_t>(block.Size) * block.Size;
  }
}

// Corners and split points of block u's triangles.
void SetBlockCorners(const TriangleMesh& mesh, const Unit& unit, Id u, TextureAtlas& atlas)
{
  const TextureAtlas::Block& block = atlas.Blocks[u];
  const Id s = block.Size - 1;
  const Id t = block.Lower;
  const Id* tri = mesh.Triangle(t);
  const int h = unit.Edge;
  const Id a = tri[h], b = tri[(h + 1) % 3];
  const Id pointA = static_cast<Id>(atlas.SplitPoints.size());
  auto setCorner = [&](Id triangle, int corner, Id x, Id y, Id split)
  {
    atlas.CornerTexel[6 * static_cast<size_t>(triangle) + 2 * corner] = block.X + x;
    atlas.CornerTexel[6 * static_cast<size_t>(triangle) + 2 * corner + 1] = block.Y + y;
    atlas.CornerPoint[3 * static_cast<size_t>(triangle) + corner] = split;
  };
  atlas.SplitPoints.push_back(a);
  atlas.SplitPoints.push_back(b);
  atlas.SplitPoints.push_back(tri[(h + 2) % 3]);
  setCorner(t, h, s, 0, pointA);
  setCorner(t, (h + 1) % 3, 0, s, pointA + 1);
  setCorner(t, (h + 2) % 3, 0, 0, pointA + 2);
  atlas.TriangleBlock[t] = u;
  if (block.Upper != InvalidId)
  {
    const Id* other = mesh.Triangle(block.Upper);
    const int ca = CornerOf(other, a), cb = CornerOf(other, b);
    const int apex = 3 - ca - cb;
    atlas.SplitPoints.push_back(other[apex]);
    setCorner(block.Upper, ca, s, 0, pointA);
    setCorner(block.Upper, cb, 0, s, pointA + 1);
    setCorner(block.Upper, apex, s, s, pointA + 3);
    atlas.TriangleBlock[block.Upper] = u;
  }
}
} // namespace

//------------------------------------------------------------------------------
void BuildTextureAtlas(const TriangleMesh& mesh, Id resolution, TextureAtlas& atlas)
{
  atlas = TextureAtlas();
  const Id nt = mesh.GetNumberOfTriangles();
  std::vector<Unit> units = PairTriangles(mesh);
  atlas.RequestedResolution = NextPowerOfTwo(std::max<Id>(resolution, 2));
  atlas.Resolution = SizeBlocks(units, atlas.RequestedResolution);
  atlas.TriangleBlock.assign(nt, InvalidId);
  atlas.CornerTexel.assign(6 * static_cast<size_t>(nt), 0);
  atlas.CornerPoint.assign(3 * static_cast<size_t>(nt), InvalidId);
  PlaceBlocks(units, atlas);
  for (size_t u = 0; u < units.size(); ++u)
  {
    SetBlockCorners(mesh, units[u], static_cast<Id>(u), atlas);
  }
}

} // namespace meshlod
