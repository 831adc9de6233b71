// vtkVertexClusterOctree texture baking (§4): atlas layout, continuity across edges, and the
// colours the baked textures reproduce, from a colour array and from an input texture.
#include "MeshLODHierarchyChecks.h"
#include "MeshLODHierarchy.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestMeshes.h"
#include "vtkLODGeomorph.h"
#include "vtkVertexClusterOctree.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGenericCell.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkImageShiftScale.h"
#include "vtkLookupTable.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"
#include "vtkTestErrorObserver.h"
#include "vtkTexturedSphereSource.h"
#include "vtkTriangle.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <vector>

namespace
{
using namespace meshlod;
using testing::SameValues;
using testing::Triangles;
using Triangle = testing::TriangleIds;
using Color = std::array<double, 3>;

// Bilinear lookup (texel centres at (i + 0.5) / size, clamped at the border).
Color Lookup(vtkImageData* image, double u, double v)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const double x = std::min(dims[0] - 1.0, std::max(0.0, u * dims[0] - 0.5));
  const double y = std::min(dims[1] - 1.0, std::max(0.0, v * dims[1] - 0.5));
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = std::min(dims[0] - 1, x0 + 1), y1 = std::min(dims[1] - 1, y0 + 1);
  const double tx = x - x0, ty = y - y0;
  Color c{};
  for (int k = 0; k < 3; ++k)
  {
    auto at = [&](int i, int j) { return scalars->GetComponent(j * dims[0] + i, k); };
    c[k] = (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x1, y0)) +
      ty * ((1 - tx) * at(x0, y1) + tx * at(x1, y1));
  }
  return c;
}

