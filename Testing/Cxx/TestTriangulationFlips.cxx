// Edge flips towards the input (Core/TriangulationFlips, the FlipEdges of vtkVertexClusterOctree
// and vtkTriangleCollapseDecimation): closest points on a triangle, exact flips on a hand-made
// tent, refusals (a quad sharp at the corners facing its edge is not judged, nor one whose
// triangles the next level makes one triangle twice), and on the hierarchies of both filters
// the same points and counts with a smaller distance to the input.
#include "Core/TriangleMesh.h"
#include "Core/TriangulationFlips.h"
#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <cmath>
#include <functional>
#include <random>
#include <utility>
#include <vector>

namespace
{
using namespace meshlod;

//------------------------------------------------------------------------------
void TestClosestPoint()
{
  const double a[3] = { 0, 0, 0 }, b[3] = { 1, 0, 0 }, c[3] = { 0, 1, 0 };
  struct Case
  {
    double P[3];
    double Closest[3];
    bool Inside;
  };
  const Case cases[] = {
    { { 0.2, 0.2, 1.0 }, { 0.2, 0.2, 0.0 }, true },  // over the face
    { { -1.0, -1.0, 0.0 }, { 0.0, 0.0, 0.0 }, false }, // beyond corner a
    { { 2.0, -0.5, 0.0 }, { 1.0, 0.0, 0.0 }, false },  // beyond corner b
    { { 0.5, -1.0, 0.5 }, { 0.5, 0.0, 0.0 }, false },  // beyond edge ab
    { { 1.0, 1.0, 0.0 }, { 0.5, 0.5, 0.0 }, false },   // beyond edge bc
    { { -2.0, 0.5, 0.0 }, { 0.0, 0.5, 0.0 }, false },  // beyond edge ca
  };
  for (const Case& k : cases)
  {
    double q[3];
    bool inside;
    const double d2 = ClosestPointOnTriangle(k.P, a, b, c, q, inside);
    double expected = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      MESHLOD_CHECK_NEAR(q[i], k.Closest[i], 1e-12);
      expected += (k.P[i] - k.Closest[i]) * (k.P[i] - k.Closest[i]);
    }
    MESHLOD_CHECK_NEAR(d2, expected, 1e-12);
    MESHLOD_CHECK_EQ(inside, k.Inside);
  }
  // Collinear corners: the closest point of the segment they span.
  const double e[3] = { 2, 0, 0 }, p[3] = { 1.5, 1, 0 };
  double q[3];
  MESHLOD_CHECK_NEAR(ClosestPointOnTriangle(p, a, b, e, q), 1.0, 1e-12);
  MESHLOD_CHECK_NEAR(q[0], 1.5, 1e-12);
  // Two corners equal (a segment) in every order, and all three (a point).
  const double u[3] = { 0.3, -0.2, 0.7 }, v[3] = { 1.3, 0.8, -0.3 }, off[3] = { 1.3, -0.2, 0.2 };
  const double* segments[][3] = { { u, v, v }, { u, u, v }, { v, u, v }, { u, v, u } };
  for (const auto& s : segments)
  {
    // off is 0.5 of the way along (v - u) plus (0.5, -0.5, 0), which is perpendicular to it.
    MESHLOD_CHECK_NEAR(ClosestPointOnTriangle(off, s[0], s[1], s[2], q), 0.5, 1e-14);
  }
  MESHLOD_CHECK_NEAR(ClosestPointOnTriangle(off, u, u, u, q), 1.25, 1e-14);
}

// Thin triangles in a tilted frame, caps, right-angled ones and needles, from 100 to 1e11 times
// longer than high: points inside them, and points a quarter unit above those, are at the
// distance they were placed at, to within 1e-12 (within the triangle's height from 1e10 times
// longer than high, where its edges stand for it). The region tests of the earlier function were
// off by more than 1e-12 in 58 of these 126 cases, by up to 0.27, and put a point lying on a
// triangle 3.3 long and 3.3e-8 high 2.5 units away.
void TestClosestPointOnThinTriangles()
{
  // An orthonormal frame: x along the triangle, y across it, n its normal.
  const double norm = std::sqrt(1.0 + 4.0 + 9.0);
  const double x[3] = { 1.0 / norm, 2.0 / norm, 3.0 / norm };
  double y[3] = { 2.0, -1.0, 0.0 }; // perpendicular to x
  const double ny = std::sqrt(5.0);
  for (double& c : y)
  {
    c /= ny;
  }
  const double n[3] = { x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
    x[0] * y[1] - x[1] * y[0] };
  const double origin[3] = { 10.0, -4.0, 7.0 };
  auto at = [&](double s, double t, double h, double out[3]) {
    for (int i = 0; i < 3; ++i)
    {
      out[i] = origin[i] + s * x[i] + t * y[i] + h * n[i];
    }
  };
  double worst = 0.0;
  for (const double aspect : { 1e-2, 1e-4, 1e-6, 1e-8, 1e-9, 1e-10, 1e-11 })
  {
    for (const double apex : { 0.4, 1.0, 1e-3 }) // a cap, a right angle, a needle
    {
      const double length = 3.0, height = length * aspect;
      double a[3], b[3], c[3];
      at(0.0, 0.0, 0.0, a);
      at(length, 0.0, 0.0, b);
      at(apex * length, height, 0.0, c);
      for (const double above : { 0.0, 0.25 })
      {
        for (const double w : { 0.2, 0.5, 0.8 })
        {
          // Inside: between the base and the apex, away from the edges.
          double p[3], q[3];
          const double s = w * length;
          const double t = 0.3 * height *
            std::min(s / (apex * length), (length - s) / (length - apex * length));
          at(s, t, above, p);
          bool inside = false;
          const double d = std::sqrt(ClosestPointOnTriangle(p, a, b, c, q, inside));
          // (Thinner than 1e-10 of its length, a triangle is measured as its three edges.)
          const double allowed = aspect < 1e-10 ? height : 1e-12;
          worst = std::max(worst, std::abs(d - above) / allowed);
        }
      }
    }
  }
  std::cerr << "  thin triangles: largest distance error " << worst << " of the allowed\n";
  MESHLOD_CHECK_LE(worst, 1.0);
}

