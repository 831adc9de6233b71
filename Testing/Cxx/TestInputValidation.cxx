// The input policy shared by every filter (MeshLODInputMesh.h), case by case.
#include "MeshLODInputMesh.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"
#include "vtkTriangleFilter.h"

#include <cmath>
#include <limits>

namespace
{
using namespace meshlod;

struct Reader
{
  vtkNew<vtkTriangleFilter> Caller; // any algorithm: it only carries the messages
  vtkNew<vtkTest::ErrorObserver> Observer;
  Reader()
  {
    this->Caller->AddObserver(vtkCommand::ErrorEvent, this->Observer);
    this->Caller->AddObserver(vtkCommand::WarningEvent, this->Observer);
  }
  InputStatus Read(vtkPolyData* input, InputMesh& result)
  {
    this->Observer->Clear();
    return ReadInputMesh(input, this->Caller, result);
  }
};

void TestEmpty(Reader& reader)
{
  InputMesh result;
  vtkNew<vtkPolyData> empty;
  MESHLOD_CHECK(reader.Read(empty, result) == InputStatus::Empty);
  MESHLOD_CHECK(!reader.Observer->GetError());
  MESHLOD_CHECK(!reader.Observer->GetWarning());
  MESHLOD_CHECK(reader.Read(nullptr, result) == InputStatus::Empty);
}

void TestCleanMeshIsShared(Reader& reader)
{
  InputMesh result;
  vtkSmartPointer<vtkPolyData> octahedron = testing::MakeOctahedron();
  MESHLOD_CHECK(reader.Read(octahedron, result) == InputStatus::Valid);
  MESHLOD_CHECK(result.SameAsInput);
  MESHLOD_CHECK(result.Source == octahedron);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 8);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfPoints(), 6);
  MESHLOD_CHECK_EQ(result.Topology.EulerCharacteristic(result.Mesh), 2);
  MESHLOD_CHECK_EQ(result.SourcePointIds.size(), 6u); // identity maps, nothing compacted
  MESHLOD_CHECK_EQ(result.SourcePointIds[5], 5);
  MESHLOD_CHECK_EQ(result.SourceCellIds.size(), 8u);
  MESHLOD_CHECK_EQ(result.SourceCellIds[7], 7);
  MESHLOD_CHECK_EQ(result.UnusedPoints, 0);
  MESHLOD_CHECK(!reader.Observer->GetError());
  MESHLOD_CHECK(!reader.Observer->GetWarning());
}

