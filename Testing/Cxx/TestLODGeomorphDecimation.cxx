// vtkLODGeomorph on real hierarchies: vtkTriangleCollapseDecimation of a small closed
// isosurface (greedy and independent-set schedules, triangle-and-edge and triangle-only
// operators) feeding vtkLODGeomorph in one pipeline. Checks, per hierarchy: whole levels
// reproduced exactly, t -> 1 landing on the next level (through MorphTargetId), fixed
// connectivity within a level, time-driven output equal to the explicit LevelOfDetail without
// re-running the decimation, and the exact-count mode giving the count asked for with valid
// closed manifolds.
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"

#include "MeshLODEventCounter.h"
#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;
using testing::Level;
using SDDP = vtkStreamingDemandDrivenPipeline;

vtkPolyData* AtLevelOfDetail(vtkLODGeomorph* filter, double lod)
{
  filter->SetLevelOfDetail(lod);
  filter->Update();
  return filter->GetOutput();
}

vtkPolyData* WithTriangles(vtkLODGeomorph* filter, vtkIdType count)
{
  filter->SetTargetNumberOfTriangles(count);
  filter->Update();
  return filter->GetOutput();
}

// The connectivity of `a` equals that of `b` (same triangles in the same order).
bool SameTriangles(vtkPolyData* a, vtkPolyData* b)
{
  vtkCellArray* x = a->GetPolys();
  vtkCellArray* y = b->GetPolys();
  if (x->GetNumberOfCells() != y->GetNumberOfCells() ||
    x->GetNumberOfConnectivityIds() != y->GetNumberOfConnectivityIds())
  {
    return false;
  }
  vtkDataArray* cx = x->GetConnectivityArray();
  vtkDataArray* cy = y->GetConnectivityArray();
  for (vtkIdType i = 0; i < cx->GetNumberOfTuples(); ++i)
  {
    if (cx->GetTuple1(i) != cy->GetTuple1(i))
    {
      return false;
    }
  }
  return true;
}

struct Variant
{
  const char* Label;
  int Schedule;
  int Operator;
};

// Whole levels: L = i gives level i itself, points and triangles.
void CheckWholeLevels(vtkLODGeomorph* filter, vtkMultiBlockDataSet* h)
{
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  for (int i = 0; i < n; ++i)
  {
    vtkPolyData* out = AtLevelOfDetail(filter, i);
    MESHLOD_CHECK(testing::SameMesh(out, Level(h, i)));
    MESHLOD_CHECK_EQ(filter->GetActualLevelOfDetail(), static_cast<double>(i));
    MESHLOD_CHECK(out->GetPointData()->GetArray(names::MorphTarget) == nullptr);
  }
}

// Within level i: level i's connectivity and point count for every t; points on the segments
// p -> MorphTarget(p); as t -> 1 every point reaches its MorphTargetId point of level i + 1.
void CheckTransitions(vtkLODGeomorph* filter, vtkMultiBlockDataSet* h)
{
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  const double almostOne = 1.0 - std::ldexp(1.0, -45);
  for (int i = 0; i + 1 < n; ++i)
  {
    vtkPolyData* level = Level(h, i);
    vtkPolyData* next = Level(h, i + 1);
    vtkDataArray* target = level->GetPointData()->GetArray(names::MorphTarget);
    vtkDataArray* targetId = level->GetPointData()->GetArray(names::MorphTargetId);
    MESHLOD_CHECK(target != nullptr && targetId != nullptr);
    if (!target || !targetId)
    {
      continue;
    }
    int wrongTopology = 0, offSegment = 0;
    for (const double t : { 0.125, 0.5, 0.875, almostOne })
    {
      vtkPolyData* out = AtLevelOfDetail(filter, i + t);
      wrongTopology += out->GetNumberOfPoints() != level->GetNumberOfPoints();
      wrongTopology += !SameTriangles(out, level);
      wrongTopology += filter->GetActualNumberOfTriangles() != level->GetNumberOfPolys();
      if (out->GetNumberOfPoints() != level->GetNumberOfPoints())
      {
        continue;
      }
      // Float points: the blend is rounded to float once.
      for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
      {
        double x[3], a[3], b[3];
        out->GetPoint(p, x);
        level->GetPoint(p, a);
        target->GetTuple(p, b);
        for (int c = 0; c < 3; ++c)
        {
          const double expected = (1.0 - t) * a[c] + t * b[c];
          offSegment += std::abs(x[c] - expected) > 1e-7 * (1.0 + std::abs(expected));
        }
      }
    }
    MESHLOD_CHECK_EQ(wrongTopology, 0);
    MESHLOD_CHECK_EQ(offSegment, 0);

    vtkPolyData* out = AtLevelOfDetail(filter, i + almostOne);
    double worst = 0.0;
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      double x[3], y[3];
      out->GetPoint(p, x);
      next->GetPoint(static_cast<vtkIdType>(targetId->GetTuple1(p)), y);
      worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(x, y)));
    }
    if (worst > 1e-12)
    {
      std::cerr << "  level " << i << ": t -> 1 is " << worst << " from level " << i + 1 << "\n";
    }
    MESHLOD_CHECK_LE(worst, 1e-12);
  }
}

