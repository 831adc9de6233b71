#include "MeshLODGeomorphInternals.h"

#include "Core/CollapseSchedule.h"
#include "Core/EdgeMerge.h"
#include "MeshLODBlend.h"
#include "MeshLODHierarchy.h"
#include "MeshLODInputArrays.h"
#include "MeshLODInputMesh.h"
#include "MeshLODNearestCorrespondence.h"
#include "MeshLODNewArray.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTypeInt32Array.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace meshlod
{
namespace geomorph
{
vtkMTimeType HierarchyTime(vtkMultiBlockDataSet* input)
{
  vtkMTimeType time = input->GetMTime();
  for (unsigned int i = 0; i < input->GetNumberOfBlocks(); ++i)
  {
    if (vtkDataObject* block = input->GetBlock(i))
    {
      time = std::max(time, block->GetMTime());
    }
  }
  return time;
}

//------------------------------------------------------------------------------
bool ReadTriangles(vtkPolyData* poly, std::vector<Id>& triangles)
{
  triangles.clear();
  if (poly->GetNumberOfCells() != poly->GetNumberOfPolys())
  {
    return false;
  }
  vtkCellArray* polys = poly->GetPolys();
  const vtkIdType n = polys->GetNumberOfCells();
  triangles.resize(3 * static_cast<size_t>(n));
  bool ok = true;
  auto visit = [&](auto* offsets, auto* connectivity) {
    const auto off = vtk::DataArrayValueRange<1>(offsets);
    const auto conn = vtk::DataArrayValueRange<1>(connectivity);
    for (vtkIdType c = 0; c < n && ok; ++c)
    {
      ok = off[c + 1] - off[c] == 3;
    }
    for (vtkIdType i = 0; i < 3 * n && ok; ++i)
    {
      triangles[i] = static_cast<Id>(conn[i]);
    }
  };
  meshlod::WithCellStorage(polys, visit);
  return ok;
}
} // namespace geomorph
} // namespace meshlod

namespace
{
using meshlod::Id;
using namespace meshlod::geomorph;

// The TCoords of a level with a texture atlas of its own (names::TextureAtlasLevel), or null.
vtkAbstractArray* UnblendedTCoords(vtkPolyData* level)
{
  return level->GetFieldData()->GetAbstractArray(meshlod::names::TextureAtlasLevel)
    ? level->GetPointData()->GetTCoords()
    : nullptr;
}

// A level split per texture square (vtkVertexClusterOctree with BakeTexture: names::
// TextureAtlasLevel) has a copy of a point for each square around it, copies that share the
// position, the target and the rank. Returns level point -> its point once the copies are
// welded (numbered in the order of their lowest copy), and the representatives (welded point
// -> its lowest copy). Copies only: distinct points with these in common stay apart unless
// they also coincide, and then joining them together changes nothing a schedule can see.
std::vector<Id> WeldCopies(const double* positions, const Id* target, const std::int64_t* rank,
  Id n, std::vector<Id>& representatives)
{
  std::vector<Id> order(n);
  std::iota(order.begin(), order.end(), Id(0));
  auto key = [&](Id p) {
    const double* x = positions + 3 * static_cast<size_t>(p);
    return std::make_tuple(target[p], rank[p], x[0], x[1], x[2]);
  };
  // Sorting by the key, ties by id, puts each point's copies together, lowest first.
  std::sort(order.begin(), order.end(), [&](Id a, Id b) {
    const auto ka = key(a), kb = key(b);
    return ka != kb ? ka < kb : a < b;
  });
  std::vector<Id> lowest(n);
  for (Id i = 0; i < n; ++i)
  {
    lowest[order[i]] = (i > 0 && key(order[i - 1]) == key(order[i])) ? lowest[order[i - 1]] : order[i];
  }
  std::vector<Id> welded(n);
  representatives.clear();
  for (Id p = 0; p < n; ++p)
  {
    if (lowest[p] == p)
    {
      welded[p] = static_cast<Id>(representatives.size());
      representatives.push_back(p);
    }
    else
    {
      welded[p] = welded[lowest[p]];
    }
  }
  return welded;
}

std::vector<Id> ToIds(vtkDataArray* array)
{
  std::vector<Id> ids(array->GetNumberOfTuples());
  const auto values = vtk::DataArrayValueRange<1>(array);
  vtkSMPTools::For(0, array->GetNumberOfTuples(), [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType i = b; i < e; ++i)
    {
      ids[i] = static_cast<Id>(values[i]);
    }
  });
  return ids;
}

vtkSmartPointer<vtkIdList> ToIdList(const std::vector<Id>& ids)
{
  auto list = vtkSmartPointer<vtkIdList>::New();
  list->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  for (size_t i = 0; i < ids.size(); ++i)
  {
    list->SetId(static_cast<vtkIdType>(i), ids[i]);
  }
  return list;
}

// The cell data of the kept cells, array by array.
vtkSmartPointer<vtkCellData> SubsetCellData(vtkCellData* in, const std::vector<Id>& kept)
{
  auto out = vtkSmartPointer<vtkCellData>::New();
  vtkSmartPointer<vtkIdList> ids = ToIdList(kept);
  for (int i = 0; i < in->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* array = in->GetAbstractArray(i);
    vtkSmartPointer<vtkAbstractArray> subset = meshlod::NewArrayLike(array, ids->GetNumberOfIds());
    array->GetTuples(ids, subset);
    const int attribute = in->IsArrayAnAttribute(i);
    if (attribute >= 0)
    {
      out->SetAttribute(subset, attribute);
    }
    else
    {
      out->AddArray(subset);
    }
  }
  return out;
}

