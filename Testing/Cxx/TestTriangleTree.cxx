// The texture baker's nearest-triangle search against a search of every triangle: the same
// triangle (the lowest id of those at the smallest distance), the same distance, to the bit, at
// random points and at points on vertices and edges, where several triangles tie.
#include "MeshLODTriangleTree.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "Core/TriangulationFlips.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include <iostream>
#include <limits>
#include <vector>

namespace
{
using namespace meshlod;

struct FlatMesh
{
  std::vector<double> Points;
  std::vector<vtkIdType> Triangles;
  vtkIdType Count() const { return static_cast<vtkIdType>(this->Triangles.size() / 3); }
  double ToTriangle(vtkIdType t, const double p[3], double x[3]) const
  {
    const vtkIdType* ids = this->Triangles.data() + 3 * t;
    return ClosestPointOnTriangle(p, this->Points.data() + 3 * ids[0],
      this->Points.data() + 3 * ids[1], this->Points.data() + 3 * ids[2], x);
  }
};

FlatMesh Flatten(vtkPolyData* mesh)
{
  FlatMesh flat;
  flat.Points.resize(3 * static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    mesh->GetPoint(p, flat.Points.data() + 3 * p);
  }
  auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    flat.Triangles.insert(flat.Triangles.end(), ids, ids + 3);
  }
  return flat;
}

// Random points in the bounding box grown by a quarter of its size each way, then every
// `stride`-th vertex, and the midpoint of every `stride`-th triangle's first edge.
std::vector<double> QueryPoints(
  vtkPolyData* mesh, const FlatMesh& flat, int randomCount, vtkIdType stride)
{
  double b[6];
  mesh->GetBounds(b);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(5);
  std::vector<double> queries;
  for (int i = 0; i < randomCount; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double size = b[2 * c + 1] - b[2 * c];
      queries.push_back(b[2 * c] - 0.25 * size + 1.5 * size * random->GetValue());
      random->Next();
    }
  }
  for (std::size_t p = 0; p < flat.Points.size(); p += 3 * stride)
  {
    queries.insert(queries.end(), flat.Points.begin() + p, flat.Points.begin() + p + 3);
  }
  for (vtkIdType t = 0; t < flat.Count(); t += stride)
  {
    const double* a = flat.Points.data() + 3 * flat.Triangles[3 * t];
    const double* c = flat.Points.data() + 3 * flat.Triangles[3 * t + 1];
    queries.insert(queries.end(), { 0.5 * (a[0] + c[0]), 0.5 * (a[1] + c[1]), 0.5 * (a[2] + c[2]) });
  }
  return queries;
}

void CompareWithEveryTriangle(
  const char* name, vtkPolyData* mesh, int randomCount = 2000, vtkIdType stride = 1)
{
  const FlatMesh flat = Flatten(mesh);
  TriangleTree tree;
  tree.Build(flat.Points.data(), flat.Triangles.data(), flat.Count());
  const std::vector<double> queries = QueryPoints(mesh, flat, randomCount, stride);
  int wrongClosest = 0, wrongLowest = 0, ties = 0;
  for (std::size_t q = 0; q < queries.size(); q += 3)
  {
    const double* p = queries.data() + q;
    // Every triangle: the smallest distance (lowest id on ties), and the lowest id within a
    // little more than it.
    vtkIdType nearest = -1;
    double nearest2 = std::numeric_limits<double>::infinity();
    for (vtkIdType t = 0; t < flat.Count(); ++t)
    {
      double x[3];
      const double d2 = flat.ToTriangle(t, p, x);
      if (d2 < nearest2)
      {
        nearest = t;
        nearest2 = d2;
      }
    }
    const double limit2 = nearest2 * (1.0 + 1e-9) + 1e-24;
    vtkIdType lowest = -1;
    int within = 0;
    for (vtkIdType t = 0; t < flat.Count(); ++t)
    {
      double x[3];
      if (flat.ToTriangle(t, p, x) <= limit2)
      {
        lowest = lowest < 0 ? t : lowest;
        ++within;
      }
    }
    ties += within > 1 ? 1 : 0;

    double closest[3], distance2 = -1.0;
    const vtkIdType found = tree.FindClosest(p, closest, distance2);
    wrongClosest += found != nearest || distance2 != nearest2 ? 1 : 0;
    double expected[3];
    flat.ToTriangle(std::max(found, vtkIdType(0)), p, expected);
    wrongClosest += closest[0] != expected[0] || closest[1] != expected[1] ||
        closest[2] != expected[2]
      ? 1
      : 0;
    wrongLowest += tree.FindLowestWithin(p, limit2, closest) != lowest ? 1 : 0;
  }
  std::cerr << "  " << name << ": " << flat.Count() << " triangles, " << queries.size() / 3
            << " queries (" << ties << " with several triangles at the smallest distance), "
            << wrongClosest << " wrong nearest, " << wrongLowest << " wrong lowest\n";
  MESHLOD_CHECK_EQ(wrongClosest, 0);
  MESHLOD_CHECK_EQ(wrongLowest, 0);
  MESHLOD_CHECK_GT(ties, 0);
}