// Driven by pipeline time (as ParaView's animation does): the same meshes as the explicit
// LevelOfDetail, one published time step per level, and the decimation upstream never re-runs.
void CheckPipelineTime(vtkTriangleCollapseDecimation* decimate, vtkMultiBlockDataSet* h,
  const int& decimationRuns)
{
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  const int runsBefore = decimationRuns;
  vtkNew<vtkLODGeomorph> timed;
  timed->SetInputConnection(decimate->GetOutputPort());
  timed->UpdateInformation();
  vtkInformation* info = timed->GetOutputInformation(0);
  MESHLOD_CHECK_EQ(info->Length(SDDP::TIME_STEPS()), n);
  if (info->Length(SDDP::TIME_STEPS()) == n)
  {
    for (int i = 0; i < n; ++i)
    {
      MESHLOD_CHECK_EQ(info->Get(SDDP::TIME_STEPS())[i], static_cast<double>(i));
    }
  }

  vtkNew<vtkLODGeomorph> explicitLod;
  explicitLod->SetInputConnection(decimate->GetOutputPort());
  explicitLod->UsePipelineTimeOff();
  int different = 0;
  for (int k = 0; k <= 8 * (n - 1); ++k)
  {
    const double time = k / 8.0;
    timed->UpdateTimeStep(time);
    MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), time);
    MESHLOD_CHECK_EQ(
      timed->GetOutput()->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), time);
    different += !testing::SameMesh(timed->GetOutput(), AtLevelOfDetail(explicitLod, time));
  }
  MESHLOD_CHECK_EQ(different, 0);
  MESHLOD_CHECK_EQ(decimationRuns, runsBefore);
}

// Problems of one exact-count output, or an empty string.
std::string ExactCountProblems(vtkPolyData* out, vtkIdType expected, std::int64_t euler)
{
  const testing::MeshReport r = testing::InspectMesh(out);
  std::string problems;
  auto add = [&](bool bad, const std::string& what) {
    if (bad)
    {
      problems += " " + what;
    }
  };
  add(r.Triangles != expected, "count " + std::to_string(r.Triangles));
  add(r.NonManifoldEdges != 0, "non-manifold edges " + std::to_string(r.NonManifoldEdges));
  add(r.NonManifoldVertices != 0, "non-manifold vertices " + std::to_string(r.NonManifoldVertices));
  add(r.DegenerateTriangles != 0, "degenerate " + std::to_string(r.DegenerateTriangles));
  add(r.DuplicateTriangles != 0, "duplicates " + std::to_string(r.DuplicateTriangles));
  add(r.BoundaryEdges != 0, "boundary edges " + std::to_string(r.BoundaryEdges));
  add(!r.ConsistentlyOriented, "inconsistent orientation");
  add(r.EulerCharacteristic != euler, "Euler " + std::to_string(r.EulerCharacteristic));
  return problems;
}