// Corners that nearly coincide, found by a randomized comparison with exact rational
// arithmetic (the expected distances are its): a needle whose short edge is 1.7e-21 long (the
// region tests gave NaN), needles and a skewed cap with edges of 1e-15 to 1e-10 beside edges
// of 0.07 to 4,100 (2e-4 to 4e-3 too far), and a point beyond a tip sharper than rounding
// resolves, which passed the side tests (1.2e-15 instead of 212).
void TestClosestPointNearCoincidentCorners()
{
  struct Case
  {
    double P[3], A[3], B[3], C[3];
    double Distance;
  };
  const Case cases[] = {
    { { 0.00019276225492827711, 4.5747833204438699e-05, 0.00047996844682112935 }, { 0, 0, 0 },
      { -1.2932529818570011e-21, -9.1096483877555952e-22, 6.0621699280853125e-22 },
      { 0.00018126589737832405, 4.3019428476814348e-05, 0.00045134308715512827 },
      3.0968074613737408e-05 },
    { { -0.43731946413710859, 0.11252309630735616, 0.19539724360620517 },
      { -0.43387580242481721, 0.094853253710665206, 0.18573669962626882 },
      { -0.44630176151194384, 0.15861234491257137, 0.22059538618820274 },
      { -0.44630176151194384, 0.15861234491257192, 0.2205953861882041 }, 7.9134891071905946e-16 },
    { { 0.24219017889109901, -0.32028818545520754, 0.079028679445251895 },
      { 0.29589464112159469, -0.39131049047778632, 0.096552894299223452 }, { 0, 0, 0 },
      { 0.29589464112140251, -0.39131049047736083, 0.096552894299182124 },
      5.6850963230547076e-14 },
    { { -950620.85247015697, -1496237.0873075542, -189893.92361563409 },
      { -951376.99979034101, -1496608.7459056573, -189794.59223045455 },
      { -947726.31920019654, -1494814.3775411365, -190274.16433259318 },
      { -947726.31920019654, -1494814.3775411365, -190274.16433259309 }, 4.3717793521501185e-11 },
    { { -191.37081960906121, -89.309010459248668, 20.408968481681462 },
      { 1847.2472789494236, 862.07409726065271, -197.00188132635006 },
      { 1847.2472789494368, 862.07409726065885, -197.00188132635145 }, { 0, 0, 0 },
      212.16836696722794 },
  };
  for (const Case& k : cases)
  {
    double longest = 0.0;
    const double* corner[3] = { k.A, k.B, k.C };
    for (int e = 0; e < 3; ++e)
    {
      double d2 = 0.0;
      for (int i = 0; i < 3; ++i)
      {
        const double d = corner[(e + 1) % 3][i] - corner[e][i];
        d2 += d * d;
      }
      longest = std::max(longest, std::sqrt(d2));
    }
    double q[3];
    const double d = std::sqrt(ClosestPointOnTriangle(k.P, k.A, k.B, k.C, q));
    MESHLOD_CHECK_LE(std::abs(d - k.Distance), 1e-12 * longest);
  }
}

//------------------------------------------------------------------------------
// The search's shortcut (TriangleTree keeps each triangle's ClosestPointCorner and measures
// with ClosestPointFromCorner) against ClosestPointOnTriangle: the same distance and point to
// the bit on random triangles of every shape (compact ones, caps, needles, segments, points)
// at points near them and far, and -1 for exactly the triangles the fast tests may not measure.
void TestClosestPointFromCorner()
{
  std::mt19937_64 random(20261205);
  auto uniform = [&]() { return static_cast<double>(random() >> 11) * 0x1.0p-53 * 2.0 - 1.0; };
  int measured = 0, thin = 0, mismatches = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    double corners[3][3];
    const int shape = trial % 5;
    for (int k = 0; k < 3; ++k)
    {
      for (double& x : corners[k])
      {
        x = 3.0 * uniform();
      }
    }
    for (int i = 0; i < 3; ++i)
    {
      const double* a = corners[0];
      double* b = corners[1];
      double* c = corners[2];
      if (shape == 1) // a cap: c near the line ab
      {
        c[i] = a[i] + 0.37 * (b[i] - a[i]) + 1e-7 * uniform();
      }
      else if (shape == 2) // a needle: c next to b
      {
        c[i] = b[i] + 1e-5 * uniform();
      }
      else if (shape == 3) // a segment: c on b
      {
        c[i] = b[i];
      }
      else if (shape == 4) // a point
      {
        b[i] = c[i] = a[i];
      }
    }
    const int corner = ClosestPointCorner(corners[0], corners[1], corners[2]);
    (corner >= 0 ? measured : thin) += 1;
    if (shape == 0 && corner < 0)
    {
      continue; // a random triangle that happens to be thin
    }
    for (int q = 0; q < 4; ++q)
    {
      double p[3], expected[3], got[3];
      for (double& x : p)
      {
        x = (q < 2 ? 0.5 : 6.0) * uniform();
      }
      const double d2 = ClosestPointOnTriangle(p, corners[0], corners[1], corners[2], expected);
      if (corner < 0)
      {
        continue;
      }
      const double e2 =
        ClosestPointFromCorner(p, corners[0], corners[1], corners[2], corner, got);
      mismatches += (e2 != d2 || !std::equal(got, got + 3, expected)) ? 1 : 0;
    }
    if (shape >= 1)
    {
      // Caps, needles, segments and points must take the slow path.
      mismatches += corner >= 0 ? 1 : 0;
    }
  }
  std::cerr << "  closest point from a kept corner: " << measured << " triangles measured, "
            << thin << " thin, " << mismatches << " mismatches\n";
  MESHLOD_CHECK_EQ(mismatches, 0);
  MESHLOD_CHECK_GE(measured, 3000);
  MESHLOD_CHECK_GE(thin, 16000);
}

