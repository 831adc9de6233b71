// MeshLOD's own filters in the benchmark. Each filter is one registration below; the harness
// runs every registered method on the same meshes and targets as VTK's decimators and compares
// it with vtkQuadricDecimation (see BenchmarkMethods.h). The decimation filters are hierarchy
// methods: one timed Update() makes every level (by default 8 levels spaced geometrically down
// to the smallest target, so the default targets 10% and 1% are levels 4 and 8), and each target
// is answered by the level nearest to it.
#include "BenchmarkMethods.h"

#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include <algorithm>
#include <cstdlib>

namespace meshlod
{
namespace benchmark
{
namespace
{
// For each target, the level whose triangle count is nearest to it.
std::vector<vtkSmartPointer<vtkPolyData>> NearestLevels(
  vtkMultiBlockDataSet* hierarchy, const std::vector<vtkIdType>& targets)
{
  std::vector<vtkSmartPointer<vtkPolyData>> levels;
  for (const vtkIdType target : targets)
  {
    vtkSmartPointer<vtkPolyData> best;
    for (unsigned int i = 0; i < hierarchy->GetNumberOfBlocks(); ++i)
    {
      auto* level = vtkPolyData::SafeDownCast(hierarchy->GetBlock(i));
      if (!best ||
        std::llabs(level->GetNumberOfPolys() - target) < std::llabs(best->GetNumberOfPolys() - target))
      {
        best = level;
      }
    }
    levels.push_back(best);
  }
  return levels;
}

// Levels down to the smallest target: (1 - TargetReduction) of the input is its count.
double ReductionTo(vtkPolyData* input, const std::vector<vtkIdType>& targets)
{
  const double smallest = static_cast<double>(*std::min_element(targets.begin(), targets.end()));
  return std::min(0.999999, 1.0 - smallest / static_cast<double>(input->GetNumberOfPolys()));
}

// A threaded hierarchy method; the caller sets its Hierarchy.
Method ThreadedMethod(const std::string& name, const std::string& settings)
{
  Method method;
  method.Name = name;
  method.Settings = settings;
  method.Parallel = true;
  return method;
}

Method TriangleCollapse(const std::string& name, const std::string& settings,
  void (*configure)(vtkTriangleCollapseDecimation*))
{
  Method method = ThreadedMethod(name, settings);
  method.Hierarchy = [configure](vtkPolyData* input, const std::vector<vtkIdType>& targets) {
    vtkNew<vtkTriangleCollapseDecimation> decimate;
    decimate->SetInputData(input);
    decimate->SetTargetReduction(ReductionTo(input, targets));
    configure(decimate);
    decimate->Update();
    return NearestLevels(decimate->GetHierarchy(), targets);
  };
  return method;
}

// A variant of the triangle collapse measured on one thread only (its settings end by saying
// so): a row for the accuracy and the speed of one setting, not for the threads.
Method OneThreadTriangleCollapse(const std::string& name, const std::string& settings,
  void (*configure)(vtkTriangleCollapseDecimation*))
{
  Method method = TriangleCollapse(name, settings + "; one-thread row only", configure);
  method.Parallel = false;
  return method;
}

Method VertexCluster(const std::string& name, const std::string& settings,
  void (*configure)(vtkVertexClusterOctree*))
{
  Method method = ThreadedMethod(name, settings);
  method.Hierarchy = [configure](vtkPolyData* input, const std::vector<vtkIdType>& targets) {
    vtkNew<vtkVertexClusterOctree> cluster;
    cluster->SetInputData(input);
    cluster->SetLevelModeToTargetTriangleCounts();
    configure(cluster);
    std::vector<vtkIdType> sorted(targets);
    std::sort(sorted.rbegin(), sorted.rend());
    for (const vtkIdType target : sorted)
    {
      cluster->AddTargetTriangleCount(target);
    }
    cluster->Update();
    // Level i + 1 is the one made for the i-th largest target: where the octree misses counts,
    // the level nearest a target in triangles can be another target's (a noisy isosurface's
    // level for 1% nearer to 10% than the 10% level, 44% above it).
    vtkMultiBlockDataSet* hierarchy = cluster->GetHierarchy();
    if (hierarchy->GetNumberOfBlocks() != sorted.size() + 1)
    {
      return NearestLevels(hierarchy, targets); // a level that would keep nothing ended it
    }
    std::vector<vtkSmartPointer<vtkPolyData>> levels;
    for (const vtkIdType target : targets)
    {
      const auto made = std::find(sorted.begin(), sorted.end(), target) - sorted.begin();
      levels.push_back(vtkPolyData::SafeDownCast(hierarchy->GetBlock(static_cast<unsigned>(made + 1))));
    }
    return levels;
  };
  return method;
}
} // namespace

void RegisterMeshLODMethods(std::vector<Method>& methods)
{
  methods.push_back(TriangleCollapse("vtkTriangleCollapseDecimation",
    "defaults: quadric method, greedy schedule in parallel rounds (PartitionedGreedy), "
    "triangles and edges, 8 levels",
    [](vtkTriangleCollapseDecimation*) {}));
  methods.push_back(OneThreadTriangleCollapse("vtkTriangleCollapseDecimation strict greedy",
    "quadric method, greedy schedule with PartitionedGreedy off (one collapse after the other, "
    "the order of paper 002), triangles and edges, 8 levels",
    [](vtkTriangleCollapseDecimation* d) { d->PartitionedGreedyOff(); }));
  methods.push_back(OneThreadTriangleCollapse("vtkTriangleCollapseDecimation paper placement",
    "as vtkTriangleCollapseDecimation, with Placement PAPER_CANDIDATES (paper 002: the "
    "quadric's minimiser where its system is solvable, else the best of centroid, vertices and "
    "edge midpoints)",
    [](vtkTriangleCollapseDecimation* d) { d->SetPlacementToPaperCandidates(); }));
  methods.push_back(OneThreadTriangleCollapse("vtkTriangleCollapseDecimation uniform weights",
    "as vtkTriangleCollapseDecimation, with PlaneWeights UNIFORM_WEIGHTS (every plane weighs the "
    "input's mean triangle area, as vtkQuadricDecimation weighs them)",
    [](vtkTriangleCollapseDecimation* d) { d->SetPlaneWeightsToUniform(); }));
  methods.push_back(OneThreadTriangleCollapse("vtkTriangleCollapseDecimation paper cost",
    "as vtkTriangleCollapseDecimation, with AreaNormalization 0 (a collapse costs its merged "
    "quadric's value, paper 002's cost, not divided by the surface it stands for)",
    [](vtkTriangleCollapseDecimation* d) { d->SetAreaNormalization(0.0); }));
  methods.push_back(TriangleCollapse("vtkTriangleCollapseDecimation flipped edges",
    "as vtkTriangleCollapseDecimation, with FlipEdges on (the sharply bent edges of each level "
    "with at most a quarter of the input's triangles flipped towards the input, and the "
    "collapses going on from them; vtkLODGeomorph turns the flips continuously)",
    [](vtkTriangleCollapseDecimation* d) { d->FlipEdgesOn(); }));
  methods.push_back(TriangleCollapse("vtkTriangleCollapseDecimation independent sets",
    "quadric method, IndependentSets schedule (LevelFraction 0.025), triangles and edges, 8 levels",
    [](vtkTriangleCollapseDecimation* d) { d->SetScheduleToIndependentSets(); }));
  methods.push_back(TriangleCollapse("vtkTriangleCollapseDecimation triangles only",
    "quadric method, IndependentSets schedule, Operator TRIANGLES (every collapse merges a "
    "triangle: the papers' operator), 8 levels",
    [](vtkTriangleCollapseDecimation* d) {
      d->SetScheduleToIndependentSets();
      d->SetOperatorToTriangles();
    }));
  methods.push_back(TriangleCollapse("vtkTriangleCollapseDecimation curvature",
    "curvature method with its defaults: CurvatureCost FIT_DEVIATION (the new triangles' "
    "squared deviation from the fitted surface, or the merged planes' where larger), operator "
    "TRIANGLES_AND_EDGES (an edge instead of a triangle only at a crease), greedy schedule in "
    "parallel rounds (PartitionedGreedy), 8 levels",
    [](vtkTriangleCollapseDecimation* d) { d->SetMethodToCurvature(); }));
  methods.push_back(OneThreadTriangleCollapse(
    "vtkTriangleCollapseDecimation curvature strict greedy",
    "as vtkTriangleCollapseDecimation curvature, with PartitionedGreedy off",
    [](vtkTriangleCollapseDecimation* d) {
      d->SetMethodToCurvature();
      d->PartitionedGreedyOff();
    }));
  Method paper = TriangleCollapse("vtkTriangleCollapseDecimation curvature paper weight",
    "curvature method as in paper 000: CurvatureCost WEIGHT (weights 1/3 each), "
    "IndependentSets schedule, 8 levels",
    [](vtkTriangleCollapseDecimation* d) {
      d->SetMethodToCurvature();
      d->SetCurvatureCostToWeight();
      d->SetScheduleToIndependentSets();
    });
  paper.MaximumInputTriangles = 700000;
  methods.push_back(paper);

  // The octree clustering is compared with vtkQuadricClustering: one level per target, epsilon
  // searched by the filter inside the timed run.
  methods.push_back(VertexCluster("vtkVertexClusterOctree",
    "TargetTriangleCounts level mode, one level per target, defaults otherwise",
    [](vtkVertexClusterOctree*) {}));
  methods.push_back(VertexCluster("vtkVertexClusterOctree flipped edges",
    "as vtkVertexClusterOctree, with FlipEdges on (each level's edges flipped towards the input; "
    "for discrete levels, see the class docs)",
    [](vtkVertexClusterOctree* cluster) { cluster->FlipEdgesOn(); }));
  Method free = VertexCluster("vtkVertexClusterOctree free topology",
    "as vtkVertexClusterOctree, with PreserveTopology off (the paper's conditions only: no "
    "repair of folds, pinches or breaks, so levels may change topology); one-thread row only",
    [](vtkVertexClusterOctree* cluster) { cluster->PreserveTopologyOff(); });
  free.Parallel = false;
  methods.push_back(free);
}

} // namespace benchmark
} // namespace meshlod