void Barycentric(vtkPolyData* poly, const Triangle& t, const double x[3], double w[3])
{
  double a[3], b[3], c[3];
  poly->GetPoint(t[0], a);
  poly->GetPoint(t[1], b);
  poly->GetPoint(t[2], c);
  const double e0[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double e1[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double d[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
  const double d00 = vtkMath::Dot(e0, e0), d01 = vtkMath::Dot(e0, e1), d11 = vtkMath::Dot(e1, e1);
  const double d20 = vtkMath::Dot(d, e0), d21 = vtkMath::Dot(d, e1);
  const double den = d00 * d11 - d01 * d01;
  w[1] = den != 0.0 ? (d11 * d20 - d01 * d21) / den : 0.0;
  w[2] = den != 0.0 ? (d00 * d21 - d01 * d20) / den : 0.0;
  w[0] = 1.0 - w[1] - w[2];
}

// Mean over area-uniform samples of the input surface of the mean RGB difference between the
// input's colour there (`truth`) and the colour of the nearest point of `level` (`shade`).
double MeanColorError(vtkPolyData* input,
  const std::function<Color(const Triangle&, const double*)>& truth,
  vtkPolyData* level,
  const std::function<Color(const Triangle&, const double*)>& shade)
{
  const std::vector<Triangle> inputTris = Triangles(input);
  const std::vector<Triangle> levelTris = Triangles(level);
  std::vector<double> cumulative(inputTris.size() + 1, 0.0);
  for (size_t t = 0; t < inputTris.size(); ++t)
  {
    double a[3], b[3], c[3];
    input->GetPoint(inputTris[t][0], a);
    input->GetPoint(inputTris[t][1], b);
    input->GetPoint(inputTris[t][2], c);
    cumulative[t + 1] = cumulative[t] + vtkTriangle::TriangleArea(a, b, c);
  }
  vtkSmartPointer<vtkStaticCellLocator> locator = meshlod::BuildCellLocator(level);
  vtkNew<vtkGenericCell> cell;
  std::uint64_t state = 12345;
  auto random = [&]()
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  const int samples = 20000;
  double sum = 0.0;
  for (int i = 0; i < samples; ++i)
  {
    const double pick = random() * cumulative.back();
    const size_t t = std::min(inputTris.size() - 1,
      static_cast<size_t>(std::upper_bound(cumulative.begin() + 1, cumulative.end(), pick) -
        (cumulative.begin() + 1)));
    const double r1 = std::sqrt(random()), r2 = random();
    const double w[3] = { 1 - r1, r1 * (1 - r2), r1 * r2 };
    double x[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      const double* p = input->GetPoint(inputTris[t][k]);
      for (int c = 0; c < 3; ++c)
      {
        x[c] += w[k] * p[c];
      }
    }
    double closest[3], dist2;
    vtkIdType cellId;
    int subId;
    locator->FindClosestPoint(x, closest, cell, cellId, subId, dist2);
    double wl[3];
    Barycentric(level, levelTris[cellId], closest, wl);
    const Color expected = truth(inputTris[t], w);
    const Color got = shade(levelTris[cellId], wl);
    sum += (std::abs(expected[0] - got[0]) + std::abs(expected[1] - got[1]) +
             std::abs(expected[2] - got[2])) /
      3.0;
  }
  return sum / samples;
}

Color Interpolate(vtkDataArray* colors, const Triangle& t, const double* w, double scale = 1.0)
{
  Color c{};
  for (int k = 0; k < 3; ++k)
  {
    for (int i = 0; i < 3; ++i)
    {
      c[i] += w[k] * scale * colors->GetComponent(t[k], i);
    }
  }
  return c;
}

Color BakedColor(vtkPolyData* level, vtkImageData* texture, const Triangle& t, const double* w)
{
  vtkDataArray* tcoords = level->GetPointData()->GetTCoords();
  double uv[2] = { 0, 0 };
  for (int k = 0; k < 3; ++k)
  {
    uv[0] += w[k] * tcoords->GetComponent(t[k], 0);
    uv[1] += w[k] * tcoords->GetComponent(t[k], 1);
  }
  return Lookup(texture, uv[0], uv[1]);
}

//------------------------------------------------------------------------------
// Atlas layout: coordinates inside [0, 1]^2, no two texture triangles overlapping, and the two
// copies of every edge showing the same colours.
void CheckAtlas(vtkPolyData* level, vtkImageData* texture)
{
  vtkDataArray* tcoords = level->GetPointData()->GetTCoords();
  MESHLOD_REQUIRE(tcoords != nullptr && tcoords->GetNumberOfComponents() == 2);
  int dims[3];
  texture->GetDimensions(dims);
  MESHLOD_CHECK_EQ(dims[0], dims[1]);
  MESHLOD_CHECK_EQ(dims[0] & (dims[0] - 1), 0);
  for (vtkIdType p = 0; p < tcoords->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 2; ++c)
    {
      MESHLOD_CHECK_GE(tcoords->GetComponent(p, c), 0.0);
      MESHLOD_CHECK_LE(tcoords->GetComponent(p, c), 1.0);
    }
  }

  // Overlaps: 4 x 4 samples per texel; a sample strictly inside two triangles is an overlap.
  const int side = 4 * dims[0];
  std::vector<unsigned char> covered(static_cast<size_t>(side) * side, 0);
  vtkIdType overlaps = 0;
  for (const Triangle& t : Triangles(level))
  {
    double uv[3][2];
    for (int k = 0; k < 3; ++k)
    {
      uv[k][0] = tcoords->GetComponent(t[k], 0) * side;
      uv[k][1] = tcoords->GetComponent(t[k], 1) * side;
    }
    const double area2 =
      (uv[1][0] - uv[0][0]) * (uv[2][1] - uv[0][1]) - (uv[1][1] - uv[0][1]) * (uv[2][0] - uv[0][0]);
    MESHLOD_CHECK(area2 != 0.0);
    const int x0 = static_cast<int>(std::floor(std::min({ uv[0][0], uv[1][0], uv[2][0] })));
    const int x1 = static_cast<int>(std::ceil(std::max({ uv[0][0], uv[1][0], uv[2][0] })));
    const int y0 = static_cast<int>(std::floor(std::min({ uv[0][1], uv[1][1], uv[2][1] })));
    const int y1 = static_cast<int>(std::ceil(std::max({ uv[0][1], uv[1][1], uv[2][1] })));
    for (int y = std::max(0, y0); y < std::min(side, y1); ++y)
    {
      for (int x = std::max(0, x0); x < std::min(side, x1); ++x)
      {
        const double px = x + 0.5, py = y + 0.5;
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k)
        {
          const double* a = uv[(k + 1) % 3];
          const double* b = uv[(k + 2) % 3];
          const double cross = (a[0] - px) * (b[1] - py) - (a[1] - py) * (b[0] - px);
          inside = cross * area2 > 1e-9;
        }
        if (inside)
        {
          unsigned char& c = covered[static_cast<size_t>(y) * side + x];
          overlaps += c ? 1 : 0;
          c = 1;
        }
      }
    }
  }
  MESHLOD_CHECK_EQ(overlaps, 0);

  // Edges: the same two end points (by position) in two triangles. Compare the texture along
  // both copies.
  std::map<std::array<double, 6>, std::vector<std::pair<vtkIdType, vtkIdType>>> edges;
  for (const Triangle& t : Triangles(level))
  {
    for (int k = 0; k < 3; ++k)
    {
      vtkIdType a = t[k], b = t[(k + 1) % 3];
      double pa[3], pb[3];
      level->GetPoint(a, pa);
      level->GetPoint(b, pb);
      if (std::lexicographical_compare(pb, pb + 3, pa, pa + 3))
      {
        std::swap(a, b);
        std::swap(pa, pb);
      }
      edges[{ pa[0], pa[1], pa[2], pb[0], pb[1], pb[2] }].push_back({ a, b });
    }
  }
  double worst = 0.0, sum = 0.0;
  vtkIdType compared = 0, shared = 0, identical = 0;
  for (const auto& edge : edges)
  {
    if (edge.second.size() != 2)
    {
      continue;
    }
    ++shared;
    const auto& e0 = edge.second[0];
    const auto& e1 = edge.second[1];
    bool same = true;
    for (int c = 0; c < 2; ++c)
    {
      same = same && tcoords->GetComponent(e0.first, c) == tcoords->GetComponent(e1.first, c) &&
        tcoords->GetComponent(e0.second, c) == tcoords->GetComponent(e1.second, c);
    }
    identical += same ? 1 : 0;
    for (int step = 0; step <= 16; ++step)
    {
      const double s = step / 16.0;
      auto at = [&](const std::pair<vtkIdType, vtkIdType>& e)
      {
        return Lookup(texture,
          (1 - s) * tcoords->GetComponent(e.first, 0) + s * tcoords->GetComponent(e.second, 0),
          (1 - s) * tcoords->GetComponent(e.first, 1) + s * tcoords->GetComponent(e.second, 1));
      };
      const Color c0 = at(e0), c1 = at(e1);
      for (int c = 0; c < 3; ++c)
      {
        const double d = std::abs(c0[c] - c1[c]);
        worst = std::max(worst, d);
        sum += d;
        ++compared;
      }
    }
  }
  const double mean = compared ? sum / compared : 0.0;
  std::cout << "  edges shared " << shared << ", on one square diagonal " << identical
            << "; colour difference along shared edges: mean " << mean << ", largest " << worst
            << "\n";
  MESHLOD_CHECK_GT(identical, shared / 4); // about half the triangles pair up
  MESHLOD_CHECK_LE(mean, 0.25);
  MESHLOD_CHECK_LE(worst, 12.0);
}

//------------------------------------------------------------------------------
// Colours a mesh's points by a scalar function of position through a lookup table of the given
// range (scalars named "Colors"; RGBA).
vtkSmartPointer<vtkUnsignedCharArray> ColorPoints(vtkPolyData* mesh, double range,
  const std::function<double(const double*)>& value, bool hues = false)
{
  vtkNew<vtkFloatArray> field;
  field->SetName("Field");
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    field->InsertNextValue(static_cast<float>(value(mesh->GetPoint(p))));
  }
  vtkNew<vtkLookupTable> lut;
  if (hues)
  {
    lut->SetHueRange(0.0, 0.7);
  }
  lut->SetTableRange(-range, range);
  lut->Build();
  vtkSmartPointer<vtkUnsignedCharArray> colors =
    vtk::TakeSmartPointer(lut->MapScalars(field, VTK_COLOR_MODE_DEFAULT, -1));
  colors->SetName("Colors");
  mesh->GetPointData()->SetScalars(colors);
  return colors;
}

