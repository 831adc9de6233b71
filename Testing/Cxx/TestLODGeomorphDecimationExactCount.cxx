// vtkLODGeomorph's exact triangle count on vtkTriangleCollapseDecimation hierarchies of a small
// closed isosurface, for EVERY count from the coarsest level to the finest (the four
// schedule / operator combinations): even counts are met exactly, odd ones give the even count
// below (a closed surface loses triangles two at a time), and every output is a closed,
// manifold, consistently oriented mesh of the input's genus without degenerate or repeated
// triangles. (TestLODGeomorphDecimation checks a sample of the counts with InspectMesh; this
// one checks them all, with the flat topology of Core/TriangleMesh.h to stay quick; and every
// 11th count on a mesh large enough for the greedy order's parallel rounds.)
//
// The counts in the middle of a collapse cluster (the points sharing one CollapseRank) are the
// delicate ones: joining the cluster's points in a careless order passes through meshes with a
// non-manifold edge or a doubled triangle. This test found such counts for the greedy
// hierarchies (e.g. 3318 on this mesh) before the join order checked each join.
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "Core/TriangleMesh.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkCommand.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;
using testing::Level;

// What is wrong with a mesh that should be closed, manifold, consistently oriented, of Euler
// characteristic `euler`, with every point used and no degenerate or repeated triangle; empty
// when nothing is.
std::string ClosedMeshProblems(vtkPolyData* poly, std::int64_t euler)
{
  const TriangleMesh mesh = testing::ToTriangleMesh(poly);
  TriangleTopology topology;
  topology.Build(mesh);
  const TriangleTopology::EdgeCounts edges = topology.CountEdges(mesh);
  std::string problems;
  auto add = [&](std::int64_t count, const char* what) {
    if (count != 0)
    {
      problems += " " + std::to_string(count) + " " + what;
    }
  };
  add(edges.NonManifold, "non-manifold edges");
  add(edges.Boundary, "boundary edges");
  add(topology.CountVertices(VertexKind::NonManifold), "non-manifold vertices");
  add(topology.CountVertices(VertexKind::Unused), "unused points");
  add(topology.IsConsistentlyOriented(mesh) ? 0 : 1, "inconsistent orientation");
  const std::int64_t chi = topology.EulerCharacteristic(mesh);
  if (chi != euler)
  {
    problems += " Euler characteristic " + std::to_string(chi);
  }

  double bounds[6];
  poly->GetBounds(bounds);
  const double diagonal2 = (bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]);
  std::vector<std::array<Id, 3>> sorted;
  std::int64_t degenerate = 0;
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* tri = mesh.Triangle(t);
    double u[3], v[3], n[3];
    vtkMath::Subtract(mesh.Point(tri[1]), mesh.Point(tri[0]), u);
    vtkMath::Subtract(mesh.Point(tri[2]), mesh.Point(tri[0]), v);
    vtkMath::Cross(u, v, n);
    degenerate += vtkMath::Norm(n) <= 1e-14 * diagonal2;
    std::array<Id, 3> key = { tri[0], tri[1], tri[2] };
    std::sort(key.begin(), key.end());
    sorted.push_back(key);
  }
  std::sort(sorted.begin(), sorted.end());
  add(degenerate, "degenerate triangles");
  add(static_cast<std::int64_t>(sorted.end() - std::unique(sorted.begin(), sorted.end())),
    "repeated triangles");
  return problems;
}

