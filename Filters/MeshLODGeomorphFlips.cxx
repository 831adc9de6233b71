// Private to vtkLODGeomorph: the geomorph across the edge flips of a hierarchy made with
// FlipEdges (see vtkLODGeomorph.h, "Edge flips between levels").
//
// A level made with FlipEdges is the triangles the collapses leave (the images of the finer
// level's triangles) with some quads' diagonals flipped. Where every difference between the
// images and the level is such a quad and no two quads share a point (vtkTriangleCollapseDecimation
// flips at most one edge per vertex and goes on collapsing from the flipped triangles), each flip
// is made continuous by a point m in the middle of its quad: the quad's old triangles (a, b, c)
// and (b, a, d), split at m on their shared edge, are four triangles around m, and as m moves
// from the middle of (a, b) to the middle of (c, d) they become the halves of the new
// triangles (c, a, d) and (d, b, c). Nothing else moves meanwhile: the collapses have finished.
// Any other difference (vtkVertexClusterOctree's flips, which its next level is not cut from,
// mostly differ in other ways) leaves the level to jump at its end, as without this.
#include "MeshLODGeomorphInternals.h"

#include "MeshLODBlend.h"
#include "MeshLODNewArray.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPoints.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <utility>

namespace
{
using meshlod::Id;
using Triangle = std::array<Id, 3>;

// Whether an array that is attribute `attribute` of a level (-1: none) stays that attribute in
// the output while flips turn. Global ids do not: a midpoint takes a corner's values and the
// triangles split at it their source triangle's, so ids repeat, which the attribute forbids;
// they stay as plain arrays of the same name.
bool KeepsAttribute(int attribute)
{
  return attribute >= 0 && attribute != vtkDataSetAttributes::GLOBALIDS;
}

// The triangle turned so that its smallest id comes first (its orientation kept).
Triangle Turned(const Id* t)
{
  const int first = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
  return { t[first], t[(first + 1) % 3], t[(first + 2) % 3] };
}

// Triangle t (its three corners) mapped through `map` when given and turned; false when the
// mapped triangle is degenerate (two corners the same).
bool MappedTurned(const Id* t, const Id* map, Triangle& turned)
{
  Id corners[3];
  for (int k = 0; k < 3; ++k)
  {
    corners[k] = map ? map[t[k]] : t[k];
  }
  if (corners[0] == corners[1] || corners[1] == corners[2] || corners[0] == corners[2])
  {
    return false;
  }
  turned = Turned(corners);
  return true;
}

// The triangles of `of` (indices) that `in` does not have, as multisets: `of` and `in` sorted.
std::vector<std::size_t> Missing(
  const std::vector<std::pair<Triangle, Id>>& of, const std::vector<std::pair<Triangle, Id>>& in)
{
  std::vector<std::size_t> missing;
  std::size_t j = 0;
  for (std::size_t i = 0; i < of.size(); ++i)
  {
    while (j < in.size() && in[j].first < of[i].first)
    {
      ++j;
    }
    if (j < in.size() && in[j].first == of[i].first)
    {
      ++j;
    }
    else
    {
      missing.push_back(i);
    }
  }
  return missing;
}

// The triangles of a level as sorted (turned triangle, index) pairs.
std::vector<std::pair<Triangle, Id>> Sorted(const std::vector<Id>& triangles, const Id* map)
{
  std::vector<std::pair<Triangle, Id>> sorted;
  const Id n = static_cast<Id>(triangles.size() / 3);
  sorted.reserve(n);
  Triangle turned;
  for (Id t = 0; t < n; ++t)
  {
    if (MappedTurned(triangles.data() + 3 * static_cast<std::size_t>(t), map, turned))
    {
      sorted.emplace_back(turned, t);
    }
  }
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

// A hash of the multiset of the triangles (mapped through `map` when given, degenerate ones
// left out, each turned to its smallest id first): equal for equal multisets, whatever the
// order, so that a hierarchy without flips is told apart in one pass without sorting.
std::uint64_t TriangleSetHash(const std::vector<Id>& triangles, const Id* map)
{
  std::uint64_t sum = 0;
  Triangle turned;
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
  {
    if (!MappedTurned(triangles.data() + t, map, turned))
    {
      continue;
    }
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (const Id v : turned)
    {
      // splitmix64's finaliser over the running value and each id
      h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)) + 0x9e3779b97f4a7c15ull;
      h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
      h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
      h ^= h >> 31;
    }
    sum += h;
  }
  return sum;
}