// The mesh with its coincident points welded into one (the lowest id's), unused points kept:
// a baked level's copies of a point, split per texture square, become the point again.
vtkSmartPointer<vtkPolyData> WeldCoincidentPoints(vtkPolyData* mesh)
{
  std::map<std::array<double, 3>, vtkIdType> first;
  std::vector<vtkIdType> welded(mesh->GetNumberOfPoints());
  vtkNew<vtkPoints> points;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    std::array<double, 3> x;
    mesh->GetPoint(p, x.data());
    const auto inserted = first.emplace(x, points->GetNumberOfPoints());
    if (inserted.second)
    {
      points->InsertNextPoint(x.data());
    }
    welded[p] = inserted.first->second;
  }
  vtkNew<vtkCellArray> cells;
  for (const Triangle& t : Triangles(mesh))
  {
    const vtkIdType ids[3] = { welded[t[0]], welded[t[1]], welded[t[2]] };
    cells->InsertNextCell(3, ids);
  }
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->SetPoints(points);
  result->SetPolys(cells);
  return result;
}

// The texture coordinates of a triangle's corners, as a sorted triple (single precision).
using UVTriple = std::array<std::array<float, 2>, 3>;
UVTriple CornerUVs(vtkDataArray* tcoords, const Triangle& t)
{
  UVTriple uv;
  for (int k = 0; k < 3; ++k)
  {
    const double* x = tcoords->GetTuple2(t[k]);
    uv[k] = { static_cast<float>(x[0]), static_cast<float>(x[1]) };
  }
  std::sort(uv.begin(), uv.end());
  return uv;
}

