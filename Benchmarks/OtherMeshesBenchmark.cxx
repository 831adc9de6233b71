// Beyond isosurfaces: vtkTriangleCollapseDecimation (defaults, then the curvature method, then
// uniform plane weights, then PreserveTopology off) against vtkQuadricDecimation, and
// vtkVertexClusterOctree against vtkQuadricClustering, on meshes made by VTK's own sources, the
// kinds a user feeds in besides marching-cubes output: a CAD-like faceted solid, a parametric
// surface with a seam, scan-like noisy spheres, open surfaces (a scan-like sphere with holes, a
// terrain), a non-orientable surface, a superquadric with rounded edges, VTK's wavelet test
// volume's isosurface (open, with many handles), a mesh in georeferenced coordinates (far from
// the origin), the smoothed surfaces between the regions of a segmented volume, where three
// sheets meet along curves, a binary mask's terraced isosurface and thin tubes; then, through
// both filters' defaults only (the first table and the octree's), 21 more shapes from VTK's
// sources (SurveyMeshes.cxx). Prints five markdown tables
// (quality and Euler characteristics, or the counts reached; no timing) that run-benchmarks.sh
// appends to RESULTS.md.
//
//   OtherMeshesBenchmark [samples]   (surface samples per side for the distances, default 100000)
#include "BenchmarkMethods.h"
#include "BenchmarkArguments.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestMeshes.h"
#include "OtherMeshes.h"
#include "vtkTriangleCollapseDecimation.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCylinderSource.h"
#include "vtkDiscreteFlyingEdges3D.h"
#include "vtkFlyingEdges3D.h"
#include "vtkImageData.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkParametricBoy.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkQuadricDecimation.h"
#include "vtkRemoveDuplicatePolys.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkSuperquadricSource.h"
#include "vtkTubeFilter.h"
#include "vtkWindowedSincPolyDataFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using meshlod::benchmark::Prepare;
using meshlod::benchmark::TestMesh;

// A volume of `size`^3 samples over [-1, 1]^3 whose point scalars (a vtkShortArray named
// `name`) are `label` of each sample's position.
vtkSmartPointer<vtkImageData> LabelVolume(
  int size, const char* name, const std::function<short(const double x[3])>& label)
{
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->SetDimensions(size, size, size);
  const double spacing = 2.0 / (size - 1);
  volume->SetSpacing(spacing, spacing, spacing);
  volume->SetOrigin(-1.0, -1.0, -1.0);
  vtkNew<vtkShortArray> values;
  values->SetName(name);
  values->SetNumberOfTuples(static_cast<vtkIdType>(size) * size * size);
  vtkIdType id = 0;
  for (int k = 0; k < size; ++k)
  {
    for (int j = 0; j < size; ++j)
    {
      for (int i = 0; i < size; ++i, ++id)
      {
        const double x[3] = { -1.0 + i * spacing, -1.0 + j * spacing, -1.0 + k * spacing };
        values->SetValue(id, label(x));
      }
    }
  }
  volume->GetPointData()->SetScalars(values);
  return volume;
}

// Three overlapping balls labelled 1, 2 and 3 in a volume of `size`^3 samples (first label
// wins where they overlap): vtkDiscreteFlyingEdges3D's surfaces of the labels, each face
// between two labels kept once (vtkRemoveDuplicatePolys), smoothed as segmentations are before
// decimation (vtkWindowedSincPolyDataFilter, 20 iterations, pass band 0.05, non-manifold
// smoothing on). Sheets meet three at a time along the curves where balls touch.
vtkSmartPointer<vtkPolyData> SegmentedBalls(int size)
{
  const double balls[3][4] = { { -0.3, 0.0, 0.0, 0.55 }, { 0.3, 0.0, 0.0, 0.55 },
    { 0.0, 0.35, 0.1, 0.45 } };
  vtkSmartPointer<vtkImageData> labels = LabelVolume(size, "label", [&](const double x[3]) {
    short label = 0;
    for (int b = 2; b >= 0; --b)
    {
      const double dx = x[0] - balls[b][0], dy = x[1] - balls[b][1], dz = x[2] - balls[b][2];
      label = dx * dx + dy * dy + dz * dz < balls[b][3] * balls[b][3] ? static_cast<short>(b + 1) : label;
    }
    return label;
  });
  vtkNew<vtkDiscreteFlyingEdges3D> contour;
  contour->SetInputData(labels);
  contour->GenerateValues(3, 1, 3);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  vtkSmartPointer<vtkPolyData> mesh = meshlod::testing::TriangulateAndClean(contour);
  vtkNew<vtkRemoveDuplicatePolys> once;
  once->SetInputData(mesh);
  vtkNew<vtkWindowedSincPolyDataFilter> smooth;
  smooth->SetInputConnection(once->GetOutputPort());
  smooth->SetNumberOfIterations(20);
  smooth->SetPassBand(0.05);
  smooth->NonManifoldSmoothingOn();
  smooth->NormalizeCoordinatesOn();
  smooth->BoundarySmoothingOff();
  smooth->FeatureEdgeSmoothingOff();
  smooth->Update();
  // Triangles only: cleaning turned the contour's collapsed triangles into lines and vertices.
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(smooth->GetOutput()->GetPoints());
  surface->SetPolys(smooth->GetOutput()->GetPolys());
  return surface;
}

