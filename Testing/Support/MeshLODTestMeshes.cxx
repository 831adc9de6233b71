#include "MeshLODTestMeshes.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkSMPTools.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

namespace meshlod
{
namespace testing
{
namespace
{
double FieldValue(Field field, double x, double y, double z)
{
  switch (field)
  {
    case Field::Sphere:
      return std::sqrt(x * x + y * y + z * z) - 0.7;
    case Field::Torus:
    {
      const double ring = std::sqrt(x * x + y * y) - 0.55;
      return ring * ring + z * z - 0.25 * 0.25;
    }
    case Field::Metaballs:
    {
      // Five blobs of different sizes, close enough to fuse into one surface.
      static const double blobs[5][4] = { { -0.35, -0.2, 0.0, 0.11 }, { 0.3, -0.25, 0.05, 0.08 },
        { 0.0, 0.35, -0.1, 0.09 }, { 0.05, 0.0, 0.4, 0.05 }, { -0.1, 0.05, -0.4, 0.04 } };
      double sum = 0.0;
      for (const auto& b : blobs)
      {
        const double dx = x - b[0], dy = y - b[1], dz = z - b[2];
        sum += b[3] / (dx * dx + dy * dy + dz * dz + 1e-9);
      }
      return 1.0 - sum;
    }
    case Field::Gyroid:
    {
      const double k = 1.5 * 3.14159265358979323846;
      return std::sin(k * x) * std::cos(k * y) + std::sin(k * y) * std::cos(k * z) +
        std::sin(k * z) * std::cos(k * x);
    }
    case Field::Wavelet:
      break;
  }
  return 0.0;
}
} // namespace

//------------------------------------------------------------------------------
const char* FieldName(Field field)
{
  switch (field)
  {
    case Field::Sphere:
      return "sphere";
    case Field::Torus:
      return "torus";
    case Field::Metaballs:
      return "metaballs";
    case Field::Gyroid:
      return "gyroid";
    case Field::Wavelet:
      return "wavelet";
  }
  return "unknown";
}

bool FieldFromName(const std::string& name, Field& field)
{
  for (Field f : { Field::Sphere, Field::Torus, Field::Metaballs, Field::Gyroid, Field::Wavelet })
  {
    if (name == FieldName(f))
    {
      field = f;
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> SampleField(Field field, int resolution)
{
  const double spacing = 2.0 / (resolution - 1);
  if (field == Field::Wavelet)
  {
    // VTK's wavelet source, rescaled to [-1, 1]^3 so all fields share one frame.
    vtkNew<vtkRTAnalyticSource> wavelet;
    const int half = (resolution - 1) / 2;
    wavelet->SetWholeExtent(-half, half, -half, half, -half, half);
    wavelet->SetXFreq(60.0 * 10.0 / half);
    wavelet->SetYFreq(30.0 * 10.0 / half);
    wavelet->SetZFreq(40.0 * 10.0 / half);
    wavelet->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->ShallowCopy(wavelet->GetOutput());
    image->SetSpacing(1.0 / half, 1.0 / half, 1.0 / half);
    image->SetOrigin(0.0, 0.0, 0.0);
    image->GetPointData()->GetScalars()->SetName("Field");
    return image;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(resolution, resolution, resolution);
  image->SetOrigin(-1.0, -1.0, -1.0);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkFloatArray> values;
  values->SetName("Field");
  const vtkIdType n = static_cast<vtkIdType>(resolution) * resolution * resolution;
  values->SetNumberOfValues(n);
  float* out = values->GetPointer(0);
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      const int ix = static_cast<int>(i % resolution);
      const int iy = static_cast<int>((i / resolution) % resolution);
      const int iz = static_cast<int>(i / (static_cast<vtkIdType>(resolution) * resolution));
      out[i] = static_cast<float>(
        FieldValue(field, -1.0 + ix * spacing, -1.0 + iy * spacing, -1.0 + iz * spacing));
    }
  });
  image->GetPointData()->SetScalars(values);
  return image;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MakeIsosurface(
  Field field, int resolution, bool computeNormals, bool computeScalars)
{
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(SampleField(field, resolution));
  contour->SetValue(0, field == Field::Wavelet ? 157.0 : 0.0);
  contour->SetComputeNormals(computeNormals);
  contour->SetComputeGradients(false);
  contour->SetComputeScalars(computeScalars);
  contour->Update();
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->ShallowCopy(contour->GetOutput());
  return surface;
}

int ResolutionForTriangles(Field field, double triangles)
{
  const int probe = 64;
  const double probed = static_cast<double>(MakeIsosurface(field, probe)->GetNumberOfPolys());
  return std::max(8, static_cast<int>(std::lround(probe * std::sqrt(triangles / probed))));
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MakePolyData(
  const std::vector<double>& points, const std::vector<long long>& triangles)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (size_t i = 0; i + 2 < points.size(); i += 3)
  {
    pts->InsertNextPoint(points[i], points[i + 1], points[i + 2]);
  }
  vtkNew<vtkCellArray> polys;
  for (size_t i = 0; i + 2 < triangles.size(); i += 3)
  {
    const vtkIdType ids[3] = { static_cast<vtkIdType>(triangles[i]),
      static_cast<vtkIdType>(triangles[i + 1]), static_cast<vtkIdType>(triangles[i + 2]) };
    polys->InsertNextCell(3, ids);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(pts);
  mesh->SetPolys(polys);
  return mesh;
}

vtkSmartPointer<vtkPolyData> MakeTwinTouchingAt(vtkPolyData* mesh,
  vtkIdType first,
  vtkIdType second,
  const std::function<void(double[3])>& move,
  bool mirrored)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<double> points;
  std::vector<long long> triangles;
  for (int copy = 0; copy < 2; ++copy)
  {
    for (vtkIdType p = 0; p < n; ++p)
    {
      double x[3];
      mesh->GetPoint(p, x);
      if (copy == 1)
      {
        move(x);
      }
      points.insert(points.end(), x, x + 3);
    }
    vtkIdType size;
    const vtkIdType* ids;
    for (vtkIdType c = 0; c < mesh->GetNumberOfPolys(); ++c)
    {
      mesh->GetPolys()->GetCellAtId(c, size, ids);
      for (const int k : { 0, mirrored && copy == 1 ? 2 : 1, mirrored && copy == 1 ? 1 : 2 })
      {
        triangles.push_back(copy == 1 && ids[k] == second ? first : copy * n + ids[k]);
      }
    }
  }
  return MakePolyData(points, triangles);
}

// Grid points are numbered row by row: point (i, j) = j * (nx + 1) + i at (i, j, 0).
// Square (i, j) becomes triangles (a, b, c) and (a, c, d), counter-clockwise seen from +z.
vtkSmartPointer<vtkPolyData> MakeGrid(int nx, int ny)
{
  std::vector<double> points;
  for (int j = 0; j <= ny; ++j)
  {
    for (int i = 0; i <= nx; ++i)
    {
      points.insert(points.end(), { double(i), double(j), 0.0 });
    }
  }
  std::vector<long long> triangles;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const long long a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      triangles.insert(triangles.end(), { a, b, c, a, c, d });
    }
  }
  return MakePolyData(points, triangles);
}

vtkSmartPointer<vtkPolyData> MakeQuadGrid(int nx, int ny)
{
  vtkSmartPointer<vtkPolyData> grid = MakeGrid(nx, ny);
  vtkNew<vtkCellArray> quads;
  for (vtkIdType j = 0; j < ny; ++j)
  {
    for (vtkIdType i = 0; i < nx; ++i)
    {
      const vtkIdType a = j * (nx + 1) + i;
      const vtkIdType corners[4] = { a, a + 1, a + nx + 2, a + nx + 1 };
      quads->InsertNextCell(4, corners);
    }
  }
  grid->SetPolys(quads);
  return grid;
}

vtkSmartPointer<vtkPolyData> MakeFan(int n)
{
  std::vector<double> points = { 0.0, 0.0, 0.3 };
  for (int i = 0; i < n; ++i)
  {
    const double a = 2.0 * vtkMath::Pi() * i / n;
    points.insert(points.end(), { std::cos(a), std::sin(a), 0.05 * std::sin(7.0 * a) });
  }
  std::vector<long long> triangles;
  for (int i = 0; i < n; ++i)
  {
    triangles.insert(triangles.end(), { 0, 1 + i, 1 + (i + 1) % n });
  }
  return MakePolyData(points, triangles);
}

vtkSmartPointer<vtkPolyData> MakeFlatFanInRing(int n)
{
  std::vector<double> points = { 0.0, 0.0, 0.0 };
  for (const double radius : { 1.0, 2.0 })
  {
    for (int i = 0; i < n; ++i)
    {
      const double a = 2.0 * vtkMath::Pi() * i / n;
      points.insert(points.end(), { radius * std::cos(a), radius * std::sin(a), 0.0 });
    }
  }
  std::vector<long long> triangles;
  for (long long i = 0; i < n; ++i)
  {
    const long long j = (i + 1) % n;
    triangles.insert(triangles.end(), { 0, 1 + i, 1 + j });
    triangles.insert(triangles.end(), { 1 + i, 1 + n + i, 1 + n + j });
    triangles.insert(triangles.end(), { 1 + i, 1 + n + j, 1 + j });
  }
  return MakePolyData(points, triangles);
}

vtkSmartPointer<vtkPolyData> MakeConesSharingApex(int cones, int sides)
{
  std::vector<double> points = { 0.0, 0.0, 0.0 };
  std::vector<long long> triangles;
  const double golden = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  for (int c = 0; c < cones; ++c)
  {
    const double z = 1.0 - 2.0 * (c + 0.5) / cones, r = std::sqrt(1.0 - z * z);
    double d[3] = { r * std::cos(golden * c), r * std::sin(golden * c), z }, u[3], v[3];
    vtkMath::Perpendiculars(d, u, v, 0.0);
    const long long tip = static_cast<long long>(points.size() / 3), rim = tip + 1;
    points.insert(points.end(), d, d + 3);
    for (int i = 0; i < sides; ++i)
    {
      const double a = 2.0 * vtkMath::Pi() * i / sides;
      for (int k = 0; k < 3; ++k)
      {
        points.push_back(0.8 * d[k] + 0.1 * (std::cos(a) * u[k] + std::sin(a) * v[k]));
      }
    }
    for (long long i = 0; i < sides; ++i)
    {
      const long long p = rim + i, q = rim + (i + 1) % sides;
      triangles.insert(triangles.end(), { 0, p, q }); // lateral
      triangles.insert(triangles.end(), { tip, q, p }); // base
    }
  }
  return MakePolyData(points, triangles);
}

void Scale(vtkPolyData* mesh, double scale)
{
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    mesh->GetPoints()->SetPoint(p, scale * x[0], scale * x[1], scale * x[2]);
  }
}

void PerturbRadially(vtkPolyData* mesh, double amplitude, int seed)
{
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(seed);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    const double f = 1.0 + amplitude * (random->GetValue() - 0.5);
    random->Next();
    mesh->GetPoints()->SetPoint(p, f * x[0], f * x[1], f * x[2]);
  }
}

