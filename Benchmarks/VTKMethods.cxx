// VTK's decimators as benchmark methods, and the helpers they share.
#include "BenchmarkMethods.h"

#include "vtkBinnedDecimation.h"
#include "vtkDecimatePro.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkQuadricClustering.h"
#include "vtkQuadricDecimation.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace meshlod
{
namespace benchmark
{
namespace
{
vtkSmartPointer<vtkPolyData> TakeOutput(vtkPolyData* output)
{
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(output);
  return result;
}

double ReductionFor(vtkPolyData* input, vtkIdType target)
{
  const double triangles = static_cast<double>(input->GetNumberOfPolys());
  return triangles > 0.0 ? std::clamp(1.0 - target / triangles, 0.0, 1.0) : 0.0;
}

/// Grid divisions with `longest` cells along the longest side of the input's bounding box and
/// cells as close to cubes as whole numbers allow.
std::array<int, 3> Divisions(vtkPolyData* input, double longest)
{
  double bounds[6];
  input->GetBounds(bounds);
  const double extent[3] = { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
  const double maxExtent = std::max({ extent[0], extent[1], extent[2], 1e-300 });
  std::array<int, 3> divisions;
  for (int k = 0; k < 3; ++k)
  {
    divisions[k] = std::max(1, static_cast<int>(std::lround(longest * extent[k] / maxExtent)));
  }
  return divisions;
}

/// A grid-clustering method: searches the grid (untimed) whose output is nearest the target,
/// then times one run with that grid. `run(input, divisions)` runs the filter.
Job PrepareGrid(vtkPolyData* input,
  vtkIdType target,
  const std::function<vtkSmartPointer<vtkPolyData>(vtkPolyData*, const std::array<int, 3>&)>& run)
{
  // A closed surface of area A in cells of side h keeps about A / h^2 cells: start there.
  const double first = std::max(2.0, std::sqrt(static_cast<double>(target) / 4.0));
  const double longest = SearchSetting(first, target, /*integer=*/true, [&](double x) {
    return run(input, Divisions(input, x))->GetNumberOfPolys();
  });
  const std::array<int, 3> divisions = Divisions(input, longest);
  return [input, divisions, run]() { return run(input, divisions); };
}
} // namespace

//------------------------------------------------------------------------------
Method SimpleMethod(const std::string& name,
  const std::string& settings,
  bool parallel,
  std::function<vtkSmartPointer<vtkPolyData>(vtkPolyData*, vtkIdType)> decimate)
{
  Method method;
  method.Name = name;
  method.Settings = settings;
  method.Parallel = parallel;
  method.Prepare = [decimate](vtkPolyData* input, vtkIdType target) -> Job {
    return [decimate, input, target]() { return decimate(input, target); };
  };
  return method;
}

//------------------------------------------------------------------------------
double SearchSetting(
  double first, vtkIdType target, bool integer, const std::function<vtkIdType(double)>& count)
{
  const double wanted = std::max<double>(1.0, static_cast<double>(target));
  auto snap = [integer](double x) { return integer ? std::max(1.0, std::round(x)) : x; };
  // How far a count is from the target, as a ratio either way.
  auto miss = [wanted](double c) { return std::abs(std::log(std::max(c, 1.0) / wanted)); };

  double bestX = snap(first), bestMiss = HUGE_VAL;
  double lowX = 0.0, lowCount = 0.0, highX = 0.0, highCount = 0.0; // bracket, 0 = none yet
  double x = bestX;
  for (int tries = 0; tries < 16; ++tries)
  {
    const double c = static_cast<double>(count(x));
    if (miss(c) < bestMiss)
    {
      bestMiss = miss(c);
      bestX = x;
    }
    if (bestMiss < 0.005)
    {
      break;
    }
    if (c < wanted && (lowX == 0.0 || x > lowX))
    {
      lowX = x;
      lowCount = std::max(c, 1.0);
    }
    else if (c >= wanted && (highX == 0.0 || x < highX))
    {
      highX = x;
      highCount = std::max(c, 1.0);
    }

    double next;
    if (lowX > 0.0 && highX > 0.0)
    {
      // Interpolate in log-log space between the bracket's ends; bisect if that stalls.
      const double power = std::log(highCount / lowCount) / std::log(highX / lowX);
      next = snap(lowX * std::pow(wanted / lowCount, 1.0 / std::max(power, 0.1)));
      if (next <= lowX || next >= highX)
      {
        next = snap(std::sqrt(lowX * highX));
      }
      if (next <= lowX || next >= highX)
      {
        break; // neighbouring integers: nothing left in between
      }
    }
    else
    {
      // Not bracketed yet: assume the count grows like x^2 (a surface in a grid).
      next = snap(x * std::sqrt(wanted / std::max(c, 1.0)));
      if (next == x)
      {
        next = snap(c < wanted ? x * 1.05 + 1.0 : x / 1.05 - 1.0);
      }
      if (next <= 0.0)
      {
        break;
      }
    }
    x = next;
  }
  return bestX;
}

//------------------------------------------------------------------------------
void RegisterVTKMethods(std::vector<Method>& methods)
{
  methods.push_back(SimpleMethod("vtkQuadricDecimation",
    "TargetReduction = 1 - target / input; everything else default (no attribute error metric)",
    false,
    [](vtkPolyData* input, vtkIdType target) {
      vtkNew<vtkQuadricDecimation> decimate;
      decimate->SetInputData(input);
      decimate->SetTargetReduction(ReductionFor(input, target));
      decimate->Update();
      return TakeOutput(decimate->GetOutput());
    }));

  methods.push_back(SimpleMethod("vtkDecimatePro",
    "TargetReduction = 1 - target / input; PreserveTopology off (with it on, a 143k-triangle "
    "gyroid asked for 1% stopped at 5,029 triangles instead of 1,428); Splitting and "
    "BoundaryVertexDeletion on, "
    "FeatureAngle 15, MaximumError unlimited (defaults)",
    false,
    [](vtkPolyData* input, vtkIdType target) {
      vtkNew<vtkDecimatePro> decimate;
      decimate->SetInputData(input);
      decimate->SetTargetReduction(ReductionFor(input, target));
      decimate->PreserveTopologyOff();
      decimate->Update();
      return TakeOutput(decimate->GetOutput());
    }));

  Method clustering;
  clustering.Name = "vtkQuadricClustering";
  clustering.Settings = "grid with cube-like cells, resolution searched (untimed) for the output "
                        "count nearest the target; AutoAdjustNumberOfDivisions off (it caps the "
                        "grid); everything else default";
  clustering.Prepare = [](vtkPolyData* input, vtkIdType target) {
    return PrepareGrid(input, target, [](vtkPolyData* mesh, const std::array<int, 3>& divisions) {
      vtkNew<vtkQuadricClustering> cluster;
      cluster->SetInputData(mesh);
      cluster->AutoAdjustNumberOfDivisionsOff();
      cluster->SetNumberOfDivisions(divisions[0], divisions[1], divisions[2]);
      cluster->Update();
      return TakeOutput(cluster->GetOutput());
    });
  };
  methods.push_back(clustering);

  Method binned;
  binned.Name = "vtkBinnedDecimation";
  binned.Settings = "grid with cube-like cells, resolution searched (untimed) for the output count "
                    "nearest the target; AutoAdjustNumberOfDivisions off; PointGenerationMode "
                    "BIN_AVERAGES (the best of its four modes); threaded with vtkSMPTools";
  binned.Parallel = true;
  binned.Prepare = [](vtkPolyData* input, vtkIdType target) {
    return PrepareGrid(input, target, [](vtkPolyData* mesh, const std::array<int, 3>& divisions) {
      vtkNew<vtkBinnedDecimation> cluster;
      cluster->SetInputData(mesh);
      cluster->AutoAdjustNumberOfDivisionsOff();
      cluster->SetNumberOfDivisions(divisions[0], divisions[1], divisions[2]);
      cluster->SetPointGenerationModeToBinAverages();
      cluster->Update();
      return TakeOutput(cluster->GetOutput());
    });
  };
  methods.push_back(binned);

  // A hierarchy from a method that makes one level at a time: the baseline a hierarchy filter
  // has to beat. It also keeps the harness's hierarchy path exercised.
  Method chained;
  chained.Name = "vtkQuadricDecimation chained";
  chained.Settings = "hierarchy made by vtkQuadricDecimation level after level, each level "
                     "decimating the one before it (largest target first), defaults otherwise";
  chained.Hierarchy = [](vtkPolyData* input, const std::vector<vtkIdType>& targets) {
    std::vector<size_t> order(targets.size());
    for (size_t i = 0; i < order.size(); ++i)
    {
      order[i] = i;
    }
    std::sort(
      order.begin(), order.end(), [&](size_t a, size_t b) { return targets[a] > targets[b]; });
    std::vector<vtkSmartPointer<vtkPolyData>> levels(targets.size());
    vtkSmartPointer<vtkPolyData> previous = input;
    for (size_t i : order)
    {
      vtkNew<vtkQuadricDecimation> decimate;
      decimate->SetInputData(previous);
      decimate->SetTargetReduction(ReductionFor(previous, targets[i]));
      decimate->Update();
      levels[i] = TakeOutput(decimate->GetOutput());
      previous = levels[i];
    }
    return levels;
  };
  methods.push_back(chained);
}

} // namespace benchmark
} // namespace meshlod
