#include "MeshLODInputMesh.h"

#include "Core/FreshMemory.h"
#include "Core/Vector3.h"
#include "MeshLODInputArrays.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTriangleFilter.h"
#include "vtkTypeInt32Array.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace meshlod
{
namespace
{
constexpr vtkIdType MaximumCount = std::numeric_limits<Id>::max();

bool IsFinitePoint(const double* x)
{
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
}

// Index of the first point with a NaN or infinite coordinate, or -1.
vtkIdType FirstNonFinitePoint(const std::vector<double>& xyz)
{
  const vtkIdType n = static_cast<vtkIdType>(xyz.size() / 3);
  vtkSMPThreadLocal<vtkIdType> firstBad(std::numeric_limits<vtkIdType>::max());
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    vtkIdType& local = firstBad.Local();
    for (vtkIdType i = begin; i < end && i < local; ++i)
    {
      if (!IsFinitePoint(xyz.data() + 3 * i))
      {
        local = i;
      }
    }
  });
  vtkIdType first = std::numeric_limits<vtkIdType>::max();
  for (vtkIdType v : firstBad)
  {
    first = std::min(first, v);
  }
  return first == std::numeric_limits<vtkIdType>::max() ? -1 : first;
}

// A point with a NaN or infinite coordinate that no triangle uses is dropped with the other
// unused points (CompactMesh); until then it takes the coordinates of a used point, so that the
// bounding box and the seam search see finite numbers only. Returns the first non-finite point
// a triangle uses (nothing is changed then), or -1.
vtkIdType SettleUnusedNonFinitePoints(TriangleMesh& mesh)
{
  const Id nv = mesh.GetNumberOfPoints();
  std::vector<unsigned char> used(nv, 0);
  for (const Id v : mesh.Triangles)
  {
    used[v] = 1;
  }
  for (Id v = 0; v < nv; ++v)
  {
    if (used[v] && !IsFinitePoint(mesh.Point(v)))
    {
      return v;
    }
  }
  if (mesh.Triangles.empty())
  {
    return -1;
  }
  // A used point: finite (checked above), so it is never itself overwritten.
  const double* stand = mesh.Point(mesh.Triangles[0]);
  for (Id v = 0; v < nv; ++v)
  {
    if (!IsFinitePoint(mesh.Point(v)))
    {
      std::copy_n(stand, 3, mesh.Points.begin() + 3 * static_cast<std::size_t>(v));
    }
  }
  return -1;
}

// Points as doubles: straight from the array's memory for float and double points (the usual
// case; a virtual GetTuple per point costs more than the copy), through GetTuple otherwise.
template <typename ValueT>
bool CopyTypedPoints(vtkDataArray* xyz, std::vector<double>& points)
{
  auto* typed = vtkAOSDataArrayTemplate<ValueT>::FastDownCast(xyz);
  if (typed == nullptr || typed->GetNumberOfComponents() != 3)
  {
    return false;
  }
  const ValueT* src = typed->GetPointer(0);
  const vtkIdType n = 3 * typed->GetNumberOfTuples();
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    std::copy(src + begin, src + end, points.data() + begin);
  });
  return true;
}

void CopyPoints(vtkDataArray* xyz, std::vector<double>& points)
{
  if (CopyTypedPoints<float>(xyz, points) || CopyTypedPoints<double>(xyz, points))
  {
    return;
  }
  vtkSMPTools::For(0, xyz->GetNumberOfTuples(), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      xyz->GetTuple(i, points.data() + 3 * i);
    }
  });
}

// Copy the connectivity of an all-triangle cell array into 32-bit ids.
template <typename ArrayT>
void CopyTriangles(ArrayT* connectivity, std::vector<Id>& triangles)
{
  const auto* src = connectivity->GetPointer(0);
  const vtkIdType n = connectivity->GetNumberOfValues();
  ResizeFresh(triangles, n);
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      triangles[i] = static_cast<Id>(src[i]);
    }
  });
}

// Drop triangles that repeat a vertex id; returns how many were dropped.
vtkIdType DropDegenerateTriangles(std::vector<Id>& triangles, std::vector<vtkIdType>& cellIds)
{
  size_t kept = 0;
  for (size_t t = 0; t < cellIds.size(); ++t)
  {
    const Id a = triangles[3 * t], b = triangles[3 * t + 1], c = triangles[3 * t + 2];
    if (a == b || b == c || c == a)
    {
      continue;
    }
    triangles[3 * kept] = a;
    triangles[3 * kept + 1] = b;
    triangles[3 * kept + 2] = c;
    cellIds[kept++] = cellIds[t];
  }
  const vtkIdType dropped = static_cast<vtkIdType>(cellIds.size() - kept);
  triangles.resize(3 * kept);
  cellIds.resize(kept);
  return dropped;
}