vtkSmartPointer<vtkPolyData> MakeNoisyIsosurface(int resolution, double noise, int seed)
{
  const double step = 2.0 / (resolution - 1);
  const double radius = 0.7;
  const double amplitude = noise * step / radius; // the field changes by step / radius per step
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(resolution, resolution, resolution);
  volume->SetSpacing(step, step, step);
  volume->SetOrigin(-1.0, -1.0, -1.0);
  vtkNew<vtkFloatArray> values;
  values->SetName("Field");
  values->SetNumberOfTuples(static_cast<vtkIdType>(resolution) * resolution * resolution);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(seed);
  vtkIdType i = 0;
  for (int k = 0; k < resolution; ++k)
  {
    for (int j = 0; j < resolution; ++j)
    {
      for (int l = 0; l < resolution; ++l, ++i)
      {
        const double x = -1.0 + l * step, y = -1.0 + j * step, z = -1.0 + k * step;
        const double smooth = 1.0 - std::sqrt(x * x + y * y + z * z) / radius +
          0.15 * std::sin(5.0 * x) * std::sin(4.0 * y) * std::sin(3.0 * z);
        values->SetValue(i, smooth + amplitude * (2.0 * random->GetValue() - 1.0));
        random->Next();
      }
    }
  }
  volume->GetPointData()->SetScalars(values);
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(volume);
  contour->SetValue(0, 0.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(contour->GetOutputPort());
  clean->ConvertPolysToLinesOff(); // a triangle that degenerates goes, rather than becoming a line
  clean->Update();
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->ShallowCopy(clean->GetOutput());
  return surface;
}

vtkSmartPointer<vtkPolyData> TriangulateAndClean(vtkAlgorithm* source)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->Update();
  vtkSmartPointer<vtkPolyData> mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(clean->GetOutput());
  return mesh;
}