// The counts of the sweep in a transition from `fine` to `coarse` triangles (closed surface:
// even counts only): all of the first and last 24, and 24 more spread between.
std::vector<vtkIdType> SweepCounts(vtkIdType fine, vtkIdType coarse)
{
  std::vector<vtkIdType> counts;
  for (vtkIdType c = fine - 2; c > coarse && c > fine - 50; c -= 2)
  {
    counts.push_back(c);
  }
  for (vtkIdType c = coarse + 2; c < fine && c < coarse + 50; c += 2)
  {
    counts.push_back(c);
  }
  const vtkIdType stride = std::max<vtkIdType>(2, ((fine - coarse) / 25) & ~vtkIdType(1));
  for (vtkIdType c = coarse + stride; c < fine; c += stride)
  {
    counts.push_back(c);
  }
  std::sort(counts.begin(), counts.end());
  counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
  return counts;
}

// The exact count: every count of the sweep (and each level's own count) is met exactly with a
// closed, manifold, consistently oriented mesh of the input's genus; an odd count gives the
// even count below it; a level's own count gives that level.
void CheckExactCount(vtkTriangleCollapseDecimation* decimate, vtkMultiBlockDataSet* h)
{
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  const std::int64_t euler = testing::InspectMesh(Level(h, 0)).EulerCharacteristic;
  vtkNew<vtkLODGeomorph> filter;
  filter->SetInputConnection(decimate->GetOutputPort());
  int tried = 0, wrongCount = 0, invalid = 0;
  for (int i = 0; i + 1 < n; ++i)
  {
    const vtkIdType fine = Level(h, i)->GetNumberOfPolys();
    const vtkIdType coarse = Level(h, i + 1)->GetNumberOfPolys();
    for (const vtkIdType count : SweepCounts(fine, coarse))
    {
      ++tried;
      vtkPolyData* out = WithTriangles(filter, count);
      wrongCount += filter->GetActualNumberOfTriangles() != count;
      const std::string problems = ExactCountProblems(out, count, euler);
      if (!problems.empty() && ++invalid <= 5)
      {
        std::cerr << "  exact count " << count << " (transition " << i << " -> " << i + 1
                  << "):" << problems << "\n";
      }
    }
    // A level's own count: the level itself.
    vtkPolyData* out = WithTriangles(filter, coarse);
    MESHLOD_CHECK(out->GetPoints() == Level(h, i + 1)->GetPoints());
    MESHLOD_CHECK_EQ(filter->GetActualLevelOfDetail(), static_cast<double>(i + 1));
    // An odd count is not reachable on a closed surface: the even count below it.
    out = WithTriangles(filter, (fine + coarse) / 2 | 1);
    MESHLOD_CHECK_EQ(out->GetNumberOfPolys(), ((fine + coarse) / 2 | 1) - 1);
  }
  std::cerr << "  exact count: " << tried << " counts tried\n";
  MESHLOD_CHECK_GT(tried, 100);
  MESHLOD_CHECK_EQ(wrongCount, 0);
  MESHLOD_CHECK_EQ(invalid, 0);
  filter->SetTargetNumberOfTriangles(-1);
}

void TestVariant(vtkPolyData* surface, const Variant& variant)
{
  std::cerr << "checking " << variant.Label << "\n";
  vtkNew<vtkTriangleCollapseDecimation> decimate;
  decimate->SetInputData(surface);
  decimate->SetSchedule(variant.Schedule);
  decimate->SetOperator(variant.Operator);
  const testing::EventCounter decimationRuns(decimate, vtkCommand::EndEvent);
  decimate->Update();
  MESHLOD_CHECK_EQ(decimationRuns.Count, 1);
  vtkMultiBlockDataSet* h = decimate->GetHierarchy();
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  MESHLOD_CHECK_EQ(n, 9);
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  for (int i = 1; i < n; ++i)
  {
    MESHLOD_CHECK_LT(Level(h, i)->GetNumberOfPolys(), Level(h, i - 1)->GetNumberOfPolys());
  }

  // The geomorph reads the decimation's output port: one pipeline, as a user builds it.
  vtkNew<vtkLODGeomorph> geomorph;
  geomorph->SetInputConnection(decimate->GetOutputPort());
  geomorph->UsePipelineTimeOff();
  CheckWholeLevels(geomorph, h);
  CheckTransitions(geomorph, h);
  CheckPipelineTime(decimate, h, decimationRuns.Count);
  CheckExactCount(decimate, h);
  MESHLOD_CHECK_EQ(decimationRuns.Count, 1);
}