// Exact triangle counts between level i and i + 1 of a hierarchy whose TCoords address a
// texture of each level's own (baked levels, whose points are split per texture square, or
// level 0 with the input's texture), about 190 counts evenly spread. The geomorph's schedule
// joins each point's copies as one: every count between the levels is reached (a closed
// surface's within parity, never above), the output is the level's surface once its coincident
// points are welded (closed, manifold, no degenerate triangle), and its points stay apart with
// their own texture coordinates: every output triangle has the corner coordinates of a
// triangle of the level (points merged across a seam would mix squares), and no point is left
// without a triangle. With the copies joined one at a time, as before, few counts were
// reachable (8 of the 489 between a UV sphere's baked levels of 986 and 496 triangles).
void CheckExactCountsWithOwnTextures(vtkMultiBlockDataSet* h, unsigned int i)
{
  auto* fine = vtkPolyData::SafeDownCast(h->GetBlock(i));
  auto* coarse = vtkPolyData::SafeDownCast(h->GetBlock(i + 1));
  const testing::MeshReport fineReport = testing::InspectMesh(WeldCoincidentPoints(fine));
  MESHLOD_CHECK_EQ(fineReport.NonManifoldEdges, 0);
  MESHLOD_CHECK_EQ(fineReport.BoundaryEdges, 0);
  // The output's TCoords are those of level floor(L) (ActualLevelOfDetail), whose texture they
  // address: level i's, or level i + 1's where only the whole transition reaches the count.
  std::set<UVTriple> levelUVs[2];
  for (unsigned int k = 0; k < 2; ++k)
  {
    auto* level = vtkPolyData::SafeDownCast(h->GetBlock(i + k));
    for (const Triangle& t : Triangles(level))
    {
      levelUVs[k].insert(CornerUVs(level->GetPointData()->GetTCoords(), t));
    }
  }
  vtkNew<vtkLODGeomorph> geomorph;
  geomorph->SetInputData(h);
  const vtkIdType first = coarse->GetNumberOfPolys() + 1, last = fine->GetNumberOfPolys() - 1;
  int counts = 0, missed = 0, above = 0, broken = 0, foreign = 0, unused = 0, atNext = 0;
  const vtkIdType stride = std::max<vtkIdType>(1, (last - first) / 190);
  for (vtkIdType count = first; count <= last; count += stride)
  {
    for (const double fraction : { 0.0, 0.6 })
    {
      geomorph->SetTargetNumberOfTriangles(count);
      geomorph->SetCollapseFraction(fraction);
      geomorph->Update();
      vtkPolyData* out = geomorph->GetOutput();
      ++counts;
      missed += count - out->GetNumberOfPolys() > 1 ? 1 : 0;
      above += out->GetNumberOfPolys() > count ? 1 : 0;
      const testing::MeshReport report = testing::InspectMesh(WeldCoincidentPoints(out));
      broken += (report.NonManifoldEdges || report.NonManifoldVertices || report.BoundaryEdges ||
                  report.DegenerateTriangles || report.DuplicateTriangles ||
                  !report.ConsistentlyOriented ||
                  report.EulerCharacteristic != fineReport.EulerCharacteristic)
        ? 1
        : 0;
      vtkDataArray* tcoords = out->GetPointData()->GetTCoords();
      MESHLOD_CHECK(tcoords != nullptr);
      const int k = static_cast<int>(std::floor(geomorph->GetActualLevelOfDetail())) -
        static_cast<int>(i);
      MESHLOD_CHECK(k == 0 || k == 1);
      atNext += k == 1 ? 1 : 0;
      std::vector<std::uint8_t> used(out->GetNumberOfPoints(), 0);
      for (const Triangle& t : Triangles(out))
      {
        used[t[0]] = used[t[1]] = used[t[2]] = 1;
        foreign += tcoords && (k != 0 && k != 1 || levelUVs[k].count(CornerUVs(tcoords, t)) == 0)
          ? 1
          : 0;
      }
      unused += static_cast<int>(std::count(used.begin(), used.end(), 0));
    }
  }
  std::cout << "  exact counts between levels " << i << " and " << i + 1 << " ("
            << fine->GetNumberOfPolys() << " and "
            << coarse->GetNumberOfPolys() << " triangles): " << counts << " outputs, " << missed
            << " missed by more than parity, " << broken << " not a closed manifold once welded\n";
  MESHLOD_CHECK_GT(counts, 100);
  MESHLOD_CHECK_EQ(missed, 0);
  MESHLOD_CHECK_EQ(above, 0);
  MESHLOD_CHECK_EQ(broken, 0);
  MESHLOD_CHECK_EQ(unused, 0);
  MESHLOD_CHECK_EQ(foreign, 0);
  // The first count, one above the next level's, is reached only at the transition's end
  // (a closed surface's counts go in steps of two): the next level, with its own TCoords.
  MESHLOD_CHECK_GE(atNext, 1);
}