// Merge points that coincide up to rounding (at most SeamTolerance of the bounding diagonal
// apart, or SeamRoundingUnits double-precision epsilons of the largest coordinate where that is
// more) among the vertices of boundary and non-manifold edges: a triangle soup (an STL file)
// or a duplicated seam (a parametric surface whose seam points differ in the last bits and are
// joined by zero-area triangles) becomes one surface. Near-equal points are found in a grid of
// cells (SeamGrid), so pairs within the tolerance are compared whichever coordinates differ (up
// to MaximumSeamComparisons a point in its own cell and in each neighbouring cell). Returns the
// number of points merged away; triangles are re-indexed to the lowest id of each group. Points
// whose point data differ (`agree` is false) stay apart; `keptApart` counts the points left
// apart from a point they coincide with.
constexpr double SeamTolerance = 1e-12;
constexpr double SeamRoundingUnits = 64.0; // times DBL_EPSILON times the largest coordinate
// Comparisons per point at most: many coincident points with distinct data (a pathological
// input) would otherwise cost the square of their number.
constexpr size_t MaximumSeamComparisons = 64;

// The distance up to which seam points coincide (see MergeSeamPoints). Rounding is relative to
// the coordinates themselves: far from the origin (a scan in georeferenced coordinates) the last
// bits of a seam point are worth more than SeamTolerance of the diagonal, and the same mesh would
// stay open there that is stitched at the origin.
double SeamPointTolerance(const TriangleMesh& mesh, const std::vector<Id>& candidates)
{
  double largest = 0.0;
  for (const Id v : candidates)
  {
    for (int k = 0; k < 3; ++k)
    {
      largest = std::max(largest, std::abs(mesh.Point(v)[k]));
    }
  }
  return std::max(SeamTolerance * mesh.BoundingDiagonal(),
    SeamRoundingUnits * std::numeric_limits<double>::epsilon() * largest);
}

// The candidate points by grid cell, as (hash of the cell, point) sorted: cells that share a hash
// share a run, which the distance test then tells apart (16 bytes a point, not a key of three
// 64-bit integers and an index). A cell is CellTolerances tolerances wide, so that most points
// are farther than the tolerance from every face of their cell and are compared with their own
// cell's points only.
struct SeamGrid
{
  static constexpr double CellTolerances = 64.0;
  double CellSize;
  std::vector<std::pair<std::uint64_t, Id>> Points;

  SeamGrid(const TriangleMesh& mesh, const std::vector<Id>& candidates, double tolerance)
    : CellSize(tolerance > 0.0 ? CellTolerances * tolerance : 1.0) // 0: all points at the origin
  {
    this->Points.reserve(candidates.size());
    for (const Id v : candidates)
    {
      std::int64_t cell[3];
      this->CellOf(mesh.Point(v), cell);
      this->Points.emplace_back(Hash(cell), v);
    }
    std::sort(this->Points.begin(), this->Points.end());
  }

  void CellOf(const double* x, std::int64_t cell[3]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      cell[k] = static_cast<std::int64_t>(std::floor(x[k] / this->CellSize));
    }
  }

  static std::uint64_t Hash(const std::int64_t cell[3])
  {
    std::uint64_t h = static_cast<std::uint64_t>(cell[0]) * 0x9e3779b97f4a7c15ull ^
      static_cast<std::uint64_t>(cell[1]) * 0xc2b2ae3d27d4eb4full ^
      static_cast<std::uint64_t>(cell[2]) * 0x165667b19e3779f9ull;
    h ^= h >> 29;
    return h * 0xbf58476d1ce4e5b9ull;
  }

  // Calls visit(u) for the candidates of the neighbouring cells within the tolerance of x (none
  // for most points: only where x is that near a face, edge or corner of its cell).
  template <typename Visit>
  void ForNeighbourCells(const double* x, Visit&& visit) const
  {
    std::int64_t own[3], side[3];
    this->CellOf(x, own);
    int nearFaces = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double within = x[k] / this->CellSize - static_cast<double>(own[k]);
      const double margin = 1.0 / CellTolerances;
      side[k] = within < margin ? -1 : (within > 1.0 - margin ? 1 : 0);
      nearFaces |= side[k] != 0 ? 1 << k : 0;
    }
    for (int corner = 1; corner < 8; ++corner)
    {
      if ((corner & ~nearFaces) != 0)
      {
        continue; // a step along an axis whose faces are far
      }
      const std::int64_t cell[3] = { own[0] + ((corner & 1) ? side[0] : 0),
        own[1] + ((corner & 2) ? side[1] : 0), own[2] + ((corner & 4) ? side[2] : 0) };
      const std::uint64_t hash = Hash(cell);
      auto it = std::lower_bound(this->Points.begin(), this->Points.end(),
        std::make_pair(hash, std::numeric_limits<Id>::min()));
      for (size_t seen = 0; it != this->Points.end() && it->first == hash &&
           seen < MaximumSeamComparisons;
           ++it, ++seen)
      {
        visit(it->second);
      }
    }
  }
};