// An empty input (an isosurface empty at some iso-value) flows through the pipeline silently:
// a hierarchy of one empty level, an empty geomorph. NaN for the level of detail or the time
// is an error and an empty output (it used to index a level with a garbage integer).
void TestEmptyAndNaN(vtkPolyData* surface)
{
  vtkNew<vtkTest::ErrorObserver> observer;
  vtkNew<vtkTriangleCollapseDecimation> decimate;
  vtkNew<vtkLODGeomorph> geomorph;
  geomorph->SetInputConnection(decimate->GetOutputPort());
  for (vtkAlgorithm* a : { static_cast<vtkAlgorithm*>(decimate), static_cast<vtkAlgorithm*>(geomorph) })
  {
    a->AddObserver(vtkCommand::ErrorEvent, observer);
    a->AddObserver(vtkCommand::WarningEvent, observer);
    a->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  }
  vtkNew<vtkPolyData> empty;
  decimate->SetInputData(empty);
  geomorph->UpdateTimeStep(0.5);
  MESHLOD_CHECK(!observer->GetError());
  MESHLOD_CHECK(!observer->GetWarning());
  MESHLOD_CHECK_EQ(geomorph->GetOutput()->GetNumberOfPoints(), 0);

  decimate->SetInputData(surface);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  geomorph->UpdateTimeStep(nan);
  MESHLOD_CHECK(observer->GetErrorMessage().find("UPDATE_TIME_STEP) is NaN") != std::string::npos);
  MESHLOD_CHECK_EQ(geomorph->GetOutput()->GetNumberOfPoints(), 0);
  observer->Clear();
  geomorph->UsePipelineTimeOff();
  geomorph->SetLevelOfDetail(nan);
  geomorph->Update();
  MESHLOD_CHECK(observer->GetErrorMessage().find("LevelOfDetail is NaN") != std::string::npos);
  MESHLOD_CHECK_EQ(geomorph->GetOutput()->GetNumberOfPoints(), 0);
  observer->Clear();
  geomorph->SetLevelOfDetail(1.5);
  geomorph->Update();
  MESHLOD_CHECK(!observer->GetError());
  MESHLOD_CHECK_GT(geomorph->GetOutput()->GetNumberOfPoints(), 0);
}
} // namespace

int TestLODGeomorphDecimation(int, char*[])
{
  vtkSmartPointer<vtkPolyData> surface = testing::MakeIsosurface(testing::Field::Metaballs, 32);
  const testing::MeshReport input = testing::InspectMesh(surface);
  MESHLOD_CHECK_EQ(input.BoundaryEdges, 0);
  MESHLOD_CHECK_EQ(input.NonManifoldEdges, 0);
  const Variant variants[] = {
    { "greedy, triangles and edges (defaults)", vtkTriangleCollapseDecimation::GREEDY,
      vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES },
    { "independent sets, triangles and edges", vtkTriangleCollapseDecimation::INDEPENDENT_SETS,
      vtkTriangleCollapseDecimation::TRIANGLES_AND_EDGES },
    { "greedy, triangles only", vtkTriangleCollapseDecimation::GREEDY,
      vtkTriangleCollapseDecimation::TRIANGLES },
    { "independent sets, triangles only", vtkTriangleCollapseDecimation::INDEPENDENT_SETS,
      vtkTriangleCollapseDecimation::TRIANGLES },
  };
  for (const Variant& variant : variants)
  {
    TestVariant(surface, variant);
  }
  TestEmptyAndNaN(surface);
  return testing::Result();
}