// An ellipsoid segmented as a binary mask (1 inside, 0 outside) on a `size`^3 grid over
// [-1, 1]^3 and contoured at 0.5 by flying edges: the terraced surface a segmentation gives
// when its mask is contoured without smoothing (every point halfway along a grid edge).
vtkSmartPointer<vtkPolyData> MaskIsosurface(int size)
{
  vtkSmartPointer<vtkImageData> mask = LabelVolume(size, "mask", [](const double x[3]) {
    return static_cast<short>(
      x[0] * x[0] / 0.8 + x[1] * x[1] / 0.4 + x[2] * x[2] / 0.25 < 0.8 ? 1 : 0);
  });
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(mask);
  contour->SetValue(0, 0.5);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  return meshlod::testing::TriangulateAndClean(contour);
}

// Three capped tubes (vtkTubeFilter, 24 sides, radius 0.02) around helices of radius 0.3
// rising from z = -1 to about 1, 400 points each: thin parts, as vessels or fibres, whose
// radius is about a hundredth of the mesh's diagonal.
vtkSmartPointer<vtkPolyData> ThinTubes()
{
  vtkNew<vtkAppendPolyData> tubes;
  for (int t = 0; t < 3; ++t)
  {
    constexpr int n = 400;
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> line;
    line->InsertNextCell(n);
    for (int i = 0; i < n; ++i)
    {
      const double angle = 0.05 * i + 2.0 * t;
      line->InsertCellPoint(points->InsertNextPoint(
        0.3 * std::cos(angle), 0.3 * std::sin(angle), -1.0 + 2.0 * i / n));
    }
    vtkNew<vtkPolyData> helix;
    helix->SetPoints(points);
    helix->SetLines(line);
    vtkNew<vtkTubeFilter> tube;
    tube->SetInputData(helix);
    tube->SetRadius(0.02);
    tube->SetNumberOfSides(24);
    tube->CappingOn();
    tube->Update();
    tubes->AddInputData(tube->GetOutput());
  }
  return meshlod::testing::TriangulateAndClean(tubes);
}

// V - E + F over the points the triangles use.
long long EulerCharacteristic(vtkPolyData* mesh)
{
  return static_cast<long long>(meshlod::testing::InspectMesh(mesh).EulerCharacteristic);
}