void TestEveryCount(
  vtkPolyData* surface, int schedule, int op, const char* label, vtkIdType stride = 1)
{
  vtkNew<vtkTriangleCollapseDecimation> decimate;
  decimate->SetInputData(surface);
  decimate->SetSchedule(schedule);
  decimate->SetOperator(op);
  decimate->Update();
  vtkMultiBlockDataSet* h = decimate->GetHierarchy();
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  MESHLOD_CHECK_EQ(n, 9);
  const std::int64_t euler = 2; // the metaballs: one closed genus-0 surface
  MESHLOD_CHECK_EQ(ClosedMeshProblems(Level(h, 0), euler), std::string());

  vtkNew<vtkLODGeomorph> geomorph;
  vtkNew<vtkTest::ErrorObserver> observer;
  geomorph->AddObserver(vtkCommand::WarningEvent, observer);
  geomorph->SetInputData(h);
  const vtkIdType coarsest = Level(h, n - 1)->GetNumberOfPolys();
  const vtkIdType finest = Level(h, 0)->GetNumberOfPolys();
  int wrongCount = 0, invalid = 0;
  for (vtkIdType count = coarsest; count <= finest; count += stride)
  {
    geomorph->SetTargetNumberOfTriangles(count);
    geomorph->Update();
    vtkPolyData* out = geomorph->GetOutput();
    const vtkIdType expected = count - count % 2;
    wrongCount += out->GetNumberOfPolys() != expected;
    wrongCount += geomorph->GetActualNumberOfTriangles() != expected;
    const std::string problems = ClosedMeshProblems(out, euler);
    if (!problems.empty() && ++invalid <= 4)
    {
      std::cerr << "  " << label << ", count " << count << " (level of detail "
                << geomorph->GetActualLevelOfDetail() << "):" << problems << "\n";
    }
  }
  std::cerr << label << ": " << (finest - coarsest) / stride + 1 << " counts, " << invalid
            << " invalid\n";
  MESHLOD_CHECK_EQ(wrongCount, 0);
  MESHLOD_CHECK_EQ(invalid, 0);
  MESHLOD_CHECK(!observer->GetWarning()); // every count reached: nothing to warn about
}

// Two levels far apart (97% of the triangles gone at once): clusters of many points joined one
// point at a time. Made strictly in rank order, a cluster whose merge is valid only after a
// neighbour's left every step up to that neighbour out of reach: 11 of these 22 counts missed
// by more than parity (asked for 200, 120 came). Such a cluster now waits for its neighbour,
// and every count is reached. A miss would still be the nearest count below, with a warning.
void TestLevelsFarApart()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(16);
  vtkNew<vtkTriangleCollapseDecimation> decimate;
  decimate->SetInputConnection(sphere->GetOutputPort());
  decimate->AddLevelReduction(0.97);
  vtkNew<vtkLODGeomorph> geomorph;
  vtkNew<vtkTest::ErrorObserver> observer;
  geomorph->AddObserver(vtkCommand::WarningEvent, observer);
  geomorph->SetInputConnection(decimate->GetOutputPort());
  int warned = 0, far = 0;
  for (vtkIdType count = 20; count <= 440; count += 20)
  {
    observer->Clear();
    geomorph->SetTargetNumberOfTriangles(count);
    geomorph->Update();
    const vtkIdType reached = geomorph->GetOutput()->GetNumberOfPolys();
    MESHLOD_CHECK_LE(reached, count);
    const bool missed = count - reached > std::max<vtkIdType>(3, count / 50);
    far += missed;
    const bool said = observer->GetWarningMessage().find("nearest reachable count below it is " +
                        std::to_string(reached)) != std::string::npos;
    warned += said;
    MESHLOD_CHECK_EQ(said, missed);
  }
  std::cerr << "levels far apart: " << far << " of 22 counts missed by more than parity, "
            << warned << " warnings\n";
  MESHLOD_CHECK_EQ(far, 0);
  MESHLOD_CHECK_EQ(warned, 0);
}

// Triangles of `poly` whose twice-area normal n has n . direction(centroid) <= 0: facing the
// wrong way, or without area.
int WrongFacing(vtkPolyData* poly, bool outwardFromOrigin)
{
  int wrong = 0;
  const vtkIdType* ids;
  vtkIdType npts;
  for (vtkIdType c = 0; c < poly->GetNumberOfCells(); ++c)
  {
    poly->GetCellPoints(c, npts, ids);
    double p[3][3], u[3], v[3], n[3];
    for (int k = 0; k < 3; ++k)
    {
      poly->GetPoint(ids[k], p[k]);
    }
    vtkMath::Subtract(p[1], p[0], u);
    vtkMath::Subtract(p[2], p[0], v);
    vtkMath::Cross(u, v, n);
    const double centroid[3] = { p[0][0] + p[1][0] + p[2][0], p[0][1] + p[1][1] + p[2][1],
      p[0][2] + p[1][2] + p[2][2] };
    const double up[3] = { 0.0, 0.0, 1.0 };
    wrong += vtkMath::Dot(n, outwardFromOrigin ? centroid : up) > 0.0 ? 0 : 1;
  }
  return wrong;
}

