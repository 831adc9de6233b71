// The curvature method's local fit (paper 000, section 4) and its collapse point, with exact
// expectations on analytic surfaces.
#include "Core/CollapseCosts.h"
#include "Core/CollapseMesh.h"
#include "Core/LevelData.h"
#include "Core/LevelTracker.h"
#include "Core/LocalSurfaceFit.h"
#include "MeshLODInputMesh.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
using namespace meshlod;

// Points of the height field d = 0.3 u^2 - 0.2 u v + 0.5 v^2 + 0.1 u - 0.4 v + 0.25 in a frame
// tilted away from the coordinate axes, on a 5 x 5 grid of (u, v).
void TestExactQuadratic()
{
  const double origin[3] = { 1.0, -2.0, 0.5 };
  double normal[3] = { 1.0, 2.0, 2.0 };
  for (double& x : normal)
  {
    x /= 3.0;
  }
  // Any in-plane axes: the fit chooses its own, and reports them.
  const double a[3] = { 2.0 / 3.0, 1.0 / 3.0, -2.0 / 3.0 };
  const double b[3] = { normal[1] * a[2] - normal[2] * a[1], normal[2] * a[0] - normal[0] * a[2],
    normal[0] * a[1] - normal[1] * a[0] };
  auto height = [](double u, double v) {
    return 0.3 * u * u - 0.2 * u * v + 0.5 * v * v + 0.1 * u - 0.4 * v + 0.25;
  };
  std::vector<double> points;
  for (int i = -2; i <= 2; ++i)
  {
    for (int j = -2; j <= 2; ++j)
    {
      const double u = 0.5 * i, v = 0.5 * j, d = height(u, v);
      for (int k = 0; k < 3; ++k)
      {
        points.push_back(origin[k] + u * a[k] + v * b[k] + d * normal[k]);
      }
    }
  }
  const SurfaceFitResult fit =
    FitQuadraticHeightField(origin, normal, points.data(), static_cast<int>(points.size() / 3), 0.5);
  MESHLOD_CHECK(fit.Valid);
  MESHLOD_CHECK_NEAR(fit.Height, 0.25, 1e-12);
  // The fitted surface passes through every point, whatever the fit's own axes.
  for (std::size_t p = 0; p < points.size() / 3; ++p)
  {
    double u = 0, v = 0, d = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double x = points[3 * p + k] - origin[k];
      u += x * fit.U[k];
      v += x * fit.V[k];
      d += x * normal[k];
    }
    MESHLOD_CHECK_NEAR(fit.At(u, v), d, 1e-12);
  }

  // The paraboloid d = u^2 + v^2 has both principal curvatures 2 at its apex.
  points.clear();
  for (int i = -2; i <= 2; ++i)
  {
    for (int j = -2; j <= 2; ++j)
    {
      const double u = 0.1 * i, v = 0.1 * j;
      points.insert(points.end(), { u, v, u * u + v * v });
    }
  }
  const double zero[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
  const SurfaceFitResult apex = FitQuadraticHeightField(zero, up, points.data(), 25, 0.1);
  MESHLOD_CHECK(apex.Valid);
  MESHLOD_CHECK_NEAR(apex.Kappa1, 2.0, 1e-6);
  MESHLOD_CHECK_NEAR(apex.Kappa2, 2.0, 1e-6);
  MESHLOD_CHECK_NEAR(apex.AbsoluteCurvature, 4.0, 1e-6);

  // Points on one line cannot determine a surface.
  points.clear();
  for (int i = 0; i < 10; ++i)
  {
    points.insert(points.end(), { 0.1 * i, 0.0, 0.0 });
  }
  MESHLOD_CHECK(!FitQuadraticHeightField(zero, up, points.data(), 10, 0.1).Valid);
}

// The curvature method's evaluation of the given triangles of a mesh, as the filter's first
// pass makes it (the candidates' collapse points, curvatures and costs).
std::vector<CollapseCandidate> EvaluateCurvature(
  vtkPolyData* mesh, CurvatureCost ranking, const std::vector<Id>& triangles)
{
  vtkNew<vtkTriangleFilter> caller;
  InputMesh input;
  ReadInputMesh(mesh, caller, input);
  TriangleCollapseOptions options;
  options.Method = CollapseMethod::Curvature;
  options.CurvatureRanking = ranking;
  OriginalPointReader original;
  original.Copy = input.Mesh.Points;
  CollapseMesh state;
  LevelTracker tracker;
  tracker.Initialize(input.Mesh.GetNumberOfPoints(), true);
  state.Initialize(std::move(input.Mesh), std::move(input.Topology), 1.0, 0.0);
  CollapseCostModel model(options, state, tracker, original);
  CostScratch scratch;
  std::vector<CollapseCandidate> candidates(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    MESHLOD_CHECK(model.Evaluate(triangles[i], candidates[i], scratch));
  }
  return candidates;
}

