#include "MeshLODHierarchyChecks.h"
#include "MeshLODTestMeshes.h"
#include "MeshLODSurfaceDistance.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkGenericCell.h"
#include "vtkLine.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace meshlod
{
namespace testing
{
namespace
{
using Triangle = TriangleIds;

// The rotation of a triangle that starts with its smallest id: equal for equal oriented
// triangles.
Triangle Canonical(const Triangle& t)
{
  const int first = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
  return { t[first], t[(first + 1) % 3], t[(first + 2) % 3] };
}

void Normal(vtkPolyData* mesh, const Triangle& t, double n[3])
{
  double p[3][3];
  for (int k = 0; k < 3; ++k)
  {
    mesh->GetPoint(t[k], p[k]);
  }
  double e1[3], e2[3];
  vtkMath::Subtract(p[1], p[0], e1);
  vtkMath::Subtract(p[2], p[0], e2);
  vtkMath::Cross(e1, e2, n);
}

bool Report(std::int64_t& count, const char* what)
{
  if (++count <= 5)
  {
    std::cerr << "  " << what << "\n";
  }
  return false;
}
} // namespace

//------------------------------------------------------------------------------
MeshReport InspectMesh(vtkPolyData* mesh)
{
  MeshReport report;
  const std::vector<Triangle> triangles = Triangles(mesh);
  report.Triangles = static_cast<std::int64_t>(triangles.size());
  std::map<std::pair<vtkIdType, vtkIdType>, std::vector<int>> edges; // sorted edge -> directions
  std::set<Triangle> seen, seenOriented;
  std::vector<std::vector<vtkIdType>> fans(mesh->GetNumberOfPoints());
  double bounds[6];
  mesh->GetBounds(bounds);
  const double diagonal2 = std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) +
    std::pow(bounds[5] - bounds[4], 2);
  for (size_t i = 0; i < triangles.size(); ++i)
  {
    const Triangle& t = triangles[i];
    Triangle sorted = t;
    std::sort(sorted.begin(), sorted.end());
    report.DuplicateTriangles += seen.insert(sorted).second ? 0 : 1;
    report.SameOrientationDuplicates += seenOriented.insert(Canonical(t)).second ? 0 : 1;
    double n[3];
    Normal(mesh, t, n);
    report.DegenerateTriangles += vtkMath::Norm(n) <= 1e-14 * diagonal2 ? 1 : 0;
    for (int k = 0; k < 3; ++k)
    {
      const vtkIdType a = t[k], b = t[(k + 1) % 3];
      edges[{ std::min(a, b), std::max(a, b) }].push_back(a < b ? 1 : -1);
      fans[a].push_back(static_cast<vtkIdType>(i));
    }
  }
  std::map<vtkIdType, int> boundaryEdgesAt;
  for (const auto& edge : edges)
  {
    const std::vector<int>& directions = edge.second;
    if (directions.size() == 1)
    {
      ++report.BoundaryEdges;
      ++boundaryEdgesAt[edge.first.first];
      ++boundaryEdgesAt[edge.first.second];
    }
    else if (directions.size() > 2)
    {
      ++report.NonManifoldEdges;
    }
    else if (directions[0] == directions[1])
    {
      report.ConsistentlyOriented = false;
    }
  }
  // A manifold vertex has one fan: its triangles are connected through the edges at it.
  std::int64_t usedPoints = 0;
  for (vtkIdType v = 0; v < mesh->GetNumberOfPoints(); ++v)
  {
    const std::vector<vtkIdType>& fan = fans[v];
    if (fan.empty())
    {
      continue;
    }
    ++usedPoints;
    std::vector<int> component(fan.size(), -1);
    int components = 0;
    for (size_t s = 0; s < fan.size(); ++s)
    {
      if (component[s] >= 0)
      {
        continue;
      }
      std::vector<size_t> stack{ s };
      component[s] = components;
      while (!stack.empty())
      {
        const size_t i = stack.back();
        stack.pop_back();
        for (size_t j = 0; j < fan.size(); ++j)
        {
          if (component[j] >= 0)
          {
            continue;
          }
          // Connected when they share a second vertex besides v.
          int shared = 0;
          for (const vtkIdType a : triangles[fan[i]])
          {
            for (const vtkIdType b : triangles[fan[j]])
            {
              shared += (a == b && a != v) ? 1 : 0;
            }
          }
          if (shared > 0)
          {
            component[j] = components;
            stack.push_back(j);
          }
        }
      }
      ++components;
    }
    const auto b = boundaryEdgesAt.find(v);
    report.NonManifoldVertices +=
      (components > 1 || (b != boundaryEdgesAt.end() && b->second > 2)) ? 1 : 0;
  }
  report.EulerCharacteristic =
    usedPoints - static_cast<std::int64_t>(edges.size()) + report.Triangles;
  return report;
}

//------------------------------------------------------------------------------
std::int64_t CountCorrespondenceViolations(vtkMultiBlockDataSet* hierarchy)
{
  std::int64_t violations = 0;
  const unsigned int levels = hierarchy->GetNumberOfBlocks();
  for (unsigned int i = 0; i + 1 < levels; ++i)
  {
    auto* fine = vtkPolyData::SafeDownCast(hierarchy->GetBlock(i));
    auto* coarse = vtkPolyData::SafeDownCast(hierarchy->GetBlock(i + 1));
    vtkDataArray* targetId = fine->GetPointData()->GetArray("MorphTargetId");
    vtkDataArray* target = fine->GetPointData()->GetArray("MorphTarget");
    vtkDataArray* rank = fine->GetPointData()->GetArray("CollapseRank");
    if (!targetId || !target || !rank)
    {
      Report(violations, "missing morph arrays");
      continue;
    }
    std::vector<vtkIdType> preimages(coarse->GetNumberOfPoints(), 0);
    for (vtkIdType p = 0; p < fine->GetNumberOfPoints(); ++p)
    {
      const vtkIdType to = static_cast<vtkIdType>(targetId->GetTuple1(p));
      if (to < 0 || to >= coarse->GetNumberOfPoints())
      {
        Report(violations, "MorphTargetId out of range");
        continue;
      }
      ++preimages[to];
      double x[3], y[3], q[3];
      target->GetTuple(p, x);
      coarse->GetPoint(to, y);
      if (x[0] != y[0] || x[1] != y[1] || x[2] != y[2])
      {
        Report(violations, "MorphTarget differs from the target point");
      }
      fine->GetPoint(p, q);
      if (rank->GetTuple1(p) < 0 && (q[0] != y[0] || q[1] != y[1] || q[2] != y[2]))
      {
        Report(violations, "a point with CollapseRank -1 moves");
      }
    }
    for (vtkIdType p = 0; p < fine->GetNumberOfPoints(); ++p)
    {
      const vtkIdType to = static_cast<vtkIdType>(targetId->GetTuple1(p));
      if (rank->GetTuple1(p) < 0 && to >= 0 && to < coarse->GetNumberOfPoints() && preimages[to] != 1)
      {
        Report(violations, "a point with CollapseRank -1 merges");
      }
    }
    std::set<Triangle> coarseTriangles, images;
    for (const Triangle& t : Triangles(coarse))
    {
      coarseTriangles.insert(Canonical(t));
    }
    for (const Triangle& t : Triangles(fine))
    {
      const Triangle mapped = { static_cast<vtkIdType>(targetId->GetTuple1(t[0])),
        static_cast<vtkIdType>(targetId->GetTuple1(t[1])),
        static_cast<vtkIdType>(targetId->GetTuple1(t[2])) };
      if (mapped[0] == mapped[1] || mapped[1] == mapped[2] || mapped[2] == mapped[0])
      {
        continue; // collapses away
      }
      const Triangle canonical = Canonical(mapped);
      if (!coarseTriangles.count(canonical))
      {
        Report(violations, "a triangle maps to no triangle of the next level");
      }
      images.insert(canonical);
    }
    if (images.size() != coarseTriangles.size())
    {
      Report(violations, "a triangle of the next level is nobody's image");
    }
  }
  return violations;
}

//------------------------------------------------------------------------------
std::int64_t CountFlippedTriangles(vtkPolyData* fine, vtkPolyData* coarse)
{
  vtkSmartPointer<vtkStaticCellLocator> locator = BuildCellLocator(fine);
  vtkNew<vtkGenericCell> cell;
  std::int64_t flipped = 0;
  const std::vector<Triangle> fineTriangles = Triangles(fine);
  for (const Triangle& t : Triangles(coarse))
  {
    double n[3], centroid[3] = { 0, 0, 0 }, p[3];
    Normal(coarse, t, n);
    for (int k = 0; k < 3; ++k)
    {
      coarse->GetPoint(t[k], p);
      for (int c = 0; c < 3; ++c)
      {
        centroid[c] += p[c] / 3.0;
      }
    }
    double closest[3], dist2;
    vtkIdType cellId;
    int subId;
    locator->FindClosestPoint(centroid, closest, cell, cellId, subId, dist2);
    double m[3];
    Normal(fine, fineTriangles[cellId], m);
    flipped += vtkMath::Dot(n, m) < 0.0 ? 1 : 0;
  }
  return flipped;
}

//------------------------------------------------------------------------------
double BoundaryDeviation(vtkPolyData* fine, vtkPolyData* coarse)
{
  auto boundary = [](vtkPolyData* mesh) {
    std::map<std::pair<vtkIdType, vtkIdType>, int> count;
    for (const Triangle& t : Triangles(mesh))
    {
      for (int k = 0; k < 3; ++k)
      {
        const vtkIdType a = t[k], b = t[(k + 1) % 3];
        ++count[{ std::min(a, b), std::max(a, b) }];
      }
    }
    std::vector<std::pair<vtkIdType, vtkIdType>> edges;
    for (const auto& e : count)
    {
      if (e.second == 1)
      {
        edges.push_back(e.first);
      }
    }
    return edges;
  };
  const auto fineEdges = boundary(fine);
  double worst = 0.0;
  std::set<vtkIdType> coarseVertices;
  for (const auto& e : boundary(coarse))
  {
    coarseVertices.insert(e.first);
    coarseVertices.insert(e.second);
  }
  for (const vtkIdType v : coarseVertices)
  {
    double x[3];
    coarse->GetPoint(v, x);
    double best = VTK_DOUBLE_MAX;
    for (const auto& e : fineEdges)
    {
      double a[3], b[3], t;
      fine->GetPoint(e.first, a);
      fine->GetPoint(e.second, b);
      double closest[3];
      best = std::min(best, vtkLine::DistanceToLine(x, a, b, t, closest));
    }
    worst = std::max(worst, std::sqrt(best));
  }
  return worst;
}

//------------------------------------------------------------------------------
std::vector<TriangleIds> Triangles(vtkPolyData* mesh)
{
  std::vector<TriangleIds> triangles;
  vtkIdType n;
  const vtkIdType* ids;
  vtkCellArray* polys = mesh->GetPolys();
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, n, ids);
    if (n == 3)
    {
      triangles.push_back({ ids[0], ids[1], ids[2] });
    }
  }
  return triangles;
}