vtkIdType MergeSeamPoints(TriangleMesh& mesh, const TriangleTopology& topology,
  const PointDataAgreement& agree, vtkIdType& keptApart)
{
  keptApart = 0;
  const Id nv = mesh.GetNumberOfPoints();
  std::vector<Id> candidates;
  for (Id v = 0; v < nv; ++v)
  {
    if (topology.VertexKinds[v] == VertexKind::Boundary ||
      topology.VertexKinds[v] == VertexKind::NonManifold)
    {
      candidates.push_back(v);
    }
  }
  if (candidates.size() < 2)
  {
    return 0;
  }
  const double tolerance = SeamPointTolerance(mesh, candidates);
  const double tolerance2 = tolerance * tolerance;
  const SeamGrid grid(mesh, candidates, tolerance);
  std::vector<Id> root = FreshVector<Id>(nv);
  std::iota(root.begin(), root.end(), 0);
  // Each point is joined to the near points of the same data (a group's root is its lowest
  // id). A second pass, only where points of other data were near, marks the points left apart
  // from such a point (counted after all joins; not noted as pairs in the first, which took
  // memory for every pair of a soup labelled per triangle).
  std::vector<unsigned char> apart;
  bool differing = false;
  auto compare = [&](Id u, Id v) {
    if (u == v || Distance2(mesh.Point(u), mesh.Point(v)) > tolerance2)
    {
      return;
    }
    if (!apart.empty())
    {
      if (FindRoot(root, u) != FindRoot(root, v))
      {
        apart[u] = apart[v] = 1;
      }
    }
    else if (agree(u, v))
    {
      const Id a = FindRoot(root, u), b = FindRoot(root, v);
      root[std::max(a, b)] = std::min(a, b);
    }
    else
    {
      differing = true;
    }
  };
  const auto& points = grid.Points;
  auto comparePairs = [&]()
  {
    for (size_t begin = 0; begin < points.size();)
    {
      size_t end = begin + 1;
      while (end < points.size() && points[end].first == points[begin].first)
      {
        ++end;
      }
      for (size_t i = begin; i < end; ++i)
      {
        const Id v = points[i].second;
        for (size_t j = i + 1; j < std::min(end, i + MaximumSeamComparisons); ++j)
        {
          compare(v, points[j].second);
        }
        grid.ForNeighbourCells(mesh.Point(v), [&](Id u) { compare(u, v); });
      }
      begin = end;
    }
  };
  comparePairs();
  if (differing)
  {
    apart.assign(nv, 0);
    comparePairs();
  }
  keptApart = std::count(apart.begin(), apart.end(), 1);
  vtkIdType merged = 0;
  for (const Id v : candidates)
  {
    merged += FindRoot(root, v) != v ? 1 : 0;
  }
  if (merged > 0)
  {
    for (Id& v : mesh.Triangles)
    {
      v = FindRoot(root, v);
    }
  }
  return merged;
}

// Flip triangles so that each orientable part (triangles joined by manifold edges) has one
// orientation, the one most of its triangles already have: an inconsistently oriented input (an
// STL export, a merged soup) otherwise refuses most collapses, whose link test follows the
// triangles' winding. A part that is not orientable (a Moebius band) is left as it is. Returns
// the number of triangles flipped; the topology must then be rebuilt. `current`: the topology
// was built from the mesh as it is (no triangle dropped since).
vtkIdType OrientConsistently(TriangleMesh& mesh, const TriangleTopology& topology, bool current)
{
  if (current ? topology.OrientedWhenBuilt : topology.IsConsistentlyOriented(mesh))
  {
    return 0;
  }
  const Id nt = mesh.GetNumberOfTriangles();
  std::vector<signed char> flip(nt, -1); // -1: not reached; else relative to the part's seed
  std::vector<Id> part, stack;
  vtkIdType flipped = 0;
  for (Id seed = 0; seed < nt; ++seed)
  {
    if (flip[seed] >= 0 || mesh.Triangle(seed)[0] == InvalidId)
    {
      continue;
    }
    part.clear();
    bool orientable = true;
    flip[seed] = 0;
    stack.assign(1, seed);
    while (!stack.empty())
    {
      const Id t = stack.back();
      stack.pop_back();
      part.push_back(t);
      const Id* tri = mesh.Triangle(t);
      for (int k = 0; k < 3; ++k)
      {
        const Id nb = topology.EdgeNeighbors[3 * static_cast<size_t>(t) + k];
        if (nb < 0 || mesh.Triangle(nb)[0] == InvalidId)
        {
          continue;
        }
        // t runs a -> b on this edge; a consistent neighbour runs b -> a.
        const Id* ntri = mesh.Triangle(nb);
        const bool consistent = ntri[(CornerOf(ntri, tri[(k + 1) % 3]) + 1) % 3] == tri[k];
        const signed char wanted = static_cast<signed char>(flip[t] ^ (consistent ? 0 : 1));
        if (flip[nb] < 0)
        {
          flip[nb] = wanted;
          stack.push_back(nb);
        }
        else if (flip[nb] != wanted)
        {
          orientable = false;
        }
      }
    }
    if (!orientable)
    {
      continue;
    }
    const std::size_t relative = static_cast<std::size_t>(
      std::count_if(part.begin(), part.end(), [&](Id t) { return flip[t] == 1; }));
    const signed char keep = relative * 2 > part.size() ? 1 : 0; // the majority stays as it is
    for (const Id t : part)
    {
      if (flip[t] != keep)
      {
        Id* tri = mesh.Triangle(t);
        std::swap(tri[1], tri[2]);
        ++flipped;
      }
    }
  }
  return flipped;
}