// Colours from a point array (a scalar field through a lookup table).
void TestColorArray()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Metaballs, 60);
  vtkSmartPointer<vtkUnsignedCharArray> colors = ColorPoints(mesh, 1.5,
    [](const double* x) { return std::sin(9.0 * x[0]) * std::cos(7.0 * x[1]) + x[2]; }, true);
  vtkNew<vtkIdTypeArray> globalIds;
  globalIds->SetName("GlobalIds");
  globalIds->SetNumberOfTuples(mesh->GetNumberOfPoints());
  std::iota(globalIds->Begin(), globalIds->End(), vtkIdType(100));
  mesh->GetPointData()->SetGlobalIds(globalIds);

  const vtkIdType n = mesh->GetNumberOfPolys();
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(mesh);
  filter->SetLevelModeToTargetTriangleCounts();
  filter->AddTargetTriangleCount(n / 20);
  filter->AddTargetTriangleCount(n / 100);
  filter->BakeTextureOn();
  filter->SetTextureResolution(256);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  vtkMultiBlockDataSet* textures = filter->GetTextures();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK_EQ(textures->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK(CheckHierarchyLayout(h, true).empty());
  MESHLOD_CHECK(textures->GetBlock(0) == nullptr);
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    auto* level = vtkPolyData::SafeDownCast(h->GetBlock(i));
    auto* texture = vtkImageData::SafeDownCast(textures->GetBlock(i));
    MESHLOD_CHECK(level && texture);
    if (!level || !texture)
    {
      continue;
    }
    MESHLOD_CHECK_EQ(texture->GetPointData()->GetScalars()->GetNumberOfComponents(), 4);
    MESHLOD_CHECK_LE(
      std::abs(level->GetNumberOfPolys() - (i == 1 ? n / 20 : n / 100)), 2 + n / 5000);
    CheckAtlas(level, texture);
    // The copies of a split point share its global id: the values stay, the GlobalIds
    // attribute (one point per id) does not.
    MESHLOD_CHECK(level->GetPointData()->GetGlobalIds() == nullptr);
    MESHLOD_CHECK(vtkIdTypeArray::SafeDownCast(level->GetPointData()->GetArray("GlobalIds")));
  }
  MESHLOD_CHECK(
    vtkPolyData::SafeDownCast(h->GetBlock(0))->GetPointData()->GetGlobalIds() == globalIds);

  // The coarsest level's baked texture against per-vertex averaging at the same level.
  auto* level = vtkPolyData::SafeDownCast(h->GetBlock(2));
  auto* texture = vtkImageData::SafeDownCast(textures->GetBlock(2));
  auto truth = [&](const Triangle& t, const double* w) { return Interpolate(colors, t, w); };
  const double baked = MeanColorError(mesh,
    truth,
    level,
    [&](const Triangle& t, const double* w) { return BakedColor(level, texture, t, w); });
  vtkDataArray* averaged = level->GetPointData()->GetArray("Colors");
  const double perVertex = MeanColorError(mesh,
    truth,
    level,
    [&](const Triangle& t, const double* w) { return Interpolate(averaged, t, w); });
  std::cout << "  1% level, mean colour error (0-255): baked texture " << baked
            << ", per-vertex average " << perVertex << "\n";
  MESHLOD_CHECK_LT(baked, 4.0);
  MESHLOD_CHECK_LT(baked, 0.2 * perVertex);

  // Each baked level's TCoords address its own texture, and say so; a geomorph between two such
  // levels keeps the finer level's (blending them mixed two atlases: meaningless coordinates).
  for (unsigned int i = 1; i < h->GetNumberOfBlocks(); ++i)
  {
    vtkDataArray* mark = vtkPolyData::SafeDownCast(h->GetBlock(i))
                           ->GetFieldData()
                           ->GetArray(meshlod::names::TextureAtlasLevel);
    MESHLOD_CHECK(mark != nullptr && mark->GetTuple1(0) == i);
  }
  auto* fine = vtkPolyData::SafeDownCast(h->GetBlock(1));
  for (const bool exact : { false, true })
  {
    vtkNew<vtkLODGeomorph> geomorph;
    geomorph->SetInputData(h);
    geomorph->SetLevelOfDetail(1.5);
    if (exact)
    {
      geomorph->SetTargetNumberOfTriangles(
        (fine->GetNumberOfPolys() + level->GetNumberOfPolys()) / 2);
    }
    geomorph->Update();
    vtkPolyData* out = geomorph->GetOutput();
    // It says which texture its TCoords address: level 1's.
    vtkDataArray* atlasLevel =
      out->GetFieldData()->GetArray(meshlod::names::TextureAtlasLevel);
    MESHLOD_CHECK(atlasLevel != nullptr && atlasLevel->GetTuple1(0) == 1.0);
    vtkDataArray* tcoords = out->GetPointData()->GetTCoords();
    MESHLOD_CHECK(tcoords != nullptr);
    if (!tcoords)
    {
      continue;
    }
    // Every output point's coordinates are those of a point of level 1 at its own position
    // in level 1's atlas: the output's triangles sample level 1's texture where level 1 does.
    std::set<std::array<float, 2>> atlas;
    for (vtkIdType p = 0; p < fine->GetNumberOfPoints(); ++p)
    {
      const double* uv = fine->GetPointData()->GetTCoords()->GetTuple2(p);
      atlas.insert({ static_cast<float>(uv[0]), static_cast<float>(uv[1]) });
    }
    vtkIdType foreign = 0;
    for (vtkIdType p = 0; p < tcoords->GetNumberOfTuples(); ++p)
    {
      const double* uv = tcoords->GetTuple2(p);
      foreign += atlas.count({ static_cast<float>(uv[0]), static_cast<float>(uv[1]) }) == 0;
    }
    MESHLOD_CHECK_EQ(foreign, 0);
  }
  CheckExactCountsWithOwnTextures(h, 1);
}