//------------------------------------------------------------------------------
// The tent z = height * (1 - |x|) over [-1, 1]^2 as an n x n grid (n even, so that the ridge
// x = 0 is a grid line), triangles facing +z.
TriangleMesh Tent(int n, double height)
{
  TriangleMesh mesh;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      const double x = -1.0 + 2.0 * i / n, y = -1.0 + 2.0 * j / n;
      mesh.Points.insert(mesh.Points.end(), { x, y, height * (1.0 - std::abs(x)) });
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const Id v = j * (n + 1) + i;
      mesh.Triangles.insert(mesh.Triangles.end(), { v, v + 1, v + n + 2, v, v + n + 2, v + n + 1 });
    }
  }
  return mesh;
}

// Level points A (-1, 0), B (1, 0), C (0, -1), D (0, 1) on the tent, as input vertices.
struct TentQuad
{
  TriangleMesh Level;
  std::vector<Id> Start;
};

// Level points A, B, C, D at the input vertices `corners`, joined by `triangles`.
TentQuad QuadAt(const TriangleMesh& input, const std::array<Id, 4>& corners,
  const std::array<Id, 6>& triangles)
{
  TentQuad quad;
  for (const Id v : corners)
  {
    quad.Level.Points.insert(quad.Level.Points.end(), input.Point(v), input.Point(v) + 3);
    quad.Start.push_back(v);
  }
  quad.Level.Triangles.assign(triangles.begin(), triangles.end());
  return quad;
}

TentQuad MakeQuad(const TriangleMesh& input, int n, const std::array<Id, 6>& triangles)
{
  const Id half = n / 2;
  return QuadAt(
    input, { half * (n + 1), half * (n + 1) + n, half, n * (n + 1) + half }, triangles);
}

void TestTentFlips()
{
  constexpr int n = 10;
  const TriangleMesh tent = Tent(n, 1.0);
  const LevelZeroView input = LevelZeroView::Of(tent);
  VertexTriangleAdjacency adjacency;
  adjacency.Build(tent);
  constexpr Id A = 0, B = 1, C = 2, D = 3;

  // Across the ridge (diagonal AB, 1/sqrt(2) under it at the middle): flipped onto the ridge,
  // where the two new triangles are the tent's faces exactly.
  TentQuad across = MakeQuad(tent, n, { B, A, C, A, B, D });
  MESHLOD_CHECK_EQ(ImproveTriangulation(input, adjacency, across.Start, 0.5, across.Level), 1);
  const std::vector<Id> flipped = { C, B, D, D, A, C };
  MESHLOD_CHECK(across.Level.Triangles == flipped);
  // Judged again, the flipped pair stays.
  MESHLOD_CHECK_EQ(ImproveTriangulation(input, adjacency, across.Start, 0.5, across.Level), 0);

  // The same input read as vtkTriangleCollapseDecimation reads its level 0 (single-precision
  // points, 64-bit ids, the adjacency built from the view): the same flip.
  const std::vector<float> floats(tent.Points.begin(), tent.Points.end());
  const std::vector<vtkTypeInt64> ids64(tent.Triangles.begin(), tent.Triangles.end());
  LevelZeroView single;
  single.Floats = floats.data();
  single.Ids64 = ids64.data();
  single.Points = tent.GetNumberOfPoints();
  single.Triangles = tent.GetNumberOfTriangles();
  VertexTriangleAdjacency singleAdjacency;
  single.BuildAdjacency(singleAdjacency);
  MESHLOD_CHECK(singleAdjacency.Offsets == adjacency.Offsets);
  MESHLOD_CHECK(singleAdjacency.Triangles == adjacency.Triangles);
  TentQuad acrossSingle = MakeQuad(tent, n, { B, A, C, A, B, D });
  MESHLOD_CHECK_EQ(
    ImproveTriangulation(single, singleAdjacency, acrossSingle.Start, 0.5, acrossSingle.Level), 1);
  MESHLOD_CHECK(acrossSingle.Level.Triangles == flipped);

  // Without an error bound (an exact level) or with one far below the local error (the walk
  // would be lost) nothing is judged.
  TentQuad unbounded = MakeQuad(tent, n, { B, A, C, A, B, D });
  MESHLOD_CHECK_EQ(ImproveTriangulation(input, adjacency, unbounded.Start, 0.0, unbounded.Level), 0);
  MESHLOD_CHECK_EQ(ImproveTriangulation(input, adjacency, unbounded.Start, 0.1, unbounded.Level), 0);

  // On a flat input either diagonal is exact: no flip.
  const TriangleMesh flat = Tent(n, 0.0);
  VertexTriangleAdjacency flatAdjacency;
  flatAdjacency.Build(flat);
  TentQuad plane = MakeQuad(flat, n, { B, A, C, A, B, D });
  MESHLOD_CHECK_EQ(
    ImproveTriangulation(LevelZeroView::Of(flat), flatAdjacency, plane.Start, 0.5, plane.Level), 0);

  // A quad that is not convex at A (D moved out beyond A, so that the other diagonal passes
  // outside the quad): one flipped triangle would face down.
  TentQuad folded = MakeQuad(tent, n, { B, A, C, A, B, D });
  const double pulled[3] = { -3.0, 1.0, 0.0 };
  std::copy_n(pulled, 3, folded.Level.Point(D));
  MESHLOD_CHECK_EQ(ImproveTriangulation(input, adjacency, folded.Start, 0.5, folded.Level), 0);

  // A boundary edge (one triangle) is never flipped.
  TentQuad one = MakeQuad(tent, n, { B, A, C, B, A, C });
  one.Level.Triangles.resize(3);
  MESHLOD_CHECK_EQ(ImproveTriangulation(input, adjacency, one.Start, 0.5, one.Level), 0);
}