// On a sphere the paper's collapse point c + f(0, 0) n lies on the sphere, and the new
// triangles, chords of a convex surface, lie inside it. The collapse point is placed where they
// lie on the fitted surface on average: outside the sphere, by a fraction of the sagitta.
void TestCollapsePointOnSphere()
{
  for (const CollapseCandidate& c :
    EvaluateCurvature(testing::MakeIcosphere(3), CurvatureCost::Weight, { 0, 100, 700 }))
  {
    const double radius =
      std::sqrt(c.Position[0] * c.Position[0] + c.Position[1] * c.Position[1] +
        c.Position[2] * c.Position[2]);
    // Edges of a level-3 icosphere are about 0.13 long and the stencil boundary is about two
    // edges from the centroid: the new triangles' chords have a sagitta of about 0.03, and the
    // point that puts them on the sphere on average is outside it by a good part of that.
    MESHLOD_CHECK_GT(radius, 1.005);
    MESHLOD_CHECK_LT(radius, 1.03);
    MESHLOD_CHECK_NEAR(c.Kappa, 2.0, 0.1); // both principal curvatures of the unit sphere are 1
  }
}

// CurvatureCost FitDeviation: the cost of a collapse is the integral of the new triangles'
// squared height above the fitted surface. On a plane it is zero; on a sphere it is positive
// and, an area times a squared length, grows 2^4 = 16 times when the sphere's radius doubles.
double FitDeviationCost(vtkPolyData* mesh, Id t)
{
  return EvaluateCurvature(mesh, CurvatureCost::FitDeviation, { t })[0].Cost;
}

void TestFitDeviation()
{
  // An interior triangle of a flat grid (the grid's middle row).
  MESHLOD_CHECK_EQ(FitDeviationCost(testing::MakeGrid(8, 8), 70), 0.0);
  vtkSmartPointer<vtkPolyData> unit = testing::MakeIcosphere(3);
  vtkNew<vtkPolyData> doubled;
  doubled->DeepCopy(unit);
  for (vtkIdType i = 0; i < doubled->GetNumberOfPoints(); ++i)
  {
    double x[3];
    doubled->GetPoint(i, x);
    doubled->GetPoints()->SetPoint(i, 2.0 * x[0], 2.0 * x[1], 2.0 * x[2]);
  }
  for (const Id t : { 0, 100, 700 })
  {
    const double cost = FitDeviationCost(unit, t);
    MESHLOD_CHECK_GT(cost, 0.0);
    MESHLOD_CHECK_NEAR(FitDeviationCost(doubled, t) / cost, 16.0, 1e-6);
  }
}

// The original points come back relative to the engine's centre, the same numbers whether read
// from a copy made after the move to the centre or from the input's float or double array
// through the map from engine vertex to input point.
void TestOriginalPointReader()
{
  const float floats[9] = { 1.5f, -2.25f, 3.1f, 0.1f, 0.2f, 0.3f, 7.0f, 8.5f, -9.75f };
  double doubles[9];
  std::copy_n(floats, 9, doubles);
  const long long ids[2] = { 2, 0 }; // engine vertex 0 is input point 2, vertex 1 is point 0
  OriginalPointReader copy, fromFloats, fromDoubles;
  for (OriginalPointReader* r : { &copy, &fromFloats, &fromDoubles })
  {
    r->Centre[0] = 0.3;
    r->Centre[1] = -1.7;
    r->Centre[2] = 2.9;
  }
  for (const long long p : ids)
  {
    for (int k = 0; k < 3; ++k)
    {
      copy.Copy.push_back(doubles[3 * p + k] - copy.Centre[k]);
    }
  }
  fromFloats.Float = floats;
  fromFloats.Ids = ids;
  fromDoubles.Double = doubles;
  fromDoubles.Ids = ids;
  for (Id v = 0; v < 2; ++v)
  {
    double a[3], b[3], c[3];
    copy.Get(v, a);
    fromFloats.Get(v, b);
    fromDoubles.Get(v, c);
    for (int k = 0; k < 3; ++k)
    {
      MESHLOD_CHECK_EQ(a[k], b[k]);
      MESHLOD_CHECK_EQ(a[k], c[k]);
    }
  }
  double x[3];
  fromFloats.Get(0, x);
  MESHLOD_CHECK_EQ(x[0], static_cast<double>(7.0f) - 0.3);
}