// Mark triangles that have the same three vertices as a triangle with a lower id.
vtkIdType DropDuplicateTriangles(
  TriangleMesh& mesh, const TriangleTopology& topology, std::vector<vtkIdType>& cellIds)
{
  const Id nt = mesh.GetNumberOfTriangles();
  std::vector<unsigned char> duplicate = FreshVector<unsigned char>(nt, 0);
  vtkSMPTools::For(0, nt, [&](Id begin, Id end) {
    for (Id t = begin; t < end; ++t)
    {
      const Id* tri = mesh.Triangle(t);
      const VertexTriangleAdjacency& adj = topology.VertexTriangles;
      // Scanned from the corner with the fewest triangles (a fan's centre would make this
      // quadratic).
      int k = 0;
      for (int c = 1; c < 3; ++c)
      {
        k = adj.Count(tri[c]) < adj.Count(tri[k]) ? c : k;
      }
      const Id u = tri[(k + 1) % 3], w = tri[(k + 2) % 3];
      for (Id i = adj.Begin(tri[k]); i < adj.End(tri[k]); ++i)
      {
        const Id other = adj.Triangles[i];
        const Id* o = mesh.Triangle(other);
        if (other < t && CornerOf(o, u) >= 0 && CornerOf(o, w) >= 0)
        {
          duplicate[t] = 1;
          break;
        }
      }
    }
  });
  const vtkIdType count = std::count(duplicate.begin(), duplicate.end(), 1);
  if (count > 0)
  {
    for (Id t = 0; t < nt; ++t)
    {
      if (duplicate[t])
      {
        mesh.Triangle(t)[0] = InvalidId;
      }
    }
  }
  return count;
}
} // namespace

//------------------------------------------------------------------------------
bool CheckInputDiagonal(double diagonal, vtkAlgorithm* caller, const char* what)
{
  if (diagonal <= MaximumInputDiagonal && (diagonal == 0.0 || diagonal >= MinimumInputDiagonal))
  {
    return true;
  }
  vtkErrorWithObjectMacro(caller,
    "The input's bounding-box diagonal, " << diagonal << ", is outside ["
                                          << MinimumInputDiagonal << ", " << MaximumInputDiagonal
                                          << "], the range " << what
                                          << " hold; scale the input first (vtkTransformFilter).");
  return false;
}

vtkIdType FirstCellWithBadOffset(vtkCellArray* cells)
{
  // Offsets from 0 to the connectivity's end, never decreasing: else cells would be read past
  // its end (the cell that ends at the first bad offset is reported).
  auto scan = [](auto* offsets, auto* connectivity)
  {
    const auto starts = vtk::DataArrayValueRange<1>(offsets);
    const vtkIdType size = connectivity->GetNumberOfValues();
    for (vtkIdType c = 0; c < starts.size(); ++c)
    {
      const vtkIdType start = static_cast<vtkIdType>(starts[c]);
      const vtkIdType before = c > 0 ? static_cast<vtkIdType>(starts[c - 1]) : 0;
      if (start < before || start > size || (c == 0 && start != 0) ||
        (c == starts.size() - 1 && start != size))
      {
        return std::max(vtkIdType(0), c - 1);
      }
    }
    return vtkIdType(-1);
  };
  return cells == nullptr ? -1 : WithCellStorage(cells, scan);
}

vtkIdType FirstCellWithBadId(vtkCellArray* cells, vtkIdType numberOfPoints)
{
  if (cells == nullptr || cells->GetNumberOfCells() == 0)
  {
    return -1;
  }
  vtkIdType bad = -1; // the first bad entry of the connectivity
  auto scan = [&](auto* offsets, auto* connectivity)
  {
    const auto ids = vtk::DataArrayValueRange<1>(connectivity);
    for (vtkIdType i = 0; i < ids.size() && bad < 0; ++i)
    {
      bad = (ids[i] < 0 || ids[i] >= numberOfPoints) ? i : -1;
    }
    if (bad < 0)
    {
      return vtkIdType(-1);
    }
    // The cell holding that entry: the last whose offset is at most its index.
    const auto starts = vtk::DataArrayValueRange<1>(offsets);
    const auto after = std::upper_bound(starts.begin(), starts.end(), bad);
    return static_cast<vtkIdType>(after - starts.begin()) - 1;
  };
  return WithCellStorage(cells, scan);
}