vtkSmartPointer<vtkPolyData> MakeWaveletIsosurface(int halfExtent)
{
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(-halfExtent, halfExtent, -halfExtent, halfExtent, -halfExtent, halfExtent);
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputConnection(wavelet->GetOutputPort());
  contour->SetValue(0, 160.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  return TriangulateAndClean(contour);
}

// Points: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z. Outward-facing triangles.
vtkSmartPointer<vtkPolyData> MakeOctahedron()
{
  return MakePolyData({ 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 },
    { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 });
}

// Points: the four corners of a regular tetrahedron. Outward-facing triangles.
vtkSmartPointer<vtkPolyData> MakeTetrahedron()
{
  return MakePolyData(
    { 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1 }, { 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2 });
}

vtkSmartPointer<vtkPolyData> MakeIcosphere(int levels)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<double> points = { -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1,
    -t, 0, 1, -t, t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1 };
  std::vector<long long> triangles = { 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5,
    11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4,
    11, 6, 2, 10, 8, 6, 7, 9, 8, 1 };
  for (int level = 0; level < levels; ++level)
  {
    std::map<std::pair<long long, long long>, long long> midpoints;
    auto midpoint = [&](long long a, long long b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = midpoints.find(key);
      if (it != midpoints.end())
      {
        return it->second;
      }
      const long long id = static_cast<long long>(points.size() / 3);
      for (int c = 0; c < 3; ++c)
      {
        points.push_back(0.5 * (points[3 * a + c] + points[3 * b + c]));
      }
      midpoints[key] = id;
      return id;
    };
    std::vector<long long> finer;
    for (size_t i = 0; i < triangles.size(); i += 3)
    {
      const long long a = triangles[i], b = triangles[i + 1], c = triangles[i + 2];
      const long long ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), { a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca });
    }
    triangles.swap(finer);
  }
  for (size_t i = 0; i < points.size(); i += 3)
  {
    const double r =
      std::sqrt(points[i] * points[i] + points[i + 1] * points[i + 1] + points[i + 2] * points[i + 2]);
    for (int c = 0; c < 3; ++c)
    {
      points[i + c] /= r;
    }
  }
  return MakePolyData(points, triangles);
}