void TestQuadsAndStripsAreTriangulated(Reader& reader)
{
  // Four quads of a 2x2 grid with a cell array "Square" naming each quad.
  vtkSmartPointer<vtkPolyData> grid = testing::MakeQuadGrid(2, 2);
  vtkNew<vtkIntArray> square;
  square->SetName("Square");
  for (int q = 0; q < 4; ++q)
  {
    square->InsertNextValue(q);
  }
  grid->GetCellData()->AddArray(square);
  vtkNew<vtkIdTypeArray> globalIds; // one id per quad
  globalIds->SetName("QuadIds");
  for (vtkIdType q = 0; q < 4; ++q)
  {
    globalIds->InsertNextValue(100 + q);
  }
  grid->GetCellData()->SetGlobalIds(globalIds);
  InputMesh result;
  MESHLOD_CHECK(reader.Read(grid, result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 8);
  MESHLOD_CHECK(!result.SameAsInput);
  MESHLOD_CHECK(!reader.Observer->GetWarning());
  // Each triangle still knows its quad through the source's cell data.
  vtkDataArray* mapped = result.Source->GetCellData()->GetArray("Square");
  MESHLOD_CHECK(mapped != nullptr);
  if (mapped)
  {
    for (Id t = 0; t < 8; ++t)
    {
      MESHLOD_CHECK_EQ(mapped->GetTuple1(result.SourceCellIds[t]), static_cast<double>(t / 2));
    }
  }
  // So do the global ids, but as a plain array: two triangles share each quad's id, and the
  // GlobalIds attribute promises one cell per id.
  vtkDataArray* quadIds = result.Source->GetCellData()->GetArray("QuadIds");
  MESHLOD_CHECK(quadIds != nullptr && result.Source->GetCellData()->GetGlobalIds() == nullptr);
  if (quadIds)
  {
    for (Id t = 0; t < 8; ++t)
    {
      MESHLOD_CHECK_EQ(quadIds->GetTuple1(result.SourceCellIds[t]), 100.0 + t / 2);
    }
  }

  // A strip of 5 points: 3 triangles.
  vtkSmartPointer<vtkPolyData> strip = testing::MakeGrid(2, 1);
  vtkNew<vtkCellArray> strips;
  const vtkIdType ids[5] = { 0, 3, 1, 4, 2 };
  strips->InsertNextCell(5, ids);
  strip->SetPolys(nullptr);
  strip->SetStrips(strips);
  MESHLOD_CHECK(reader.Read(strip, result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 3);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfPoints(), 5); // point 5 is unused
  MESHLOD_CHECK_EQ(result.UnusedPoints, 1);
}

void TestVertsAndLinesIgnored(Reader& reader)
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeOctahedron();
  vtkNew<vtkCellArray> verts, lines;
  const vtkIdType v[1] = { 0 };
  const vtkIdType l[2] = { 0, 1 };
  verts->InsertNextCell(1, v);
  lines->InsertNextCell(2, l);
  lines->InsertNextCell(2, l);
  mesh->SetVerts(verts);
  mesh->SetLines(lines);
  InputMesh result;
  MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Valid);
  MESHLOD_CHECK(reader.Observer->GetWarning());
  MESHLOD_CHECK(!reader.Observer->GetError());
  MESHLOD_CHECK_EQ(result.IgnoredVerts, 1);
  MESHLOD_CHECK_EQ(result.IgnoredLines, 2);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 8);
  // Polys come after verts and lines in the cell numbering.
  MESHLOD_CHECK_EQ(result.SourceCellIds[0], 3);

  // Only lines: empty, with a warning, no error.
  vtkNew<vtkPolyData> onlyLines;
  onlyLines->SetPoints(mesh->GetPoints());
  onlyLines->SetLines(lines);
  MESHLOD_CHECK(reader.Read(onlyLines, result) == InputStatus::Empty);
  MESHLOD_CHECK(!reader.Observer->GetError());
}

void TestNonFiniteRefused(Reader& reader)
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeOctahedron();
  mesh->GetPoints()->SetPoint(3, 0.0, std::numeric_limits<double>::quiet_NaN(), 0.0);
  InputMesh result;
  MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Invalid);
  MESHLOD_CHECK(reader.Observer->GetError());
  MESHLOD_CHECK(reader.Observer->GetErrorMessage().find("Point 3") != std::string::npos);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 0);

  mesh = testing::MakeOctahedron();
  mesh->GetPoints()->SetPoint(5, std::numeric_limits<double>::infinity(), 0.0, 0.0);
  MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Invalid);
  MESHLOD_CHECK(reader.Observer->GetErrorMessage().find("Point 5") != std::string::npos);
}

// A non-finite point that no triangle uses is dropped with the unused points: the octahedron
// comes through whole, its box (and so the seam tolerance) from its own six points.
void TestUnusedNonFinitePointDropped(Reader& reader)
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeOctahedron();
  InputMesh plain;
  MESHLOD_CHECK(reader.Read(mesh, plain) == InputStatus::Valid);
  mesh->GetPoints()->InsertPoint(6, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  mesh->GetPoints()->InsertPoint(7, 0.0, -std::numeric_limits<double>::infinity(), 1e300);
  InputMesh result;
  MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Valid);
  MESHLOD_CHECK(!reader.Observer->GetError());
  MESHLOD_CHECK_EQ(result.UnusedPoints, 2);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfPoints(), 6);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 8);
  MESHLOD_CHECK_EQ(result.Mesh.BoundingDiagonal(), plain.Mesh.BoundingDiagonal());
  MESHLOD_CHECK_EQ(result.SourcePointIds.size(), 6u);
  for (Id v = 0; v < static_cast<Id>(result.SourcePointIds.size()); ++v)
  {
    MESHLOD_CHECK_EQ(result.SourcePointIds[v], v);
  }
}