//------------------------------------------------------------------------------
// A square RGB texture of `size` texels a side, texel (x, y) coloured by `rgb`.
vtkSmartPointer<vtkImageData> MakeTexture(
  int size, const std::function<std::array<unsigned char, 3>(int x, int y)>& rgb)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size, size, 1);
  vtkNew<vtkUnsignedCharArray> texels;
  texels->SetNumberOfComponents(3);
  texels->SetNumberOfTuples(size * size);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      texels->SetTypedTuple(y * size + x, rgb(x, y).data());
    }
  }
  image->GetPointData()->SetScalars(texels);
  return image;
}

// Colours from an input texture at the input's texture coordinates.
void TestInputTexture()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Torus, 50);
  double bounds[6];
  mesh->GetBounds(bounds);
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName("UV");
  tcoords->SetNumberOfComponents(2);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const double* x = mesh->GetPoint(p);
    const float uv[2] = { static_cast<float>((x[0] - bounds[0]) / (bounds[1] - bounds[0])),
      static_cast<float>((x[1] - bounds[2]) / (bounds[3] - bounds[2])) };
    tcoords->InsertNextTypedTuple(uv);
  }
  mesh->GetPointData()->SetTCoords(tcoords);
  const int size = 64;
  vtkSmartPointer<vtkImageData> image = MakeTexture(size, [&](int x, int y) {
    const double u = (x + 0.5) / size, v = (y + 0.5) / size;
    return std::array<unsigned char, 3>{ static_cast<unsigned char>(
                                           127.5 + 127.5 * std::sin(12.0 * u)),
      static_cast<unsigned char>(127.5 + 127.5 * std::cos(9.0 * v)),
      static_cast<unsigned char>(255.0 * u * v) };
  });

  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputData(mesh);
  filter->SetTextureData(image);
  filter->SetLevelModeToTargetTriangleCounts();
  filter->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 50);
  filter->BakeTextureOn();
  filter->SetTextureResolution(128);
  filter->Update();
  vtkMultiBlockDataSet* h = filter->GetHierarchy();
  vtkMultiBlockDataSet* textures = filter->GetTextures();
  MESHLOD_CHECK_EQ(h->GetNumberOfBlocks(), 2u);
  MESHLOD_CHECK_EQ(textures->GetNumberOfBlocks(), 2u);
  MESHLOD_CHECK(textures->GetBlock(0) == image.GetPointer());
  auto* level = vtkPolyData::SafeDownCast(h->GetBlock(1));
  auto* texture = vtkImageData::SafeDownCast(textures->GetBlock(1));
  MESHLOD_REQUIRE(level && texture);
  MESHLOD_CHECK(level->GetPointData()->GetTCoords() != nullptr &&
    std::string(level->GetPointData()->GetTCoords()->GetName()) == "UV");
  MESHLOD_CHECK_EQ(texture->GetPointData()->GetScalars()->GetNumberOfComponents(), 3);
  CheckAtlas(level, texture);
  auto truth = [&](const Triangle& t, const double* w)
  {
    double uv[2] = { 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      uv[0] += w[k] * tcoords->GetComponent(t[k], 0);
      uv[1] += w[k] * tcoords->GetComponent(t[k], 1);
    }
    return Lookup(image, uv[0], uv[1]);
  };
  const double baked = MeanColorError(mesh,
    truth,
    level,
    [&](const Triangle& t, const double* w) { return BakedColor(level, texture, t, w); });
  std::cout << "  textured input, mean colour error (0-255): " << baked << "\n";
  MESHLOD_CHECK_LT(baked, 4.0);
  CheckExactCountsWithOwnTextures(h, 0);
}