// Whether directed edge (from, to) is an edge of triangle t; then `apex` is its third corner.
bool HasDirectedEdge(const Triangle& t, Id from, Id to, Id& apex)
{
  for (int k = 0; k < 3; ++k)
  {
    if (t[k] == from && t[(k + 1) % 3] == to)
    {
      apex = t[(k + 2) % 3];
      return true;
    }
  }
  return false;
}

// `source` with, per midpoint, the values at its weighted corners appended: floating-point
// arrays blended (the Normals renormalised), others taken from the corner of the largest weight
// (ids and labels are not interpolated).
vtkSmartPointer<vtkAbstractArray> WithMidpoints(vtkAbstractArray* source, bool normals,
  const std::vector<Id>& corners, const std::vector<double>& weights)
{
  const vtkIdType n = source->GetNumberOfTuples();
  const vtkIdType added = static_cast<vtkIdType>(corners.size() / 4);
  vtkSmartPointer<vtkAbstractArray> result;
  result.TakeReference(source->NewInstance());
  result->DeepCopy(source); // one bulk copy; the midpoints go after
  result->Resize(n + added);
  result->SetNumberOfTuples(n + added);
  auto* values = vtkDataArray::FastDownCast(source);
  auto* out = vtkDataArray::FastDownCast(result);
  const bool blend =
    values && (values->GetDataType() == VTK_FLOAT || values->GetDataType() == VTK_DOUBLE);
  const int components = source->GetNumberOfComponents();
  std::vector<double> tuple(components);
  for (vtkIdType q = 0; q < added; ++q)
  {
    const Id* c = corners.data() + 4 * q;
    const double* w = weights.data() + 4 * q;
    if (!blend)
    {
      const int largest = static_cast<int>(std::max_element(w, w + 4) - w);
      result->SetTuple(n + q, c[largest], source);
      continue;
    }
    std::fill(tuple.begin(), tuple.end(), 0.0);
    for (int k = 0; k < 4; ++k)
    {
      for (int j = 0; j < components; ++j)
      {
        tuple[j] += w[k] * values->GetComponent(c[k], j);
      }
    }
    double length = 0.0;
    for (const double v : tuple)
    {
      length += v * v;
    }
    length = std::sqrt(length);
    for (double& v : tuple)
    {
      v = normals && length > 0.0 ? v / length : v;
    }
    out->SetTuple(n + q, tuple.data());
  }
  return result;
}
} // namespace