std::vector<TestMesh> Meshes()
{
  std::vector<TestMesh> meshes;
  meshes.push_back({ "faceted cylinder", "vtkCylinderSource, 64 sides, capped, 4 subdivisions",
    [] {
      vtkNew<vtkCylinderSource> cylinder;
      cylinder->SetResolution(64);
      cylinder->CappingOn();
      return Prepare(cylinder, 4);
    } });
  meshes.push_back({ "parametric torus", "vtkParametricTorus, 300 x 300 (seam closed by rounding)",
    [] {
      vtkNew<vtkParametricTorus> torus;
      vtkNew<vtkParametricFunctionSource> source;
      source->SetParametricFunction(torus);
      source->SetUResolution(300);
      source->SetVResolution(300);
      return Prepare(source, 0);
    } });
  // The same sphere with three noise seeds: at 1% the Hausdorff distance, a maximum, moves by
  // tens of percent from seed to seed for both filters, so one seed alone says little.
  for (const int seed : { 7, 8, 9 })
  {
    meshes.push_back({ "noisy sphere, seed " + std::to_string(seed),
      "vtkSphereSource 400 x 200, radii perturbed by 0.1% (uniform noise, "
      "vtkMinimalStandardRandomSequence)",
      [seed] {
        vtkNew<vtkSphereSource> sphere;
        sphere->SetThetaResolution(400);
        sphere->SetPhiResolution(200);
        vtkSmartPointer<vtkPolyData> mesh = Prepare(sphere, 0);
        meshlod::testing::PerturbRadially(mesh, 0.002, seed);
        return mesh;
      } });
  }
  // Noise of more than an edge: many input triangles face inwards.
  meshes.push_back({ "very noisy sphere",
    "vtkSphereSource 400 x 200, radii perturbed by 4% (uniform noise, seed 7)", [] {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetThetaResolution(400);
      sphere->SetPhiResolution(200);
      vtkSmartPointer<vtkPolyData> mesh = Prepare(sphere, 0);
      meshlod::testing::PerturbRadially(mesh, 0.08, 7);
      return mesh;
    } });
  // Open surfaces, where the boundary's weight against the surface decides how many triangles
  // the boundary keeps: a scan-like surface with holes and a terrain.
  meshes.push_back({ "sphere with holes",
    "icosphere (7 subdivisions), radii scaled by smooth bumps, six holes cut "
    "(MeshLODTestMeshes: MakeBumpySphereWithHoles)",
    [] { return meshlod::testing::MakeBumpySphereWithHoles(7); } });
  meshes.push_back({ "terrain", "400 x 400 grid, heights a sum of sines at six frequencies "
                                "(MeshLODTestMeshes: MakeTerrain)",
    [] { return meshlod::testing::MakeTerrain(400); } });
  // Non-orientable: no orientation of its triangles is consistent everywhere.
  meshes.push_back({ "Boy's surface", "vtkParametricBoy, 300 x 300, no normals", [] {
                      vtkNew<vtkParametricBoy> boy;
                      vtkNew<vtkParametricFunctionSource> source;
                      source->SetParametricFunction(boy);
                      source->SetUResolution(300);
                      source->SetVResolution(300);
                      source->GenerateNormalsOff();
                      return Prepare(source, 0);
                    } });
  meshes.push_back({ "superquadric", "vtkSuperquadricSource 300 x 300, roundness 0.3", [] {
                      vtkNew<vtkSuperquadricSource> superquadric;
                      superquadric->SetThetaResolution(300);
                      superquadric->SetPhiResolution(300);
                      superquadric->SetThetaRoundness(0.3);
                      superquadric->SetPhiRoundness(0.3);
                      return Prepare(superquadric, 0);
                    } });
  // Rough at the scale of its edges, with small handles and specks: as a real scan's
  // isosurface (the noise of a CT volume), unlike the smooth fields of the main benchmark.
  meshes.push_back({ "noisy isosurface",
    "a bumpy sphere's field on a 120^3 grid plus uniform noise of one grid step's change, "
    "flying edges, cleaned (MeshLODTestMeshes: MakeNoisyIsosurface(120, 1.0, 5))",
    [] { return meshlod::testing::MakeNoisyIsosurface(120, 1.0, 5); } });
  // VTK's own test volume: vtkRTAnalyticSource's isosurface is cut open by the volume's faces
  // and full of handles, which vtkQuadricDecimation closes and our levels keep.
  meshes.push_back({ "wavelet isosurface",
    "vtkRTAnalyticSource on [-60, 60]^3, flying edges at 160, cleaned: 7 pieces, open at the "
    "volume's faces, Euler characteristic -53",
    [] { return meshlod::testing::MakeWaveletIsosurface(60); } });
  // A survey or a scan in georeferenced coordinates: far from the origin, in double precision.
  meshes.push_back({ "metaballs, georeferenced",
    "the main benchmark's metaballs isosurface (154,184 triangles) with double coordinates, "
    "moved by (600000, 4000000, 300)",
    [] {
      vtkSmartPointer<vtkPolyData> surface = meshlod::testing::MakeIsosurface(
        meshlod::testing::Field::Metaballs,
        meshlod::testing::ResolutionForTriangles(meshlod::testing::Field::Metaballs, 150000));
      vtkNew<vtkPoints> points;
      points->SetDataType(VTK_DOUBLE);
      points->SetNumberOfPoints(surface->GetNumberOfPoints());
      for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
      {
        double x[3];
        surface->GetPoint(p, x);
        points->SetPoint(p, x[0] + 6.0e5, x[1] + 4.0e6, x[2] + 300.0);
      }
      vtkNew<vtkPolyData> moved;
      moved->SetPoints(points);
      moved->SetPolys(surface->GetPolys());
      return vtkSmartPointer<vtkPolyData>(moved);
    } });
  meshes.push_back({ "segmented balls",
    "three overlapping balls labelled in a 128^3 volume: vtkDiscreteFlyingEdges3D, faces "
    "between labels once (vtkRemoveDuplicatePolys), vtkWindowedSincPolyDataFilter (20 "
    "iterations, pass band 0.05); three sheets meet along each curve where balls touch",
    [] { return SegmentedBalls(128); } });
  meshes.push_back({ "segmentation mask",
    "an ellipsoid's binary mask on a 160^3 grid, flying edges at 0.5 (terraced), cleaned",
    [] { return MaskIsosurface(160); } });
  meshes.push_back({ "thin tubes",
    "three capped tubes (vtkTubeFilter, 24 sides) of radius 1% of the diagonal around helices",
    [] { return ThinTubes(); } });
  return meshes;
}

