// Where a collapse goes: paper 002's rule (PlaceByCandidates: the quadric's minimiser when its
// 3x3 system is solvable, else the cheapest of the centroid, the merging points and their
// midpoints) on quadrics whose answers are known by hand, and the regularised solve
// (Quadric::MinimizeRegularized) on the same quadrics.
#include "Core/Quadric.h"
#include "MeshLODTestCheck.h"

namespace
{
using meshlod::PlaceByCandidates;
using meshlod::Quadric;

constexpr double Tolerance = 1e-6; // the filter's PaperSolvableTolerance

void CheckPoint(const double x[3], double a, double b, double c, double tolerance = 1e-12)
{
  MESHLOD_CHECK_NEAR(x[0], a, tolerance);
  MESHLOD_CHECK_NEAR(x[1], b, tolerance);
  MESHLOD_CHECK_NEAR(x[2], c, tolerance);
}

// Three orthogonal planes through (1, 2, 3): solvable, the corner whatever the points.
void CheckSolvable()
{
  Quadric q;
  const double corner[3] = { 1, 2, 3 };
  const double x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 }, z[3] = { 0, 0, 1 };
  q.AddPlane(x, corner, 1.0);
  q.AddPlane(y, corner, 2.0);
  q.AddPlane(z, corner, 0.5);
  const double a[3] = { 0, 0, 0 }, b[3] = { 4, 0, 0 }, c[3] = { 0, 4, 4 };
  const double* points[3] = { a, b, c };
  double result[3];
  MESHLOD_CHECK(PlaceByCandidates(q, points, 3, Tolerance, result));
  CheckPoint(result, 1, 2, 3);
  q.MinimizeRegularized(a, result);
  CheckPoint(result, 1, 2, 3, 1e-9);
}

// One plane, z = 0: singular. The candidates of the triangle (0, 0, 1), (2, 0, 0), (0, 2, 0)
// cost the squared heights: centroid 1/9, vertices 1, 0, 0, midpoints 1/4, 0, 1/4. The first
// of the cheapest is the vertex (2, 0, 0); the regularised solve drops the centroid onto the
// plane instead.
void CheckSingularTriangle()
{
  Quadric q;
  const double origin[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
  q.AddPlane(up, origin, 1.0);
  const double a[3] = { 0, 0, 1 }, b[3] = { 2, 0, 0 }, c[3] = { 0, 2, 0 };
  const double* points[3] = { a, b, c };
  double result[3];
  MESHLOD_CHECK(!PlaceByCandidates(q, points, 3, Tolerance, result));
  CheckPoint(result, 2, 0, 0);
  const double centroid[3] = { 2.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0 };
  q.MinimizeRegularized(centroid, result);
  CheckPoint(result, 2.0 / 3.0, 2.0 / 3.0, 0.0, 1e-9);

  // Every candidate on the plane: all cost 0 and the centroid, the first, is taken.
  const double d[3] = { 0, 0, 0 }, e[3] = { 3, 0, 0 }, f[3] = { 0, 3, 0 };
  const double* flat[3] = { d, e, f };
  MESHLOD_CHECK(!PlaceByCandidates(q, flat, 3, Tolerance, result));
  CheckPoint(result, 1, 1, 0);
}

// A crease, the planes x = 0 and y = 0 (rank 2): an edge from (0, 0, 0) to (1, 1, 2) takes the
// end on the crease, (0, 0, 0), its midpoint (0.5, 0.5, 1) costing 0.5.
void CheckSingularEdge()
{
  Quadric q;
  const double origin[3] = { 0, 0, 0 }, x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 };
  q.AddPlane(x, origin, 1.0);
  q.AddPlane(y, origin, 1.0);
  const double a[3] = { 1, 1, 2 }, b[3] = { 0, 0, 0 };
  const double* points[2] = { a, b };
  double result[3];
  MESHLOD_CHECK(!PlaceByCandidates(q, points, 2, Tolerance, result));
  CheckPoint(result, 0, 0, 0);
}

// A quadric without planes: nothing to solve, every candidate free: the centroid.
void CheckEmpty()
{
  const Quadric q;
  const double a[3] = { 0, 0, 0 }, b[3] = { 2, 4, 6 };
  const double* points[2] = { a, b };
  double result[3];
  MESHLOD_CHECK(!PlaceByCandidates(q, points, 2, Tolerance, result));
  CheckPoint(result, 1, 2, 3);
}
} // namespace

int TestQuadricPlacement(int, char*[])
{
  CheckSolvable();
  CheckSingularTriangle();
  CheckSingularEdge();
  CheckEmpty();
  return meshlod::testing::Result();
}