// The points of one collapse settle one at a time, and the triangles between the settled ones
// (at the collapse point) and the others can fold over, or lay three corners on a line, on the
// way. The join order prefers points whose join folds nothing: on a sphere every even count
// from 1% to the input has no triangle facing inwards (before: 37 of 951 counts had one), on a
// flat grid no triangle faces down or lies flat (before: 9 of 199 counts).
void TestNoFolds()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(32);
  vtkNew<vtkSphereSource> finer;
  finer->SetThetaResolution(40);
  finer->SetPhiResolution(40);
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(10, 10);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  for (const int kind : { 0, 1, 2 })
  {
    // 0: the sphere, 1: the flat grid, 2: a 40 x 40 sphere's vertex-clustering levels
    // (clusters of many points, whose whole merges folded triangles until neighbouring ones
    // were made: 648 of its 1490 counts had one before such collapses waited).
    const bool closed = kind != 1;
    vtkNew<vtkTriangleCollapseDecimation> decimate;
    vtkNew<vtkVertexClusterOctree> cluster;
    vtkPolyDataAlgorithm* producer = kind == 2
      ? static_cast<vtkPolyDataAlgorithm*>(cluster)
      : static_cast<vtkPolyDataAlgorithm*>(decimate);
    producer->SetInputConnection(kind == 0 ? sphere->GetOutputPort()
        : kind == 1                        ? triangles->GetOutputPort()
                                           : finer->GetOutputPort());
    producer->Update();
    auto* h = vtkMultiBlockDataSet::SafeDownCast(producer->GetOutputDataObject(0));
    vtkNew<vtkLODGeomorph> geomorph;
    geomorph->SetInputData(h);
    const vtkIdType coarsest = Level(h, h->GetNumberOfBlocks() - 1)->GetNumberOfPolys();
    const vtkIdType finest = Level(h, 0)->GetNumberOfPolys();
    int counts = 0, folded = 0;
    for (vtkIdType count = coarsest; count <= finest; count += closed ? 2 : 1)
    {
      geomorph->SetTargetNumberOfTriangles(count);
      geomorph->Update();
      folded += WrongFacing(geomorph->GetOutput(), closed) > 0 ? 1 : 0;
      ++counts;
    }
    const char* names[] = { "sphere", "flat grid", "40 x 40 sphere, vertex clustering" };
    std::cerr << names[kind] << ": " << counts << " counts, " << folded
              << " with a folded or flat triangle\n";
    MESHLOD_CHECK_GT(counts, 150);
    // (Vertex clustering: 1 of 1490 counts still has one, a collapse that waited to the end.)
    MESHLOD_CHECK_LE(folded, kind == 2 ? counts / 100 : 0);
  }
}
} // namespace

int TestLODGeomorphDecimationExactCount(int, char*[])
{
  vtkSmartPointer<vtkPolyData> surface = testing::MakeIsosurface(testing::Field::Metaballs, 32);
  TestEveryCount(surface, vtkTriangleCollapseDecimation::GREEDY,
    vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES, "greedy, triangles and edges");
  TestEveryCount(surface, vtkTriangleCollapseDecimation::INDEPENDENT_SETS,
    vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES, "independent sets, triangles and edges");
  TestEveryCount(surface, vtkTriangleCollapseDecimation::GREEDY,
    vtkTriangleCollapseDecimation::TRIANGLES, "greedy, triangles only");
  TestEveryCount(surface, vtkTriangleCollapseDecimation::INDEPENDENT_SETS,
    vtkTriangleCollapseDecimation::TRIANGLES, "independent sets, triangles only");
  // Large enough for the greedy order's parallel rounds (collapse numbers interleaved across
  // cells): every 11th count (odd and even ones alike).
  vtkSmartPointer<vtkPolyData> larger = testing::MakeIsosurface(testing::Field::Metaballs,
    testing::ResolutionForTriangles(testing::Field::Metaballs, 40000));
  TestEveryCount(larger, vtkTriangleCollapseDecimation::GREEDY,
    vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES, "parallel greedy rounds", 11);
  TestLevelsFarApart();
  TestNoFolds();
  return testing::Result();
}
