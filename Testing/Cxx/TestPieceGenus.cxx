// HandleMeasures (the genus check of vtkVertexClusterOctree's levels) on tiny hand-made
// meshes with exact expected results: twice the genus of an orientable piece, the cross-caps
// of a non-orientable one, unchanged when a hole closes, surfaces touching at a point counted
// as their parts, and the side flags.
#include "Core/PieceGenus.h"
#include "MeshLODTestCheck.h"

#include "vtkSMPTools.h"

#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;

// An n x m grid of squares, two triangles each, with its points (i, j) numbered j * columns + i.
// wrapI / wrapJ close it across i or j (twistJ closes j with i reversed: a Klein bottle with
// wrapI). Open sides have their own row or column of points.
std::vector<Id> Grid(int n, int m, bool wrapI, bool wrapJ, bool twistJ = false)
{
  const int columns = wrapI ? n : n + 1;
  auto point = [&](int i, int j)
  {
    if (wrapJ && j == m)
    {
      j = 0;
      i = twistJ ? (n - i) % n : i;
    }
    return static_cast<Id>(j * columns + (wrapI ? i % n : i));
  };
  std::vector<Id> triangles;
  for (int j = 0; j < m; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const Id a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
      triangles.insert(triangles.end(), { a, b, c, a, c, d });
    }
  }
  return triangles;
}

Id PointsOf(const std::vector<Id>& triangles)
{
  Id most = -1;
  for (const Id p : triangles)
  {
    most = std::max(most, p);
  }
  return most + 1;
}

// The handles (twice the genus) of a mesh taken as one group, checking its number of pieces.
Id Measure(const std::vector<Id>& triangles, Id pieces = 1)
{
  const std::vector<Id> group(PointsOf(triangles), 0);
  const PieceMeasure m =
    HandleMeasures(triangles.data(), static_cast<Id>(triangles.size() / 3), group, 1)[0];
  MESHLOD_CHECK(m.Measured);
  MESHLOD_CHECK_EQ(m.Pieces, pieces);
  return m.Handles;
}

const std::vector<Id> Tetrahedron = { 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2 };

void TestSurfaces()
{
  MESHLOD_CHECK_EQ(Measure(Tetrahedron), 0);                  // sphere
  MESHLOD_CHECK_EQ(Measure(Grid(4, 4, true, true)), 2);       // torus: genus 1
  MESHLOD_CHECK_EQ(Measure(Grid(4, 4, true, true, true)), 2); // Klein bottle: two cross-caps
  MESHLOD_CHECK_EQ(Measure(Grid(3, 2, false, false)), 0);     // disk
  MESHLOD_CHECK_EQ(Measure(Grid(4, 2, true, false)), 0);      // annulus: a disk with a hole
  // A torus with a square hole cut (two triangles fewer): still genus 1, one boundary loop.
  std::vector<Id> holed = Grid(4, 4, true, true);
  holed.erase(holed.begin(), holed.begin() + 6);
  MESHLOD_CHECK_EQ(Measure(holed), 2);
  // Two tetrahedra touching at point 0: two spheres, not a pinched surface of one point less
  // (whose 2 - V + E - F is 2 - 3 = -1).
  std::vector<Id> spheres = Tetrahedron;
  for (const Id p : Tetrahedron)
  {
    spheres.push_back(p == 0 ? 0 : p + 3);
  }
  MESHLOD_CHECK_EQ(Measure(spheres, 2), 0);
  // Two tori touching at a point: 2 + 2, where one torus alone has 2 (a sum over the
  // surface's fans alone, 2 - V + E - F, is 2 for both).
  const std::vector<Id> torus = Grid(4, 4, true, true);
  std::vector<Id> tori = torus;
  for (const Id p : torus)
  {
    tori.push_back(p == 0 ? 0 : p + 15);
  }
  MESHLOD_CHECK_EQ(Measure(tori, 2), 4);
}