void TestTriangleSoupIsStitched(Reader& reader)
{
  // The octahedron with three private points per triangle, as an STL file would store it.
  vtkSmartPointer<vtkPolyData> octahedron = testing::MakeOctahedron();
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkIdType n;
  const vtkIdType* ids;
  for (vtkIdType c = 0; c < 8; ++c)
  {
    octahedron->GetPolys()->GetCellAtId(c, n, ids);
    vtkIdType soup[3];
    for (int k = 0; k < 3; ++k)
    {
      soup[k] = points->InsertNextPoint(octahedron->GetPoint(ids[k]));
    }
    polys->InsertNextCell(3, soup);
  }
  vtkNew<vtkPolyData> soup;
  soup->SetPoints(points);
  soup->SetPolys(polys);
  InputMesh result;
  MESHLOD_CHECK(reader.Read(soup, result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.MergedPoints, 18);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfPoints(), 6);
  MESHLOD_CHECK_EQ(result.Topology.CountEdges(result.Mesh).Boundary, 0);
  MESHLOD_CHECK_EQ(result.Topology.EulerCharacteristic(result.Mesh), 2);
  MESHLOD_CHECK(result.Topology.IsConsistentlyOriented(result.Mesh));
  // Each kept point refers to the first soup point at its position.
  MESHLOD_CHECK_EQ(result.SourcePointIds[0], 0);
  for (Id v = 0; v < 6; ++v)
  {
    double p[3];
    soup->GetPoint(result.SourcePointIds[v], p);
    MESHLOD_CHECK(p[0] == result.Mesh.Point(v)[0] && p[1] == result.Mesh.Point(v)[1] &&
      p[2] == result.Mesh.Point(v)[2]);
  }
}

void TestDegenerateAndDuplicateDropped(Reader& reader)
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeOctahedron();
  const vtkIdType duplicate[3] = { 2, 4, 0 }; // triangle 0 = (0, 2, 4), rotated
  const vtkIdType degenerate[3] = { 1, 1, 3 };
  mesh->GetPolys()->InsertNextCell(3, duplicate);
  mesh->GetPolys()->InsertNextCell(3, degenerate);
  InputMesh result;
  MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.DuplicateTriangles, 1);
  MESHLOD_CHECK_EQ(result.DegenerateTriangles, 1);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 8);
  MESHLOD_CHECK(reader.Observer->GetWarning());
  MESHLOD_CHECK_EQ(result.Topology.CountEdges(result.Mesh).NonManifold, 0);
}

void TestNonManifoldKept(Reader& reader)
{
  InputMesh result;
  MESHLOD_CHECK(reader.Read(testing::MakeNonManifoldEdge(), result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 3);
  MESHLOD_CHECK_EQ(result.Topology.CountVertices(VertexKind::NonManifold), 2);
  MESHLOD_CHECK(!reader.Observer->GetError());
  MESHLOD_CHECK(reader.Read(testing::MakeBowTie(), result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.Topology.CountVertices(VertexKind::NonManifold), 1);
}

void TestUnusedPointsDropped(Reader& reader)
{
  InputMesh result;
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeGridWithHole(); // point 12 unused
  MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.UnusedPoints, 1);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfPoints(), 24);
  MESHLOD_CHECK_EQ(result.SourcePointIds[11], 11);
  MESHLOD_CHECK_EQ(result.SourcePointIds[12], 13);
  MESHLOD_CHECK(!result.SameAsInput);
}
// Two triangles of an octahedron wound the wrong way are flipped back (the majority wins), with
// a warning; a Moebius band, which has no consistent orientation, is left as it is.
void TestOrientationMadeConsistent(Reader& reader)
{
  InputMesh result;
  vtkSmartPointer<vtkPolyData> octahedron = testing::MakePolyData(
    { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 },
    { 0, 4, 2, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 5, 0, 1, 2, 5, 3, 1, 5, 0, 3, 5 });
  MESHLOD_CHECK(reader.Read(octahedron, result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.FlippedTriangles, 2);
  MESHLOD_CHECK(result.Topology.IsConsistentlyOriented(result.Mesh));
  MESHLOD_CHECK(!result.SameAsInput);
  MESHLOD_CHECK(reader.Observer->GetWarning());
  MESHLOD_CHECK_EQ(result.Mesh.Triangle(0)[1], 2); // (0, 4, 2) became (0, 2, 4)
  MESHLOD_CHECK_EQ(result.Mesh.Triangle(1)[1], 1); // the majority's winding is kept

  // A Moebius band of 8 quads: the strip closes with a half twist.
  std::vector<double> points;
  const int n = 8;
  for (int i = 0; i < n; ++i)
  {
    const double a = 2.0 * vtkMath::Pi() * i / n;
    for (const double s : { -0.3, 0.3 })
    {
      const double r = 1.0 + s * std::cos(0.5 * a);
      points.insert(points.end(), { r * std::cos(a), r * std::sin(a), s * std::sin(0.5 * a) });
    }
  }
  std::vector<long long> triangles;
  for (int i = 0; i < n; ++i)
  {
    const long long a = 2 * i, b = 2 * i + 1;
    // The last quad joins the band's ends with its sides exchanged (the half twist).
    const long long c = i + 1 < n ? 2 * i + 3 : 0, d = i + 1 < n ? 2 * i + 2 : 1;
    triangles.insert(triangles.end(), { a, b, c, a, c, d });
  }
  MESHLOD_CHECK(reader.Read(testing::MakePolyData(points, triangles), result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.FlippedTriangles, 0);
  MESHLOD_CHECK(!result.Topology.IsConsistentlyOriented(result.Mesh));
  MESHLOD_CHECK_EQ(result.Topology.CountEdges(result.Mesh).Boundary, 2 * n);
}
// A point id out of range is refused (it used to corrupt the heap while building the
// vertex -> triangle rows), in polygons and in strips.
void TestBadPointIdsRefused(Reader& reader)
{
  for (const vtkIdType bad : { vtkIdType(6), vtkIdType(-1) })
  {
    vtkSmartPointer<vtkPolyData> mesh = testing::MakeOctahedron();
    vtkIdType n;
    const vtkIdType* ids;
    mesh->GetPolys()->GetCellAtId(2, n, ids);
    const vtkIdType replaced[3] = { ids[0], bad, ids[2] };
    mesh->GetPolys()->ReplaceCellAtId(2, 3, replaced);
    InputMesh result;
    MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Invalid);
    MESHLOD_CHECK(reader.Observer->GetErrorMessage().find("Polygon 2") != std::string::npos);
    MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfTriangles(), 0);
  }
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeOctahedron();
  vtkNew<vtkCellArray> strips;
  const vtkIdType strip[4] = { 0, 1, 2, 9 };
  strips->InsertNextCell(4, strip);
  mesh->SetStrips(strips);
  InputMesh result;
  MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Invalid);
  MESHLOD_CHECK(reader.Observer->GetErrorMessage().find("Triangle strip 0") != std::string::npos);
}