// Points 0 and 1 form the shared edge; 2, 3, 4 are the three apexes.
vtkSmartPointer<vtkPolyData> MakeNonManifoldEdge()
{
  return MakePolyData(
    { 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1 }, { 0, 1, 2, 1, 0, 3, 0, 1, 4 });
}

// Point 0 is the shared apex; 1-2-3 and 4-5-6 are the rims of two open fans.
vtkSmartPointer<vtkPolyData> MakeBowTie()
{
  return MakePolyData({ 0, 0, 0, 1, 1, 0, 1, 0, 0, 1, -1, 0, -1, -1, 0, -1, 0, 0, -1, 1, 0 },
    { 0, 3, 2, 0, 2, 1, 0, 6, 5, 0, 5, 4 });
}

vtkSmartPointer<vtkPolyData> MakeBumpySphereWithHoles(int levels)
{
  vtkSmartPointer<vtkPolyData> sphere = MakeIcosphere(levels);
  vtkPoints* points = sphere->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double x[3];
    points->GetPoint(i, x);
    const double r = 1.0 + 0.1 * std::sin(5 * x[0]) * std::sin(4 * x[1] + 1) * std::cos(6 * x[2]);
    points->SetPoint(i, r * x[0], 0.8 * r * x[1], 0.6 * r * x[2]);
  }
  const double holes[6][4] = { { 1, 0, 0, 0.35 }, { -1, 0.3, 0, 0.2 }, { 0, 1, 0.2, 0.3 },
    { 0.2, -1, 0.5, 0.15 }, { 0, 0, 1, 0.25 }, { 0.6, 0.6, -1, 0.3 } };
  vtkNew<vtkCellArray> kept;
  vtkCellArray* polys = sphere->GetPolys();
  for (vtkIdType t = 0; t < polys->GetNumberOfCells(); ++t)
  {
    vtkIdType n;
    const vtkIdType* ids;
    polys->GetCellAtId(t, n, ids);
    double c[3] = { 0, 0, 0 };
    for (vtkIdType k = 0; k < n; ++k)
    {
      double x[3];
      points->GetPoint(ids[k], x);
      vtkMath::Add(c, x, c);
    }
    vtkMath::Normalize(c);
    bool inHole = false;
    for (const auto& hole : holes)
    {
      double d[3] = { hole[0], hole[1], hole[2] };
      vtkMath::Normalize(d);
      inHole = inHole || std::acos(std::min(1.0, vtkMath::Dot(c, d))) < hole[3];
    }
    if (!inHole)
    {
      kept->InsertNextCell(n, ids);
    }
  }
  sphere->SetPolys(kept);
  vtkNew<vtkCleanPolyData> clean; // drops the points of the holes
  clean->SetInputData(sphere);
  clean->Update();
  return clean->GetOutput();
}

