// Input order: one isosurface in the contouring filter's order and with its ids shuffled
// (MeshLODTestMeshes' ShuffleIds: points renumbered and triangles reordered at random, fixed
// seed), through vtkQuadricDecimation and vtkQuadricClustering for the 10% target and both MeshLOD
// filters in the main table's configuration (the whole hierarchy down to 1%), on one thread
// (run-benchmarks.sh runs it with VTK_SMP_BACKEND_IN_USE=Sequential). For each, the fastest of
// three runs in each order (alternating, so that both meet the machine's slow and fast phases
// alike), their ratio, and the 10% output's triangle count and distances to the input (both
// orders measured against the contoured one: the same surface). MeshLOD renumbers a mesh whose
// ids are scattered in space before simplifying it (Filters/Core/SpatialOrder.h). Prints a
// markdown table, which run-benchmarks.sh appends to RESULTS.md.
//
//   InputOrderBenchmark [samples [field:triangles ...]]   (defaults 100000 and gyroid:600000)
#include "BenchmarkArguments.h"
#include "BenchmarkMethods.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestMeshes.h"

#include "vtkPolyData.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

namespace
{
using meshlod::benchmark::Method;

// One timed run of `method` on `input`: its output for the 10% target.
vtkSmartPointer<vtkPolyData> RunOnce(const Method& method, vtkPolyData* input, double& seconds)
{
  const vtkIdType n = input->GetNumberOfPolys();
  const vtkIdType tenth = std::max<vtkIdType>(4, std::llround(0.1 * n));
  const vtkIdType hundredth = std::max<vtkIdType>(4, std::llround(0.01 * n));
  meshlod::benchmark::Job job;
  if (method.Prepare)
  {
    job = method.Prepare(input, tenth); // untimed: a search for the grid's resolution
  }
  const auto start = std::chrono::steady_clock::now();
  vtkSmartPointer<vtkPolyData> output =
    method.Prepare ? job() : method.Hierarchy(input, { tenth, hundredth }).front();
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return output;
}
} // namespace

int main(int argc, char* argv[])
{
  int exitCode = 0;
  if (!meshlod::benchmark::NumberArguments(argc, argv, 1, true,
        "[samples [field:triangles ...]] (defaults 100000 and gyroid:600000)", exitCode))
  {
    return exitCode;
  }
  meshlod::SurfaceDistanceOptions yardstick;
  if (argc > 1)
  {
    yardstick.SamplesPerSurface = std::max(1000LL, std::atoll(argv[1]));
    yardstick.MaximumVertexSamples = yardstick.SamplesPerSurface;
  }
  std::vector<std::pair<meshlod::testing::Field, double>> meshes;
  if (!meshlod::benchmark::MeshArguments(argc, argv, 2, meshes))
  {
    return 2;
  }
  if (meshes.empty())
  {
    meshes = { { meshlod::testing::Field::Gyroid, 600000.0 } };
  }
  std::vector<Method> methods;
  meshlod::benchmark::RegisterVTKMethods(methods);
  meshlod::benchmark::RegisterMeshLODMethods(methods);
  const char* const names[] = { "vtkQuadricDecimation", "vtkTriangleCollapseDecimation",
    "vtkQuadricClustering", "vtkVertexClusterOctree" };

  std::printf("| mesh | method | ids | triangles at 10%% | time (s) | shuffled / contoured "
              "| Hausdorff %% | RMS %% |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|\n");
  for (const auto& spec : meshes)
  {
    int resolution = 0;
    vtkIdType dropped = 0;
    vtkSmartPointer<vtkPolyData> inputs[2];
    inputs[0] = meshlod::benchmark::MakeBenchmarkMesh(spec.first, spec.second, resolution, dropped);
    inputs[1] = meshlod::testing::ShuffleIds(inputs[0], 1);
    const meshlod::SurfaceDistanceMeter meter(inputs[0], yardstick);
    for (const char* name : names)
    {
      const Method& method = meshlod::benchmark::FindMethod(methods, name);
      double best[2] = { 1e300, 1e300 };
      vtkSmartPointer<vtkPolyData> outputs[2];
      for (int pass = 0; pass < 3; ++pass)
      {
        for (int order = 0; order < 2; ++order)
        {
          double seconds = 0.0;
          outputs[order] = RunOnce(method, inputs[order], seconds);
          best[order] = std::min(best[order], seconds);
        }
      }
      for (int order = 0; order < 2; ++order)
      {
        const meshlod::SurfaceDistance distance = meter.Measure(outputs[order]);
        char ratio[32] = "";
        if (order == 1)
        {
          std::snprintf(ratio, sizeof(ratio), "%.2f", best[1] / best[0]);
        }
        std::printf("| %s %lld | %s | %s | %lld | %.3f | %s | %.4f | %.5f |\n",
          meshlod::testing::FieldName(spec.first),
          static_cast<long long>(inputs[0]->GetNumberOfPolys()), name,
          order == 0 ? "contoured" : "shuffled",
          static_cast<long long>(outputs[order]->GetNumberOfPolys()), best[order], ratio,
          distance.HausdorffPercent(), distance.RmsPercent());
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
