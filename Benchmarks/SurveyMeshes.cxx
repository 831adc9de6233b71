// The survey meshes of OtherMeshesBenchmark (see OtherMeshes.h), and how every mesh there is
// prepared.
#include "OtherMeshes.h"

#include "MeshLODTestMeshes.h"

#include "vtkAppendPolyData.h"
#include "vtkArrowSource.h"
#include "vtkBox.h"
#include "vtkClipPolyData.h"
#include "vtkCubeSource.h"
#include "vtkCylinderSource.h"
#include "vtkDelaunay2D.h"
#include "vtkDiskSource.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkParametricBohemianDome.h"
#include "vtkParametricConicSpiral.h"
#include "vtkParametricCrossCap.h"
#include "vtkParametricDini.h"
#include "vtkParametricEllipsoid.h"
#include "vtkParametricEnneper.h"
#include "vtkParametricFigure8Klein.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricPseudosphere.h"
#include "vtkParametricRandomHills.h"
#include "vtkParametricRoman.h"
#include "vtkParametricSuperToroid.h"
#include "vtkPlatonicSolidSource.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"

#include <cmath>

namespace meshlod
{
namespace benchmark
{
//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> Prepare(vtkAlgorithm* source, int subdivisions)
{
  vtkSmartPointer<vtkPolyData> mesh = meshlod::testing::TriangulateAndClean(source);
  if (subdivisions > 0)
  {
    vtkNew<vtkLinearSubdivisionFilter> subdivide;
    subdivide->SetInputData(mesh);
    subdivide->SetNumberOfSubdivisions(subdivisions);
    subdivide->Update();
    mesh = subdivide->GetOutput();
  }
  return mesh;
}

namespace
{
// A parametric surface sampled u x v, positions only (no normals, texture coordinates or
// scalars, so that seams are stitched by cleaning alone).
TestMesh Parametric(const std::string& name, vtkSmartPointer<vtkParametricFunction> function,
  int u, int v)
{
  return { name,
    std::string(function->GetClassName()) + ", " + std::to_string(u) + " x " + std::to_string(v),
    [function, u, v] {
      vtkNew<vtkParametricFunctionSource> source;
      source->SetParametricFunction(function);
      source->SetUResolution(u);
      source->SetVResolution(v);
      source->GenerateTextureCoordinatesOff();
      source->GenerateNormalsOff();
      source->SetScalarModeToNone();
      return Prepare(source, 0);
    } };
}

// A smooth height field over the unit square from scattered random points.
vtkSmartPointer<vtkPolyData> DelaunayTerrain()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(3);
  for (int i = 0; i < 60000; ++i)
  {
    const double x = random->GetValue();
    random->Next();
    const double y = random->GetValue();
    random->Next();
    points->InsertNextPoint(
      x, y, 0.1 * std::sin(7.0 * x) * std::cos(5.0 * y) + 0.03 * std::sin(23.0 * x + 11.0 * y));
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkDelaunay2D> delaunay;
  delaunay->SetInputData(cloud);
  return Prepare(delaunay, 0);
}

// One large sphere and 39 small ones of random radii scattered beside it.
vtkSmartPointer<vtkPolyData> SpheresOfManySizes()
{
  vtkNew<vtkAppendPolyData> append;
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(5);
  for (int i = 0; i < 40; ++i)
  {
    vtkNew<vtkSphereSource> sphere;
    const double radius = i == 0 ? 1.0 : 0.02 + 0.1 * random->GetValue();
    random->Next();
    double centre[3] = { 0.0, 0.0, 0.0 };
    for (int k = 0; k < 3 && i > 0; ++k)
    {
      centre[k] = 3.0 * (random->GetValue() - 0.5) + (k == 0 ? 2.5 : 0.0);
      random->Next();
    }
    sphere->SetRadius(radius);
    sphere->SetCenter(centre);
    sphere->SetThetaResolution(i == 0 ? 300 : 40);
    sphere->SetPhiResolution(i == 0 ? 150 : 20);
    sphere->Update();
    vtkNew<vtkPolyData> copy;
    copy->DeepCopy(sphere->GetOutput());
    append->AddInputData(copy);
  }
  return Prepare(append, 0);
}

// Six capped cylinders and six boxes side by side, each subdivided.
vtkSmartPointer<vtkPolyData> BoxesAndCylinders()
{
  vtkNew<vtkAppendPolyData> append;
  for (int i = 0; i < 6; ++i)
  {
    vtkNew<vtkCylinderSource> cylinder;
    cylinder->SetResolution(48);
    cylinder->SetRadius(0.2 + 0.05 * i);
    cylinder->SetHeight(1.0 + 0.3 * i);
    cylinder->SetCenter(0.9 * i, 0.0, 0.0);
    cylinder->CappingOn();
    append->AddInputData(Prepare(cylinder, 3));
    vtkNew<vtkCubeSource> box;
    box->SetBounds(0.9 * i - 0.4, 0.9 * i + 0.4, 0.6, 0.9, -0.3, 0.3 + 0.1 * i);
    append->AddInputData(Prepare(box, 5));
  }
  return Prepare(append, 0);
}
} // namespace

//------------------------------------------------------------------------------
std::vector<TestMesh> SurveyMeshes()
{
  std::vector<TestMesh> meshes;
  meshes.push_back({ "subdivided cube", "vtkCubeSource, 6 subdivisions", [] {
                      vtkNew<vtkCubeSource> cube;
                      return Prepare(cube, 6);
                    } });
  meshes.push_back({ "Delaunay terrain",
    "vtkDelaunay2D of 60,000 random points of the unit square lifted by sines",
    [] { return DelaunayTerrain(); } });
  meshes.push_back({ "UV sphere", "vtkSphereSource 800 x 400 (two poles of 800 triangles each)",
    [] {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetThetaResolution(800);
      sphere->SetPhiResolution(400);
      return Prepare(sphere, 0);
    } });
  meshes.push_back({ "box-clipped sphere",
    "vtkSphereSource 500 x 250 clipped by a box (vtkClipPolyData, vtkBox): an open surface with "
    "straight cut edges",
    [] {
      vtkNew<vtkSphereSource> sphere;
      sphere->SetThetaResolution(500);
      sphere->SetPhiResolution(250);
      vtkNew<vtkBox> box;
      box->SetBounds(-0.3, 0.3, -0.6, 0.6, -0.35, 0.6);
      vtkNew<vtkClipPolyData> clip;
      clip->SetInputConnection(sphere->GetOutputPort());
      clip->SetClipFunction(box);
      clip->InsideOutOn();
      return Prepare(clip, 0);
    } });
  meshes.push_back({ "spheres of many sizes",
    "one sphere of 300 x 150 and 39 of 40 x 20 with radii 1-6% of its diameter scattered beside "
    "it",
    [] { return SpheresOfManySizes(); } });
  meshes.push_back(Parametric("random hills", vtkSmartPointer<vtkParametricRandomHills>::New(), 300, 300));
  meshes.push_back(Parametric("Enneper", vtkSmartPointer<vtkParametricEnneper>::New(), 300, 300));
  meshes.push_back(
    Parametric("conic spiral", vtkSmartPointer<vtkParametricConicSpiral>::New(), 400, 200));
  meshes.push_back(Parametric("Dini", vtkSmartPointer<vtkParametricDini>::New(), 300, 300));
  meshes.push_back(
    Parametric("Klein figure 8", vtkSmartPointer<vtkParametricFigure8Klein>::New(), 300, 300));
  meshes.push_back(Parametric("Roman", vtkSmartPointer<vtkParametricRoman>::New(), 300, 300));
  meshes.push_back(Parametric("cross cap", vtkSmartPointer<vtkParametricCrossCap>::New(), 300, 300));
  meshes.push_back(
    Parametric("Bohemian dome", vtkSmartPointer<vtkParametricBohemianDome>::New(), 300, 300));
  meshes.push_back(
    Parametric("pseudosphere", vtkSmartPointer<vtkParametricPseudosphere>::New(), 300, 300));
  auto toroid = vtkSmartPointer<vtkParametricSuperToroid>::New();
  toroid->SetN1(0.3);
  toroid->SetN2(0.3);
  meshes.push_back(Parametric("super toroid (N1 = N2 = 0.3)", toroid, 300, 300));
  // Radii 10, 1 and 0.5: the u-circles are ellipses of 10:1, so every triangle is a needle.
  auto ellipsoid = vtkSmartPointer<vtkParametricEllipsoid>::New();
  ellipsoid->SetXRadius(10.0);
  ellipsoid->SetYRadius(1.0);
  ellipsoid->SetZRadius(0.5);
  meshes.push_back(Parametric("ellipsoid 10 : 1 : 0.5", ellipsoid, 400, 200));
  meshes.push_back({ "boxes and cylinders",
    "six capped vtkCylinderSource (48 sides, 3 subdivisions) and six vtkCubeSource boxes (5 "
    "subdivisions) side by side",
    [] { return BoxesAndCylinders(); } });
  meshes.push_back({ "annulus", "vtkDiskSource, radii 0.3 and 1, 60 x 400", [] {
                      vtkNew<vtkDiskSource> disk;
                      disk->SetInnerRadius(0.3);
                      disk->SetOuterRadius(1.0);
                      disk->SetRadialResolution(60);
                      disk->SetCircumferentialResolution(400);
                      return Prepare(disk, 0);
                    } });
  meshes.push_back({ "arrow", "vtkArrowSource, 64 sides, 4 subdivisions", [] {
                      vtkNew<vtkArrowSource> arrow;
                      arrow->SetTipResolution(64);
                      arrow->SetShaftResolution(64);
                      return Prepare(arrow, 4);
                    } });
  meshes.push_back({ "octagonal prism", "vtkCylinderSource, 8 sides, capped, 6 subdivisions", [] {
                      vtkNew<vtkCylinderSource> prism;
                      prism->SetResolution(8);
                      prism->CappingOn();
                      return Prepare(prism, 6);
                    } });
  meshes.push_back({ "icosahedron", "vtkPlatonicSolidSource icosahedron, 6 subdivisions", [] {
                      vtkNew<vtkPlatonicSolidSource> solid;
                      solid->SetSolidTypeToIcosahedron();
                      return Prepare(solid, 6);
                    } });
  return meshes;
}
} // namespace benchmark
} // namespace meshlod
