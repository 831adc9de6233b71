// Both filters give the same hierarchy, up to the transform, for an input scaled by a power of
// two (a part modelled in metres or in nanometres) or moved far from the origin with double
// coordinates (a scan in georeferenced coordinates): no tolerance anywhere is absolute. The
// measured level errors, the baked textures and the geomorph included, which use cell locators
// (VTK pads their cells by an absolute 0.001 by default, which ran out of memory on a larger
// surface this small: TestSurfaceDistance guards that), and the seams level 0 stitches.
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace
{
using namespace meshlod;

struct Similarity
{
  std::string Name;
  double Scale;
  double Offset[3];

  void Apply(const double x[3], double y[3]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      y[k] = this->Scale * x[k] + this->Offset[k];
    }
  }
};

// `surface` (by default the metaballs isosurface) transformed, with double points, a colour
// array (the active scalars, which the octree bakes) and a float array, both functions of the
// untransformed position.
vtkSmartPointer<vtkPolyData> MakeInput(const Similarity& transform, vtkPolyData* surface)
{
  const vtkIdType n = surface->GetNumberOfPoints();
  vtkNew<vtkPoints> points;
  points->SetDataType(VTK_DOUBLE);
  points->SetNumberOfPoints(n);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> field;
  field->SetName("Field");
  field->SetNumberOfTuples(n);
  for (vtkIdType p = 0; p < n; ++p)
  {
    double x[3], y[3];
    surface->GetPoint(p, x);
    transform.Apply(x, y);
    points->SetPoint(p, y);
    for (int k = 0; k < 3; ++k)
    {
      const double value = 127.5 + 127.0 * std::sin(5.0 * x[k]);
      colors->SetTypedComponent(p, k, static_cast<unsigned char>(value));
    }
    field->SetValue(p, static_cast<float>(x[0] * x[1] - x[2]));
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(surface->GetPolys());
  mesh->GetPointData()->SetScalars(colors);
  mesh->GetPointData()->AddArray(field);
  return mesh;
}

vtkSmartPointer<vtkPolyData> MakeInput(const Similarity& transform)
{
  return MakeInput(transform, testing::MakeIsosurface(testing::Field::Metaballs, 40));
}

double Diagonal(vtkPolyData* mesh)
{
  double b[6];
  mesh->GetBounds(b);
  return std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
}

// The largest coordinate difference between moved's points and plain's points transformed:
// 0 for a scale by a power of two; an offset rounds differently.
double LargestMove(vtkPolyData* plain, vtkPolyData* moved, const Similarity& transform)
{
  double largest = 0.0;
  for (vtkIdType p = 0; p < plain->GetNumberOfPoints() && p < moved->GetNumberOfPoints(); ++p)
  {
    double x[3], expected[3], y[3];
    plain->GetPoint(p, x);
    transform.Apply(x, expected);
    moved->GetPoint(p, y);
    for (int k = 0; k < 3; ++k)
    {
      largest = std::max(largest, std::abs(y[k] - expected[k]));
    }
  }
  return largest;
}

double FieldValue(vtkPolyData* level, const char* name)
{
  vtkDataArray* array = level->GetFieldData()->GetArray(name);
  return array ? array->GetComponent(0, 0) : -1.0;
}

// Level by level: the same triangles on the transformed points, the same point data, and the
// errors (world units) scaled.
void CompareHierarchies(vtkMultiBlockDataSet* plain, vtkMultiBlockDataSet* moved,
  const Similarity& transform, const char* filter)
{
  std::cout << filter << ", " << transform.Name << "\n";
  MESHLOD_CHECK_GT(plain->GetNumberOfBlocks(), 2u);
  MESHLOD_CHECK_EQ(moved->GetNumberOfBlocks(), plain->GetNumberOfBlocks());
  for (unsigned int i = 0; i < plain->GetNumberOfBlocks() && i < moved->GetNumberOfBlocks(); ++i)
  {
    auto* a = vtkPolyData::SafeDownCast(plain->GetBlock(i));
    auto* b = vtkPolyData::SafeDownCast(moved->GetBlock(i));
    MESHLOD_CHECK(a && b);
    if (!a || !b)
    {
      continue;
    }
    MESHLOD_CHECK_EQ(b->GetNumberOfPolys(), a->GetNumberOfPolys());
    MESHLOD_CHECK_EQ(b->GetNumberOfPoints(), a->GetNumberOfPoints());
    // Double in, double out: float points near 4e6 would round a level to a quarter unit.
    MESHLOD_CHECK_EQ(b->GetPoints()->GetDataType(), VTK_DOUBLE);
    if (b->GetNumberOfPoints() != a->GetNumberOfPoints())
    {
      continue;
    }
    MESHLOD_CHECK(testing::Triangles(a) == testing::Triangles(b));
    const double tolerance = 1e-6 * Diagonal(b);
    const bool scaleAlone =
      transform.Offset[0] == 0.0 && transform.Offset[1] == 0.0 && transform.Offset[2] == 0.0;
    MESHLOD_CHECK_LE(LargestMove(a, b, transform), scaleAlone ? 0.0 : tolerance);
    for (const char* name : { "Field", names::MorphTargetId })
    {
      vtkDataArray* fa = a->GetPointData()->GetArray(name);
      vtkDataArray* fb = b->GetPointData()->GetArray(name);
      if (i + 1 == plain->GetNumberOfBlocks() && fa == nullptr)
      {
        continue; // the coarsest level has no MorphTargetId
      }
      MESHLOD_CHECK(fa && fb);
      double difference = 0.0;
      for (vtkIdType p = 0; fa && fb && p < a->GetNumberOfPoints(); ++p)
      {
        difference =
          std::max(difference, std::abs(fa->GetComponent(p, 0) - fb->GetComponent(p, 0)));
      }
      MESHLOD_CHECK_LE(difference, 1e-5);
    }
    for (const char* name : { names::EstimatedError, names::MeasuredHausdorff, names::MeasuredRMS })
    {
      const double ea = FieldValue(a, name), eb = FieldValue(b, name);
      MESHLOD_CHECK_GE(ea, 0.0);
      MESHLOD_CHECK_NEAR(eb, transform.Scale * ea, 1e-6 * transform.Scale * ea + tolerance);
    }
  }
}

// The geomorph between the first two levels, half way: the transformed points.
void CompareGeomorphs(vtkMultiBlockDataSet* plain, vtkMultiBlockDataSet* moved,
  const Similarity& transform)
{
  vtkNew<vtkLODGeomorph> a, b;
  a->SetInputData(plain);
  b->SetInputData(moved);
  for (vtkLODGeomorph* morph : { a.Get(), b.Get() })
  {
    morph->SetLevelOfDetail(0.5);
    morph->Update();
  }
  vtkPolyData* pa = a->GetOutput();
  vtkPolyData* pb = b->GetOutput();
  MESHLOD_CHECK_GT(pa->GetNumberOfPolys(), 0);
  MESHLOD_CHECK_EQ(pb->GetNumberOfPolys(), pa->GetNumberOfPolys());
  MESHLOD_CHECK_EQ(pb->GetNumberOfPoints(), pa->GetNumberOfPoints());
  MESHLOD_CHECK_LE(LargestMove(pa, pb, transform), 1e-6 * Diagonal(pb));
}

void CompareTextures(vtkMultiBlockDataSet* plain, vtkMultiBlockDataSet* moved)
{
  MESHLOD_CHECK_GT(plain->GetNumberOfBlocks(), 1u);
  MESHLOD_CHECK_EQ(moved->GetNumberOfBlocks(), plain->GetNumberOfBlocks());
  for (unsigned int i = 1; i < plain->GetNumberOfBlocks() && i < moved->GetNumberOfBlocks(); ++i)
  {
    auto* a = vtkImageData::SafeDownCast(plain->GetBlock(i));
    auto* b = vtkImageData::SafeDownCast(moved->GetBlock(i));
    MESHLOD_CHECK(a && b);
    if (!a || !b)
    {
      continue;
    }
    vtkDataArray* ta = a->GetPointData()->GetScalars();
    vtkDataArray* tb = b->GetPointData()->GetScalars();
    MESHLOD_CHECK(ta && tb);
    if (!ta || !tb)
    {
      continue;
    }
    MESHLOD_CHECK_EQ(tb->GetNumberOfValues(), ta->GetNumberOfValues());
    MESHLOD_CHECK_EQ(tb->GetNumberOfComponents(), ta->GetNumberOfComponents());
    // Colours interpolated at the nearest surface point: a texel near a tie may round by one.
    double largest = 0.0;
    const int components = ta->GetNumberOfComponents();
    for (vtkIdType v = 0; v < ta->GetNumberOfValues() && v < tb->GetNumberOfValues(); ++v)
    {
      const vtkIdType tuple = v / components;
      const int component = static_cast<int>(v % components);
      largest = std::max(largest,
        std::abs(ta->GetComponent(tuple, component) - tb->GetComponent(tuple, component)));
    }
    MESHLOD_CHECK_LE(largest, 1.0);
  }
}

// Runs `Filter`, set up by `configure`, on the input under each transform and compares the
// results with the untransformed run's (the first transform is the identity).
template <typename Filter, typename Configure>
void TestFilter(const std::vector<Similarity>& transforms, const char* name, Configure configure,
  vtkPolyData* surface = nullptr)
{
  const auto input = [surface](const Similarity& transform) {
    return surface ? MakeInput(transform, surface) : MakeInput(transform);
  };
  vtkNew<Filter> reference;
  configure(input(transforms.front()), reference.Get());
  for (size_t t = 1; t < transforms.size(); ++t)
  {
    vtkNew<Filter> filter;
    configure(input(transforms[t]), filter.Get());
    CompareHierarchies(reference->GetHierarchy(), filter->GetHierarchy(), transforms[t], name);
    CompareGeomorphs(reference->GetHierarchy(), filter->GetHierarchy(), transforms[t]);
    if constexpr (std::is_same_v<Filter, vtkVertexClusterOctree>)
    {
      CompareTextures(reference->GetTextures(), filter->GetTextures());
    }
  }
}
// A parametric torus's seam points differ in their last bits: level 0 stitches them at the
// origin and far from it alike (there the last bits are worth far more than 1e-12 of the
// diagonal, which alone left the moved torus open along its seam).
void TestSeamFarFromOrigin()
{
  vtkNew<vtkParametricTorus> torus;
  vtkNew<vtkParametricFunctionSource> source;
  source->SetParametricFunction(torus);
  source->SetUResolution(40);
  source->SetVResolution(40);
  source->GenerateTextureCoordinatesOff();
  source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  source->Update();
  for (const double offset : { 0.0, 4.0e6 })
  {
    vtkNew<vtkPolyData> surface;
    surface->DeepCopy(source->GetOutput());
    surface->GetPointData()->Initialize(); // normals differ across the seam
    // The copies of a seam point differ in their last two bits at their own magnitude (adding
    // the offset would round the source's own differences away).
    std::map<std::array<long long, 3>, vtkIdType> first;
    int nudged = 0;
    for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p)
    {
      double x[3];
      surface->GetPoint(p, x);
      const std::array<long long, 3> key = { std::llround(1e6 * x[0]), std::llround(1e6 * x[1]),
        std::llround(1e6 * x[2]) };
      x[0] += offset;
      x[1] -= 0.5 * offset;
      if (!first.emplace(key, p).second)
      {
        x[0] = std::nextafter(std::nextafter(x[0], 1e300), 1e300);
        ++nudged;
      }
      surface->GetPoints()->SetPoint(p, x);
    }
    MESHLOD_CHECK_GT(nudged, 40);
    vtkNew<vtkTriangleCollapseDecimation> filter;
    filter->SetInputData(surface);
    filter->SetNumberOfLevels(1);
    filter->Update();
    vtkPolyData* level0 = vtkPolyData::SafeDownCast(filter->GetHierarchy()->GetBlock(0));
    MESHLOD_CHECK(level0 != nullptr);
    if (level0)
    {
      const testing::MeshReport report = testing::InspectMesh(level0);
      MESHLOD_CHECK_EQ(report.BoundaryEdges, 0);
      MESHLOD_CHECK_EQ(report.EulerCharacteristic, 0);
    }
  }
}
} // namespace

