// How much one comparison at one triangle count says. A Hausdorff distance is the distance at a
// single spot, so its ratio between two methods at one target moves by chance when the target
// moves a little: each method's largest deviation appears, grows and vanishes as the
// collapses around it go one way or the other. This program asks vtkTriangleCollapseDecimation
// (defaults, the main table's configuration: 8 levels down to the 1% target, the level nearest
// each target) for nine 1% targets 0.4% apart, the first the main table's, and compares each
// level nearest 10% and 1% with vtkQuadricDecimation asked for the level's own triangle count
// (its configuration in the main table). It prints a markdown table of the ratios' spread,
// which run-benchmarks.sh appends to RESULTS.md. No timing.
//
//   TargetSensitivityBenchmark [samples [draws [field:triangles ...]]]
//
// samples: yardstick samples per surface (default 100000); draws: targets per mesh (default 9);
// meshes: the main benchmark's isosurfaces (BenchmarkHarness.cxx), by default all three:
// metaballs:150000, gyroid:600000 and gyroid:2300000 (about ten minutes in all on two cores, eight
// of them for the largest).
#include "BenchmarkMethods.h"
#include "BenchmarkArguments.h"
#include "MeshLODSurfaceDistance.h"

#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
struct Spread
{
  std::vector<double> Hausdorff, Rms; // ratios to vtkQuadricDecimation, one per target
  std::vector<vtkIdType> Counts;      // our level's triangle count
};

std::string MinMedianMax(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t half = values.size() / 2;
  const double median =
    values.size() % 2 == 1 ? values[half] : 0.5 * (values[half - 1] + values[half]);
  char text[96];
  std::snprintf(text, sizeof(text), "%.2f, %.2f, %.2f", values.front(), median, values.back());
  return text;
}
} // namespace

int main(int argc, char* argv[])
{
  int exitCode = 0;
  if (!meshlod::benchmark::NumberArguments(argc, argv, 2, true,
        "[samples [draws [field:triangles ...]]] (defaults 100000, 9 and the three isosurfaces "
        "of the main benchmark)",
        exitCode))
  {
    return exitCode;
  }
  meshlod::SurfaceDistanceOptions yardstick;
  if (argc > 1)
  {
    yardstick.SamplesPerSurface = std::max(1000LL, std::atoll(argv[1]));
    yardstick.MaximumVertexSamples = yardstick.SamplesPerSurface;
  }
  const int draws = argc > 2 ? std::max(1, std::atoi(argv[2])) : 9;
  std::vector<std::pair<meshlod::testing::Field, double>> meshes;
  if (!meshlod::benchmark::MeshArguments(argc, argv, 3, meshes))
  {
    return 2;
  }
  if (meshes.empty())
  {
    meshes = { { meshlod::testing::Field::Metaballs, 150000.0 },
      { meshlod::testing::Field::Gyroid, 600000.0 },
      { meshlod::testing::Field::Gyroid, 2300000.0 } };
  }

  std::vector<meshlod::benchmark::Method> methods;
  meshlod::benchmark::RegisterVTKMethods(methods);
  meshlod::benchmark::RegisterMeshLODMethods(methods);
  const meshlod::benchmark::Method& ours =
    meshlod::benchmark::FindMethod(methods, "vtkTriangleCollapseDecimation");
  const meshlod::benchmark::Method& peer =
    meshlod::benchmark::FindMethod(methods, "vtkQuadricDecimation");
  if (!ours.Hierarchy || !peer.Prepare)
  {
    std::fprintf(stderr, "the triangle collapse must make a hierarchy, the peer one output\n");
    return 1;
  }

  std::printf("| mesh | target | our triangle counts | Hausdorff x QD: least, median, largest "
              "| above 1.0 | RMS x QD: least, median, largest |\n");
  std::printf("|---|---:|---|---:|---:|---:|\n");
  const double fractions[2] = { 0.1, 0.01 };
  for (const auto& spec : meshes)
  {
    int resolution = 0;
    vtkIdType dropped = 0;
    vtkSmartPointer<vtkPolyData> input =
      meshlod::benchmark::MakeBenchmarkMesh(spec.first, spec.second, resolution, dropped);
    const double n = static_cast<double>(input->GetNumberOfPolys());
    const meshlod::SurfaceDistanceMeter meter(input, yardstick);
    Spread spread[2];
    for (int k = 0; k < draws; ++k)
    {
      // The main table's targets (the first draw) and nearby ones, all the fractions moved
      // together so that the levels between them keep their spacing.
      std::vector<vtkIdType> targets;
      for (const double fraction : fractions)
      {
        targets.push_back(std::max<vtkIdType>(4, std::llround(fraction * (1.0 + 0.004 * k) * n)));
      }
      const auto levels = ours.Hierarchy(input, targets);
      for (int f = 0; f < 2; ++f)
      {
        const vtkIdType count = levels[f]->GetNumberOfPolys();
        const vtkSmartPointer<vtkPolyData> reference = peer.Prepare(input, count)();
        const meshlod::SurfaceDistance mine = meter.Measure(levels[f]);
        const meshlod::SurfaceDistance theirs = meter.Measure(reference);
        spread[f].Hausdorff.push_back(mine.Hausdorff / theirs.Hausdorff);
        spread[f].Rms.push_back(mine.Rms / theirs.Rms);
        spread[f].Counts.push_back(count);
      }
    }
    for (int f = 0; f < 2; ++f)
    {
      const Spread& s = spread[f];
      const auto above = std::count_if(
        s.Hausdorff.begin(), s.Hausdorff.end(), [](double r) { return r > 1.0; });
      std::printf("| %s %lld | %g%% | %lld-%lld | %s | %lld of %d | %s |\n",
        meshlod::testing::FieldName(spec.first), static_cast<long long>(n),
        100.0 * fractions[f], static_cast<long long>(s.Counts.front()),
        static_cast<long long>(s.Counts.back()), MinMedianMax(s.Hausdorff).c_str(),
        static_cast<long long>(above), draws, MinMedianMax(s.Rms).c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}