// A kite across a low ridge: diagonal AB short (A (-0.2, 0), B (0.2, 0)), 0.04 under the ridge at
// its middle, C (0, -1) and D (0, 1) on the ridge, so that the other diagonal lies on the input
// exactly. The angles facing AB add up to 45 degrees: with the default MinimumOppositeAngles the
// edge is not judged; with 0 the flip is made.
void TestSharpQuadNotJudged()
{
  constexpr int n = 10;
  const TriangleMesh tent = Tent(n, 0.2);
  const LevelZeroView input = LevelZeroView::Of(tent);
  VertexTriangleAdjacency adjacency;
  adjacency.Build(tent);
  constexpr Id A = 0, B = 1, C = 2, D = 3;
  const std::array<Id, 4> corners = { 5 * (n + 1) + 4, 5 * (n + 1) + 6, 5, n * (n + 1) + 5 };
  auto kite = [&] { return QuadAt(tent, corners, { B, A, C, A, B, D }); };
  TentQuad sharp = kite();
  MESHLOD_CHECK_EQ(ImproveTriangulation(input, adjacency, sharp.Start, 0.2, sharp.Level), 0);
  TentQuad judged = kite();
  TriangulationFlipOptions everyEdge;
  everyEdge.MinimumOppositeAngles = 0.0;
  MESHLOD_CHECK_EQ(
    ImproveTriangulation(input, adjacency, judged.Start, 0.2, judged.Level, everyEdge), 1);
  const std::vector<Id> flipped = { C, B, D, D, A, C };
  MESHLOD_CHECK(judged.Level.Triangles == flipped);
}

//------------------------------------------------------------------------------
// A manifold, consistently oriented mesh without degenerate or duplicate triangles.
void CheckValidMesh(vtkPolyData* mesh)
{
  const testing::MeshReport report = testing::InspectMesh(mesh);
  MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
  MESHLOD_CHECK_EQ(report.DuplicateTriangles, 0);
  MESHLOD_CHECK_EQ(report.DegenerateTriangles, 0);
  MESHLOD_CHECK(report.ConsistentlyOriented);
}

// A valid flipped level (CheckValidMesh) with the Euler characteristic of the level made
// without flips and no triangle turned against the finer flipped level's.
void CheckValidFlippedLevel(vtkPolyData* plain, vtkPolyData* flipped, vtkPolyData* finer)
{
  CheckValidMesh(flipped);
  MESHLOD_CHECK_EQ(testing::InspectMesh(flipped).EulerCharacteristic,
    testing::InspectMesh(plain).EulerCharacteristic);
  MESHLOD_CHECK_EQ(testing::CountFlippedTriangles(finer, flipped), 0);
}

// A level made with flips against the same level made without: the same points and counts, and
// a valid flipped level (CheckValidFlippedLevel); returns how many triangles the flips changed.
vtkIdType CheckFlippedLevel(vtkPolyData* plain, vtkPolyData* flipped, vtkPolyData* finer)
{
  MESHLOD_CHECK_EQ(plain->GetNumberOfPoints(), flipped->GetNumberOfPoints());
  MESHLOD_CHECK_EQ(plain->GetNumberOfPolys(), flipped->GetNumberOfPolys());
  vtkIdType moved = 0;
  const bool samePoints = plain->GetNumberOfPoints() == flipped->GetNumberOfPoints();
  for (vtkIdType p = 0; samePoints && p < plain->GetNumberOfPoints(); ++p)
  {
    double x[3], y[3];
    plain->GetPoint(p, x);
    flipped->GetPoint(p, y);
    moved += (x[0] != y[0] || x[1] != y[1] || x[2] != y[2]) ? 1 : 0;
  }
  MESHLOD_CHECK_EQ(moved, 0);
  CheckValidFlippedLevel(plain, flipped, finer);
  vtkIdType changed = 0;
  const auto ta = testing::Triangles(plain), tb = testing::Triangles(flipped);
  for (size_t t = 0; t < ta.size() && ta.size() == tb.size(); ++t)
  {
    changed += ta[t] == tb[t] ? 0 : 1;
  }
  return changed;
}

