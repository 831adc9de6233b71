// Cost of vtkLODGeomorph per frame, against a plain copy of the level's points.
//
// A flying-edges isosurface of about 1M vertices (2M triangles) becomes a two-level hierarchy
// with real morph data (independent triangle collapses, MeshLODTestHierarchies.h). Then, for
// the default SMP backend and for the sequential one, it measures the median over many frames:
// - the geomorph update within level 0 (only LevelOfDetail changes between frames), with and
//   without a point normal array to blend;
// - a plain copy of level 0's point array: memcpy into a ready buffer, and vtkPoints::DeepCopy
//   into a new vtkPoints (which allocates, as the filter does);
// - the exact-count mode: the first query (collapse schedule), a new count, a new fraction;
// - the nearest-vertex mode (no morph data): the first update, which builds the
//   correspondence, and the updates after it.
// Prints a Markdown table.
//
// Usage: GeomorphBenchmark [vertices (default 1000000)] [frames (default 41)]
#include "vtkLODGeomorph.h"

#include "BenchmarkArguments.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkDataArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Median time in milliseconds of `frames` calls of `frame(i)`.
double MedianMs(int frames, const std::function<void(int)>& frame)
{
  std::vector<double> times;
  for (int i = 0; i < frames; ++i)
  {
    const Clock::time_point start = Clock::now();
    frame(i);
    times.push_back(1000.0 * Seconds(start));
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

struct Row
{
  std::string What;
  double Ms;
  double Ratio; // to the memcpy of the point array; negative: not shown
};

void PrintTable(const char* title, const std::vector<Row>& rows)
{
  std::printf("\n### %s\n\n| measurement | time (ms) | / memcpy |\n|---|---:|---:|\n", title);
  for (const Row& row : rows)
  {
    if (row.Ratio >= 0.0)
    {
      std::printf("| %s | %.2f | %.2f |\n", row.What.c_str(), row.Ms, row.Ratio);
    }
    else
    {
      std::printf("| %s | %.2f | |\n", row.What.c_str(), row.Ms);
    }
  }
}

std::vector<Row> Measure(vtkMultiBlockDataSet* withNormals, vtkMultiBlockDataSet* plain, int frames)
{
  auto* level0 = vtkPolyData::SafeDownCast(plain->GetBlock(0));
  vtkDataArray* points = level0->GetPoints()->GetData();
  const size_t bytes = static_cast<size_t>(points->GetNumberOfValues()) * points->GetDataTypeSize();
  std::vector<Row> rows;

  // Baselines: a plain copy of the level's points.
  std::vector<char> buffer(bytes);
  std::memcpy(buffer.data(), points->GetVoidPointer(0), bytes); // touch the pages once
  const double memcpyMs =
    MedianMs(frames, [&](int) { std::memcpy(buffer.data(), points->GetVoidPointer(0), bytes); });
  char mebibytes[32];
  std::snprintf(mebibytes, sizeof(mebibytes), "%.1f", bytes / 1048576.0);
  rows.push_back(
    { std::string("memcpy of level 0's points (") + mebibytes + " MiB)", memcpyMs, 1.0 });
  const double deepCopyMs = MedianMs(frames, [&](int) {
    vtkNew<vtkPoints> copy;
    copy->DeepCopy(level0->GetPoints());
  });
  rows.push_back({ "vtkPoints::DeepCopy (new vtkPoints)", deepCopyMs, deepCopyMs / memcpyMs });

  // Geomorph within level 0: only L changes.
  for (vtkMultiBlockDataSet* h : { plain, withNormals })
  {
    vtkNew<vtkLODGeomorph> filter;
    filter->SetInputData(h);
    filter->SetLevelOfDetail(0.5);
    filter->Update(); // first update: validation and caches
    const double ms = MedianMs(frames, [&](int i) {
      filter->SetLevelOfDetail(0.01 + 0.98 * i / frames);
      filter->Update();
    });
    rows.push_back(
      { h == plain ? "geomorph update, points only" : "geomorph update, points + normals", ms,
        ms / memcpyMs });
  }

  // Exact count.
  {
    vtkNew<vtkLODGeomorph> filter;
    filter->SetInputData(plain);
    const vtkIdType finest = level0->GetNumberOfPolys();
    const vtkIdType coarse = vtkPolyData::SafeDownCast(plain->GetBlock(1))->GetNumberOfPolys();
    filter->SetTargetNumberOfTriangles((finest + coarse) / 2);
    Clock::time_point start = Clock::now();
    filter->Update();
    const double first = 1000.0 * Seconds(start);
    rows.push_back({ "exact count, first query (collapse schedule)", first, first / memcpyMs });
    const double newCount = MedianMs(frames, [&](int i) {
      filter->SetTargetNumberOfTriangles(coarse + (finest - coarse) * (i + 1) / (frames + 2));
      filter->Update();
    });
    rows.push_back({ "exact count, new count per frame", newCount, newCount / memcpyMs });
    const double newFraction = MedianMs(frames, [&](int i) {
      filter->SetCollapseFraction(static_cast<double>(i) / frames);
      filter->Update();
    });
    rows.push_back(
      { "exact count, new CollapseFraction per frame", newFraction, newFraction / memcpyMs });
  }

  // Nearest vertices (the morph arrays ignored).
  {
    vtkNew<vtkLODGeomorph> filter;
    filter->SetInputData(plain);
    filter->SetCorrespondenceToNearestVertices();
    filter->SetLevelOfDetail(0.0);
    filter->Update(); // validation only
    filter->SetLevelOfDetail(0.5);
    Clock::time_point start = Clock::now();
    filter->Update();
    const double first = 1000.0 * Seconds(start);
    rows.push_back(
      { "nearest vertices, first update (correspondence build)", first, first / memcpyMs });
    const double ms = MedianMs(frames, [&](int i) {
      filter->SetLevelOfDetail(0.01 + 0.98 * i / frames);
      filter->Update();
    });
    rows.push_back({ "nearest vertices, update per frame", ms, ms / memcpyMs });
  }
  return rows;
}
} // namespace

int main(int argc, char* argv[])
{
  int exitCode = 0;
  if (!meshlod::benchmark::NumberArguments(argc, argv, 2, false,
        "[vertices (default 1000000)] [frames (default 41)]", exitCode))
  {
    return exitCode;
  }
  const double vertices = argc > 1 ? std::atof(argv[1]) : 1e6;
  const int frames = argc > 2 ? std::atoi(argv[2]) : 41;
  const meshlod::testing::Field field = meshlod::testing::Field::Metaballs;

  Clock::time_point start = Clock::now();
  const int resolution = meshlod::testing::ResolutionForTriangles(field, 2.0 * vertices);
  vtkSmartPointer<vtkPolyData> surface = meshlod::testing::MakeIsosurface(field, resolution, true);
  const double meshSeconds = Seconds(start);

  meshlod::testing::CollapseHierarchyOptions options;
  options.MaximumLevels = 2;
  start = Clock::now();
  vtkSmartPointer<vtkMultiBlockDataSet> withNormals =
    meshlod::testing::MakeCollapseHierarchy(surface, options);
  const double hierarchySeconds = Seconds(start);
  surface->GetPointData()->Initialize();
  vtkSmartPointer<vtkMultiBlockDataSet> plain =
    meshlod::testing::MakeCollapseHierarchy(surface, options);

  auto* level0 = vtkPolyData::SafeDownCast(plain->GetBlock(0));
  auto* level1 = vtkPolyData::SafeDownCast(plain->GetBlock(1));
  std::printf("## vtkLODGeomorph benchmark\n\n");
  std::printf("Metaballs isosurface at resolution %d: %lld vertices, %lld triangles (%.1f s); "
              "level 1: %lld vertices, %lld triangles (hierarchy %.1f s). Points: %s. "
              "Median of %d frames.\n",
    resolution, static_cast<long long>(level0->GetNumberOfPoints()),
    static_cast<long long>(level0->GetNumberOfPolys()), meshSeconds,
    static_cast<long long>(level1->GetNumberOfPoints()),
    static_cast<long long>(level1->GetNumberOfPolys()), hierarchySeconds,
    level0->GetPoints()->GetData()->GetDataTypeAsString(), frames);

  const std::string initial = vtkSMPTools::GetBackend();
  const std::vector<Row> parallel = Measure(withNormals, plain, frames);
  vtkSMPTools::SetBackend("Sequential");
  const std::vector<Row> sequential = Measure(withNormals, plain, frames);
  vtkSMPTools::SetBackend(initial.c_str());
  PrintTable(("SMP backend " + initial + ", " +
               std::to_string(vtkSMPTools::GetEstimatedNumberOfThreads()) + " threads")
               .c_str(),
    parallel);
  PrintTable("SMP backend Sequential (one thread)", sequential);
  return EXIT_SUCCESS;
}