vtkSmartPointer<vtkPolyData> MakeTerrain(int n)
{
  // Sums of sines at doubling frequencies (a rough, deterministic landscape).
  vtkSmartPointer<vtkPolyData> grid = MakeGrid(n, n);
  vtkPoints* points = grid->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    const double x = 2.0 * p[0] / n - 1.0, y = 2.0 * p[1] / n - 1.0;
    double z = 0.0;
    for (int k = 1; k <= 6; ++k)
    {
      const double f = std::pow(2.0, k);
      z += 0.5 / f *
        (std::sin(1.7 * f * x + k) * std::cos(1.3 * f * y + 2 * k) +
          0.5 * std::sin(f * (x + y) + 3 * k));
    }
    points->SetPoint(i, x, y, 0.4 * z);
  }
  return grid;
}

vtkSmartPointer<vtkPolyData> MakeGridWithHole()
{
  vtkSmartPointer<vtkPolyData> grid = MakeGrid(4, 4);
  vtkNew<vtkCellArray> polys;
  vtkIdType n;
  const vtkIdType* ids;
  vtkCellArray* all = grid->GetPolys();
  for (vtkIdType c = 0; c < all->GetNumberOfCells(); ++c)
  {
    all->GetCellAtId(c, n, ids);
    const vtkIdType square = c / 2; // squares are numbered row by row, 4 per row
    const int i = static_cast<int>(square % 4), j = static_cast<int>(square / 4);
    if (i >= 1 && i <= 2 && j >= 1 && j <= 2)
    {
      continue;
    }
    polys->InsertNextCell(n, ids);
  }
  grid->SetPolys(polys);
  return grid;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MakeSphereWithEquatorialDisk(int around, int rings, int diskRings)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  const auto angle = [&](int i) { return 2.0 * vtkMath::Pi() * i / around; };
  const vtkIdType north = points->InsertNextPoint(0.0, 0.0, 1.0);
  std::vector<vtkIdType> ringStart;
  for (int r = 1; r <= rings; ++r)
  {
    const double polar = vtkMath::Pi() * r / (rings + 1);
    ringStart.push_back(points->GetNumberOfPoints());
    for (int i = 0; i < around; ++i)
    {
      points->InsertNextPoint(
        std::sin(polar) * std::cos(angle(i)), std::sin(polar) * std::sin(angle(i)), std::cos(polar));
    }
  }
  const vtkIdType south = points->InsertNextPoint(0.0, 0.0, -1.0);
  const auto at = [&](vtkIdType start, int i) { return start + (i % around); };
  for (int i = 0; i < around; ++i)
  {
    const vtkIdType cap[3] = { north, at(ringStart[0], i), at(ringStart[0], i + 1) };
    triangles->InsertNextCell(3, cap);
    const vtkIdType bottom[3] = { south, at(ringStart.back(), i + 1), at(ringStart.back(), i) };
    triangles->InsertNextCell(3, bottom);
  }
  // Quads between rings, and between the disk's rings (the outermost is the equator).
  const auto band = [&](vtkIdType upper, vtkIdType lower) {
    for (int i = 0; i < around; ++i)
    {
      const vtkIdType a = at(upper, i), b = at(upper, i + 1), c = at(lower, i), d = at(lower, i + 1);
      const vtkIdType first[3] = { a, c, d }, second[3] = { a, d, b };
      triangles->InsertNextCell(3, first);
      triangles->InsertNextCell(3, second);
    }
  };
  for (std::size_t r = 0; r + 1 < ringStart.size(); ++r)
  {
    band(ringStart[r], ringStart[r + 1]);
  }
  const vtkIdType equator = ringStart[ringStart.size() / 2];
  vtkIdType outer = equator;
  for (int k = diskRings - 1; k >= 1; --k)
  {
    const double radius = static_cast<double>(k) / diskRings;
    const vtkIdType inner = points->GetNumberOfPoints();
    for (int i = 0; i < around; ++i)
    {
      points->InsertNextPoint(radius * std::cos(angle(i)), radius * std::sin(angle(i)), 0.0);
    }
    band(inner, outer);
    outer = inner;
  }
  const vtkIdType centre = points->InsertNextPoint(0.0, 0.0, 0.0);
  for (int i = 0; i < around; ++i)
  {
    const vtkIdType fan[3] = { centre, at(outer, i + 1), at(outer, i) };
    triangles->InsertNextCell(3, fan);
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(triangles);
  return mesh;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> ShuffleIds(
  vtkPolyData* mesh, unsigned int seed, std::vector<vtkIdType>* newIds)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::mt19937 random(seed);
  std::vector<vtkIdType> newId(n);
  std::iota(newId.begin(), newId.end(), 0);
  std::shuffle(newId.begin(), newId.end(), random);
  vtkNew<vtkPoints> points;
  points->SetDataType(mesh->GetPoints()->GetDataType());
  points->SetNumberOfPoints(n);
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->GetPointData()->CopyAllocate(mesh->GetPointData(), n);
  for (vtkIdType p = 0; p < n; ++p)
  {
    points->SetPoint(newId[p], mesh->GetPoint(p));
    result->GetPointData()->CopyData(mesh->GetPointData(), p, newId[p]);
  }
  // Each triangle with the id of its cell (cells are numbered vertices, lines, then polygons).
  std::vector<std::array<vtkIdType, 4>> triangles;
  vtkIdType count;
  const vtkIdType* ids;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType cell = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  for (polys->InitTraversal(); polys->GetNextCell(count, ids); ++cell)
  {
    if (count == 3)
    {
      triangles.push_back({ newId[ids[0]], newId[ids[1]], newId[ids[2]], cell });
    }
  }
  std::shuffle(triangles.begin(), triangles.end(), random);
  vtkNew<vtkCellArray> shuffled;
  shuffled->AllocateExact(static_cast<vtkIdType>(triangles.size()), 3 * triangles.size());
  result->GetCellData()->CopyAllocate(mesh->GetCellData(), triangles.size());
  for (const auto& t : triangles)
  {
    result->GetCellData()->CopyData(mesh->GetCellData(), t[3], shuffled->InsertNextCell(3, t.data()));
  }
  result->SetPoints(points);
  result->SetPolys(shuffled);
  if (newIds)
  {
    newIds->swap(newId);
  }
  return result;
}

} // namespace testing
} // namespace meshlod