void TestGroups()
{
  // A tetrahedron (group 0), a torus (group 2), nothing in group 1, and a fin: an edge of
  // three triangles (group 3), which is not measured.
  std::vector<Id> triangles = Tetrahedron;
  std::vector<Id> group(4, 0);
  for (const Id p : Grid(4, 4, true, true))
  {
    triangles.push_back(p + 4);
  }
  group.resize(4 + 16, 2);
  const Id fin = static_cast<Id>(group.size());
  triangles.insert(triangles.end(), { fin, fin + 1, fin + 2, fin + 1, fin, fin + 3, fin, fin + 1, fin + 4 });
  group.resize(fin + 5, 3);
  std::vector<unsigned char> sides;
  const std::vector<PieceMeasure> measures =
    HandleMeasures(triangles.data(), static_cast<Id>(triangles.size() / 3), group, 4, &sides);
  MESHLOD_CHECK_EQ(measures.size(), 4u);
  MESHLOD_CHECK(measures[0].Measured && measures[0].Handles == 0 && measures[0].Pieces == 1);
  MESHLOD_CHECK(!measures[1].Measured);
  MESHLOD_CHECK(measures[2].Measured && measures[2].Handles == 2 && measures[2].Pieces == 1);
  MESHLOD_CHECK(!measures[3].Measured);
  // Side flags: none on the closed pieces; each fin triangle has its first side on the edge of
  // three triangles and its two others on the boundary.
  MESHLOD_CHECK_EQ(sides.size(), triangles.size() / 3);
  for (size_t t = 0; t + 3 < sides.size(); ++t)
  {
    MESHLOD_CHECK_EQ(sides[t], 0);
  }
  for (size_t t = sides.size() - 3; t < sides.size(); ++t)
  {
    MESHLOD_CHECK(SideNonManifold(sides[t], 0));
    MESHLOD_CHECK(!SideOnBoundary(sides[t], 0));
    MESHLOD_CHECK(SideOnBoundary(sides[t], 1) && SideOnBoundary(sides[t], 2));
  }
}

void TestOpenSides()
{
  // Two triangles of a square, (0, 1, 2) and (0, 2, 3): the diagonal (the first's side 2,
  // from corner 2 to corner 0, and the second's side 0) has two triangles, the four others one.
  const std::vector<Id> square = { 0, 1, 2, 0, 2, 3 };
  std::vector<unsigned char> sides;
  const std::vector<Id> group(4, 0);
  const std::vector<PieceMeasure> measures = HandleMeasures(square.data(), 2, group, 1, &sides);
  MESHLOD_CHECK_EQ(measures[0].Handles, 0);
  MESHLOD_CHECK(SideOnBoundary(sides[0], 0) && SideOnBoundary(sides[0], 1));
  MESHLOD_CHECK(!SideOnBoundary(sides[0], 2)); // 2 -> 0, the diagonal
  MESHLOD_CHECK(!SideOnBoundary(sides[1], 0)); // 0 -> 2
  MESHLOD_CHECK(SideOnBoundary(sides[1], 1) && SideOnBoundary(sides[1], 2));
}

void TestLargeWithThreads()
{
  // A torus of 180,000 triangles (large enough for the parallel passes) with 50 square holes
  // cut apart from each other: still genus 1, with 50 boundary loops.
  const int n = 300;
  std::vector<Id> torus = Grid(n, n, true, true);
  std::vector<Id> holed;
  for (size_t t = 0; t < torus.size() / 3; ++t)
  {
    const size_t square = t / 2, i = square % n, j = square / n;
    if (!(i % 30 == 3 && j % 60 == 7)) // 10 x 5 squares
    {
      holed.insert(holed.end(), torus.begin() + 3 * t, torus.begin() + 3 * t + 3);
    }
  }
  MESHLOD_CHECK_EQ(torus.size() - holed.size(), 3u * 2 * 50);
  MESHLOD_CHECK_EQ(Measure(holed), 2);
  // Groups of points by id modulo 7, measured with one thread and with the backend in use:
  // the same measures and side flags.
  std::vector<Id> group(PointsOf(holed));
  for (size_t p = 0; p < group.size(); ++p)
  {
    group[p] = static_cast<Id>(p % 7);
  }
  const std::string initial = vtkSMPTools::GetBackend();
  std::vector<PieceMeasure> measures[2];
  std::vector<unsigned char> sides[2];
  for (int run = 0; run < 2; ++run)
  {
    vtkSMPTools::SetBackend(run == 0 ? "Sequential" : initial.c_str());
    measures[run] =
      HandleMeasures(holed.data(), static_cast<Id>(holed.size() / 3), group, 7, &sides[run]);
  }
  vtkSMPTools::SetBackend(initial.c_str());
  MESHLOD_CHECK(measures[0] == measures[1]);
  MESHLOD_CHECK(sides[0] == sides[1]);
  Id pieces = 0, boundarySides = 0;
  for (const PieceMeasure& m : measures[1])
  {
    MESHLOD_CHECK(m.Measured);
    pieces += m.Pieces;
  }
  for (const unsigned char flags : sides[1])
  {
    for (int c = 0; c < 3; ++c)
    {
      boundarySides += SideOnBoundary(flags, c) ? 1 : 0;
    }
  }
  MESHLOD_CHECK_EQ(pieces, 1);
  MESHLOD_CHECK_EQ(boundarySides, 4 * 50);
}
} // namespace

int TestPieceGenus(int, char*[])
{
  TestSurfaces();
  TestGroups();
  TestOpenSides();
  TestLargeWithThreads();
  return meshlod::testing::Result();
}