//------------------------------------------------------------------------------
std::int64_t CountRepeatedPointTriangles(vtkMultiBlockDataSet* hierarchy)
{
  std::int64_t count = 0;
  for (unsigned int i = 0; i < hierarchy->GetNumberOfBlocks(); ++i)
  {
    std::set<TriangleIds> seen;
    for (TriangleIds t : Triangles(Level(hierarchy, i)))
    {
      count += (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) ? 1 : 0;
      std::sort(t.begin(), t.end());
      count += seen.insert(t).second ? 0 : 1;
    }
  }
  return count;
}

//------------------------------------------------------------------------------
std::map<EdgeIds, int> EdgeTriangleCounts(vtkPolyData* mesh)
{
  std::map<EdgeIds, int> counts;
  for (const TriangleIds& t : Triangles(mesh))
  {
    for (int k = 0; k < 3; ++k)
    {
      ++counts[std::minmax(t[k], t[(k + 1) % 3])];
    }
  }
  return counts;
}

//------------------------------------------------------------------------------
vtkPolyData* Level(vtkMultiBlockDataSet* hierarchy, unsigned int i)
{
  return vtkPolyData::SafeDownCast(hierarchy->GetBlock(i));
}

//------------------------------------------------------------------------------
std::pair<vtkSmartPointer<vtkPolyData>, vtkSmartPointer<vtkPolyData>> RunWithBothBackends(
  const std::function<vtkSmartPointer<vtkPolyData>()>& make)
{
  const std::string initial = vtkSMPTools::GetBackend();
  auto run = [&](const char* backend) {
    vtkSMPTools::SetBackend(backend);
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->DeepCopy(make());
    return copy;
  };
  auto sequential = run("Sequential");
  auto parallel = run(initial.c_str());
  return { sequential, parallel };
}