// Rounding: with coordinates near 512 and distances near 1.2, the closest point computed on a
// triangle can lie just outside the triangle's box, its distance below the box's. A search
// that passed over such a box because it was farther than the best found so far missed the
// nearest triangle (found by a randomized search, with an earlier closest-point function that
// put triangle 0 at a squared distance of 1.4176818654678944, nearer than the box around it).
void TestClosestPointOutsideItsBox()
{
  const std::vector<double> points = { -0.46385649489489167, 0.33231536783614168,
    512.00000000000011, -0.18458379774506728, -0.69719920739597641, 512.0, 0.52344919136591828,
    0.7966183005441323, 512.0, -60, -2, 513, -60.5, 2, 513, -60, 2, 513.5, -70, -2, 513, -70.5, 2,
    513, -70, 2, 513.5, -80, -2, 513, -80.5, 2, 513, -80, 2, 513.5, 0.1258848215193972,
    0.011394630040545039, 511.99999999999994, 0.1258848225193972, 0.011394630040545039,
    511.99999999999994, 0.1258848215193972, 0.011394631040545038, 511.99999999999994, 60, -2, 513,
    60.5, 2, 513, 60, 2, 513.5, 70, -2, 513, 70.5, 2, 513, 70, 2, 513.5, 80, -2, 513, 80.5, 2, 513,
    80, 2, 513.5, 90, -2, 513, 90.5, 2, 513, 90, 2, 513.5 };
  std::vector<vtkIdType> triangles(points.size() / 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    triangles[i] = static_cast<vtkIdType>(i);
  }
  const vtkIdType count = static_cast<vtkIdType>(triangles.size() / 3);
  TriangleTree tree;
  tree.Build(points.data(), triangles.data(), count);
  const double p[3] = { 0.12588456128180478, 0.011394630040545039, 510.80933553615301 };
  vtkIdType nearest = -1;
  double nearest2 = std::numeric_limits<double>::infinity();
  for (vtkIdType t = 0; t < count; ++t)
  {
    double x[3];
    const double d2 = ClosestPointOnTriangle(p, points.data() + 9 * t,
      points.data() + 9 * t + 3, points.data() + 9 * t + 6, x);
    if (d2 < nearest2)
    {
      nearest = t;
      nearest2 = d2;
    }
  }
  MESHLOD_CHECK(nearest == 0 || nearest == 4);
  double closest[3], distance2 = 0.0;
  MESHLOD_CHECK_EQ(tree.FindClosest(p, closest, distance2), nearest);
  MESHLOD_CHECK_EQ(distance2, nearest2);
  MESHLOD_CHECK_EQ(tree.FindLowestWithin(p, nearest2, closest), nearest);
}

void TestEmpty()
{
  TriangleTree tree;
  tree.Build(nullptr, nullptr, 0);
  const double p[3] = { 0.0, 0.0, 0.0 };
  double closest[3], distance2 = 0.0;
  MESHLOD_CHECK_EQ(tree.FindClosest(p, closest, distance2), -1);
  MESHLOD_CHECK_EQ(tree.FindLowestWithin(p, 1.0, closest), -1);
}
} // namespace

int TestTriangleTree(int, char*[])
{
  TestEmpty();
  TestClosestPointOutsideItsBox();
  CompareWithEveryTriangle("noisy isosurface", testing::MakeNoisyIsosurface(16, 0.5, 3));
  // Long triangles all meeting at one point (the baker's slow case before the tree).
  CompareWithEveryTriangle("spindles sharing an apex", testing::MakeConesSharingApex(40, 8));
  // Coplanar triangles, many with a corner at one point: ties everywhere.
  CompareWithEveryTriangle("flat fan in a ring", testing::MakeFlatFanInRing(300));
  CompareWithEveryTriangle("octahedron", testing::MakeOctahedron());
  // Large enough (81,920 triangles) for the top of the tree to be split before its subtrees
  // are built in parallel, their boxes then joined.
  CompareWithEveryTriangle("icosphere", testing::MakeIcosphere(6), 1000, 128);
  return meshlod::testing::Result();
}
