// How far vtkLODGeomorph jumps when it reaches a level: the surface distance between the
// geomorph just before level i + 1 (L = i + 1 - 1e-7) and level i + 1 itself, for every
// simplified level of both filters' hierarchies with FlipEdges off (their defaults: the
// geomorph lands on each level, no jump) and on (the flipped levels are not the images of the
// finer level's triangles). Each jump is compared with the level's own distance to level 0,
// and the triangles the geomorph keeps there (DropDegenerateTriangles on) with the level's.
// Prints a Markdown table, one row per hierarchy: the largest jump (Hausdorff and RMS, in % of
// the diagonal), the range of the jump over the level's own distance over the levels that
// jump, and the largest surplus of triangles.
//
// Usage: GeomorphJumpBenchmark [samples per surface (default 100000)] [field:triangles ...]
// (default metaballs:150000 gyroid:600000, the main benchmark's two smaller isosurfaces)
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "BenchmarkArguments.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestMeshes.h"

#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

namespace
{
struct JumpSummary
{
  int Levels = 0;        // simplified levels
  int Jumping = 0;       // levels the geomorph does not land on (jump above rounding)
  double Hausdorff = 0.0; // largest jump, % of the diagonal
  double Rms = 0.0;
  double LeastHausdorffRatio = std::numeric_limits<double>::infinity();
  double MostHausdorffRatio = 0.0;
  double LeastRmsRatio = std::numeric_limits<double>::infinity();
  double MostRmsRatio = 0.0;
  long long Surplus = 0; // most triangles the geomorph keeps beyond the level's
};

// A jump below this fraction of the diagonal is rounding (the points are in single precision).
constexpr double RoundingJump = 1e-6;

JumpSummary MeasureJumps(vtkPolyData* input, vtkMultiBlockDataSet* hierarchy,
  const meshlod::SurfaceDistanceOptions& options)
{
  JumpSummary s;
  vtkNew<vtkLODGeomorph> geomorph;
  geomorph->SetInputData(hierarchy);
  geomorph->DropDegenerateTrianglesOn();
  for (unsigned int b = 1; b < hierarchy->GetNumberOfBlocks(); ++b)
  {
    vtkPolyData* level = vtkPolyData::SafeDownCast(hierarchy->GetBlock(b));
    geomorph->SetLevelOfDetail(b - 1e-7);
    geomorph->Update();
    const meshlod::SurfaceDistance jump =
      meshlod::MeasureSurfaceDistance(geomorph->GetOutput(), level, options);
    ++s.Levels;
    s.Surplus = std::max(s.Surplus,
      static_cast<long long>(geomorph->GetOutput()->GetNumberOfPolys() - level->GetNumberOfPolys()));
    if (!(jump.Hausdorff > RoundingJump * jump.Diagonal))
    {
      continue;
    }
    const meshlod::SurfaceDistance own = meshlod::MeasureSurfaceDistance(input, level, options);
    ++s.Jumping;
    s.Hausdorff = std::max(s.Hausdorff, jump.HausdorffPercent());
    s.Rms = std::max(s.Rms, jump.RmsPercent());
    const double h = jump.Hausdorff / own.Hausdorff, r = jump.Rms / own.Rms;
    s.LeastHausdorffRatio = std::min(s.LeastHausdorffRatio, h);
    s.MostHausdorffRatio = std::max(s.MostHausdorffRatio, h);
    s.LeastRmsRatio = std::min(s.LeastRmsRatio, r);
    s.MostRmsRatio = std::max(s.MostRmsRatio, r);
  }
  return s;
}

void PrintRow(const char* mesh, long long triangles, const char* method, bool flip,
  const JumpSummary& s)
{
  std::printf("| %s %lld | %s | %s | %d of %d |", mesh, triangles, method, flip ? "on" : "off",
    s.Jumping, s.Levels);
  if (s.Jumping == 0)
  {
    std::printf(" 0, 0 | - | - |");
  }
  else
  {
    std::printf(" %.4g, %.4g | %.2f-%.2f | %.2f-%.2f |", s.Hausdorff, s.Rms,
      s.LeastHausdorffRatio, s.MostHausdorffRatio, s.LeastRmsRatio, s.MostRmsRatio);
  }
  std::printf(" %lld |\n", s.Surplus);
  std::fflush(stdout);
}
} // namespace

int main(int argc, char* argv[])
{
  int exitCode = 0;
  if (!meshlod::benchmark::NumberArguments(argc, argv, 1, true,
        "[samples per surface (default 100000)] [field:triangles ...]", exitCode))
  {
    return exitCode;
  }
  meshlod::SurfaceDistanceOptions options;
  options.SamplesPerSurface = argc > 1 ? std::atoll(argv[1]) : 100000;
  options.MaximumVertexSamples = options.SamplesPerSurface;
  std::vector<std::pair<meshlod::testing::Field, double>> meshes;
  if (!meshlod::benchmark::MeshArguments(argc, argv, 2, meshes))
  {
    return 2;
  }
  if (meshes.empty())
  {
    meshes = { { meshlod::testing::Field::Metaballs, 150000.0 },
      { meshlod::testing::Field::Gyroid, 600000.0 } };
  }

  std::printf("## vtkLODGeomorph at the levels\n\n");
  std::printf("The surface distance between vtkLODGeomorph just before each simplified level\n"
              "(L = i + 1 - 1e-7, DropDegenerateTriangles on) and that level, for both filters'\n"
              "default hierarchies with FlipEdges off and on (Benchmarks/GeomorphJumpBenchmark.cxx,\n"
              "%lld samples per surface): how many levels the geomorph jumps at (more than 1e-6\n"
              "of the diagonal), the largest jump in %% of the diagonal, the jump over the level's\n"
              "own distance to level 0 (least and largest over the levels that jump), and the\n"
              "most triangles the geomorph keeps there beyond the level's count.\n\n",
    static_cast<long long>(options.SamplesPerSurface));
  std::printf("| mesh | filter | FlipEdges | levels jumped | largest jump: Hausdorff, RMS %% | "
              "jump / level's Hausdorff | jump / level's RMS | surplus triangles |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|\n");
  for (const auto& mesh : meshes)
  {
    vtkSmartPointer<vtkPolyData> input = meshlod::testing::MakeIsosurface(mesh.first,
      meshlod::testing::ResolutionForTriangles(mesh.first, mesh.second));
    const long long triangles = static_cast<long long>(input->GetNumberOfPolys());
    const char* name = meshlod::testing::FieldName(mesh.first);
    // Both filters with their defaults, FlipEdges off, then on.
    auto measure = [&](auto* filter) {
      filter->SetInputData(input);
      for (const bool flip : { false, true })
      {
        filter->SetFlipEdges(flip);
        filter->Update();
        PrintRow(name, triangles, filter->GetClassName(), flip,
          MeasureJumps(input, filter->GetHierarchy(), options));
      }
    };
    measure(vtkNew<vtkTriangleCollapseDecimation>().GetPointer());
    measure(vtkNew<vtkVertexClusterOctree>().GetPointer());
  }
  return 0;
}