//------------------------------------------------------------------------------
void PrepareForWriting(vtkAbstractArray* array)
{
  // Arrays of values stored one after the other (not bits, strings, or one array per component).
  auto* data = vtkDataArray::SafeDownCast(array);
  if (data && data->GetArrayType() == vtkAbstractArray::AoSDataArrayTemplate &&
    data->GetNumberOfValues() > 0)
  {
    const std::size_t bytes =
      static_cast<std::size_t>(data->GetDataSize()) * data->GetDataTypeSize();
    PrepareForWriting(data->GetVoidPointer(0), bytes);
  }
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkCellArray> MakeTriangleCells(const Id* triangles, Id numberOfTriangles)
{
  vtkNew<vtkTypeInt32Array> offsets;
  vtkNew<vtkTypeInt32Array> connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(numberOfTriangles) + 1);
  connectivity->SetNumberOfValues(3 * static_cast<vtkIdType>(numberOfTriangles));
  PrepareForWriting(offsets);
  PrepareForWriting(connectivity);
  std::int32_t* off = offsets->GetPointer(0);
  std::int32_t* conn = connectivity->GetPointer(0);
  vtkSMPTools::For(0, static_cast<vtkIdType>(numberOfTriangles) + 1, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType t = b; t < e; ++t)
    {
      off[t] = static_cast<std::int32_t>(3 * t);
    }
  });
  std::copy_n(triangles, 3 * static_cast<size_t>(numberOfTriangles), conn);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

//------------------------------------------------------------------------------
int FillSurfaceInputPortInformation(vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
void RequestWholeInput(vtkInformation* inputInfo)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  inputInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
  inputInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
  inputInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  if (inputInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    inputInfo->Set(SDDP::UPDATE_EXTENT(), inputInfo->Get(SDDP::WHOLE_EXTENT()), 6);
  }
}