//------------------------------------------------------------------------------
bool vtkLODGeomorph::Internals::EnsureFlips(int level)
{
  meshlod::geomorph::LevelCache& cache = this->Levels[level];
  if (cache.FlipsFound)
  {
    return !cache.FlipQuads.empty();
  }
  cache.FlipsFound = true;
  cache.FlipQuads.clear();
  meshlod::geomorph::LevelCache& next = this->Levels[level + 1];
  // (Read here, not kept: a level without flips needs neither triangle list afterwards.)
  std::vector<Id> fine, coarse;
  if (cache.TargetIds.empty() || !meshlod::geomorph::ReadTriangles(cache.Poly, fine) ||
    !meshlod::geomorph::ReadTriangles(next.Poly, coarse) ||
    TriangleSetHash(fine, cache.TargetIds.data()) == TriangleSetHash(coarse, nullptr))
  {
    return false; // no flips to follow (or levels of other cells)
  }
  // The next level's triangles that no triangle of this level becomes (new diagonals), and the
  // images that the next level does not have (old diagonals).
  const auto images = Sorted(fine, cache.TargetIds.data());
  const auto own = Sorted(coarse, nullptr);
  const std::vector<std::size_t> added = Missing(own, images);
  if (added.empty())
  {
    return false;
  }
  const std::vector<std::size_t> removed = Missing(images, own);
  std::vector<Triangle> old;
  for (const std::size_t i : removed)
  {
    old.push_back(images[i].first);
  }
  std::sort(old.begin(), old.end());
  // The added triangles by edge: a flip's two new triangles share their diagonal (c, d).
  std::map<std::pair<Id, Id>, std::vector<std::size_t>> byEdge;
  for (const std::size_t i : added)
  {
    const Triangle& t = own[i].first;
    for (int k = 0; k < 3; ++k)
    {
      byEdge[std::minmax(t[k], t[(k + 1) % 3])].push_back(i);
    }
  }
  std::map<std::size_t, int> sharedEdges; // per added triangle, its edges shared with another
  for (const auto& edge : byEdge)
  {
    if (edge.second.size() > 1)
    {
      for (const std::size_t i : edge.second)
      {
        sharedEdges[i] += 1;
      }
    }
  }
  for (const auto& edge : byEdge)
  {
    if (edge.second.size() != 2 || sharedEdges[edge.second[0]] != 1 ||
      sharedEdges[edge.second[1]] != 1)
    {
      continue; // not a lone quad: flips that chain, or a difference of another kind
    }
    // X = (c, a, d) has the directed edge d -> c, Y = (d, b, c) has c -> d.
    const Triangle& x = own[edge.second[0]].first;
    const Triangle& y = own[edge.second[1]].first;
    Id a = meshlod::InvalidId, b = meshlod::InvalidId;
    const Id p = edge.first.first, q = edge.first.second;
    Id c = p, d = q;
    if (!HasDirectedEdge(x, d, c, a))
    {
      std::swap(c, d);
      if (!HasDirectedEdge(x, d, c, a))
      {
        continue;
      }
    }
    if (!HasDirectedEdge(y, c, d, b) || a == b)
    {
      continue;
    }
    // The old diagonal (a, b): the images must hold (a, b, c) and (b, a, d).
    const Id abc[3] = { a, b, c }, bad[3] = { b, a, d };
    if (!std::binary_search(old.begin(), old.end(), Turned(abc)) ||
      !std::binary_search(old.begin(), old.end(), Turned(bad)))
    {
      continue;
    }
    const Id quad[6] = { a, b, c, d, own[edge.second[0]].second, own[edge.second[1]].second };
    cache.FlipQuads.insert(cache.FlipQuads.end(), quad, quad + 6);
  }
  // Every difference must be such a quad, and no two quads may share a point (each midpoint
  // splits its own two triangles only); otherwise the level is left to jump, as before.
  const std::size_t quads = cache.FlipQuads.size() / 6;
  std::vector<Id> corners;
  for (std::size_t q = 0; q < quads; ++q)
  {
    corners.insert(corners.end(), cache.FlipQuads.begin() + 6 * q, cache.FlipQuads.begin() + 6 * q + 4);
  }
  std::sort(corners.begin(), corners.end());
  if (2 * quads != added.size() || 2 * quads != removed.size() ||
    std::adjacent_find(corners.begin(), corners.end()) != corners.end())
  {
    cache.FlipQuads.clear();
    return false;
  }
  if (!next.TrianglesRead) // the morph reads them at every frame
  {
    next.Triangles = std::move(coarse);
    next.AllTriangles = true;
    next.TrianglesRead = true;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkLODGeomorph::Internals::BuildFlipCells(int level)
{
  meshlod::geomorph::LevelCache& cache = this->Levels[level];
  const meshlod::geomorph::LevelCache& next = this->Levels[level + 1];
  const std::vector<Id>& quads = cache.FlipQuads;
  const Id count = static_cast<Id>(quads.size() / 6);
  const vtkIdType n = next.Poly->GetNumberOfPoints();
  const vtkIdType triangles = static_cast<vtkIdType>(next.Triangles.size() / 3);
  // The next level's triangles, each flipped pair replaced by the four around its midpoint
  // (point n + q of quad q): (a, m, c) in X's place and (m, a, d) at the end, (m, b, c) in Y's
  // and (b, m, d) at the end. At m on (c, d), X = (c, a, d) and Y = (d, b, c) exactly.
  std::vector<Id> replaced(triangles, meshlod::InvalidId); // triangle -> 2 q (X) or 2 q + 1 (Y)
  for (Id q = 0; q < count; ++q)
  {
    replaced[quads[6 * q + 4]] = 2 * q;
    replaced[quads[6 * q + 5]] = 2 * q + 1;
  }
  auto quadTriangle = [&](Id q, int which, vtkIdType cell[3]) {
    const Id* v = quads.data() + 6 * q; // a, b, c, d
    const vtkIdType m = n + q;
    const vtkIdType shapes[4][3] = { { v[0], m, v[2] }, { m, v[1], v[2] }, { m, v[0], v[3] },
      { v[1], m, v[3] } };
    std::copy_n(shapes[which], 3, cell);
  };
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(triangles + 2 * count, 3 * (triangles + 2 * count));
  vtkNew<vtkIdList> sources; // the next level's triangle each output triangle's data comes from
  sources->SetNumberOfIds(triangles + 2 * count);
  for (vtkIdType j = 0; j < triangles; ++j)
  {
    vtkIdType cell[3];
    if (replaced[j] == meshlod::InvalidId)
    {
      std::copy_n(next.Triangles.data() + 3 * j, 3, cell);
    }
    else
    {
      quadTriangle(replaced[j] / 2, static_cast<int>(replaced[j] % 2), cell);
    }
    polys->InsertNextCell(3, cell);
    sources->SetId(j, j);
  }
  for (Id q = 0; q < count; ++q)
  {
    for (const int which : { 2, 3 })
    {
      vtkIdType cell[3];
      quadTriangle(q, which, cell);
      polys->InsertNextCell(3, cell);
      sources->SetId(triangles + 2 * q + (which - 2), quads[6 * q + (which == 2 ? 4 : 5)]);
    }
  }
  cache.FlipCells = polys;
  // Every cell array, copied tuple by tuple from its source triangle (global ids included: the
  // copy flags of vtkCellData::CopyData would leave them out; as a plain array, since the
  // triangles split at a midpoint repeat their source's id, see KeepsAttribute).
  vtkCellData* from = next.Poly->GetCellData();
  cache.FlipCellData = vtkSmartPointer<vtkCellData>::New();
  vtkNew<vtkIdList> destinations;
  destinations->SetNumberOfIds(sources->GetNumberOfIds());
  std::iota(destinations->begin(), destinations->end(), vtkIdType(0));
  for (int i = 0; i < from->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* source = from->GetAbstractArray(i);
    vtkSmartPointer<vtkAbstractArray> result =
      meshlod::NewArrayLike(source, sources->GetNumberOfIds());
    result->InsertTuples(destinations, sources, source);
    const int attribute = from->IsArrayAnAttribute(i);
    if (KeepsAttribute(attribute))
    {
      cache.FlipCellData->SetAttribute(result, attribute);
    }
    else
    {
      cache.FlipCellData->AddArray(result);
    }
  }
}

//------------------------------------------------------------------------------
void vtkLODGeomorph::Internals::ProduceFlipMorph(int level, double t, vtkPolyData* output)
{
  meshlod::geomorph::LevelCache& cache = this->Levels[level];
  vtkPolyData* poly = this->Levels[level + 1].Poly;
  if (!cache.FlipCells)
  {
    this->BuildFlipCells(level);
  }
  // The midpoints: from the middle of (a, b) at t = 0 to the middle of (c, d) at t = 1.
  const std::vector<Id>& quads = cache.FlipQuads;
  const Id count = static_cast<Id>(quads.size() / 6);
  std::vector<Id> corners(4 * static_cast<std::size_t>(count));
  std::vector<double> weights(4 * static_cast<std::size_t>(count));
  for (Id q = 0; q < count; ++q)
  {
    std::copy_n(quads.data() + 6 * q, 4, corners.data() + 4 * q);
    const double w[4] = { 0.5 * (1.0 - t), 0.5 * (1.0 - t), 0.5 * t, 0.5 * t };
    std::copy_n(w, 4, weights.data() + 4 * q);
  }
  vtkNew<vtkPoints> points;
  points->SetData(vtkDataArray::SafeDownCast(
    WithMidpoints(poly->GetPoints()->GetData(), false, corners, weights)));
  output->SetPoints(points);
  // The next level's point arrays, as at L = level + 1 (the morph arrays left out).
  vtkPointData* from = poly->GetPointData();
  vtkPointData* to = output->GetPointData();
  to->Initialize();
  for (int i = 0; i < from->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* source = from->GetAbstractArray(i);
    if (meshlod::IsMorphArray(source->GetName()))
    {
      continue;
    }
    const auto result = WithMidpoints(source, source == from->GetNormals(), corners, weights);
    const int attribute = from->IsArrayAnAttribute(i);
    if (KeepsAttribute(attribute))
    {
      to->SetAttribute(result, attribute);
    }
    else
    {
      to->AddArray(result);
    }
  }
  output->SetPolys(cache.FlipCells);
  output->GetCellData()->ShallowCopy(cache.FlipCellData);
}
