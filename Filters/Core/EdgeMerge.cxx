#include "EdgeMerge.h"

#include "vtkSMPTools.h"

#include <algorithm>

namespace meshlod
{
namespace
{
// Neighbours of a with a larger id, sorted and unique, appended to `out`.
void HigherNeighbors(
  const Id* triangles, const VertexTriangleAdjacency& adjacency, Id a, std::vector<Id>& out)
{
  out.clear();
  for (Id i = adjacency.Begin(a); i < adjacency.End(a); ++i)
  {
    const Id* tri = triangles + 3 * static_cast<size_t>(adjacency.Triangles[i]);
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] > a)
      {
        out.push_back(tri[k]);
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

} // namespace

//------------------------------------------------------------------------------
void EdgeList::Build(const Id* triangles, Id numberOfTriangles, Id numberOfPoints)
{
  VertexTriangleAdjacency adjacency;
  adjacency.Build(triangles, numberOfTriangles, numberOfPoints);
  // Two passes over the vertices: count each row, then fill it at its prefix-sum offset.
  std::vector<Id> offsets(static_cast<size_t>(numberOfPoints) + 1, 0);
  vtkSMPTools::For(0, numberOfPoints, [&](Id begin, Id end) {
    std::vector<Id> row;
    for (Id a = begin; a < end; ++a)
    {
      HigherNeighbors(triangles, adjacency, a, row);
      offsets[a + 1] = static_cast<Id>(row.size());
    }
  });
  for (Id a = 0; a < numberOfPoints; ++a)
  {
    offsets[a + 1] += offsets[a];
  }
  this->Ends.resize(2 * static_cast<size_t>(offsets[numberOfPoints]));
  vtkSMPTools::For(0, numberOfPoints, [&](Id begin, Id end) {
    std::vector<Id> row;
    for (Id a = begin; a < end; ++a)
    {
      HigherNeighbors(triangles, adjacency, a, row);
      Id* out = this->Ends.data() + 2 * static_cast<size_t>(offsets[a]);
      for (const Id b : row)
      {
        *out++ = a;
        *out++ = b;
      }
    }
  });
}

//------------------------------------------------------------------------------
Id MergeAlongEdges(const EdgeList& edges, const std::uint8_t* merge, Id numberOfPoints,
  std::vector<Id>& representative)
{
  representative.resize(numberOfPoints);
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    representative[p] = p;
  }
  // Union by lowest id keeps the root of every group its lowest id.
  Id merged = 0;
  for (size_t e = 0; e < edges.Size(); ++e)
  {
    if (!merge[e])
    {
      continue;
    }
    const Id ra = FindRoot(representative, edges.Ends[2 * e]);
    const Id rb = FindRoot(representative, edges.Ends[2 * e + 1]);
    if (ra != rb)
    {
      representative[std::max(ra, rb)] = std::min(ra, rb);
      ++merged;
    }
  }
  for (Id p = 0; p < numberOfPoints; ++p)
  {
    representative[p] = FindRoot(representative, p);
  }
  return merged;
}

} // namespace meshlod