//------------------------------------------------------------------------------
// A request for a piece of the mesh still gets the whole texture: the piece request used to
// reach port 1, so an image source made half the image (371 of 4,096 texels of the level's
// baked texture then differed) and an image filter there crashed on the part it was missing.
void TestTextureInPieces()
{
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetThetaResolution(40);
  sphere->SetPhiResolution(20);
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(0, 63, 0, 63, 0, 0);
  vtkNew<vtkImageShiftScale> texture;
  texture->SetInputConnection(wavelet->GetOutputPort());
  texture->SetShift(-37.0);
  texture->SetScale(1.2);
  texture->SetOutputScalarTypeToUnsignedChar();
  texture->ClampOverflowOn();
  vtkNew<vtkVertexClusterOctree> filter;
  filter->SetInputConnection(0, sphere->GetOutputPort());
  filter->SetInputConnection(1, texture->GetOutputPort());
  filter->SetNumberOfLevels(1);
  filter->BakeTextureOn();
  filter->SetTextureResolution(64);
  filter->UpdatePiece(0, 2, 0);
  const int* extent = texture->GetOutput()->GetExtent();
  MESHLOD_CHECK(extent[0] == 0 && extent[1] == 63 && extent[2] == 0 && extent[3] == 63);
  // The same textures as the same piece of the mesh baked from the whole image given as data.
  vtkMultiBlockDataSet* textures = filter->GetTextures();
  MESHLOD_CHECK_EQ(textures->GetNumberOfBlocks(), 2u);
  vtkNew<vtkImageData> whole;
  whole->DeepCopy(texture->GetOutput());
  vtkNew<vtkPolyData> piece;
  piece->DeepCopy(vtkPolyData::SafeDownCast(filter->GetInputDataObject(0, 0)));
  vtkNew<vtkVertexClusterOctree> reference;
  reference->SetInputData(piece);
  reference->SetTextureData(whole);
  reference->SetNumberOfLevels(1);
  reference->BakeTextureOn();
  reference->SetTextureResolution(64);
  reference->Update();
  auto* baked = vtkImageData::SafeDownCast(textures->GetBlock(1));
  auto* expected = vtkImageData::SafeDownCast(reference->GetTextures()->GetBlock(1));
  MESHLOD_CHECK(baked && expected &&
    SameValues(baked->GetPointData()->GetScalars(), expected->GetPointData()->GetScalars()));
}

// The same output for one thread and for several (the whole pipeline, baking included).
void CheckThreads(vtkPolyData* mesh, vtkImageData* texture)
{
  const std::string original = vtkSMPTools::GetBackend();
  std::vector<vtkSmartPointer<vtkMultiBlockDataSet>> results[2];
  const char* backends[2] = { "Sequential", original.c_str() };
  for (int run = 0; run < 2; ++run)
  {
    vtkSMPTools::SetBackend(backends[run]);
    vtkSMPTools::Initialize(run == 0 ? 1 : 2);
    vtkNew<vtkVertexClusterOctree> filter;
    vtkNew<vtkTest::ErrorObserver> warnings; // the isosurface has a few degenerate triangles
    filter->AddObserver(vtkCommand::WarningEvent, warnings);
    filter->SetInputData(mesh);
    filter->SetTextureData(texture);
    filter->SetLevelModeToTargetTriangleCounts();
    filter->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 5);
    filter->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 50);
    filter->ComputeNormalsOn();
    filter->BakeTextureOn();
    filter->SetTextureResolution(128);
    filter->Update();
    for (int port = 0; port < 2; ++port)
    {
      auto copy = vtkSmartPointer<vtkMultiBlockDataSet>::New();
      copy->DeepCopy(filter->GetOutputDataObject(port));
      results[run].push_back(copy);
    }
  }
  vtkSMPTools::SetBackend(original.c_str());
  vtkMultiBlockDataSet* one = results[0][0];
  vtkMultiBlockDataSet* two = results[1][0];
  MESHLOD_CHECK_EQ(one->GetNumberOfBlocks(), 3u);
  MESHLOD_CHECK_EQ(one->GetNumberOfBlocks(), two->GetNumberOfBlocks());
  for (unsigned int i = 0; i < std::min(one->GetNumberOfBlocks(), two->GetNumberOfBlocks()); ++i)
  {
    auto* a = vtkPolyData::SafeDownCast(one->GetBlock(i));
    auto* b = vtkPolyData::SafeDownCast(two->GetBlock(i));
    MESHLOD_CHECK(SameValues(a->GetPoints()->GetData(), b->GetPoints()->GetData()));
    MESHLOD_CHECK(Triangles(a) == Triangles(b));
    MESHLOD_CHECK_EQ(
      a->GetPointData()->GetNumberOfArrays(), b->GetPointData()->GetNumberOfArrays());
    for (int k = 0; k < a->GetPointData()->GetNumberOfArrays(); ++k)
    {
      // (By place: the arrays come in the same order, and some have no name.)
      MESHLOD_CHECK(SameValues(a->GetPointData()->GetArray(k), b->GetPointData()->GetArray(k)));
    }
    auto* ta = vtkImageData::SafeDownCast(results[0][1]->GetBlock(i));
    auto* tb = vtkImageData::SafeDownCast(results[1][1]->GetBlock(i));
    MESHLOD_CHECK((ta == nullptr) == (tb == nullptr));
    if (ta && tb)
    {
      MESHLOD_CHECK(SameValues(ta->GetPointData()->GetScalars(), tb->GetPointData()->GetScalars()));
    }
  }
}