vtkSmartPointer<vtkPoints> PointsFrom(vtkDataArray* data)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(data);
  return points;
}

// The triangles t with keep(t) whose corners, renumbered through newId(), are three distinct
// points, as a cell array built in place (parallel flags, a prefix sum, a parallel fill);
// `keptTriangles` gets their ids in the level, for the cell data.
template <typename NewId, typename Keep>
vtkSmartPointer<vtkCellArray> CompactTriangles(const std::vector<Id>& triangles, const NewId& newId,
  const Keep& keep, std::vector<Id>& keptTriangles)
{
  const vtkIdType n = static_cast<vtkIdType>(triangles.size() / 3);
  std::vector<std::uint8_t> kept(n);
  vtkSMPTools::For(0, n, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType t = b; t < e; ++t)
    {
      const Id x = newId(triangles[3 * t]), y = newId(triangles[3 * t + 1]),
               z = newId(triangles[3 * t + 2]);
      kept[t] = (keep(t) && x != y && y != z && z != x) ? 1 : 0;
    }
  });
  keptTriangles.clear();
  keptTriangles.reserve(n);
  for (vtkIdType t = 0; t < n; ++t)
  {
    if (kept[t])
    {
      keptTriangles.push_back(static_cast<Id>(t));
    }
  }
  const vtkIdType m = static_cast<vtkIdType>(keptTriangles.size());
  vtkNew<vtkTypeInt32Array> offsets;
  vtkNew<vtkTypeInt32Array> connectivity;
  offsets->SetNumberOfValues(m + 1);
  connectivity->SetNumberOfValues(3 * m);
  std::int32_t* off = offsets->GetPointer(0);
  std::int32_t* conn = connectivity->GetPointer(0);
  vtkSMPTools::For(0, m, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType i = b; i < e; ++i)
    {
      const Id* tri = triangles.data() + 3 * static_cast<size_t>(keptTriangles[i]);
      off[i] = static_cast<std::int32_t>(3 * i);
      conn[3 * i] = newId(tri[0]);
      conn[3 * i + 1] = newId(tri[1]);
      conn[3 * i + 2] = newId(tri[2]);
    }
  });
  off[m] = static_cast<std::int32_t>(3 * m);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}
} // namespace

namespace
{
// Per-edge flag: its two end points are at most `tolerance` apart.
struct ShortEdgeWorker
{
  const meshlod::EdgeList* Edges;
  double Tolerance2;
  std::vector<std::uint8_t>* Flags;

  template <typename PointArray>
  void operator()(PointArray* points) const
  {
    const auto x = vtk::DataArrayTupleRange<3>(points);
    const std::vector<Id>& ends = this->Edges->Ends;
    std::uint8_t* flags = this->Flags->data();
    const double tolerance2 = this->Tolerance2;
    vtkSMPTools::For(0, static_cast<vtkIdType>(this->Edges->Size()), [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType i = b; i < e; ++i)
      {
        const auto p = x[ends[2 * i]];
        const auto q = x[ends[2 * i + 1]];
        double d2 = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          const double d = static_cast<double>(p[c]) - static_cast<double>(q[c]);
          d2 += d * d;
        }
        flags[i] = d2 <= tolerance2 ? 1 : 0;
      }
    });
  }
};

// Per-triangle flag: two corners closer than `Tolerance` (the same position up to rounding), or
// exactly zero area.
struct DegenerateWorker
{
  const std::vector<Id>* Triangles;
  double Tolerance2;
  std::vector<std::uint8_t>* Flags;