// The distances of both levels to the input, printed.
std::pair<SurfaceDistance, SurfaceDistance> MeasureBoth(
  vtkPolyData* input, vtkPolyData* plain, vtkPolyData* flipped, vtkIdType changed)
{
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = 50000;
  const SurfaceDistance before = MeasureSurfaceDistance(input, plain, options);
  const SurfaceDistance after = MeasureSurfaceDistance(input, flipped, options);
  std::cout << "  " << flipped->GetNumberOfPolys() << " triangles, " << changed
            << " changed by flips; RMS " << before.RmsPercent() << "% -> " << after.RmsPercent()
            << "%, Hausdorff " << before.HausdorffPercent() << "% -> "
            << after.HausdorffPercent() << "%\n";
  return { before, after };
}

// Same flipped levels for any thread count.
void CheckFlipsThreadIndependent(
  const std::function<vtkSmartPointer<vtkMultiBlockDataSet>()>& run, unsigned int levels)
{
  for (unsigned int i = 1; i < levels; ++i)
  {
    const auto runs = testing::RunWithBothBackends(
      [&]
      {
        auto level = vtkSmartPointer<vtkPolyData>::New();
        level->ShallowCopy(testing::Level(run(), i));
        return level;
      });
    MESHLOD_CHECK(testing::SameMesh(runs.first, runs.second));
  }
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkMultiBlockDataSet> Octree(vtkPolyData* mesh, bool flip)
{
  vtkNew<vtkVertexClusterOctree> octree;
  octree->SetInputData(mesh);
  octree->SetLevelModeToTargetTriangleCounts();
  octree->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 10);
  octree->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 100);
  octree->SetFlipEdges(flip);
  // Centring moves points by the distances to their triangles, which the flips change: off, so
  // that only the triangles differ between the two runs.
  octree->CenterOnInputOff();
  octree->Update();
  return octree->GetHierarchy();
}

void TestOctreeFlips()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Metaballs, 80);
  const auto plain = Octree(mesh, false);
  const auto flipped = Octree(mesh, true);
  MESHLOD_CHECK_EQ(plain->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK_EQ(flipped->GetNumberOfBlocks(), 3u);
  for (unsigned int i = 1; i < 3 && flipped->GetNumberOfBlocks() == 3; ++i)
  {
    vtkPolyData* a = testing::Level(plain, i);
    vtkPolyData* b = testing::Level(flipped, i);
    const vtkIdType changed = CheckFlippedLevel(a, b, testing::Level(flipped, i - 1));
    std::cout << "  octree level " << i << ":";
    const auto distances = MeasureBoth(mesh, a, b, changed);
    MESHLOD_CHECK_GT(changed, 0);
    MESHLOD_CHECK_LT(distances.second.Rms, 0.95 * distances.first.Rms);
    MESHLOD_CHECK_LE(distances.second.Hausdorff, 1.02 * distances.first.Hausdorff);
  }
  // The points still nest; the flipped levels' triangles are no longer images of the finer
  // level's (what FlipEdges documents), the unflipped ones are.
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(plain), 0);
  MESHLOD_CHECK_GT(testing::CountCorrespondenceViolations(flipped), 0);
  CheckFlipsThreadIndependent([&] { return Octree(mesh, true); }, 3);
}

// How many triangles of `level` map through MorphTargetId onto the same triangle of the next
// level as another one (either orientation; triangles that degenerate left out).
vtkIdType CountDoubledImages(vtkPolyData* level)
{
  vtkDataArray* target = level->GetPointData()->GetArray("MorphTargetId");
  MESHLOD_CHECK(target != nullptr);
  std::vector<std::array<vtkIdType, 3>> images;
  for (const auto& corners : testing::Triangles(level))
  {
    std::array<vtkIdType, 3> image;
    for (int k = 0; k < 3; ++k)
    {
      image[k] = target ? static_cast<vtkIdType>(target->GetComponent(corners[k], 0)) : 0;
    }
    std::sort(image.begin(), image.end());
    if (image[0] != image[1] && image[1] != image[2])
    {
      images.push_back(image);
    }
  }
  std::sort(images.begin(), images.end());
  return static_cast<vtkIdType>(
    images.size() - (std::unique(images.begin(), images.end()) - images.begin()));
}