// a / b, for distances that may be 0.
double Ratio(double a, double b)
{
  return b > 0.0 ? a / b : (a > 0.0 ? 1e9 : 1.0);
}

// The level of `hierarchy` whose triangle count is nearest to `target`.
vtkPolyData* Nearest(vtkMultiBlockDataSet* hierarchy, vtkIdType target)
{
  vtkPolyData* best = nullptr;
  for (unsigned int i = 0; i < hierarchy->GetNumberOfBlocks(); ++i)
  {
    auto* level = vtkPolyData::SafeDownCast(hierarchy->GetBlock(i));
    if (!best ||
      std::llabs(level->GetNumberOfPolys() - target) < std::llabs(best->GetNumberOfPolys() - target))
    {
      best = level;
    }
  }
  return best;
}
void PrintQuadricDecimationHeader()
{
  std::printf("| mesh | triangles | target | output triangles | vtkQuadricDecimation triangles | "
              "Hausdorff %% | RMS %% | vtkQuadricDecimation Hausdorff %% | RMS %% | "
              "Hausdorff x QD | RMS x QD | Euler characteristic: level 0, ours, QD |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
}

// The rows of a hierarchy's levels nearest 10% and 1% of the input against vtkQuadricDecimation
// at the same triangle counts.
std::string QuadricDecimationRows(const TestMesh& test, vtkPolyData* mesh,
  vtkTriangleCollapseDecimation* decimate, const meshlod::SurfaceDistanceOptions& options)
{
  const vtkIdType triangles = mesh->GetNumberOfPolys();
  std::string rows;
  for (const double fraction : { 0.1, 0.01 })
  {
    vtkPolyData* level =
      Nearest(decimate->GetHierarchy(), static_cast<vtkIdType>(fraction * triangles));
    vtkNew<vtkQuadricDecimation> peer;
    peer->SetInputData(mesh);
    peer->SetTargetReduction(
      1.0 - static_cast<double>(level->GetNumberOfPolys()) / static_cast<double>(triangles));
    peer->Update();
    const meshlod::SurfaceDistance ours = meshlod::MeasureSurfaceDistance(mesh, level, options);
    const meshlod::SurfaceDistance theirs =
      meshlod::MeasureSurfaceDistance(mesh, peer->GetOutput(), options);
    char row[512];
    std::snprintf(row, sizeof(row),
      "| %s | %lld | %g%% | %lld | %lld | %.3g | %.3g | %.3g | %.3g | %.2f | %.2f | %lld, %lld, "
      "%lld |\n",
      test.Name.c_str(), static_cast<long long>(triangles), 100.0 * fraction,
      static_cast<long long>(level->GetNumberOfPolys()),
      static_cast<long long>(peer->GetOutput()->GetNumberOfPolys()), ours.HausdorffPercent(),
      ours.RmsPercent(), theirs.HausdorffPercent(), theirs.RmsPercent(),
      Ratio(ours.Hausdorff, theirs.Hausdorff), Ratio(ours.Rms, theirs.Rms),
      EulerCharacteristic(vtkPolyData::SafeDownCast(decimate->GetHierarchy()->GetBlock(0))),
      EulerCharacteristic(level), EulerCharacteristic(peer->GetOutput()));
    rows += row;
  }
  return rows;
}
} // namespace