//------------------------------------------------------------------------------
bool SameMesh(vtkPolyData* a, vtkPolyData* b)
{
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints() ||
    a->GetNumberOfPolys() != b->GetNumberOfPolys())
  {
    return false;
  }
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
  {
    double x[3], y[3];
    a->GetPoint(p, x);
    b->GetPoint(p, y);
    if (x[0] != y[0] || x[1] != y[1] || x[2] != y[2])
    {
      return false;
    }
  }
  return Triangles(a) == Triangles(b);
}

bool SameValues(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents() ||
    a->GetDataType() != b->GetDataType())
  {
    return false;
  }
  for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      if (a->GetComponent(t, c) != b->GetComponent(t, c))
      {
        return false;
      }
    }
  }
  return true;
}

std::int64_t CountDifferingLevels(vtkMultiBlockDataSet* a, vtkMultiBlockDataSet* b)
{
  const unsigned int na = a->GetNumberOfBlocks(), nb = b->GetNumberOfBlocks();
  std::int64_t differing = std::max(na, nb) - std::min(na, nb);
  for (unsigned int i = 0; i < std::min(na, nb); ++i)
  {
    if (!SameMesh(Level(a, i), Level(b, i)))
    {
      ++differing;
      std::cerr << "level " << i << " differs\n";
    }
  }
  return differing;
}

std::int64_t CountLevelsChangedByUnusedNaNPoint(
  const std::function<vtkSmartPointer<vtkMultiBlockDataSet>(vtkPolyData*)>& run)
{
  vtkSmartPointer<vtkPolyData> stray = MakeIcosphere(3);
  stray->GetPoints()->InsertNextPoint(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  const vtkSmartPointer<vtkMultiBlockDataSet> plain = run(MakeIcosphere(3));
  const vtkSmartPointer<vtkMultiBlockDataSet> withStray = run(stray);
  return CountDifferingLevels(plain, withStray);
}

} // namespace testing
} // namespace meshlod
