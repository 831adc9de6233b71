#include "MeshLODTextureBaking.h"
#include "MeshLODTriangleTree.h"
#include "Core/TriangulationFlips.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace meshlod
{
struct TextureBaker::Internals
{
  SurfaceTriangles Surface; // the input's triangles and points, and the tree over them
  // Colour mode: 4 floats (0-255) per point.
  std::vector<float> Colors;
  // Texture mode.
  std::vector<float> TCoords; // 2 per point
  std::vector<float> Texture; // 4 floats (0-255) per texel
  int TextureWidth = 0;
  int TextureHeight = 0;
  double Diagonal = 0.0; // of the surface's bounding box

  void TextureLookup(double u, double v, float rgba[4]) const;
};

namespace
{
// Barycentric coordinates of p (in the plane of the triangle) with respect to a, b, c.
void Barycentric(const double* a, const double* b, const double* c, const double p[3], double w[3])
{
  const double e0[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double e1[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double d[3] = { p[0] - a[0], p[1] - a[1], p[2] - a[2] };
  const double d00 = e0[0] * e0[0] + e0[1] * e0[1] + e0[2] * e0[2];
  const double d01 = e0[0] * e1[0] + e0[1] * e1[1] + e0[2] * e1[2];
  const double d11 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
  const double d20 = d[0] * e0[0] + d[1] * e0[1] + d[2] * e0[2];
  const double d21 = d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2];
  const double denominator = d00 * d11 - d01 * d01;
  if (!(std::abs(denominator) > 0.0))
  {
    w[0] = 1.0;
    w[1] = w[2] = 0.0;
    return;
  }
  w[1] = (d11 * d20 - d01 * d21) / denominator;
  w[2] = (d00 * d21 - d01 * d20) / denominator;
  w[0] = 1.0 - w[1] - w[2];
}

// A unique id per edge of the mesh (sorted by end points), and the edge of each corner.
struct MeshEdges
{
  std::vector<Id> Lo, Hi;   // per edge: lower and higher point id
  std::vector<Id> OfCorner; // 3 t + k (edge from corner k to k + 1) -> edge
};

MeshEdges FindEdges(const TriangleMesh& mesh)
{
  MeshEdges edges;
  const Id nt = mesh.GetNumberOfTriangles();
  std::vector<std::int64_t> order(3 * static_cast<size_t>(nt));
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](std::int64_t c)
  {
    const Id a = mesh.Triangles[c];
    const Id b = mesh.Triangles[(c / 3) * 3 + (c % 3 + 1) % 3];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  std::sort(order.begin(),
    order.end(),
    [&](std::int64_t x, std::int64_t y) { return key(x) < key(y) || (key(x) == key(y) && x < y); });
  edges.OfCorner.resize(order.size());
  for (size_t i = 0; i < order.size(); ++i)
  {
    const auto k = key(order[i]);
    if (i == 0 || k != key(order[i - 1]))
    {
      edges.Lo.push_back(k.first);
      edges.Hi.push_back(k.second);
    }
    edges.OfCorner[order[i]] = static_cast<Id>(edges.Lo.size() - 1);
  }
  return edges;
}

void Lerp(const double* a, const double* b, double t, double out[3])
{
  for (int c = 0; c < 3; ++c)
  {
    out[c] = a[c] + t * (b[c] - a[c]);
  }
}
} // namespace

//------------------------------------------------------------------------------
TextureBaker::TextureBaker()
  : Impl(new Internals)
{
}

TextureBaker::~TextureBaker()
{
  delete this->Impl;
}

//------------------------------------------------------------------------------
bool TextureBaker::SetSurface(vtkPolyData* surface, std::string& error)
{
  Internals& impl = *this->Impl;
  std::vector<vtkIdType> triangles;
  auto it = vtk::TakeSmartPointer(surface->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    if (n != 3)
    {
      error = "the surface to bake from must be made of triangles";
      return false;
    }
    triangles.insert(triangles.end(), ids, ids + 3);
  }
  impl.Surface.Build(surface->GetPoints(), std::move(triangles));
  impl.Diagonal = surface->GetLength();
  return true;
}

//------------------------------------------------------------------------------
namespace
{
// Colours in 0-255: floating ones count 0-1, 16-bit ones 0-65535 (a 16-bit image), the other
// integer types 0-255 (unsigned char, or an int RGB array holding the same numbers).
double ColorScale(vtkDataArray* colors)
{
  switch (colors->GetDataType())
  {
    case VTK_FLOAT:
    case VTK_DOUBLE:
      return 255.0;
    case VTK_UNSIGNED_SHORT:
    case VTK_SHORT:
      return 255.0 / 65535.0;
    default:
      return 1.0;
  }
}
} // namespace

//------------------------------------------------------------------------------
bool TextureBaker::InitializeFromColors(vtkPolyData* surface,
  vtkDataArray* colors,
  std::string& error)
{
  const int nc = colors ? colors->GetNumberOfComponents() : 0;
  if (colors == nullptr || (nc != 3 && nc != 4) ||
    colors->GetNumberOfTuples() != surface->GetNumberOfPoints())
  {
    error = "the colour array must be a point array with 3 (RGB) or 4 (RGBA) components";
    return false;
  }
  const double scale = ColorScale(colors);
  const vtkIdType np = colors->GetNumberOfTuples();
  Internals& impl = *this->Impl;
  impl.Colors.resize(4 * static_cast<size_t>(np));
  for (vtkIdType p = 0; p < np; ++p)
  {
    for (int c = 0; c < 4; ++c)
    {
      const double value = c < nc ? colors->GetComponent(p, c) * scale : 255.0;
      impl.Colors[4 * p + c] = static_cast<float>(std::min(255.0, std::max(0.0, value)));
    }
  }
  this->Components = nc;
  return this->SetSurface(surface, error);
}

//------------------------------------------------------------------------------
bool TextureBaker::InitializeFromTexture(vtkPolyData* surface,
  vtkDataArray* tcoords,
  vtkImageData* texture,
  std::string& error)
{
  vtkDataArray* scalars = texture ? texture->GetPointData()->GetScalars() : nullptr;
  int dims[3] = { 0, 0, 0 };
  if (texture)
  {
    texture->GetDimensions(dims);
  }
  // The image's points run along x, then y, then z: whichever two axes a 2D image spans (XY, XZ
  // or YZ), its texels lie row after row, the first of those axes along a row.
  int size[2] = { 1, 1 };
  int spanned = 0;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (dims[axis] > 1 && spanned < 2)
    {
      size[spanned] = dims[axis];
    }
    spanned += dims[axis] > 1 ? 1 : 0;
  }
  if (scalars == nullptr || scalars->GetNumberOfComponents() > 4 || dims[0] < 1 || dims[1] < 1 ||
    dims[2] < 1 || spanned > 2)
  {
    error = "the texture must be a 2D vtkImageData with 1 to 4 component scalars";
    return false;
  }
  const vtkIdType texels = static_cast<vtkIdType>(size[0]) * size[1];
  if (scalars->GetNumberOfTuples() != texels)
  {
    error = "the texture's scalars have " + std::to_string(scalars->GetNumberOfTuples()) +
      " tuples, not one for each of its " + std::to_string(texels) + " points";
    return false;
  }
  if (tcoords == nullptr || tcoords->GetNumberOfComponents() < 2 ||
    tcoords->GetNumberOfTuples() != surface->GetNumberOfPoints())
  {
    error = "the input needs point texture coordinates (2 components) to bake from a texture";
    return false;
  }
  Internals& impl = *this->Impl;
  impl.TextureWidth = size[0];
  impl.TextureHeight = size[1];
  const int nc = scalars->GetNumberOfComponents();
  const double scale = ColorScale(scalars);
  impl.Texture.resize(4 * static_cast<size_t>(texels));
  for (vtkIdType i = 0; i < texels; ++i)
  {
    double v[4];
    for (int c = 0; c < nc; ++c)
    {
      v[c] = std::min(255.0, std::max(0.0, scalars->GetComponent(i, c) * scale));
    }
    // Grey and grey-alpha images spread to RGB.
    const double rgba[4] = {
      v[0], nc >= 3 ? v[1] : v[0], nc >= 3 ? v[2] : v[0], nc == 4 ? v[3] : (nc == 2 ? v[1] : 255.0)
    };
    for (int c = 0; c < 4; ++c)
    {
      impl.Texture[4 * i + c] = static_cast<float>(rgba[c]);
    }
  }
  const vtkIdType np = tcoords->GetNumberOfTuples();
  impl.TCoords.resize(2 * static_cast<size_t>(np));
  for (vtkIdType p = 0; p < np; ++p)
  {
    impl.TCoords[2 * p] = static_cast<float>(tcoords->GetComponent(p, 0));
    impl.TCoords[2 * p + 1] = static_cast<float>(tcoords->GetComponent(p, 1));
  }
  this->Components = (nc == 2 || nc == 4) ? 4 : 3;
  return this->SetSurface(surface, error);
}

//------------------------------------------------------------------------------
void TextureBaker::Internals::TextureLookup(double u, double v, float rgba[4]) const
{
  // Texel centres sit at (i + 0.5) / width; coordinates repeat outside [0, 1].
  const double x = u * this->TextureWidth - 0.5;
  const double y = v * this->TextureHeight - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  auto wrap = [](long long i, int n) { return static_cast<int>(((i % n) + n) % n); };
  const int x0 = wrap(static_cast<long long>(fx), this->TextureWidth);
  const int x1 = wrap(static_cast<long long>(fx) + 1, this->TextureWidth);
  const int y0 = wrap(static_cast<long long>(fy), this->TextureHeight);
  const int y1 = wrap(static_cast<long long>(fy) + 1, this->TextureHeight);
  const float* t00 = this->Texture.data() + 4 * (static_cast<size_t>(y0) * this->TextureWidth + x0);
  const float* t10 = this->Texture.data() + 4 * (static_cast<size_t>(y0) * this->TextureWidth + x1);
  const float* t01 = this->Texture.data() + 4 * (static_cast<size_t>(y1) * this->TextureWidth + x0);
  const float* t11 = this->Texture.data() + 4 * (static_cast<size_t>(y1) * this->TextureWidth + x1);
  for (int c = 0; c < 4; ++c)
  {
    rgba[c] = static_cast<float>(
      (1 - ty) * ((1 - tx) * t00[c] + tx * t10[c]) + ty * ((1 - tx) * t01[c] + tx * t11[c]));
  }
}

//------------------------------------------------------------------------------
void TextureBaker::ColorAt(const double point[3], float rgba[4]) const
{
  const Internals& impl = *this->Impl;
  double closest[3];
  double dist2 = 0.0;
  vtkIdType cellId = impl.Surface.Tree.FindClosest(point, closest, dist2);
  if (cellId < 0)
  {
    rgba[0] = rgba[1] = rgba[2] = 0.0f;
    rgba[3] = 255.0f;
    return;
  }
  const vtkIdType* ids = impl.Surface.Triangles.data() + 3 * cellId;
  double w[3];
  const double* points = impl.Surface.Points.data();
  auto weigh = [&]() {
    Barycentric(points + 3 * ids[0], points + 3 * ids[1], points + 3 * ids[2], closest, w);
  };
  weigh();
  // Closest on an edge or a corner: other triangles are as close, within rounding, and which
  // of them the search met first would decide the colour where they carry different texture
  // coordinates at the shared point (a sphere's pole, one u per triangle). The lowest id of
  // them is taken, the same on every run. Well inside, only a triangle lying on this one, or
  // one elsewhere at the very same distance, could be: the search is skipped (made for every
  // texel, it made baking a quarter slower).
  if (std::min({ w[0], w[1], w[2] }) <= 1e-6)
  {
    const double tie = dist2 * (1.0 + 1e-9) + 1e-24 * impl.Diagonal * impl.Diagonal;
    const vtkIdType lowest = impl.Surface.Tree.FindLowestWithin(point, tie, closest);
    if (lowest >= 0 && lowest != cellId)
    {
      cellId = lowest;
      ids = impl.Surface.Triangles.data() + 3 * cellId;
      weigh();
    }
  }
  for (double& x : w)
  {
    x = std::min(1.0, std::max(0.0, x));
  }
  const double sum = w[0] + w[1] + w[2];
  for (double& x : w)
  {
    x /= sum;
  }
  if (!impl.Colors.empty())
  {
    for (int c = 0; c < 4; ++c)
    {
      rgba[c] = static_cast<float>(w[0] * impl.Colors[4 * ids[0] + c] +
        w[1] * impl.Colors[4 * ids[1] + c] + w[2] * impl.Colors[4 * ids[2] + c]);
    }
    return;
  }
  double uv[2] = { 0.0, 0.0 };
  for (int k = 0; k < 3; ++k)
  {
    uv[0] += w[k] * impl.TCoords[2 * ids[k]];
    uv[1] += w[k] * impl.TCoords[2 * ids[k] + 1];
  }
  impl.TextureLookup(uv[0], uv[1], rgba);
}

//------------------------------------------------------------------------------
namespace
{
// Colours sampled along every edge of the mesh from its lower point id, at the finest spacing
// of the blocks on either side: the two blocks that share an edge show the same colours along it.
struct EdgeSamples
{
  std::vector<Id> Steps;     // per edge: its intervals
  std::vector<Id> Offsets;   // per edge: its first sample
  std::vector<float> Colors; // 4 per sample

  const float* At(Id e, Id j) const
  {
    return this->Colors.data() + 4 * static_cast<size_t>(this->Offsets[e] + j);
  }
  float* At(Id e, Id j)
  {
    return this->Colors.data() + 4 * static_cast<size_t>(this->Offsets[e] + j);
  }
};

EdgeSamples SampleEdges(const TextureBaker& baker, const TriangleMesh& mesh,
  const TextureAtlas& atlas, const MeshEdges& edges)
{
  EdgeSamples samples;
  const Id ne = static_cast<Id>(edges.Lo.size());
  std::vector<Id>& steps = samples.Steps;
  steps.assign(ne, std::numeric_limits<Id>::max());
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    const Id s = atlas.Blocks[atlas.TriangleBlock[t]].Size - 1;
    for (int k = 0; k < 3; ++k)
    {
      Id& e = steps[edges.OfCorner[3 * t + k]];
      e = std::min(e, s);
    }
  }
  samples.Offsets.assign(static_cast<size_t>(ne) + 1, 0);
  for (Id e = 0; e < ne; ++e)
  {
    samples.Offsets[e + 1] = samples.Offsets[e] + steps[e] + 1;
  }
  samples.Colors.resize(4 * static_cast<size_t>(samples.Offsets[ne]));
  vtkSMPTools::For(0,
    ne,
    [&](Id begin, Id end)
    {
      for (Id e = begin; e < end; ++e)
      {
        for (Id j = 0; j <= steps[e]; ++j)
        {
          double p[3];
          Lerp(
            mesh.Point(edges.Lo[e]), mesh.Point(edges.Hi[e]), static_cast<double>(j) / steps[e], p);
          if (j == steps[e])
          {
            std::copy_n(mesh.Point(edges.Hi[e]), 3, p); // exactly the end point
          }
          baker.ColorAt(p, samples.At(e, j));
        }
      }
    });
  return samples;
}

// The texels of a square image, quantised as they are computed: a float staging image would be
// four times the texture's size (4.3 GB at TextureResolution 16384).
struct TexelWriter
{
  unsigned char* Texels;
  Id Side;
  int Components;

  void Store(Id x, Id y, const float rgba[4]) const
  {
    const size_t index = static_cast<size_t>(y) * this->Side + x;
    unsigned char* texel = this->Texels + static_cast<size_t>(this->Components) * index;
    for (int c = 0; c < this->Components; ++c)
    {
      texel[c] = static_cast<unsigned char>(std::lround(std::min(255.0f, std::max(0.0f, rgba[c]))));
    }
  }
};

// The colour of a texel of triangle t on the edge opposite corner `onEdge` (`n`: the texel's
// integer barycentrics, `area` their sum): the edge's samples interpolated at the texel's exact
// rational position along the edge, from its lower point id.
void EdgeTexelColor(const TriangleMesh& mesh, const MeshEdges& edges, const EdgeSamples& samples,
  Id t, int onEdge, const std::int64_t n[3], std::int64_t area, float out[4])
{
  const Id* tri = mesh.Triangle(t);
  const int from = (onEdge + 1) % 3, to = (onEdge + 2) % 3;
  const Id e = edges.OfCorner[3 * t + from];
  const Id steps = samples.Steps[e];
  std::int64_t numerator = n[to], denominator = area;
  if (denominator < 0)
  {
    numerator = -numerator;
    denominator = -denominator;
  }
  if (tri[to] != edges.Hi[e])
  {
    numerator = denominator - numerator;
  }
  const std::int64_t scaled = numerator * steps;
  const Id j0 = static_cast<Id>(std::min<std::int64_t>(steps, scaled / denominator));
  const Id j1 = std::min<Id>(steps, j0 + 1);
  const double w = static_cast<double>(scaled % denominator) / denominator;
  const float* s0 = samples.At(e, j0);
  const float* s1 = samples.At(e, j1);
  for (int c = 0; c < 4; ++c)
  {
    out[c] = static_cast<float>((1.0 - w) * s0[c] + w * s1[c]);
  }
}

// Row `row` of the blocks' rows (`firstRow`: the rows of the blocks before each; the blocks do
// not overlap: any order, any thread). Integer barycentrics (twice the signed areas) tell
// inside, edge and outside exactly.
void BakeRow(const TextureBaker& baker, const TriangleMesh& mesh, const TextureAtlas& atlas,
  const MeshEdges& edges, const EdgeSamples& samples, const std::vector<Id>& firstRow, Id row,
  const TexelWriter& texels)
{
  const Id b = static_cast<Id>(
    std::upper_bound(firstRow.begin(), firstRow.end(), row) - firstRow.begin() - 1);
  const TextureAtlas::Block& block = atlas.Blocks[b];
  const Id s = block.Size - 1;
  const Id y = block.Y + (row - firstRow[b]);
  for (Id x = block.X; x < block.X + block.Size; ++x)
  {
    const bool upperHalf = (x - block.X) + (y - block.Y) > s;
    const Id t = (upperHalf && block.Upper != InvalidId) ? block.Upper : block.Lower;
    const Id* tc = atlas.CornerTexel.data() + 6 * static_cast<size_t>(t);
    const Id* tri = mesh.Triangle(t);
    std::int64_t n[3];
    for (int k = 0; k < 3; ++k)
    {
      const Id* p = tc + 2 * ((k + 1) % 3);
      const Id* q = tc + 2 * ((k + 2) % 3);
      n[k] = static_cast<std::int64_t>(p[0] - x) * (q[1] - y) -
        static_cast<std::int64_t>(p[1] - y) * (q[0] - x);
    }
    const std::int64_t area = n[0] + n[1] + n[2];
    float out[4];
    int onEdge = -1;
    if (!upperHalf || block.Upper != InvalidId)
    {
      for (int k = 0; k < 3; ++k)
      {
        onEdge = (n[k] == 0) ? k : onEdge;
      }
    }
    if (onEdge >= 0)
    {
      EdgeTexelColor(mesh, edges, samples, t, onEdge, n, area, out);
      texels.Store(x, y, out);
      continue;
    }
    // Inside the triangle, or in the padding half extending the lower triangle.
    double p[3] = { 0.0, 0.0, 0.0 };
    for (int k = 0; k < 3; ++k)
    {
      const double w = static_cast<double>(n[k]) / area;
      const double* corner = mesh.Point(tri[k]);
      for (int c = 0; c < 3; ++c)
      {
        p[c] += w * corner[c];
      }
    }
    baker.ColorAt(p, out);
    texels.Store(x, y, out);
  }
}
} // namespace

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> TextureBaker::Bake(const TriangleMesh& mesh,
  const TextureAtlas& atlas, const std::function<bool(double)>& progress) const
{
  const Id side = atlas.Resolution;
  const int components = this->Components;
  auto scalars = vtkSmartPointer<vtkUnsignedCharArray>::New();
  scalars->SetName("Texture");
  scalars->SetNumberOfComponents(components);
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(side) * side);
  unsigned char* dst = scalars->GetPointer(0);
  std::fill_n(dst, static_cast<size_t>(components) * side * side, static_cast<unsigned char>(0));
  const TexelWriter texels{ dst, side, components };

  const MeshEdges edges = FindEdges(mesh);
  const EdgeSamples samples = SampleEdges(*this, mesh, atlas, edges);

  // Texels, row by row of each block. The rows go in chunks, so that a large texture
  // (TextureResolution 16384 takes minutes) reports progress and can be stopped; rows rather
  // than blocks, so that a chunk of a few large blocks still keeps every thread busy.
  const Id numberOfBlocks = static_cast<Id>(atlas.Blocks.size());
  std::vector<Id> firstRow(static_cast<size_t>(numberOfBlocks) + 1, 0); // rows of blocks before
  for (Id b = 0; b < numberOfBlocks; ++b)
  {
    firstRow[b + 1] = firstRow[b] + atlas.Blocks[b].Size;
  }
  const Id rows = firstRow[numberOfBlocks];
  constexpr int Chunks = 16;
  for (int chunk = 0; chunk < Chunks; ++chunk)
  {
    const std::int64_t all = rows; // 64 bits: rows times Chunks can pass 2^31
    vtkSMPTools::For(static_cast<Id>(all * chunk / Chunks),
      static_cast<Id>(all * (chunk + 1) / Chunks),
      [&](Id begin, Id end)
      {
        for (Id row = begin; row < end; ++row)
        {
          BakeRow(*this, mesh, atlas, edges, samples, firstRow, row, texels);
        }
      });
    if (progress && !progress(static_cast<double>(chunk + 1) / Chunks))
    {
      return nullptr;
    }
  }

  auto result = vtkSmartPointer<vtkImageData>::New();
  result->SetDimensions(static_cast<int>(side), static_cast<int>(side), 1);
  result->GetPointData()->SetScalars(scalars);
  return result;
}

} // namespace meshlod