// Flips that the next level makes into one triangle twice are refused: where it merges the
// ends of a flipped quad's old diagonal but not those of the new one, its two triangles became
// one triangle twice (a fin the geomorph passed through towards the next level). A gyroid of
// 22,550 triangles with eight levels of epsilon 0.002 x 2^i had 16 such pairs (10 between
// levels 1 and 2); none now, and the geomorph's exact counts between the first two simplified
// levels are valid meshes. A repeated level is flipped as the level it repeats.
void TestOctreeFlipsKeepImagesApart()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Gyroid, 40);
  MESHLOD_CHECK_EQ(mesh->GetNumberOfPolys(), 22550);
  vtkNew<vtkVertexClusterOctree> octree;
  octree->SetInputData(mesh);
  octree->SetNumberOfLevels(8);
  octree->SetEpsilon(0.002);
  octree->SetEpsilonFactor(2.0);
  octree->FlipEdgesOn();
  octree->Update();
  vtkMultiBlockDataSet* hierarchy = octree->GetHierarchy();
  MESHLOD_CHECK_EQ(hierarchy->GetNumberOfBlocks(), 9u);
  for (unsigned int i = 0; i + 1 < hierarchy->GetNumberOfBlocks(); ++i)
  {
    MESHLOD_CHECK_EQ(CountDoubledImages(testing::Level(hierarchy, i)), 0);
  }
  MESHLOD_CHECK_GT(testing::CountCorrespondenceViolations(hierarchy), 0); // still flipped

  // A level that repeats the one before (an epsilon that merges nothing more) waits with it for
  // the next different level: both get the same flips.
  vtkNew<vtkVertexClusterOctree> repeating;
  repeating->SetInputData(mesh);
  repeating->SetLevelModeToEpsilonList();
  for (const double epsilon : { 0.004, 0.004 * (1.0 + 1e-9), 0.008, 0.016 })
  {
    repeating->AddEpsilonValue(epsilon);
  }
  repeating->FlipEdgesOn();
  repeating->Update();
  vtkMultiBlockDataSet* repeated = repeating->GetHierarchy();
  MESHLOD_CHECK_EQ(repeated->GetNumberOfBlocks(), 5u);
  if (repeated->GetNumberOfBlocks() == 5)
  {
    MESHLOD_CHECK_EQ(testing::Level(repeated, 1)->GetNumberOfPolys(),
      testing::Level(repeated, 2)->GetNumberOfPolys());
    MESHLOD_CHECK(testing::SameMesh(testing::Level(repeated, 1), testing::Level(repeated, 2)));
    for (unsigned int i = 0; i < 4; ++i)
    {
      MESHLOD_CHECK_EQ(CountDoubledImages(testing::Level(repeated, i)), 0);
    }
  }

  vtkNew<vtkLODGeomorph> morph;
  morph->SetInputData(hierarchy);
  morph->UsePipelineTimeOff();
  const vtkIdType finer = testing::Level(hierarchy, 1)->GetNumberOfPolys();
  const vtkIdType coarser = testing::Level(hierarchy, 2)->GetNumberOfPolys();
  for (int k = 1; k < 40 && coarser < finer; ++k)
  {
    morph->SetTargetNumberOfTriangles(coarser + (finer - coarser) * k / 40);
    morph->Update();
    const testing::MeshReport report = testing::InspectMesh(morph->GetOutput());
    MESHLOD_CHECK_EQ(report.DuplicateTriangles, 0);
    MESHLOD_CHECK_EQ(report.NonManifoldEdges, 0);
  }
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkMultiBlockDataSet> Collapse(vtkPolyData* mesh, bool flip, vtkIdType* flips)
{
  vtkNew<vtkTriangleCollapseDecimation> decimate;
  decimate->SetInputData(mesh);
  decimate->SetFlipEdges(flip);
  decimate->Update();
  if (flips)
  {
    *flips = decimate->GetNumberOfFlips();
  }
  return decimate->GetHierarchy();
}

// The flips read the input where the output's level 0 holds it, in its own precision and id
// width (LevelZeroView.h): the same input with double-precision points and the other cell
// storage (32-bit ids for 64-bit, or the reverse) gets the same flips, the same triangles on
// every level and the same points up to their single-precision rounding.
void CheckFlipsStorageIndependent(
  vtkPolyData* mesh, vtkMultiBlockDataSet* flipped, vtkIdType flips)
{
  MESHLOD_CHECK_EQ(mesh->GetPoints()->GetDataType(), VTK_FLOAT);
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    coordinates->SetTuple(p, mesh->GetPoint(p));
  }
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  vtkNew<vtkCellArray> polys;
  polys->DeepCopy(mesh->GetPolys());
  const bool wide = polys->IsStorage64Bit();
  wide ? polys->ConvertTo32BitStorage() : polys->ConvertTo64BitStorage();
  MESHLOD_CHECK(polys->IsStorage64Bit() != wide);
  vtkNew<vtkPolyData> other;
  other->SetPoints(points);
  other->SetPolys(polys);

  vtkIdType otherFlips = 0;
  const auto otherLevels = Collapse(other, true, &otherFlips);
  MESHLOD_CHECK_EQ(otherFlips, flips);
  MESHLOD_CHECK_EQ(otherLevels->GetNumberOfBlocks(), flipped->GetNumberOfBlocks());
  for (unsigned int i = 1;
       i < flipped->GetNumberOfBlocks() && i < otherLevels->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* a = testing::Level(flipped, i);
    vtkPolyData* b = testing::Level(otherLevels, i);
    MESHLOD_CHECK(testing::Triangles(a) == testing::Triangles(b));
    MESHLOD_CHECK_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
    double largest = 0.0;
    for (vtkIdType p = 0; p < std::min(a->GetNumberOfPoints(), b->GetNumberOfPoints()); ++p)
    {
      double x[3], y[3];
      a->GetPoint(p, x);
      b->GetPoint(p, y);
      for (int k = 0; k < 3; ++k)
      {
        largest = std::max(largest, std::abs(x[k] - y[k]));
      }
    }
    // Single-precision rounding of coordinates below 10 in magnitude: under 1e-6.
    MESHLOD_CHECK_LT(largest, 1e-6);
  }
}