// The ancestral points the fits read (every k-th of the original vertices merged into a vertex,
// in the order the merges joined them) against a plain list per vertex, through collapses and
// level snapshots (which lay them out anew): triangle collapses on an icosphere, the first legal
// one each time, a snapshot after every 12.
void TestAncestralPoints()
{
  vtkNew<vtkTriangleFilter> caller;
  InputMesh input;
  ReadInputMesh(testing::MakeIcosphere(2), caller, input);
  const Id nv = input.Mesh.GetNumberOfPoints();
  CollapseMesh state;
  LevelTracker tracker;
  tracker.Initialize(nv, true);
  state.Initialize(std::move(input.Mesh), std::move(input.Topology), 1.0, 0.0);
  std::vector<std::vector<Id>> expected(nv);
  for (Id v = 0; v < nv; ++v)
  {
    expected[v].push_back(v);
  }
  CollapseRules rules;
  Star star;
  int collapses = 0, snapshots = 0;
  bool matches = true;
  for (std::int64_t sequence = 0; sequence < 60; ++sequence)
  {
    bool collapsed = false;
    for (Id t = 0; t < state.Mesh.GetNumberOfTriangles() && !collapsed; ++t)
    {
      if (!state.IsAlive(t) || !state.GatherStar(state.Mesh.Triangle(t), 3, star))
      {
        continue;
      }
      double x[3] = { 0, 0, 0 }, normal[3];
      for (int k = 0; k < 3; ++k)
      {
        for (int c = 0; c < 3; ++c)
        {
          x[c] += state.Mesh.Point(star.Members[k])[c] / 3.0;
        }
      }
      TriangleNormal(state.Mesh.Point(star.Members[0]), state.Mesh.Point(star.Members[1]),
        state.Mesh.Point(star.Members[2]), normal);
      if (state.IsLegal(star, x, normal, rules) != Legality::Legal)
      {
        continue;
      }
      const Id members[3] = { star.Members[0], star.Members[1], star.Members[2] };
      const double weights[3] = { 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0 };
      MESHLOD_CHECK_EQ(state.Apply(star, x), members[0]);
      tracker.Merge(members, weights, 3, sequence);
      for (int k = 1; k < 3; ++k)
      {
        expected[members[0]].insert(
          expected[members[0]].end(), expected[members[k]].begin(), expected[members[k]].end());
      }
      state.AliveTriangles -= static_cast<Id>(star.Dying.size());
      collapsed = true;
      ++collapses;
    }
    if (sequence % 12 == 11)
    {
      LevelData level;
      tracker.Snapshot(state, 0.0, level);
      ++snapshots;
    }
    // Every live vertex, several strides and starting positions.
    for (Id v = 0; v < nv; ++v)
    {
      if (state.Survivor[v] != v || state.TriangleCount(v) == 0)
      {
        continue;
      }
      matches = matches && tracker.AncestorCount(v) == static_cast<Id>(expected[v].size());
      for (const Id stride : { 1, 2, 3, 7 })
      {
        for (const Id start : { 0, 1, 5 })
        {
          std::vector<Id> got, want;
          Id index = start;
          tracker.ForEachAncestor(v, stride, index, [&](Id u) { got.push_back(u); });
          for (std::size_t p = 0; p < expected[v].size(); ++p)
          {
            if ((start + static_cast<Id>(p)) % stride == 0)
            {
              want.push_back(expected[v][p]);
            }
          }
          matches = matches && got == want &&
            index == start + static_cast<Id>(expected[v].size());
        }
      }
    }
  }
  MESHLOD_CHECK_EQ(collapses, 60);
  MESHLOD_CHECK_EQ(snapshots, 5);
  MESHLOD_CHECK(matches);
  // Sixty triangle collapses merged 120 vertices into others: someone holds several.
  std::size_t most = 0;
  for (const std::vector<Id>& list : expected)
  {
    most = std::max(most, list.size());
  }
  MESHLOD_CHECK_GE(most, 5u);
}
} // namespace

int TestLocalSurfaceFit(int, char*[])
{
  TestExactQuadratic();
  TestCollapsePointOnSphere();
  TestFitDeviation();
  TestOriginalPointReader();
  TestAncestralPoints();
  return meshlod::testing::Result();
}