  template <typename PointArray>
  void operator()(PointArray* points) const
  {
    const auto x = vtk::DataArrayTupleRange<3>(points);
    const Id* tri = this->Triangles->data();
    std::uint8_t* flags = this->Flags->data();
    const double tolerance2 = this->Tolerance2;
    vtkSMPTools::For(0, static_cast<vtkIdType>(this->Flags->size()), [&](vtkIdType b, vtkIdType e) {
      for (vtkIdType t = b; t < e; ++t)
      {
        double p[3][3];
        for (int k = 0; k < 3; ++k)
        {
          const auto v = x[tri[3 * t + k]];
          p[k][0] = v[0];
          p[k][1] = v[1];
          p[k][2] = v[2];
        }
        bool degenerate = false;
        for (int k = 0; k < 3; ++k)
        {
          degenerate =
            degenerate || vtkMath::Distance2BetweenPoints(p[k], p[(k + 1) % 3]) <= tolerance2;
        }
        const double u[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
        const double w[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
        double n[3];
        vtkMath::Cross(u, w, n);
        flags[t] = (degenerate || (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0)) ? 1 : 0;
      }
    });
  }
};

template <typename Worker>
void DispatchPoints(vtkDataArray* points, Worker& worker)
{
  if (!vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>::Execute(points, worker))
  {
    worker(points);
  }
}

// The first tuple of a real array with a NaN or infinite component, or -1 (in Found).
struct NonFiniteWorker
{
  vtkIdType Found = -1;
  template <typename ArrayT>
  void operator()(ArrayT* array)
  {
    const auto values = vtk::DataArrayValueRange(array);
    const int components = array->GetNumberOfComponents();
    vtkIdType i = 0;
    for (const auto value : values)
    {
      if (!std::isfinite(static_cast<double>(value)))
      {
        this->Found = i / components;
        return;
      }
      ++i;
    }
  }
};

vtkIdType FirstNonFiniteTuple(vtkDataArray* array)
{
  NonFiniteWorker worker;
  if (array != nullptr)
  {
    DispatchPoints(array, worker);
  }
  return worker.Found;
}
} // namespace

//------------------------------------------------------------------------------
std::string vtkLODGeomorph::Internals::Prepare(
  vtkMultiBlockDataSet* input, int requested, vtkLODGeomorph* self)
{
  this->Levels.clear();
  this->Exact = ExactTopology();
  std::string problem = meshlod::CheckHierarchyLayout(input, false);
  if (!problem.empty())
  {
    return problem;
  }
  const unsigned int n = input->GetNumberOfBlocks();
  this->Levels.resize(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    // A user-made level is held to what the filters check of their input: point ids in range
    // (a bad one crashed the exact count and the nearest-vertex correspondence), arrays of the
    // right length.
    auto* poly = vtkPolyData::SafeDownCast(input->GetBlock(i));
    const vtkIdType points = poly->GetNumberOfPoints();
    for (vtkCellArray* cells :
      { poly->GetVerts(), poly->GetLines(), poly->GetPolys(), poly->GetStrips() })
    {
      const bool badOffsets = meshlod::FirstCellWithBadOffset(cells) >= 0;
      if (badOffsets || meshlod::FirstCellWithBadId(cells, points) >= 0)
      {
        this->Levels.clear();
        std::ostringstream problem;
        problem << "level " << i;
        if (badOffsets)
        {
          problem << " has a cell array with invalid offsets";
        }
        else
        {
          problem << " has a cell that refers to a point id outside [0, " << points << ")";
        }
        return problem.str();
      }
    }
    // NaN or infinite positions would go through every blend into the output.
    const vtkIdType nonFinite =
      poly->GetPoints() ? FirstNonFiniteTuple(poly->GetPoints()->GetData()) : -1;
    if (nonFinite >= 0)
    {
      this->Levels.clear();
      std::ostringstream problem;
      problem << "level " << i << "'s point " << nonFinite << " has a NaN or infinite coordinate";
      return problem.str();
    }
    vtkSmartPointer<vtkPolyData> checked = meshlod::DropMismatchedArrays(poly, self);
    vtkPoints* given = checked->GetPoints();
    if (given && given->GetDataType() != VTK_FLOAT && given->GetDataType() != VTK_DOUBLE)
    {
      // Integer points would blend in integers (truncated): such a level is read in double, as
      // the filters read an input.
      vtkNew<vtkPoints> real;
      real->SetDataTypeToDouble();
      real->SetNumberOfPoints(given->GetNumberOfPoints());
      for (vtkIdType p = 0; p < given->GetNumberOfPoints(); ++p)
      {
        real->SetPoint(p, given->GetPoint(p));
      }
      if (checked == poly)
      {
        checked = vtkSmartPointer<vtkPolyData>::New();
        checked->ShallowCopy(poly);
      }
      checked->SetPoints(real);
    }
    if (checked != poly)
    {
      this->Levels[i].Checked = checked;
    }
    this->Levels[i].Poly = checked;
  }
  this->Mode = requested;
  if (this->Mode == AUTOMATIC)
  {
    vtkPointData* pd = this->Levels[0].Poly->GetPointData();
    const bool any = pd->GetAbstractArray(meshlod::names::MorphTarget) ||
      pd->GetAbstractArray(meshlod::names::MorphTargetId) ||
      pd->GetAbstractArray(meshlod::names::CollapseRank);
    this->Mode = (n > 1 && any) ? MORPH_ARRAYS : NEAREST_VERTICES;
  }
  if (this->Mode == MORPH_ARRAYS)
  {
    problem = meshlod::CheckHierarchyLayout(input, true);
    if (!problem.empty())
    {
      this->Levels.clear();
      return problem;
    }
    for (unsigned int i = 0; i + 1 < n; ++i)
    {
      const vtkIdType nonFinite = FirstNonFiniteTuple(
        this->Levels[i].Poly->GetPointData()->GetArray(meshlod::names::MorphTarget));
      if (nonFinite >= 0)
      {
        this->Levels.clear();
        std::ostringstream problem;
        problem << "level " << i << "'s " << meshlod::names::MorphTarget << " of point "
                << nonFinite << " is NaN or infinite";
        return problem.str();
      }
      this->Levels[i].TargetIds =
        ToIds(this->Levels[i].Poly->GetPointData()->GetArray(meshlod::names::MorphTargetId));
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
bool vtkLODGeomorph::Internals::EnsureTriangles(
  vtkLODGeomorph* self, int level, const char* purpose)
{
  LevelCache& cache = this->Levels[level];
  if (!cache.TrianglesRead)
  {
    cache.AllTriangles = meshlod::geomorph::ReadTriangles(cache.Poly, cache.Triangles);
    cache.TrianglesRead = true;
  }
  if (!cache.AllTriangles)
  {
    vtkErrorWithObjectMacro(self,
      "Level " << level << " has cells other than triangles; " << purpose
               << " needs triangles only (vtkTriangleFilter "
               << "triangulates, and drops vertices and lines).");
  }
  return cache.AllTriangles;
}

//------------------------------------------------------------------------------
bool vtkLODGeomorph::Internals::EnsureSchedule(vtkLODGeomorph* self, int level)
{
  LevelCache& cache = this->Levels[level];
  if (cache.Schedule)
  {
    return true;
  }
  if (!this->EnsureTriangles(self, level, "TargetNumberOfTriangles"))
  {
    return false;
  }
  vtkPolyData* poly = cache.Poly;
  const vtkIdType n = poly->GetNumberOfPoints();
  vtkPointData* pd = poly->GetPointData();
  vtkDataArray* rankArray = pd->GetArray(meshlod::names::CollapseRank);
  vtkDataArray* target = pd->GetArray(meshlod::names::MorphTarget);
  vtkDataArray* points = poly->GetPoints()->GetData();
  std::vector<std::int64_t> rank(n);
  std::vector<std::uint8_t> atTarget(n);
  std::vector<double> from(3 * static_cast<size_t>(n)), to(3 * static_cast<size_t>(n));
  vtkSMPTools::For(0, n, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType p = b; p < e; ++p)
    {
      double* x = from.data() + 3 * p;
      double* y = to.data() + 3 * p;
      rank[p] = static_cast<std::int64_t>(rankArray->GetComponent(p, 0));
      points->GetTuple(p, x);
      target->GetTuple(p, y);
      atTarget[p] = (x[0] == y[0] && x[1] == y[1] && x[2] == y[2]) ? 1 : 0;
    }
  });
  // A level whose TCoords address a texture of its own may have its points split per texture
  // square (the octree's baked levels): the copies of a point join as one. Joined one at a
  // time, every copy but the last would pinch the mesh at a seam of the atlas, a step no count
  // can stop at (between a UV sphere's octree levels of 986 and 496 triangles, 8 of the 489
  // counts were reachable with the copies apart, all of them welded).
  std::vector<Id> triangles, targets;
  const std::vector<Id>* scheduleTriangles = &cache.Triangles;
  const Id* scheduleTargets = cache.TargetIds.data();
  Id schedulePoints = static_cast<Id>(n);
  cache.ScheduleIds.clear();
  std::vector<Id> representatives;
  if (UnblendedTCoords(poly))
  {
    cache.ScheduleIds = WeldCopies(
      from.data(), cache.TargetIds.data(), rank.data(), static_cast<Id>(n), representatives);
    if (representatives.size() == static_cast<size_t>(n))
    {
      cache.ScheduleIds.clear(); // no copies (level 0 with the octree's input texture)
    }
  }
  if (!cache.ScheduleIds.empty())
  {
    schedulePoints = static_cast<Id>(representatives.size());
    targets.resize(schedulePoints);
    for (Id w = 0; w < schedulePoints; ++w)
    {
      const Id p = representatives[w];
      targets[w] = cache.TargetIds[p];
      rank[w] = rank[p]; // p >= w: the representatives come in increasing order
      atTarget[w] = atTarget[p];
      std::copy_n(from.data() + 3 * static_cast<size_t>(p), 3, from.data() + 3 * static_cast<size_t>(w));
      std::copy_n(to.data() + 3 * static_cast<size_t>(p), 3, to.data() + 3 * static_cast<size_t>(w));
    }
    triangles.resize(cache.Triangles.size());
    for (size_t c = 0; c < triangles.size(); ++c)
    {
      triangles[c] = cache.ScheduleIds[cache.Triangles[c]];
    }
    scheduleTriangles = &triangles;
    scheduleTargets = targets.data();
  }
  // Collapses that would fold triangles over wait for their neighbours (on a UV sphere's octree
  // levels, 44% of the counts had a folded triangle without the waiting, none with it), unless
  // the waiting leaves fewer counts reachable: collapses that keep waiting are made last, in
  // groups, and between a group's steps no count can be stopped at (two levels 97% apart: 8 of
  // 22 counts out of reach). The schedule that keeps 98% of the counts reachable or more wins;
  // when no collapse waited, the two are the same and the second is not built.
  // An abort stops a build (null): none is kept, and the next update builds it again.
  const auto build = [&](bool waitForFolds) {
    auto schedule = std::unique_ptr<meshlod::CollapseSchedule>(new meshlod::CollapseSchedule);
    schedule->AbortCheck = [self]() { return self->GetAbortExecute() != 0; };
    if (!schedule->Build(scheduleTriangles->data(),
          static_cast<Id>(scheduleTriangles->size() / 3), schedulePoints, scheduleTargets,
          rank.data(), atTarget.data(), from.data(), to.data(), waitForFolds))
    {
      schedule.reset();
    }
    return schedule;
  };
  std::unique_ptr<meshlod::CollapseSchedule> waiting = build(true);
  if (!waiting)
  {
    return false;
  }
  if (waiting->WaitedForFolds)
  {
    self->UpdateProgress(0.5);
    std::unique_ptr<meshlod::CollapseSchedule> plain = build(false);
    if (!plain)
    {
      return false;
    }
    if (waiting->NumberOfReachableCounts() < 0.98 * plain->NumberOfReachableCounts())
    {
      waiting = std::move(plain);
    }
  }
  cache.Schedule = std::move(waiting);
  return true;
}

//------------------------------------------------------------------------------
bool vtkLODGeomorph::Internals::EnsureCorrespondence(vtkLODGeomorph* self, int level)
{
  LevelCache& cache = this->Levels[level];
  if (cache.HasCorrespondence)
  {
    return true;
  }
  if (!this->EnsureTriangles(self, level, "the nearest-vertex correspondence"))
  {
    return false;
  }
  vtkPolyData* coarse = this->Levels[level + 1].Poly;
  if (!meshlod::NearestVertexCorrespondence(cache.Poly->GetPoints(), coarse->GetPoints(),
        cache.Partner, [self]() { return self->GetAbortExecute() != 0; }))
  {
    cache.Partner.clear(); // aborted: built again at the next update
    return false;
  }
  self->UpdateProgress(0.4);
  cache.Edges.Build(cache.Triangles.data(), static_cast<Id>(cache.Triangles.size() / 3),
    static_cast<Id>(cache.Poly->GetNumberOfPoints()));
  cache.Diagonal = cache.Poly->GetLength();
  cache.HasCorrespondence = true;
  ++self->NumberOfCorrespondenceBuilds;
  self->UpdateProgress(0.6);
  return true;
}

//------------------------------------------------------------------------------
vtkPointData* vtkLODGeomorph::Internals::TargetData(int level)
{
  LevelCache& cache = this->Levels[level];
  if (!cache.TargetData)
  {
    for (LevelCache& other : this->Levels)
    {
      other.TargetData = nullptr;
    }
    cache.TargetData = vtkSmartPointer<vtkPointData>::New();
    meshlod::GatherPointData(cache.Poly->GetPointData(),
      this->Levels[level + 1].Poly->GetPointData(), cache.TargetIds.data(),
      cache.Poly->GetNumberOfPoints(), cache.TargetData);
  }
  return cache.TargetData;
}

//------------------------------------------------------------------------------
void vtkLODGeomorph::Internals::ProduceLevel(int level, vtkPolyData* output)
{
  vtkPolyData* poly = this->Levels[level].Poly;
  output->SetPoints(poly->GetPoints());
  output->SetVerts(poly->GetVerts());
  output->SetLines(poly->GetLines());
  output->SetPolys(poly->GetPolys());
  output->SetStrips(poly->GetStrips());
  meshlod::BlendPlan same;
  same.NumberOfPoints = poly->GetNumberOfPoints();
  meshlod::BlendPointData(poly->GetPointData(), nullptr, same, output->GetPointData());
  output->GetCellData()->ShallowCopy(poly->GetCellData());
}

//------------------------------------------------------------------------------
bool vtkLODGeomorph::Internals::ProducePartialCollapse(
  vtkLODGeomorph* self, int level, double t, vtkPolyData* output)
{
  LevelCache& cache = this->Levels[level];
  vtkPolyData* poly = cache.Poly;
  const vtkIdType n = poly->GetNumberOfPoints();
  if (n == 0)
  {
    this->ProduceLevel(level, output);
    return true;
  }
  // Paper: p(t) = p + t (c - p), written (1 - t) p + t c so that t = 0 and 1 are exact.
  meshlod::BlendPlan geometry;
  geometry.Pool = &this->Pool;
  geometry.NumberOfPoints = n;
  geometry.Weight = t;
  vtkDataArray* target = poly->GetPointData()->GetArray(meshlod::names::MorphTarget);
  vtkSmartPointer<vtkDataArray> points =
    meshlod::BlendRealArray(poly->GetPoints()->GetData(), target, geometry, false);
  output->SetPoints(PointsFrom(points));
  geometry.Unblended = UnblendedTCoords(poly);
  meshlod::BlendPointData(
    poly->GetPointData(), this->TargetData(level), geometry, output->GetPointData());

  output->SetVerts(poly->GetVerts());
  output->SetLines(poly->GetLines());
  output->SetStrips(poly->GetStrips());
  if (!self->DropDegenerateTriangles)
  {
    output->SetPolys(poly->GetPolys());
    output->GetCellData()->ShallowCopy(poly->GetCellData());
    return true;
  }
  if (!this->EnsureTriangles(self, level, "DropDegenerateTriangles"))
  {
    return false;
  }
  // Coinciding up to rounding: a few units in the last place of the point type, at the scale of
  // the level.
  const double epsilon = points->GetDataType() == VTK_FLOAT
    ? std::numeric_limits<float>::epsilon()
    : std::numeric_limits<double>::epsilon();
  const double tolerance = 4.0 * epsilon * poly->GetLength();
  std::vector<std::uint8_t> degenerate(cache.Triangles.size() / 3);
  DegenerateWorker worker{ &cache.Triangles, tolerance * tolerance, &degenerate };
  DispatchPoints(points.Get(), worker);
  if (std::find(degenerate.begin(), degenerate.end(), 1) == degenerate.end())
  {
    output->SetPolys(poly->GetPolys());
    output->GetCellData()->ShallowCopy(poly->GetCellData());
    return true;
  }
  std::vector<Id> keptTriangles;
  output->SetPolys(CompactTriangles(
    cache.Triangles, [](Id p) { return p; }, [&](vtkIdType tri) { return !degenerate[tri]; },
    keptTriangles));
  output->GetCellData()->ShallowCopy(SubsetCellData(poly->GetCellData(), keptTriangles));
  return true;
}

//------------------------------------------------------------------------------
bool vtkLODGeomorph::Internals::ProduceNearestBlend(
  vtkLODGeomorph* self, int level, double t, vtkPolyData* output)
{
  LevelCache& cache = this->Levels[level];
  vtkPolyData* poly = cache.Poly;
  vtkPolyData* coarse = this->Levels[level + 1].Poly;
  const vtkIdType n = poly->GetNumberOfPoints();
  if (n == 0 || coarse->GetNumberOfPoints() == 0)
  {
    if (n > 0)
    {
      vtkWarningWithObjectMacro(self,
        "Level " << level + 1 << " has no points: producing level " << level << " unchanged.");
    }
    this->ProduceLevel(level, output);
    return true;
  }
  if (!this->EnsureCorrespondence(self, level))
  {
    return false;
  }
  if (self->GetAbortExecute())
  {
    return false;
  }
  // Paper step 3: P = t P_coarse + (1 - t) P_fine.
  meshlod::BlendPlan plan;
  plan.Pool = &this->Pool;
  plan.NumberOfPoints = n;
  plan.Map = cache.Partner.data();
  plan.Weight = t;
  vtkDataArray* finePoints = poly->GetPoints()->GetData();
  vtkDataArray* coarsePoints = coarse->GetPoints()->GetData();
  vtkSmartPointer<vtkDataArray> points =
    meshlod::BlendRealArray(finePoints, coarsePoints, plan, false);

  // Paper step 4: merge the points joined by an edge shorter than the tolerance, and remove the
  // triangles that degenerate.
  std::vector<std::uint8_t> shortEdge(cache.Edges.Size());
  const double tolerance = self->MergeTolerance * cache.Diagonal;
  ShortEdgeWorker lengths{ &cache.Edges, tolerance * tolerance, &shortEdge };
  DispatchPoints(points.Get(), lengths);
  if (std::find(shortEdge.begin(), shortEdge.end(), 1) == shortEdge.end())
  {
    output->SetPoints(PointsFrom(points));
    output->SetPolys(poly->GetPolys());
    output->GetCellData()->ShallowCopy(poly->GetCellData());
    plan.Unblended = UnblendedTCoords(poly);
    meshlod::BlendPointData(
      poly->GetPointData(), coarse->GetPointData(), plan, output->GetPointData());
    return true;
  }
  // The merged topology only changes when the set of short edges does (a few times between
  // t = 0 and 1): keep the last one.
  MergedTopology& merged = cache.Merged;
  if (shortEdge != merged.ShortEdges)
  {
    this->MergeShortEdges(self, level, shortEdge);
  }
  this->WarnIfMergedTooFar(self, level);
  plan.NumberOfPoints = static_cast<vtkIdType>(merged.Source.size());
  plan.Source = merged.Source.data();
  output->SetPoints(PointsFrom(meshlod::BlendRealArray(finePoints, coarsePoints, plan, false)));
  plan.Unblended = UnblendedTCoords(poly);
  meshlod::BlendPointData(
    poly->GetPointData(), coarse->GetPointData(), plan, output->GetPointData());
  output->SetPolys(merged.Cells);
  output->GetCellData()->ShallowCopy(merged.CellData);
  return true;
}

// The blend of `level` and the next with the points joined by the edges marked in `shortEdge`
// merged (taken from it), and the triangles that degenerate removed: cache.Merged.
void vtkLODGeomorph::Internals::MergeShortEdges(
  vtkLODGeomorph* self, int level, std::vector<std::uint8_t>& shortEdge)
{
  LevelCache& cache = this->Levels[level];
  vtkPolyData* poly = cache.Poly;
  vtkPolyData* coarse = this->Levels[level + 1].Poly;
  const vtkIdType n = poly->GetNumberOfPoints();
  MergedTopology& merged = cache.Merged;
  merged.ShortEdges.swap(shortEdge);
  std::vector<Id> representative;
  meshlod::MergeAlongEdges(
    cache.Edges, merged.ShortEdges.data(), static_cast<Id>(n), representative);
  std::vector<Id> newId(n);
  merged.Source.clear();
  merged.Source.reserve(n);
  for (vtkIdType p = 0; p < n; ++p)
  {
    if (representative[p] == p)
    {
      newId[p] = static_cast<Id>(merged.Source.size());
      merged.Source.push_back(static_cast<Id>(p));
    }
    else
    {
      newId[p] = newId[representative[p]]; // the representative has a lower id
    }
  }
  std::vector<Id> keptTriangles;
  merged.Cells = CompactTriangles(
    cache.Triangles, [&](Id p) { return newId[p]; }, [](vtkIdType) { return true; },
    keptTriangles);
  merged.CellData = SubsetCellData(poly->GetCellData(), keptTriangles);
}

// Merging only has to remove about what the coarser level removed; far below that it eats the
// surface (a tolerance near the mesh's size merges every edge). Half is the limit: the default
// tolerance near t = 1 can go a little below (0.2% on a 2M-triangle benchmark transition). Said
// once per tolerance value, whether or not the merged edges changed with it.
void vtkLODGeomorph::Internals::WarnIfMergedTooFar(vtkLODGeomorph* self, int level)
{
  MergedTopology& merged = this->Levels[level].Merged;
  const vtkIdType kept = merged.Cells->GetNumberOfCells();
  const vtkIdType coarseTriangles = this->Levels[level + 1].Poly->GetNumberOfPolys();
  if (2 * kept < coarseTriangles && merged.WarnedTolerance != self->MergeTolerance)
  {
    merged.WarnedTolerance = self->MergeTolerance;
    vtkWarningWithObjectMacro(self,
      "MergeTolerance " << self->MergeTolerance << " merged the blend of levels " << level
                        << " and " << level + 1 << " down to " << kept
                        << " triangles, under half of level " << level + 1 << "'s ("
                        << coarseTriangles << "): the tolerance is too large for this mesh "
                        << "(the default 1e-4 merges only edges shorter than a pixel).");
  }
}

//------------------------------------------------------------------------------
void vtkLODGeomorph::Internals::BuildExactTopology(int level, Id steps, Id nextStep)
{
  ExactTopology& exact = this->Exact;
  const LevelCache& cache = this->Levels[level];
  const meshlod::CollapseSchedule& schedule = *cache.Schedule;
  const Id n = static_cast<Id>(cache.Poly->GetNumberOfPoints());
  const Id targets = static_cast<Id>(this->Levels[level + 1].Poly->GetNumberOfPoints());
  exact.Level = level;
  exact.Steps = steps;
  exact.Source.clear();
  exact.State.clear();

  // Settled points with the same target become one point: the lowest id among them. Not so in
  // a level whose TCoords address a texture of its own: the points of a cluster, and a split
  // level's copies of a point, address different places of the texture, so they stay apart
  // (and coincide) with their own coordinates, as in the partial collapse between levels; the
  // points left without a triangle are dropped.
  const bool apart = UnblendedTCoords(cache.Poly) != nullptr;
  std::vector<std::uint8_t> used;
  if (apart)
  {
    used.assign(n, 0);
    for (size_t t = 0; t < schedule.RemovalStep.size(); ++t)
    {
      if (schedule.RemovalStep[t] > steps)
      {
        for (int c = 0; c < 3; ++c)
        {
          used[cache.Triangles[3 * t + c]] = 1;
        }
      }
    }
  }
  std::vector<Id> representative(targets, meshlod::InvalidId);
  std::vector<Id> newId(n, meshlod::InvalidId);
  for (Id p = 0; p < n; ++p)
  {
    if (apart && !used[p])
    {
      continue;
    }
    const Id step = schedule.Step[cache.ScheduleIds.empty() ? p : cache.ScheduleIds[p]];
    if (step <= steps && !apart)
    {
      Id& rep = representative[cache.TargetIds[p]];
      if (rep != meshlod::InvalidId)
      {
        newId[p] = newId[rep];
        continue;
      }
      rep = p;
    }
    newId[p] = static_cast<Id>(exact.Source.size());
    exact.Source.push_back(p);
    exact.State.push_back(step <= steps ? 2 : (nextStep > 0 && step <= nextStep ? 1 : 0));
  }
  std::vector<Id> keptTriangles;
  exact.Cells = CompactTriangles(
    cache.Triangles, [&](Id p) { return newId[p]; },
    [&](vtkIdType tri) { return schedule.RemovalStep[tri] > steps; }, keptTriangles);
  exact.CellData = SubsetCellData(cache.Poly->GetCellData(), keptTriangles);
}

//------------------------------------------------------------------------------
bool vtkLODGeomorph::Internals::ProduceExactCount(
  vtkLODGeomorph* self, vtkIdType count, double fraction, vtkPolyData* output, double& lod)
{
  // Levels are told apart by their triangle counts: a level with strips, vertices or lines would
  // be miscounted (a level of strips has no polygons at all).
  for (int i = 0; i < static_cast<int>(this->Levels.size()); ++i)
  {
    vtkPolyData* poly = this->Levels[i].Poly;
    if (poly->GetNumberOfCells() != poly->GetNumberOfPolys() &&
      !this->EnsureTriangles(self, i, "TargetNumberOfTriangles"))
    {
      return false;
    }
  }
  int level = -1;
  if (this->ProduceWholeLevelFor(self, count, fraction, output, lod, level))
  {
    return true;
  }
  if (!this->EnsureSchedule(self, level))
  {
    return false;
  }
  auto trianglesOf = [&](int i) { return this->Levels[i].Poly->GetNumberOfPolys(); };
  const meshlod::CollapseSchedule& schedule = *this->Levels[level].Schedule;
  const Id steps = schedule.StepsForCount(count);
  // Parity and single joins miss by a triangle or two; more means joins no order could make
  // valid (a transition between levels far apart, whose clusters merge many points at once).
  auto warnIfFar = [&](vtkIdType reached)
  {
    if (count - reached > std::max<vtkIdType>(3, count / 50))
    {
      vtkWarningWithObjectMacro(self,
        "TargetNumberOfTriangles " << count << ": the nearest reachable count below it is "
                                   << reached << " (between levels " << level << " and "
                                   << level + 1 << ", of " << trianglesOf(level) << " and "
                                   << trianglesOf(level + 1)
                                   << " triangles, some collapses merge too many points at "
                                      "once to be applied one point at a time; levels closer "
                                      "together give finer steps).");
    }
  };
  if (steps < 0)
  {
    // Even the whole transition leaves more: the next level is the nearest count below.
    lod = level + 1;
    this->ProduceLevel(level + 1, output);
    warnIfFar(trianglesOf(level + 1));
    return true;
  }
  const vtkIdType next = trianglesOf(level + 1);
  if (steps == schedule.NumberOfSteps() && schedule.CountAfter[steps] == next)
  {
    // Only the whole transition reaches the count: its end is the next level, produced as the
    // next level's own count is (L = level + 1, its own point data, a fraction moving its
    // first collapse), not as this level's points at their targets, whose TCoords address this
    // level's baked texture while floor(L) names the next one's.
    if (!this->ProduceExactCount(self, next, fraction, output, lod))
    {
      return false;
    }
    warnIfFar(next);
    return true;
  }
  const Id nextStep = schedule.NextRemovingStep(steps);
  this->ProduceSteps(level, steps, nextStep, fraction, output);
  warnIfFar(output->GetNumberOfPolys());
  const double moved = nextStep > 0 ? fraction * (nextStep - steps) : 0.0;
  lod = level + (steps + moved) / std::max<Id>(1, schedule.NumberOfSteps());
  // Below level + 1 even where the fraction moves the transition's last step all the way: the
  // output is level `level`'s points and data (a baked level's TCoords address texture block
  // floor(L)).
  lod = std::min(lod, std::nextafter(static_cast<double>(level + 1), 0.0));
  return true;
}

// The coarsest level with at least `count` triangles, into `level`. Where a whole level is the
// answer (that level has exactly `count` and no `fraction` of its next collapse is asked, or it
// is the finest or the coarsest and `count` lies beyond, or there are no collapse ranks to go
// part of the way), it is produced, with a warning where its count is not `count`, and true is
// returned.
bool vtkLODGeomorph::Internals::ProduceWholeLevelFor(vtkLODGeomorph* self, vtkIdType count,
  double fraction, vtkPolyData* output, double& lod, int& level)
{
  const int n = static_cast<int>(this->Levels.size());
  auto trianglesOf = [&](int i) { return this->Levels[i].Poly->GetNumberOfPolys(); };
  level = -1;
  for (int i = 0; i < n; ++i)
  {
    if (trianglesOf(i) >= count)
    {
      level = i;
    }
  }
  if (level < 0)
  {
    vtkWarningWithObjectMacro(self,
      "TargetNumberOfTriangles " << count << " is above the " << trianglesOf(0)
                                 << " triangles of the finest level; "
                                 << "producing the finest level.");
    level = 0;
  }
  // A level's own count with a fraction moves the points of its first collapse: else raising
  // the fraction to 1 there and then lowering the count would jump.
  const bool partWay = fraction > 0.0 && level < n - 1 && this->Mode == MORPH_ARRAYS;
  if (trianglesOf(level) < count || (trianglesOf(level) == count && !partWay))
  {
    lod = level;
    this->ProduceLevel(level, output);
    return true;
  }
  if (level == n - 1)
  {
    vtkWarningWithObjectMacro(self,
      "TargetNumberOfTriangles " << count << " is below the " << trianglesOf(level)
                                 << " triangles of the coarsest level; "
                                 << "producing the coarsest level.");
    lod = level;
    this->ProduceLevel(level, output);
    return true;
  }
  if (this->Mode != MORPH_ARRAYS)
  {
    // Without collapse ranks, the finest level with at most `count` triangles.
    vtkWarningWithObjectMacro(self,
      "An exact triangle count needs the morph arrays ("
        << meshlod::names::CollapseRank << "); producing level " << level + 1 << " ("
        << trianglesOf(level + 1) << " triangles) instead of " << count << " triangles.");
    lod = level + 1;
    this->ProduceLevel(level + 1, output);
    return true;
  }
  return false;
}

// The mesh after `steps` steps of the transition from `level`, the points of the step after
// (`nextStep`) moved by `fraction` of the way.
void vtkLODGeomorph::Internals::ProduceSteps(
  int level, Id steps, Id nextStep, double fraction, vtkPolyData* output)
{
  if (this->Exact.Level != level || this->Exact.Steps != steps)
  {
    this->BuildExactTopology(level, steps, nextStep);
  }
  const ExactTopology& exact = this->Exact;
  const vtkIdType m = static_cast<vtkIdType>(exact.Source.size());
  std::vector<double> weights(m);
  vtkSMPTools::For(0, m, [&](vtkIdType b, vtkIdType e) {
    for (vtkIdType q = b; q < e; ++q)
    {
      weights[q] = exact.State[q] == 2 ? 1.0 : (exact.State[q] == 1 ? fraction : 0.0);
    }
  });
  LevelCache& cache = this->Levels[level];
  vtkPolyData* poly = cache.Poly;
  meshlod::BlendPlan plan;
  plan.Pool = &this->Pool;
  plan.NumberOfPoints = m;
  plan.Source = exact.Source.data();
  plan.Weights = weights.data();
  vtkDataArray* target = poly->GetPointData()->GetArray(meshlod::names::MorphTarget);
  output->SetPoints(
    PointsFrom(meshlod::BlendRealArray(poly->GetPoints()->GetData(), target, plan, false)));
  plan.Map = cache.TargetIds.data();
  plan.Unblended = UnblendedTCoords(poly);
  meshlod::BlendPointData(poly->GetPointData(), this->Levels[level + 1].Poly->GetPointData(), plan,
    output->GetPointData());
  output->SetPolys(exact.Cells);
  output->GetCellData()->ShallowCopy(exact.CellData);
}