// The flips between a level and the next (made with FlipEdges): the next level's triangles that
// are not images of the level's (through MorphTargetId) must be lone flipped quads, two new
// triangles on the diagonal (c, d) where the images have two on (a, b), no two quads sharing a
// point (what vtkLODGeomorph morphs continuously). Returns their number, -1 when the
// differences are anything else.
vtkIdType CountLoneFlippedQuads(vtkPolyData* level, vtkPolyData* next)
{
  auto turned = [](std::array<vtkIdType, 3> t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  vtkDataArray* target = level->GetPointData()->GetArray("MorphTargetId");
  std::vector<std::array<vtkIdType, 3>> images, own;
  for (const auto& t : testing::Triangles(level))
  {
    std::array<vtkIdType, 3> image;
    for (int k = 0; k < 3; ++k)
    {
      image[k] = static_cast<vtkIdType>(target->GetTuple1(t[k]));
    }
    if (image[0] != image[1] && image[1] != image[2] && image[0] != image[2])
    {
      images.push_back(turned(image));
    }
  }
  for (const auto& t : testing::Triangles(next))
  {
    own.push_back(turned(t));
  }
  std::sort(images.begin(), images.end());
  std::sort(own.begin(), own.end());
  std::vector<std::array<vtkIdType, 3>> added, removed;
  std::set_difference(own.begin(), own.end(), images.begin(), images.end(), std::back_inserter(added));
  std::set_difference(images.begin(), images.end(), own.begin(), own.end(), std::back_inserter(removed));
  if (added.size() != removed.size() || added.size() % 2 != 0)
  {
    return -1;
  }
  // Pair the added triangles by a shared edge; each quad's four points once in all.
  std::vector<vtkIdType> points;
  std::vector<bool> paired(added.size(), false);
  vtkIdType quads = 0;
  for (std::size_t i = 0; i < added.size(); ++i)
  {
    for (std::size_t j = i + 1; j < added.size() && !paired[i]; ++j)
    {
      std::vector<vtkIdType> both(added[i].begin(), added[i].end());
      both.insert(both.end(), added[j].begin(), added[j].end());
      std::sort(both.begin(), both.end());
      both.erase(std::unique(both.begin(), both.end()), both.end());
      if (both.size() == 4 && !paired[j])
      {
        paired[i] = paired[j] = true;
        points.insert(points.end(), both.begin(), both.end());
        ++quads;
      }
    }
  }
  std::sort(points.begin(), points.end());
  const bool disjoint = std::adjacent_find(points.begin(), points.end()) == points.end();
  return disjoint && 2 * quads == static_cast<vtkIdType>(added.size()) ? quads : -1;
}

// vtkLODGeomorph through a hierarchy made with FlipEdges: continuous at the end of each
// transition (L -> i + 1 gives level i + 1, not the images of level i's triangles) and where
// the collapses hand over to the flips (L = i + 0.75), with a valid mesh while the flipped
// quads turn (two triangles more per quad).
void CheckGeomorphThroughFlips(vtkMultiBlockDataSet* hierarchy)
{
  // Each level names itself as a baked level would (TextureAtlasLevel; without TCoords it
  // changes nothing else): the output carries the name of the level whose point data it has,
  // this level's while the collapses move, the next one's while its flips turn.
  for (unsigned int i = 0; i < hierarchy->GetNumberOfBlocks(); ++i)
  {
    vtkNew<vtkIntArray> mark;
    mark->SetName(names::TextureAtlasLevel);
    mark->InsertNextValue(static_cast<int>(i));
    testing::Level(hierarchy, i)->GetFieldData()->AddArray(mark);
  }
  auto atlasLevel = [](vtkPolyData* frame) {
    vtkDataArray* mark = frame->GetFieldData()->GetArray(names::TextureAtlasLevel);
    return mark ? static_cast<int>(mark->GetTuple1(0)) : -1;
  };
  vtkNew<vtkLODGeomorph> morph;
  morph->SetInputData(hierarchy);
  morph->UsePipelineTimeOff();
  auto at = [&](double lod) {
    morph->SetLevelOfDetail(lod);
    morph->Update();
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->DeepCopy(morph->GetOutput());
    return copy;
  };
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = 20000;
  int turning = 0;
  for (unsigned int i = 0; i + 1 < hierarchy->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* next = testing::Level(hierarchy, i + 1);
    const auto end = at(i + 1 - 1e-7);
    const double diagonal = next->GetLength();
    MESHLOD_CHECK_LT(MeasureSurfaceDistance(next, end, options).Hausdorff, 1e-6 * diagonal);
    const auto before = at(i + 0.75 - 1e-7);
    const auto after = at(i + 0.75);
    MESHLOD_CHECK_LT(MeasureSurfaceDistance(before, after, options).Hausdorff, 1e-6 * diagonal);
    const vtkIdType quads = CountLoneFlippedQuads(testing::Level(hierarchy, i), next);
    MESHLOD_CHECK_GE(quads, 0);
    if (quads <= 0)
    {
      continue; // (no flips: the partial collapse all the way, FlipEdges off's geomorph)
    }
    const auto middle = at(i + 0.9);
    MESHLOD_CHECK_EQ(middle->GetNumberOfPolys(), next->GetNumberOfPolys() + 2 * quads);
    MESHLOD_CHECK_EQ(atlasLevel(middle), static_cast<int>(i + 1));
    MESHLOD_CHECK_EQ(atlasLevel(at(i + 0.5)), static_cast<int>(i));
    // The arrays of the level it turns into (no morph arrays), one value per point and cell.
    const auto landed = at(i + 1);
    MESHLOD_CHECK_EQ(
      middle->GetPointData()->GetNumberOfArrays(), landed->GetPointData()->GetNumberOfArrays());
    MESHLOD_CHECK(!middle->GetPointData()->GetArray("MorphTargetId"));
    MESHLOD_CHECK_EQ(
      middle->GetCellData()->GetNumberOfArrays(), landed->GetCellData()->GetNumberOfArrays());
    MESHLOD_CHECK_EQ(middle->GetPointData()->GetNumberOfArrays(), 2);
    for (int a = 0; a < middle->GetPointData()->GetNumberOfArrays(); ++a)
    {
      MESHLOD_CHECK_EQ(middle->GetPointData()->GetAbstractArray(a)->GetNumberOfTuples(),
        middle->GetNumberOfPoints());
    }
    vtkDataArray* normals = middle->GetPointData()->GetNormals();
    MESHLOD_CHECK(normals != nullptr);
    for (vtkIdType p = next->GetNumberOfPoints(); normals && p < middle->GetNumberOfPoints(); ++p)
    {
      double n[3];
      normals->GetTuple(p, n);
      MESHLOD_CHECK_LT(std::abs(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0), 1e-6);
    }
    CheckValidMesh(middle);
    ++turning;
  }
  MESHLOD_CHECK_GE(turning, 4);
}

// vtkTriangleCollapseDecimation's FlipEdges on a gyroid isosurface (34,988 triangles, 8 levels
// down to 1%): the levels with more than a quarter of the input's triangles stay as they are;
// each of the others is a valid level whose flips against the images of the finer level's
// triangles are lone quads (one flip per point; the collapses go on from the flipped
// triangles), with a lower RMS distance and no higher a Hausdorff distance than the level made
// without flips, and the long edges across saddles go: two levels' Hausdorff distances fall by
// a sixth to a quarter (0.36% -> 0.27% at 3,498 triangles, 0.75% -> 0.62% at 1,967) with 2 to
// 6 flips a level (only quads bent by 1.5 times the error scale are judged).
void TestTriangleCollapseFlips()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Gyroid, 50);
  vtkIdType flips = 0;
  const auto plain = Collapse(mesh, false, nullptr);
  const auto flipped = Collapse(mesh, true, &flips);
  const unsigned int levels = plain->GetNumberOfBlocks();
  MESHLOD_CHECK_EQ(levels, 9u);
  MESHLOD_CHECK_EQ(flipped->GetNumberOfBlocks(), levels);
  MESHLOD_CHECK_GT(flips, 0);
  vtkIdType quadsInAll = 0;
  int muchCloser = 0;
  bool firstFlipped = true;
  for (unsigned int i = 1; i < levels && flipped->GetNumberOfBlocks() == levels; ++i)
  {
    vtkPolyData* a = testing::Level(plain, i);
    vtkPolyData* b = testing::Level(flipped, i);
    if (4 * a->GetNumberOfPolys() > mesh->GetNumberOfPolys())
    {
      MESHLOD_CHECK(testing::SameMesh(a, b)); // a level above a quarter of the input is not flipped
      continue;
    }
    if (firstFlipped)
    {
      // The collapses up to the first flipped level are those without flips.
      MESHLOD_CHECK_GT(CheckFlippedLevel(a, b, testing::Level(flipped, i - 1)), 0);
      firstFlipped = false;
    }
    else
    {
      CheckValidFlippedLevel(a, b, testing::Level(flipped, i - 1));
    }
    MESHLOD_CHECK_LE(std::abs(a->GetNumberOfPolys() - b->GetNumberOfPolys()), 2);
    const vtkIdType quads = CountLoneFlippedQuads(testing::Level(flipped, i - 1), b);
    MESHLOD_CHECK_GT(quads, 0);
    quadsInAll += quads;
    std::cout << "  collapse level " << i << ":";
    const auto distances = MeasureBoth(mesh, a, b, 2 * quads);
    MESHLOD_CHECK_LT(distances.second.Rms, distances.first.Rms);
    MESHLOD_CHECK_LE(distances.second.Hausdorff, 1.001 * distances.first.Hausdorff);
    muchCloser += distances.second.Hausdorff < 0.85 * distances.first.Hausdorff ? 1 : 0;
  }
  // Every flip is one of those quads.
  MESHLOD_CHECK_EQ(quadsInAll, flips);
  MESHLOD_CHECK_GE(muchCloser, 2);
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(plain), 0);
  MESHLOD_CHECK_GT(testing::CountCorrespondenceViolations(flipped), 0);
  CheckFlipsThreadIndependent([&] { return Collapse(mesh, true, nullptr); }, levels);
  CheckFlipsStorageIndependent(mesh, flipped, flips);
  // The same surface with normals and scalars, carried by the geomorph through the flips.
  const auto withData = testing::MakeIsosurface(testing::Field::Gyroid, 50, true, true);
  MESHLOD_CHECK_EQ(withData->GetPointData()->GetNumberOfArrays(), 2);
  CheckGeomorphThroughFlips(Collapse(withData, true, nullptr));
}
} // namespace

int TestTriangulationFlips(int, char*[])
{
  TestClosestPoint();
  TestClosestPointOnThinTriangles();
  TestClosestPointNearCoincidentCorners();
  TestClosestPointFromCorner();
  TestTentFlips();
  TestSharpQuadNotJudged();
  TestOctreeFlips();
  TestOctreeFlipsKeepImagesApart();
  TestTriangleCollapseFlips();
  return meshlod::testing::Result();
}