int main(int argc, char* argv[])
{
  int exitCode = 0;
  if (!meshlod::benchmark::NumberArguments(argc, argv, 1, false,
        "[samples (surface samples per side for the distances, default 100000)]", exitCode))
  {
    return exitCode;
  }
  meshlod::SurfaceDistanceOptions options;
  options.SamplesPerSurface = argc > 1 ? std::atoll(argv[1]) : 100000;
  options.MaximumVertexSamples = options.SamplesPerSurface;

  PrintQuadricDecimationHeader();
  std::vector<std::string> notes;
  // The octree and the grid clustering come from the main benchmark's registry, with its
  // settings (the octree's levels at the targets, the grid searched for the octree's count).
  std::vector<meshlod::benchmark::Method> methods;
  meshlod::benchmark::RegisterVTKMethods(methods);
  meshlod::benchmark::RegisterMeshLODMethods(methods);
  using meshlod::benchmark::FindMethod;
  const meshlod::benchmark::Method& octree = FindMethod(methods, "vtkVertexClusterOctree");
  const meshlod::benchmark::Method& flipped =
    FindMethod(methods, "vtkVertexClusterOctree flipped edges");
  const meshlod::benchmark::Method& free =
    FindMethod(methods, "vtkVertexClusterOctree free topology");
  const meshlod::benchmark::Method& grid = FindMethod(methods, "vtkQuadricClustering");
  std::ostringstream octreeRows, curvatureRows, uniformRows, paperCostRows, freeTopologyRows;
  // The survey meshes go through the defaults only: the first table and the octree's.
  std::vector<TestMesh> meshes = Meshes();
  const std::size_t variantMeshes = meshes.size();
  for (TestMesh& survey : meshlod::benchmark::SurveyMeshes())
  {
    meshes.push_back(std::move(survey));
  }
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const TestMesh& test = meshes[m];
    vtkSmartPointer<vtkPolyData> mesh = test.Make();
    const vtkIdType triangles = mesh->GetNumberOfPolys();
    notes.push_back("- " + test.Name + ": " + test.Description);
    // vtkTriangleCollapseDecimation on the mesh, defaults but for what `configure` sets.
    auto reduce = [&](const std::function<void(vtkTriangleCollapseDecimation*)>& configure) {
      auto decimate = vtkSmartPointer<vtkTriangleCollapseDecimation>::New();
      decimate->SetInputData(mesh);
      configure(decimate);
      decimate->Update();
      return decimate;
    };
    const auto decimate = reduce([](vtkTriangleCollapseDecimation*) {});
    std::printf("%s", QuadricDecimationRows(test, mesh, decimate, options).c_str());
    std::fflush(stdout);
    if (m < variantMeshes)
    {
      // PreserveTopology off changes only meshes with small closed pieces.
      const auto freeTopology =
        reduce([](vtkTriangleCollapseDecimation* d) { d->PreserveTopologyOff(); });
      if (meshlod::testing::CountDifferingLevels(
            decimate->GetHierarchy(), freeTopology->GetHierarchy()) > 0)
      {
        freeTopologyRows << QuadricDecimationRows(test, mesh, freeTopology, options);
      }
      curvatureRows << QuadricDecimationRows(test, mesh,
        reduce([](vtkTriangleCollapseDecimation* d) { d->SetMethodToCurvature(); }), options);
      uniformRows << QuadricDecimationRows(test, mesh,
        reduce([](vtkTriangleCollapseDecimation* d) { d->SetPlaneWeightsToUniform(); }), options);
      paperCostRows << QuadricDecimationRows(test, mesh,
        reduce([](vtkTriangleCollapseDecimation* d) { d->SetAreaNormalization(0.0); }), options);
    }
    const std::vector<vtkIdType> targets = { triangles / 10, triangles / 100 };
    const std::vector<vtkSmartPointer<vtkPolyData>> levels = octree.Hierarchy(mesh, targets);
    // FlipEdges changes no count: the same grid answers both.
    const std::vector<vtkSmartPointer<vtkPolyData>> flippedLevels = flipped.Hierarchy(mesh, targets);
    // PreserveTopology off reaches other counts: its own grid.
    const std::vector<vtkSmartPointer<vtkPolyData>> freeLevels = free.Hierarchy(mesh, targets);
    // A level's distance to the input, the grid searched for the level's count, and the grid's
    // distance.
    struct AgainstGrid
    {
      meshlod::SurfaceDistance Ours, Theirs;
      vtkIdType GridTriangles;
    };
    auto againstGrid = [&](vtkPolyData* level) {
      const vtkSmartPointer<vtkPolyData> peer = grid.Prepare(mesh, level->GetNumberOfPolys())();
      return AgainstGrid{ meshlod::MeasureSurfaceDistance(mesh, level, options),
        meshlod::MeasureSurfaceDistance(mesh, peer, options), peer->GetNumberOfPolys() };
    };
    for (std::size_t i = 0; i < targets.size(); ++i)
    {
      vtkPolyData* level = levels[i];
      const auto [ours, theirs, gridTriangles] = againstGrid(level);
      const meshlod::SurfaceDistance flips =
        meshlod::MeasureSurfaceDistance(mesh, flippedLevels[i], options);
      vtkPolyData* freeLevel = freeLevels[i];
      const auto [freeOurs, freeTheirs, freeGridTriangles] = againstGrid(freeLevel);
      char row[512];
      std::snprintf(row, sizeof(row),
        "| %s | %lld | %lld | %lld | %lld | %.3g | %.3g | %.3g | %.3g | %.2f | %.2f | %.2f, %.2f "
        "| %lld, %.2f, %.2f |\n",
        test.Name.c_str(), static_cast<long long>(triangles),
        static_cast<long long>(targets[i]), static_cast<long long>(level->GetNumberOfPolys()),
        static_cast<long long>(gridTriangles), ours.HausdorffPercent(),
        ours.RmsPercent(), theirs.HausdorffPercent(), theirs.RmsPercent(),
        Ratio(ours.Hausdorff, theirs.Hausdorff), Ratio(ours.Rms, theirs.Rms),
        Ratio(flips.Hausdorff, theirs.Hausdorff), Ratio(flips.Rms, theirs.Rms),
        static_cast<long long>(freeLevel->GetNumberOfPolys()),
        Ratio(freeOurs.Hausdorff, freeTheirs.Hausdorff), Ratio(freeOurs.Rms, freeTheirs.Rms));
      octreeRows << row;
    }
  }
  std::printf("\n");
  for (const std::string& note : notes)
  {
    std::printf("%s\n", note.c_str());
  }
  std::printf("\nvtkVertexClusterOctree (levels at 10%% and 1%% of the input) and vtkQuadricClustering "
              "(grid searched for the octree's count) on the same meshes; a count the octree "
              "misses is reported by a warning, and the grid is compared at the count reached; the "
              "next column is the octree with FlipEdges on (same counts), the last with "
              "PreserveTopology off (its count, and the grid searched for that count):\n\n");
  std::printf("| mesh | triangles | target | octree triangles | vtkQuadricClustering triangles | "
              "Hausdorff %% | RMS %% | vtkQuadricClustering Hausdorff %% | RMS %% | "
              "Hausdorff x QC | RMS x QC | flipped edges: Hausdorff, RMS x QC | "
              "free topology: triangles, Hausdorff, RMS x QC |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::printf("%s", octreeRows.str().c_str());
  std::printf("\nvtkTriangleCollapseDecimation's curvature method (SetMethodToCurvature(), "
              "defaults otherwise) and vtkQuadricDecimation, as in the first table:\n\n");
  PrintQuadricDecimationHeader();
  std::printf("%s", curvatureRows.str().c_str());
  std::printf("\nvtkTriangleCollapseDecimation with PlaneWeights UNIFORM_WEIGHTS (every plane "
              "weighs the input's mean triangle area, as vtkQuadricDecimation weighs them; "
              "defaults otherwise) and vtkQuadricDecimation, as in the first table:\n\n");
  PrintQuadricDecimationHeader();
  std::printf("%s", uniformRows.str().c_str());
  std::printf("\nvtkTriangleCollapseDecimation with AreaNormalization 0 (a collapse costs its merged "
              "quadric's value, paper 002's cost, not divided by the surface it stands for; "
              "defaults otherwise) and vtkQuadricDecimation, as in the first table:\n\n");
  PrintQuadricDecimationHeader();
  std::printf("%s", paperCostRows.str().c_str());
  std::printf("\nvtkTriangleCollapseDecimation with PreserveTopology off (small closed pieces may "
              "vanish; defaults otherwise) and vtkQuadricDecimation, as in the first table, on "
              "the meshes where it changes a level:\n\n");
  PrintQuadricDecimationHeader();
  std::printf("%s", freeTopologyRows.str().c_str());
  return 0;
}