//------------------------------------------------------------------------------
bool SurfaceInput(vtkInformationVector* port, vtkAlgorithm* caller, vtkPolyData*& input)
{
  vtkDataObject* data = vtkDataObject::GetData(port);
  input = vtkPolyData::SafeDownCast(data);
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkErrorWithObjectMacro(caller,
      "The input is composite data (a "
        << composite->GetClassName()
        << "): a hierarchy is made from one surface. Merge the blocks into one vtkPolyData "
           "first (vtkAppendPolyData, or vtkMergeBlocks and vtkGeometryFilter), or run one "
           "filter per block (vtkExtractBlock).");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
namespace
{
// Whether the polygons' and strips' offsets are valid and every point id is in range (a bad id
// would read and write past the end of every array); an error names the first bad cell.
bool PointIdsInRange(vtkPolyData* input, vtkAlgorithm* caller)
{
  const vtkIdType numberOfInputPoints = input->GetNumberOfPoints();
  for (vtkCellArray* cells : { input->GetPolys(), input->GetStrips() })
  {
    const char* kind = cells == input->GetPolys() ? "Polygon " : "Triangle strip ";
    const vtkIdType badOffset = FirstCellWithBadOffset(cells);
    if (badOffset >= 0)
    {
      vtkErrorWithObjectMacro(caller,
        << kind << badOffset
          << " has an invalid offset: a cell array's offsets run from 0 to the end of its "
             "connectivity and never decrease (vtkCellArray::IsValid); no output is produced.");
      return false;
    }
    const vtkIdType badCell = FirstCellWithBadId(cells, numberOfInputPoints);
    if (badCell >= 0)
    {
      vtkErrorWithObjectMacro(caller,
        << kind << badCell << " refers to a point id outside [0, " << numberOfInputPoints
          << "); no output is produced.");
      return false;
    }
  }
  return true;
}

void ReportNonFinitePoint(vtkAlgorithm* caller, vtkIdType id, const double* x)
{
  vtkErrorWithObjectMacro(caller,
    "Point " << id << " has a NaN or infinite coordinate (" << x[0] << ", " << x[1] << ", "
             << x[2] << "); no output is produced. Remove or fix such points first.");
}

// The first point with a NaN or infinite coordinate that a polygon or strip uses, or -1 (checked
// before triangulating: vtkTriangleFilter drops polygons it cannot triangulate, and with them the
// use of such a point).
vtkIdType FirstNonFiniteCellPoint(vtkPolyData* input)
{
  const auto xyz = vtk::DataArrayTupleRange<3>(input->GetPoints()->GetData());
  std::vector<bool> bad;
  for (vtkIdType p = 0; p < xyz.size(); ++p)
  {
    const double x[3] = { static_cast<double>(xyz[p][0]), static_cast<double>(xyz[p][1]),
      static_cast<double>(xyz[p][2]) };
    if (!IsFinitePoint(x))
    {
      bad.resize(xyz.size(), false);
      bad[p] = true;
    }
  }
  if (bad.empty())
  {
    return -1;
  }
  vtkIdType first = -1;
  for (vtkCellArray* cells : { input->GetPolys(), input->GetStrips() })
  {
    WithCellStorage(cells, [&](auto*, auto* connectivity) {
      for (const auto id : vtk::DataArrayValueRange<1>(connectivity))
      {
        if (bad[static_cast<size_t>(id)] && (first < 0 || id < first))
        {
          first = static_cast<vtkIdType>(id);
        }
      }
    });
  }
  return first;
}

// The triangles polygons make when every one triangulates: n - 2 for n points, a point repeated
// next to itself counted once (a triangle stored as a quad [a, b, c, c] makes one). For strips
// (`strip`) every n - 2 triangles, degenerate ones too.
vtkIdType TrianglesOfCells(vtkCellArray* cells, bool strip)
{
  vtkIdType count = 0;
  auto sum = [&](auto* offsets, auto* connectivity)
  {
    const auto starts = vtk::DataArrayValueRange<1>(offsets);
    const auto ids = vtk::DataArrayValueRange<1>(connectivity);
    for (vtkIdType c = 0; c + 1 < starts.size(); ++c)
    {
      const vtkIdType first = starts[c], end = starts[c + 1];
      vtkIdType distinct = end - first;
      for (vtkIdType i = first; !strip && i < end && end - first > 1; ++i)
      {
        distinct -= ids[i] == ids[i + 1 < end ? i + 1 : first] ? 1 : 0;
      }
      count += std::max(vtkIdType(0), distinct - 2);
    }
  };
  WithCellStorage(cells, sum);
  return count;
}

// The polygons with a point repeated next to itself ([a, b, b, c]: a triangle stored as a quad)
// without the repeats, or null when no polygon has one. vtkTriangleFilter cuts such a polygon into
// a degenerate triangle, losing the real one, unless the repeat comes last. A polygon left with
// fewer than three points stays as it was (it makes no triangle either way).
vtkSmartPointer<vtkCellArray> WithoutAdjacentRepeats(vtkCellArray* polys)
{
  auto repeats = [](vtkIdType n, const vtkIdType* pts)
  {
    for (vtkIdType i = 0; i < n && n > 1; ++i)
    {
      if (pts[i] == pts[(i + 1) % n])
      {
        return true;
      }
    }
    return false;
  };
  vtkIdType n;
  const vtkIdType* pts;
  bool any = false;
  auto cells = vtk::TakeSmartPointer(polys->NewIterator());
  for (cells->GoToFirstCell(); !any && !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    cells->GetCurrentCell(n, pts);
    any = repeats(n, pts);
  }
  if (!any)
  {
    return nullptr;
  }
  auto kept = vtkSmartPointer<vtkCellArray>::New();
  kept->AllocateExact(polys->GetNumberOfCells(), polys->GetNumberOfConnectivityIds());
  std::vector<vtkIdType> ids;
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    cells->GetCurrentCell(n, pts);
    ids.clear();
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (pts[i] != pts[(i + 1) % n])
      {
        ids.push_back(pts[i]);
      }
    }
    if (ids.size() < 3)
    {
      ids.assign(pts, pts + n);
    }
    kept->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  return kept;
}

// The input's polygons and strips as triangles, with their point data and the cell data of
// polygons and strips (the cells from `firstPolyCellId` on: the verts and lines in front of
// them are skipped).
vtkSmartPointer<vtkPolyData> Triangulate(vtkPolyData* input, vtkIdType firstPolyCellId)
{
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(input->GetPoints());
  const vtkSmartPointer<vtkCellArray> polys = WithoutAdjacentRepeats(input->GetPolys());
  surface->SetPolys(polys != nullptr ? polys.Get() : input->GetPolys());
  surface->SetStrips(input->GetStrips());
  surface->GetPointData()->ShallowCopy(input->GetPointData());
  // A polygon or strip becomes several triangles, and each keeps its cell's data. Global ids
  // promise one cell per id, so the triangles keep theirs in a plain array of the same name
  // (copied like any other; the copy flags would drop the attribute).
  vtkNew<vtkCellData> cells;
  cells->ShallowCopy(input->GetCellData());
  cells->SetActiveAttribute(-1, vtkDataSetAttributes::GLOBALIDS);
  const vtkIdType numberOfSurfaceCells = input->GetNumberOfPolys() + input->GetNumberOfStrips();
  surface->GetCellData()->CopyAllocate(cells, numberOfSurfaceCells);
  for (vtkIdType c = 0; c < numberOfSurfaceCells; ++c)
  {
    surface->GetCellData()->CopyData(cells, firstPolyCellId + c, c);
  }
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(surface);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  return triangulate->GetOutput();
}

// result.Mesh from result.Source's points (as doubles) and triangles; false, with an error and
// `result` cleared, when a point that triangles use is not finite (unused ones are settled).
bool CopySourceMesh(InputMesh& result, vtkAlgorithm* caller)
{
  vtkCellArray* polys = result.Source->GetPolys();
  TriangleMesh& mesh = result.Mesh;
  ResizeFresh(mesh.Points, 3 * static_cast<size_t>(result.Source->GetNumberOfPoints()));
  CopyPoints(result.Source->GetPoints()->GetData(), mesh.Points);
  WithCellStorage(
    polys, [&](auto*, auto* connectivity) { CopyTriangles(connectivity, mesh.Triangles); });
  if (FirstNonFinitePoint(mesh.Points) >= 0)
  {
    const vtkIdType bad = SettleUnusedNonFinitePoints(mesh);
    if (bad >= 0)
    {
      ReportNonFinitePoint(caller, bad, &mesh.Points[3 * bad]);
      result = InputMesh();
      return false;
    }
  }
  return true;
}

// Degenerate triangles dropped, seams stitched, duplicate triangles dropped and each part
// oriented consistently, with a warning for each kind of change (result.Topology built for the
// mesh as it ends). Returns whether triangles were flipped.
bool RepairMesh(InputMesh& result, vtkAlgorithm* caller)
{
  TriangleMesh& mesh = result.Mesh;
  result.DegenerateTriangles = DropDegenerateTriangles(mesh.Triangles, result.SourceCellIds);
  result.Topology.Build(mesh);

  vtkIdType keptApart = 0;
  result.MergedPoints = MergeSeamPoints(
    mesh, result.Topology, PointDataAgreement(result.Source->GetPointData()), keptApart);
  if (keptApart > 0)
  {
    vtkWarningWithObjectMacro(caller,
      "Did not stitch " << keptApart
                        << " points on open boundaries to the points they coincide with: their "
                           "point data differ (an attribute seam, such as split normals or a "
                           "texture's wrap), so the surface stays open there and its sides "
                           "simplify separately. To join them anyway, run vtkCleanPolyData "
                           "first (it merges coincident points whatever their data).");
  }
  if (result.MergedPoints > 0)
  {
    // Stitching makes the triangles between merged points degenerate (a sliver between two
    // coincident points).
    result.DegenerateTriangles += DropDegenerateTriangles(mesh.Triangles, result.SourceCellIds);
    result.Topology.Build(mesh);
  }
  result.DuplicateTriangles = DropDuplicateTriangles(mesh, result.Topology, result.SourceCellIds);
  if (result.DegenerateTriangles > 0 || result.DuplicateTriangles > 0)
  {
    vtkWarningWithObjectMacro(caller,
      "Dropped " << result.DegenerateTriangles << " degenerate and " << result.DuplicateTriangles
                 << " duplicate triangles.");
  }
  result.FlippedTriangles =
    OrientConsistently(mesh, result.Topology, result.DuplicateTriangles == 0);
  if (result.FlippedTriangles > 0)
  {
    vtkWarningWithObjectMacro(caller,
      "Flipped " << result.FlippedTriangles
                 << " triangles so that each connected part is consistently oriented (each part "
                    "keeps the orientation most of its triangles had).");
    result.Topology.Build(mesh);
    return true;
  }
  return false;
}

// Compact away dropped triangles and unused points, keeping the maps to the source
// (`numberOfPoints`: result.Source's; `changed`: the mesh differs from the input so far). Most
// inputs have neither: then no copy is made (it would be the largest allocation here).
InputStatus CompactInput(InputMesh& result, vtkIdType numberOfPoints, bool changed)
{
  TriangleMesh& mesh = result.Mesh;
  if (result.MergedPoints == 0 && result.DuplicateTriangles == 0 &&
    result.Topology.CountVertices(VertexKind::Unused) == 0)
  {
    result.UnusedPoints = 0;
    ResizeFresh(result.SourcePointIds, numberOfPoints);
    std::iota(result.SourcePointIds.begin(), result.SourcePointIds.end(), 0);
    result.SameAsInput = !changed && result.DegenerateTriangles == 0;
    return mesh.GetNumberOfTriangles() > 0 ? InputStatus::Valid : InputStatus::Empty;
  }
  TriangleMesh compact;
  CompactionMaps maps;
  CompactMesh(mesh, compact, maps);
  result.UnusedPoints = numberOfPoints - compact.GetNumberOfPoints() - result.MergedPoints;
  changed = changed || result.MergedPoints > 0 || result.DegenerateTriangles > 0 ||
    result.DuplicateTriangles > 0 || compact.GetNumberOfPoints() != numberOfPoints;
  if (compact.GetNumberOfTriangles() != mesh.GetNumberOfTriangles() ||
    compact.GetNumberOfPoints() != mesh.GetNumberOfPoints())
  {
    std::vector<vtkIdType> cellIds(compact.GetNumberOfTriangles());
    for (Id t = 0; t < compact.GetNumberOfTriangles(); ++t)
    {
      cellIds[t] = result.SourceCellIds[maps.KeptTriangles[t]];
    }
    result.SourceCellIds.swap(cellIds);
    mesh = std::move(compact);
    result.Topology.Build(mesh);
  }
  result.SourcePointIds.assign(maps.KeptPoints.begin(), maps.KeptPoints.end());
  result.SameAsInput = !changed;
  return mesh.GetNumberOfTriangles() > 0 ? InputStatus::Valid : InputStatus::Empty;
}

} // namespace