// Arrays with a tuple count other than the number of points or cells are left out with a
// warning naming them (levels used to carry garbage read past their end); the input keeps them.
void TestMismatchedArraysIgnored(Reader& reader)
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeOctahedron();
  vtkNew<vtkFloatArray> shortPoints;
  shortPoints->SetName("ShortPointArray");
  shortPoints->SetNumberOfTuples(3);
  shortPoints->Fill(1.0f);
  mesh->GetPointData()->AddArray(shortPoints);
  vtkNew<vtkFloatArray> good;
  good->SetName("Good");
  good->SetNumberOfTuples(6);
  good->Fill(2.0f);
  mesh->GetPointData()->AddArray(good);
  vtkNew<vtkFloatArray> longCells;
  longCells->SetName("LongCellArray");
  longCells->SetNumberOfTuples(20);
  longCells->Fill(3.0f);
  mesh->GetCellData()->AddArray(longCells);
  InputMesh result;
  MESHLOD_CHECK(reader.Read(mesh, result) == InputStatus::Valid);
  MESHLOD_CHECK(!reader.Observer->GetError());
  MESHLOD_CHECK(reader.Observer->GetWarningMessage().find("LongCellArray") != std::string::npos);
  MESHLOD_CHECK(result.Source->GetPointData()->GetArray("ShortPointArray") == nullptr);
  MESHLOD_CHECK(result.Source->GetCellData()->GetArray("LongCellArray") == nullptr);
  MESHLOD_CHECK(result.Source->GetPointData()->GetArray("Good") != nullptr);
  MESHLOD_CHECK(!result.SameAsInput);
  MESHLOD_CHECK(mesh->GetPointData()->GetArray("ShortPointArray") != nullptr);
  MESHLOD_CHECK(mesh->GetCellData()->GetArray("LongCellArray") != nullptr);
}