void TestThreads()
{
  vtkSmartPointer<vtkPolyData> mesh =
    testing::MakeIsosurface(testing::Field::Gyroid, 40, false, true);
  ColorPoints(mesh, 1.0, [](const double* x) { return std::sin(5.0 * x[0]); });
  CheckThreads(mesh, nullptr);
  // Looked up in an input texture: at a sphere's poles many triangles share the closest point,
  // each with its own texture coordinates there, and the one the cell locator returned depended
  // on the SMP backend (19 to 46 texels of a level differed between TBB and Sequential).
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  sphere->Update();
  vtkSmartPointer<vtkImageData> image = MakeTexture(64, [](int x, int y) {
    return std::array<unsigned char, 3>{ static_cast<unsigned char>(4 * x),
      static_cast<unsigned char>(4 * y), static_cast<unsigned char>(8 * (x ^ y)) };
  });
  CheckThreads(sphere->GetOutput(), image);
}

// Baking reports progress as it goes (a texture of TextureResolution 16384 takes minutes) and
// stops at an abort.
void TestBakingProgress()
{
  vtkSmartPointer<vtkPolyData> mesh = testing::MakeIsosurface(testing::Field::Metaballs, 40);
  ColorPoints(mesh, 1.0, [](const double* x) { return std::sin(5.0 * x[0]); });
  struct Reports
  {
    std::vector<double> Values;
    double AbortAbove = 2.0;
  };
  for (const double abortAbove : { 2.0, 0.7 })
  {
    vtkNew<vtkVertexClusterOctree> filter;
    vtkNew<vtkTest::ErrorObserver> errors;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    Reports reports;
    reports.AbortAbove = abortAbove;
    vtkNew<vtkCallbackCommand> progress;
    progress->SetClientData(&reports);
    progress->SetCallback(
      [](vtkObject* caller, unsigned long, void* data, void*)
      {
        auto* algorithm = static_cast<vtkAlgorithm*>(caller);
        auto* r = static_cast<Reports*>(data);
        r->Values.push_back(algorithm->GetProgress());
        if (algorithm->GetProgress() > r->AbortAbove)
        {
          algorithm->AbortExecuteOn();
        }
      });
    filter->AddObserver(vtkCommand::ProgressEvent, progress);
    filter->SetInputData(mesh);
    filter->SetLevelModeToTargetTriangleCounts();
    filter->AddTargetTriangleCount(mesh->GetNumberOfPolys() / 50);
    filter->BakeTextureOn();
    filter->SetTextureResolution(512);
    filter->Update();
    MESHLOD_CHECK(!errors->GetError());
    // The one level's baking covers (0.65, 0.9] in 16 chunks.
    const auto baking = std::count_if(reports.Values.begin(), reports.Values.end(),
      [](double v) { return v > 0.65 && v <= 0.9; });
    MESHLOD_CHECK(std::is_sorted(reports.Values.begin(), reports.Values.end()));
    if (abortAbove > 1.0)
    {
      MESHLOD_CHECK_GE(baking, 16);
      MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 2u);
      MESHLOD_CHECK_EQ(filter->GetTextures()->GetNumberOfBlocks(), 2u);
    }
    else
    {
      // Stopped inside the baking, at the first report past 0.7: both outputs empty.
      MESHLOD_CHECK_GE(baking, 1);
      MESHLOD_CHECK_LT(baking, 16);
      MESHLOD_CHECK_EQ(filter->GetHierarchy()->GetNumberOfBlocks(), 0u);
      MESHLOD_CHECK_EQ(filter->GetTextures()->GetNumberOfBlocks(), 0u);
    }
  }
}
} // namespace

int TestVertexClusterOctreeTexture(int, char*[])
{
  TestColorArray();
  TestInputTexture();
  TestTextureInPieces();
  TestThreads();
  TestBakingProgress();
  return meshlod::testing::Result();
}