//------------------------------------------------------------------------------
InputStatus ReadInputMesh(vtkPolyData* input, vtkAlgorithm* caller, InputMesh& result)
{
  result = InputMesh();
  // Cells without points to refer to are checked like any others (their ids are out of range).
  if (input != nullptr && input->GetNumberOfPolys() + input->GetNumberOfStrips() > 0 &&
    !PointIdsInRange(input, caller))
  {
    return InputStatus::Invalid;
  }
  if (input == nullptr || input->GetNumberOfPoints() == 0 ||
    input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    if (input != nullptr && input->GetNumberOfCells() > 0)
    {
      vtkWarningWithObjectMacro(caller,
        "The input has " << input->GetNumberOfVerts() << " vertices and "
                         << input->GetNumberOfLines()
                         << " lines but no polygons: there is nothing to simplify.");
    }
    return InputStatus::Empty;
  }
  // Arrays with the wrong number of tuples are left out (see DropMismatchedArrays); from here
  // on `input` is the checked dataset, `original` the one given.
  vtkPolyData* original = input;
  const vtkSmartPointer<vtkPolyData> checked = DropMismatchedArrays(input, caller);
  input = checked;

  result.IgnoredVerts = input->GetNumberOfVerts();
  result.IgnoredLines = input->GetNumberOfLines();
  if (result.IgnoredVerts > 0 || result.IgnoredLines > 0)
  {
    vtkWarningWithObjectMacro(caller,
      "Ignoring " << result.IgnoredVerts << " vertex cells and " << result.IgnoredLines
                  << " line cells: only polygons and triangle strips are simplified.");
  }
  if (input->GetNumberOfPoints() > MaximumCount)
  {
    vtkErrorWithObjectMacro(caller,
      "The input has " << input->GetNumberOfPoints() << " points; at most " << MaximumCount
                       << " are supported.");
    return InputStatus::Invalid;
  }

  // Triangulate polygons and strips when they are not all triangles already.
  vtkIdType firstPolyCellId = result.IgnoredVerts + result.IgnoredLines;
  result.Source = input;
  if (input->GetNumberOfStrips() > 0 || input->GetPolys()->IsHomogeneous() != 3)
  {
    const vtkIdType bad = FirstNonFiniteCellPoint(input);
    if (bad >= 0)
    {
      ReportNonFinitePoint(caller, bad, input->GetPoint(bad));
      return InputStatus::Invalid;
    }
    result.Source = Triangulate(input, firstPolyCellId);
    firstPolyCellId = 0;
    const vtkIdType lost = TrianglesOfCells(input->GetPolys(), false) +
      TrianglesOfCells(input->GetStrips(), true) - result.Source->GetNumberOfPolys();
    if (lost > 0)
    {
      vtkWarningWithObjectMacro(caller,
        "Triangulating the input's polygons made "
          << lost
          << " triangles fewer than their points allow: vtkTriangleFilter drops a polygon it "
             "cannot triangulate (one that crosses itself or has no area), so the surface has "
             "a hole in its place on every level.");
    }
  }
  const vtkIdType numberOfTriangles = result.Source->GetPolys()->GetNumberOfCells();
  if (numberOfTriangles > MaximumCount)
  {
    vtkErrorWithObjectMacro(caller,
      "The input has " << numberOfTriangles << " triangles; at most " << MaximumCount
                       << " are supported.");
    return InputStatus::Invalid;
  }
  if (!CopySourceMesh(result, caller))
  {
    return InputStatus::Invalid;
  }
  ResizeFresh(result.SourceCellIds, numberOfTriangles);
  std::iota(result.SourceCellIds.begin(), result.SourceCellIds.end(), firstPolyCellId);

  const bool flipped = RepairMesh(result, caller);
  const bool changed = result.Source != original || flipped;
  return CompactInput(result, result.Source->GetNumberOfPoints(), changed);
}

} // namespace meshlod