int TestMeshLODTransformInvariance(int, char*[])
{
  const std::vector<Similarity> transforms = {
    { "identity", 1.0, { 0.0, 0.0, 0.0 } },
    { "scaled by 2^-20", std::ldexp(1.0, -20), { 0.0, 0.0, 0.0 } },
    { "scaled by 2^-40", std::ldexp(1.0, -40), { 0.0, 0.0, 0.0 } },
    { "scaled by 2^30", std::ldexp(1.0, 30), { 0.0, 0.0, 0.0 } },
    // Near the ends of the accepted diagonals (1e-30, 1e30): squared lengths in single
    // precision (the centring's sample areas) overflowed or vanished there.
    { "scaled by 2^-75", std::ldexp(1.0, -75), { 0.0, 0.0, 0.0 } },
    { "scaled by 2^75", std::ldexp(1.0, 75), { 0.0, 0.0, 0.0 } },
    { "moved by (6e5, 4e6, 300)", 1.0, { 6.0e5, 4.0e6, 300.0 } },
  };
  TestFilter<vtkTriangleCollapseDecimation>(transforms, "vtkTriangleCollapseDecimation",
    [](vtkPolyData* input, vtkTriangleCollapseDecimation* filter) {
      filter->SetInputData(input);
      filter->SetNumberOfLevels(4);
      filter->ComputeLevelErrorOn();
      filter->Update();
    });
  TestFilter<vtkVertexClusterOctree>(transforms, "vtkVertexClusterOctree",
    [](vtkPolyData* input, vtkVertexClusterOctree* filter) {
      filter->SetInputData(input);
      filter->SetLevelModeToTargetTriangleCounts();
      filter->AddTargetTriangleCount(input->GetNumberOfPolys() / 10);
      filter->AddTargetTriangleCount(input->GetNumberOfPolys() / 50);
      filter->MeasureLevelErrorsOn();
      filter->BakeTextureOn();
      filter->SetTextureResolution(64);
      filter->Update();
    });
  TestSeamFarFromOrigin();

  // Near the ends of the accepted diagonals (1e-30 to 1e30), on surfaces that reach the
  // collapse rules the smooth metaballs do not: a noisy sphere (triangles turning against the
  // surface's facing) and a flat grid (every collapse free, ordered by how far it moves
  // points). Both keep squared lengths in single precision, which overflowed or vanished there.
  const std::vector<Similarity> extremes = {
    { "identity", 1.0, { 0.0, 0.0, 0.0 } },
    { "scaled by 2^-95", std::ldexp(1.0, -95), { 0.0, 0.0, 0.0 } },
    { "scaled by 2^93", std::ldexp(1.0, 93), { 0.0, 0.0, 0.0 } },
  };
  vtkSmartPointer<vtkPolyData> noisy = testing::MakeIcosphere(4);
  testing::PerturbRadially(noisy, 0.05, 3);
  vtkSmartPointer<vtkPolyData> grid = testing::MakeGrid(32, 32);
  for (vtkPolyData* surface : { noisy.Get(), grid.Get() })
  {
    TestFilter<vtkTriangleCollapseDecimation>(extremes, "vtkTriangleCollapseDecimation",
      [](vtkPolyData* input, vtkTriangleCollapseDecimation* filter) {
        filter->SetInputData(input);
        filter->SetNumberOfLevels(4);
        filter->ComputeLevelErrorOn();
        filter->Update();
      },
      surface);
  }
  return testing::Result();
}