// vtkCubeSource has 24 points, four per face, with the face's normal: the 3 coincident points
// at each corner differ in their normals, an attribute seam, and are not stitched (stitching
// them gave level 0 normals perpendicular to their faces). Without the normals, the same
// corners are stitched into a closed cube.
void TestAttributeSeamKept(Reader& reader)
{
  vtkNew<vtkCubeSource> cube;
  cube->Update();
  InputMesh result;
  MESHLOD_CHECK(reader.Read(cube->GetOutput(), result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.MergedPoints, 0);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfPoints(), 24);
  MESHLOD_CHECK(reader.Observer->GetWarningMessage().find("Did not stitch 24 points") !=
    std::string::npos);

  vtkNew<vtkPolyData> bare;
  bare->SetPoints(cube->GetOutput()->GetPoints());
  bare->SetPolys(cube->GetOutput()->GetPolys());
  bare->GetPointData()->AddArray(cube->GetOutput()->GetPointData()->GetArray("TCoords"));
  MESHLOD_CHECK(reader.Read(bare, result) == InputStatus::Valid);
  // The texture coordinates of a corner's points differ for most corners: the seam stays.
  MESHLOD_CHECK_GE(result.Mesh.GetNumberOfPoints(), 16);

  // Three coincident points whose ids sort as (same data, other data, same data): the first
  // and the last are stitched although the one between them differs (comparing neighbours in
  // sort order only left them apart). A soup of three triangles, two coplanar sharing an edge
  // (normal +z) and one standing on that edge (normal +y), with per-face normals.
  {
    const double xyz[9][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, // flat, +z
      { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, -1 },                          // standing, +y
      { 1, 0, 0 }, { 0, 0, 0 }, { 0, -1, 0 } };                        // flat, +z
    const double normals[3][3] = { { 0, 0, 1 }, { 0, 1, 0 }, { 0, 0, 1 } };
    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> normal;
    normal->SetName("Normals");
    normal->SetNumberOfComponents(3);
    vtkNew<vtkCellArray> polys;
    for (int t = 0; t < 3; ++t)
    {
      vtkIdType ids[3];
      for (int k = 0; k < 3; ++k)
      {
        ids[k] = points->InsertNextPoint(xyz[3 * t + k]);
        normal->InsertNextTuple(normals[t]);
      }
      polys->InsertNextCell(3, ids);
    }
    vtkNew<vtkPolyData> soup;
    soup->SetPoints(points);
    soup->SetPolys(polys);
    soup->GetPointData()->SetNormals(normal);
    MESHLOD_CHECK(reader.Read(soup, result) == InputStatus::Valid);
    MESHLOD_CHECK_EQ(result.MergedPoints, 2); // the two flat triangles share their edge
    MESHLOD_CHECK_EQ(result.Topology.CountEdges(result.Mesh).Boundary, 7);
  }

  // An infinite value does not make every pair agree (the tolerance comes from the finite
  // range).
  {
    vtkNew<vtkPolyData> withInfinity;
    withInfinity->DeepCopy(bare);
    vtkNew<vtkFloatArray> values;
    values->SetName("Values");
    values->SetNumberOfTuples(withInfinity->GetNumberOfPoints());
    for (vtkIdType p = 0; p < withInfinity->GetNumberOfPoints(); ++p)
    {
      values->SetValue(p, static_cast<float>(p));
    }
    values->SetValue(0, std::numeric_limits<float>::infinity());
    withInfinity->GetPointData()->AddArray(values);
    MESHLOD_CHECK(reader.Read(withInfinity, result) == InputStatus::Valid);
    MESHLOD_CHECK_EQ(result.MergedPoints, 0);
  }

  bare->GetPointData()->Initialize();
  MESHLOD_CHECK(reader.Read(bare, result) == InputStatus::Valid);
  MESHLOD_CHECK_EQ(result.MergedPoints, 16);
  MESHLOD_CHECK_EQ(result.Mesh.GetNumberOfPoints(), 8);
  MESHLOD_CHECK_EQ(result.Topology.CountEdges(result.Mesh).Boundary, 0);
}
} // namespace

int TestInputValidation(int, char*[])
{
  Reader reader;
  TestEmpty(reader);
  TestCleanMeshIsShared(reader);
  TestQuadsAndStripsAreTriangulated(reader);
  TestVertsAndLinesIgnored(reader);
  TestNonFiniteRefused(reader);
  TestUnusedNonFinitePointDropped(reader);
  TestBadPointIdsRefused(reader);
  TestMismatchedArraysIgnored(reader);
  TestAttributeSeamKept(reader);
  TestTriangleSoupIsStitched(reader);
  TestDegenerateAndDuplicateDropped(reader);
  TestNonManifoldKept(reader);
  TestUnusedPointsDropped(reader);
  TestOrientationMadeConsistent(reader);
  return meshlod::testing::Result();
}
