#include "MeshLODHierarchy.h"

#include "Core/FreshMemory.h"
#include "MeshLODInputMesh.h"
#include "MeshLODNewArray.h"
#include "MeshLODSurfaceDistance.h"

#include "vtkAlgorithm.h"
#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

#include <cmath>
#include <cstring>
#include <sstream>
#include <utility>
#include <vector>

namespace meshlod
{
namespace
{
// Integer-valued arrays hold ids, labels or categories: averaging them would invent values.
bool IsCategorical(vtkAbstractArray* array)
{
  auto* data = vtkDataArray::SafeDownCast(array);
  return data == nullptr || !(array->GetDataType() == VTK_FLOAT || array->GetDataType() == VTK_DOUBLE);
}

// The parent with the largest weight (the first one on ties).
Id DominantParent(const PointSources& s, vtkIdType p)
{
  Id best = s.Parents[s.Offsets[p]];
  float bestWeight = s.Weights[s.Offsets[p]];
  for (Id i = s.Offsets[p] + 1; i < s.Offsets[p + 1]; ++i)
  {
    if (s.Weights[i] > bestWeight)
    {
      best = s.Parents[i];
      bestWeight = s.Weights[i];
    }
  }
  return best;
}

// Point data of the new level: floating arrays interpolated with the sources' weights.
struct InterpolateWorker
{
  const PointSources* Sources;

  template <typename InArray, typename OutArray>
  void operator()(InArray* in, OutArray* out) const
  {
    const auto src = vtk::DataArrayTupleRange(in);
    auto dst = vtk::DataArrayTupleRange(out);
    const int nc = in->GetNumberOfComponents();
    const PointSources& s = *this->Sources;
    vtkSMPTools::For(0, dst.size(), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType p = begin; p < end; ++p)
      {
        // The weights are kept in single precision: as offsets from the first parent's value,
        // divided by their own sum, they keep a constant array exact and a large value with
        // small variations (a date, a georeferenced coordinate) to double precision.
        const Id first = s.Offsets[p];
        double weights = 0.0;
        for (Id i = first; i < s.Offsets[p + 1]; ++i)
        {
          weights += s.Weights[i];
        }
        for (int c = 0; c < nc; ++c)
        {
          const double base = static_cast<double>(src[s.Parents[first]][c]);
          double sum = 0.0;
          for (Id i = first + 1; i < s.Offsets[p + 1]; ++i)
          {
            sum += s.Weights[i] * (static_cast<double>(src[s.Parents[i]][c]) - base);
          }
          double value = weights > 0.0 ? base + sum / weights : base;
          if (!std::isfinite(value))
          {
            // Infinite values among the parents: the plain weighted sum (inf - inf is NaN).
            value = 0.0;
            for (Id i = first; i < s.Offsets[p + 1]; ++i)
            {
              value += s.Weights[i] * static_cast<double>(src[s.Parents[i]][c]);
            }
            bool nanParent = false;
            for (Id i = first; i < s.Offsets[p + 1]; ++i)
            {
              nanParent = nanParent || std::isnan(static_cast<double>(src[s.Parents[i]][c]));
            }
            if (std::isnan(value) && !nanParent)
            {
              // Infinities of both signs have no mean: the value of the heaviest parent. (A NaN
              // among the parents stays NaN, as in any mean.)
              value = static_cast<double>(src[DominantParent(s, p)][c]);
            }
          }
          dst[p][c] = static_cast<typename decltype(dst[p])::value_type>(value);
        }
      }
    });
  }
};

void InterpolatePointData(vtkPointData* from, const PointSources& sources, vtkIdType count,
  vtkPointData* to, const char* const* skipNames, int skipCount)
{
  vtkNew<vtkIdList> dominantIds, identity;
  for (int a = 0; a < from->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* in = from->GetAbstractArray(a);
    bool skip = false;
    for (int k = 0; k < skipCount; ++k)
    {
      skip = skip || (in->GetName() && std::string(in->GetName()) == skipNames[k]);
    }
    if (skip)
    {
      continue;
    }
    vtkSmartPointer<vtkAbstractArray> out = NewArrayLike(in, count);
    PrepareForWriting(out);
    if (!IsCategorical(in))
    {
      InterpolateWorker worker{ &sources };
      auto* inData = vtkDataArray::SafeDownCast(in);
      auto* outData = vtkDataArray::SafeDownCast(out);
      using Reals = vtkArrayDispatch::Reals;
      if (!vtkArrayDispatch::Dispatch2ByValueType<Reals, Reals>::Execute(inData, outData, worker))
      {
        worker(inData, outData);
      }
      if (in == from->GetNormals() && in->GetNumberOfComponents() == 3)
      {
        vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
          for (vtkIdType p = begin; p < end; ++p)
          {
            double n[3];
            outData->GetTuple(p, n);
            if (vtkMath::Normalize(n) > 0.0)
            {
              outData->SetTuple(p, n);
            }
          }
        });
      }
    }
    else
    {
      if (dominantIds->GetNumberOfIds() == 0)
      {
        dominantIds->SetNumberOfIds(count);
        identity->SetNumberOfIds(count);
        for (vtkIdType p = 0; p < count; ++p)
        {
          dominantIds->SetId(p, DominantParent(sources, p));
          identity->SetId(p, p);
        }
      }
      out->InsertTuples(identity, dominantIds, in);
    }
    const int attribute = from->IsArrayAnAttribute(a);
    if (attribute >= 0)
    {
      to->SetAttribute(out, attribute);
    }
    else
    {
      to->AddArray(out);
    }
  }
}

// The point type of every level: the one asked for, else the input's when it is float or
// double, else double. Integer points (VTK allows them) would truncate every collapse point and
// every geomorph frame.
int LevelPointType(vtkPoints* input, int precision)
{
  if (precision == vtkAlgorithm::SINGLE_PRECISION)
  {
    return VTK_FLOAT;
  }
  if (precision == vtkAlgorithm::DOUBLE_PRECISION)
  {
    return VTK_DOUBLE;
  }
  const int type = input ? input->GetDataType() : VTK_FLOAT;
  return type == VTK_FLOAT || type == VTK_DOUBLE ? type : VTK_DOUBLE;
}

vtkSmartPointer<vtkPoints> MakePoints(const TriangleMesh& mesh, int dataType)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataType(dataType);
  points->SetNumberOfPoints(mesh.GetNumberOfPoints());
  PrepareForWriting(points->GetData());
  vtkDataArray* data = points->GetData();
  vtkSMPTools::For(0, mesh.GetNumberOfPoints(), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType p = begin; p < end; ++p)
    {
      data->SetTuple(p, mesh.Point(static_cast<Id>(p)));
    }
  });
  return points;
}

// A point that is its one parent alone (weight 1) did not move: it takes the parent's
// coordinates exactly. (The engines work in their own frame, about the bounding box's centre,
// and the way back can differ from the input in the last bit: points of CollapseRank -1 had a
// MorphTarget 1e-16 away from themselves.) Only where the two agree to 1e-9 of the diagonal.
void KeepUnmovedPoints(
  const PointSources& sources, vtkDataArray* previous, double diagonal, vtkDataArray* points)
{
  const double tolerance2 = 1e-18 * diagonal * diagonal;
  vtkSMPTools::For(0, points->GetNumberOfTuples(), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType p = begin; p < end; ++p)
    {
      const Id first = sources.Offsets[p];
      if (sources.Offsets[p + 1] != first + 1 || sources.Weights[first] != 1.0f)
      {
        continue;
      }
      double x[3], y[3];
      points->GetTuple(p, x);
      previous->GetTuple(sources.Parents[first], y);
      const double d[3] = { x[0] - y[0], x[1] - y[1], x[2] - y[2] };
      if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= tolerance2)
      {
        points->SetTuple(p, y);
      }
    }
  });
}

template <typename T>
vtkSmartPointer<vtkIdList> ToIdList(const std::vector<T>& ids)
{
  auto list = vtkSmartPointer<vtkIdList>::New();
  list->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  for (size_t i = 0; i < ids.size(); ++i)
  {
    list->SetId(static_cast<vtkIdType>(i), static_cast<vtkIdType>(ids[i]));
  }
  return list;
}

vtkSmartPointer<vtkIdList> Iota(vtkIdType count)
{
  auto list = vtkSmartPointer<vtkIdList>::New();
  list->SetNumberOfIds(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    list->SetId(i, i);
  }
  return list;
}

// `to` allocated for `count` tuples of every array of `from`, attributes kept. Global ids too,
// which CopyAllocate's default flags leave out (they must stay unique): every use here takes each
// tuple at most once (a level's points from distinct input points, its triangles from distinct
// level-0 triangles). The flags are VTK's default again afterwards, for later users of `to`
// (CopyData copies what CopyAllocate chose).
void AllocateLike(vtkDataSetAttributes* from, vtkDataSetAttributes* to, vtkIdType count)
{
  to->SetCopyGlobalIds(1, vtkDataSetAttributes::COPYTUPLE);
  to->CopyAllocate(from, count);
  to->SetCopyGlobalIds(0, vtkDataSetAttributes::COPYTUPLE);
}

// The tuples fromIds of every array (AllocateLike).
void CopySubset(vtkDataSetAttributes* from, vtkIdList* fromIds, vtkDataSetAttributes* to)
{
  AllocateLike(from, to, fromIds->GetNumberOfIds());
  to->CopyData(from, fromIds, Iota(fromIds->GetNumberOfIds()));
}

void SetLevelFieldData(vtkPolyData* poly, int level, double estimatedError)
{
  vtkNew<vtkIntArray> index;
  index->SetName(names::LevelIndex);
  index->InsertNextValue(level);
  vtkNew<vtkIdTypeArray> triangles;
  triangles->SetName(names::NumberOfTriangles);
  triangles->InsertNextValue(poly->GetNumberOfPolys());
  vtkNew<vtkDoubleArray> error;
  error->SetName(names::EstimatedError);
  error->InsertNextValue(estimatedError);
  vtkFieldData* fd = poly->GetFieldData();
  fd->AddArray(index);
  fd->AddArray(triangles);
  fd->AddArray(error);
}

void SetDoubleField(vtkPolyData* poly, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  poly->GetFieldData()->AddArray(array);
}
} // namespace

//------------------------------------------------------------------------------
bool IsLevelFieldName(const char* name)
{
  for (const char* own : { names::LevelIndex, names::NumberOfTriangles, names::EstimatedError,
         names::MeasuredHausdorff, names::MeasuredRMS, names::TextureAtlasLevel })
  {
    if (std::strcmp(name, own) == 0)
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
void PassMetadata(vtkFieldData* from, vtkFieldData* to)
{
  for (int a = 0; from && a < from->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = from->GetAbstractArray(a);
    const char* name = array ? array->GetName() : nullptr;
    if (array && (!name || (!IsLevelFieldName(name) && !to->GetAbstractArray(name))))
    {
      to->AddArray(array);
    }
  }
}

//------------------------------------------------------------------------------
std::string LevelBlockName(int level)
{
  return "Level " + std::to_string(level);
}

void WarnAboutReservedNames(vtkPolyData* input, vtkObject* caller)
{
  for (const char* name : { names::MorphTarget, names::MorphTargetId, names::CollapseRank })
  {
    if (input != nullptr && input->GetPointData()->GetAbstractArray(name) != nullptr)
    {
      vtkWarningWithObjectMacro(caller,
        "The input's point-data array \"" << name << "\" is replaced on the levels by the "
                                            "hierarchy's own array of that name; rename it to "
                                            "keep it.");
    }
  }
}

struct HierarchyBuilder::Internals
{
  std::vector<vtkSmartPointer<vtkPolyData>> Levels;
  vtkSmartPointer<vtkFieldData> InputFieldData; // passed to every level by Finish
};

HierarchyBuilder::HierarchyBuilder()
  : Impl(new Internals)
{
}

HierarchyBuilder::~HierarchyBuilder()
{
  delete this->Impl;
}

int HierarchyBuilder::GetNumberOfLevels() const
{
  return static_cast<int>(this->Impl->Levels.size());
}

vtkPolyData* HierarchyBuilder::GetLevel(int level) const
{
  return this->Impl->Levels[level];
}

//------------------------------------------------------------------------------
void HierarchyBuilder::SetLevelZero(const InputMesh& input, int precision)
{
  this->Impl->Levels.clear();
  auto level0 = vtkSmartPointer<vtkPolyData>::New();
  vtkPolyData* source = input.Source;
  const bool cellsFirst = input.SourceCellIds.empty() || input.SourceCellIds[0] == 0;
  const int pointType = LevelPointType(source->GetPoints(), precision);
  if (input.SameAsInput)
  {
    level0->SetPoints(pointType == source->GetPoints()->GetDataType()
        ? source->GetPoints()
        : MakePoints(input.Mesh, pointType).GetPointer());
    level0->SetPolys(source->GetPolys());
    level0->GetPointData()->ShallowCopy(source->GetPointData());
  }
  else
  {
    level0->SetPoints(MakePoints(input.Mesh, pointType));
    level0->SetPolys(MakeTriangleCells(input.Mesh.Triangles.data(), input.Mesh.GetNumberOfTriangles()));
    CopySubset(source->GetPointData(), ToIdList(input.SourcePointIds), level0->GetPointData());
  }
  if (input.SameAsInput && cellsFirst && source->GetNumberOfCells() == source->GetNumberOfPolys())
  {
    level0->GetCellData()->ShallowCopy(source->GetCellData());
  }
  else
  {
    CopySubset(source->GetCellData(), ToIdList(input.SourceCellIds), level0->GetCellData());
  }
  SetLevelFieldData(level0, 0, 0.0);
  this->Impl->Levels.push_back(level0);
  this->Impl->InputFieldData = source->GetFieldData();
}

//------------------------------------------------------------------------------
LevelZeroView HierarchyBuilder::GetLevelZeroView(std::vector<double>& copy) const
{
  vtkPolyData* level0 = this->Impl->Levels.front();
  LevelZeroView view;
  vtkDataArray* points = level0->GetPoints()->GetData();
  if (auto* doubles = vtkDoubleArray::FastDownCast(points))
  {
    view.Doubles = doubles->GetPointer(0);
  }
  else if (auto* floats = vtkFloatArray::FastDownCast(points))
  {
    view.Floats = floats->GetPointer(0);
  }
  else
  {
    copy.resize(3 * static_cast<size_t>(points->GetNumberOfTuples()));
    for (vtkIdType p = 0; p < points->GetNumberOfTuples(); ++p)
    {
      points->GetTuple(p, copy.data() + 3 * p);
    }
    view.Doubles = copy.data();
  }
  vtkCellArray* polys = level0->GetPolys();
  if (polys->IsStorage64Bit())
  {
    view.Ids64 = polys->GetConnectivityArray64()->GetPointer(0);
  }
  else
  {
    view.Ids32 = polys->GetConnectivityArray32()->GetPointer(0);
  }
  view.Points = static_cast<Id>(points->GetNumberOfTuples());
  view.Triangles = static_cast<Id>(polys->GetNumberOfCells());
  return view;
}

//------------------------------------------------------------------------------
void HierarchyBuilder::SetEmptyLevelZero(vtkPolyData* input, int precision)
{
  this->Impl->Levels.clear();
  this->Impl->InputFieldData = input ? input->GetFieldData() : nullptr;
  auto level0 = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataType(LevelPointType(input ? input->GetPoints() : nullptr, precision));
  level0->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  level0->SetPolys(polys);
  if (input != nullptr)
  {
    AllocateLike(input->GetPointData(), level0->GetPointData(), 0);
    AllocateLike(input->GetCellData(), level0->GetCellData(), 0);
  }
  SetLevelFieldData(level0, 0, 0.0);
  this->Impl->Levels.push_back(level0);
}

//------------------------------------------------------------------------------
void HierarchyBuilder::AppendLevel(LevelData&& level)
{
  vtkPolyData* previous = this->Impl->Levels.back();
  vtkPolyData* level0 = this->Impl->Levels.front();
  const int index = static_cast<int>(this->Impl->Levels.size());
  const vtkIdType numberOfPoints = level.Mesh.GetNumberOfPoints();

  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(MakePoints(level.Mesh, level0->GetPoints()->GetDataType()));
  KeepUnmovedPoints(level.Sources, previous->GetPoints()->GetData(), level0->GetLength(),
    poly->GetPoints()->GetData());
  Release(level.Mesh.Points);
  poly->SetPolys(MakeTriangleCells(level.Mesh.Triangles.data(), level.Mesh.GetNumberOfTriangles()));
  Release(level.Mesh.Triangles);
  static const char* const morphNames[] = { names::MorphTarget, names::MorphTargetId,
    names::CollapseRank };
  InterpolatePointData(
    previous->GetPointData(), level.Sources, numberOfPoints, poly->GetPointData(), morphNames, 3);
  Release(level.Sources.Offsets);
  Release(level.Sources.Parents);
  Release(level.Sources.Weights);
  CopySubset(level0->GetCellData(), ToIdList(level.LevelZeroTriangle), poly->GetCellData());
  Release(level.LevelZeroTriangle);
  SetLevelFieldData(poly, index, level.EstimatedError);

  // Morph arrays on the previous level: ids and ranks in 32 bits, like the module's ids (a
  // quarter of a level's memory would otherwise go to these two arrays).
  const vtkIdType previousPoints = previous->GetNumberOfPoints();
  vtkNew<vtkTypeInt32Array> targetId;
  targetId->SetName(names::MorphTargetId);
  targetId->SetNumberOfValues(previousPoints);
  vtkNew<vtkTypeInt32Array> rank;
  rank->SetName(names::CollapseRank);
  rank->SetNumberOfValues(previousPoints);
  vtkSmartPointer<vtkDataArray> target =
    vtk::TakeSmartPointer(poly->GetPoints()->GetData()->NewInstance());
  target->SetName(names::MorphTarget);
  target->SetNumberOfComponents(3);
  target->SetNumberOfTuples(previousPoints);
  PrepareForWriting(targetId);
  PrepareForWriting(rank);
  PrepareForWriting(target);
  vtkDataArray* newPoints = poly->GetPoints()->GetData();
  vtkSMPTools::For(0, previousPoints, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType p = begin; p < end; ++p)
    {
      const Id to = level.Target[p];
      targetId->SetValue(p, to);
      rank->SetValue(p, level.Rank[p]);
      double x[3];
      newPoints->GetTuple(to, x);
      target->SetTuple(p, x);
    }
  });
  Release(level.Target);
  Release(level.Rank);
  // The previous level may share its point data object with the input: give it its own.
  vtkNew<vtkPointData> previousData;
  previousData->ShallowCopy(previous->GetPointData());
  previousData->AddArray(target);
  previousData->AddArray(targetId);
  previousData->AddArray(rank);
  previous->GetPointData()->ShallowCopy(previousData);

  this->Impl->Levels.push_back(poly);
}

//------------------------------------------------------------------------------
void HierarchyBuilder::MeasureLevelErrors()
{
  // Level 0 is sampled and located once for all levels.
  SurfaceDistanceOptions options;
  options.SamplesPerSurface = LevelErrorSamples;
  options.MaximumVertexSamples = LevelErrorSamples;
  const SurfaceDistanceMeter meter(this->Impl->Levels.front(), options);
  for (size_t i = 0; i < this->Impl->Levels.size(); ++i)
  {
    vtkPolyData* level = this->Impl->Levels[i];
    const SurfaceDistance d = i > 0 ? meter.Measure(level) : SurfaceDistance();
    SetDoubleField(level, names::MeasuredHausdorff, d.Hausdorff);
    SetDoubleField(level, names::MeasuredRMS, d.Rms);
  }
}

//------------------------------------------------------------------------------
void HierarchyBuilder::Finish(vtkMultiBlockDataSet* output)
{
  output->Initialize();
  output->SetNumberOfBlocks(static_cast<unsigned int>(this->Impl->Levels.size()));
  for (size_t i = 0; i < this->Impl->Levels.size(); ++i)
  {
    // The input's field data on every level; the layout's own names are left out even where
    // this level has no such array (an input that is itself a measured level must not lend its
    // MeasuredHausdorff to unmeasured ones).
    PassMetadata(this->Impl->InputFieldData, this->Impl->Levels[i]->GetFieldData());
    output->SetBlock(static_cast<unsigned int>(i), this->Impl->Levels[i]);
    output->GetMetaData(static_cast<unsigned int>(i))
      ->Set(vtkCompositeDataSet::NAME(), LevelBlockName(static_cast<int>(i)).c_str());
  }
  this->Impl->Levels.clear();
}

//------------------------------------------------------------------------------
int FillHierarchyOutputPortInformation(vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkMultiBlockDataSet");
  return 1;
}

//------------------------------------------------------------------------------
std::string CheckHierarchyLayout(vtkMultiBlockDataSet* hierarchy, bool requireMorphData)
{
  std::ostringstream problem;
  if (hierarchy == nullptr || hierarchy->GetNumberOfBlocks() == 0)
  {
    return "the hierarchy has no levels";
  }
  const unsigned int n = hierarchy->GetNumberOfBlocks();
  for (unsigned int i = 0; i < n; ++i)
  {
    auto* level = vtkPolyData::SafeDownCast(hierarchy->GetBlock(i));
    if (level == nullptr)
    {
      problem << "block " << i << " is not a vtkPolyData";
      return problem.str();
    }
    if (!requireMorphData || i + 1 == n)
    {
      continue;
    }
    auto* next = vtkPolyData::SafeDownCast(hierarchy->GetBlock(i + 1));
    vtkPointData* pd = level->GetPointData();
    vtkDataArray* targetId = pd->GetArray(names::MorphTargetId);
    vtkDataArray* target = pd->GetArray(names::MorphTarget);
    vtkDataArray* rank = pd->GetArray(names::CollapseRank);
    if (!targetId || !target || !rank || target->GetNumberOfComponents() != 3 ||
      targetId->GetNumberOfComponents() != 1 || rank->GetNumberOfComponents() != 1 ||
      targetId->GetNumberOfTuples() != level->GetNumberOfPoints() ||
      target->GetNumberOfTuples() != level->GetNumberOfPoints() ||
      rank->GetNumberOfTuples() != level->GetNumberOfPoints())
    {
      problem << "level " << i << " lacks complete " << names::MorphTarget << ", "
              << names::MorphTargetId << " and " << names::CollapseRank
              << " point arrays (3, 1 and 1 components, one tuple per point)";
      return problem.str();
    }
    // Scan the values (not GetRange(): its cached range misses in-place edits).
    bool inRange = true;
    for (vtkIdType p = 0; p < targetId->GetNumberOfTuples() && inRange; ++p)
    {
      const double id = targetId->GetTuple1(p);
      inRange = id >= 0 && id < static_cast<double>(next->GetNumberOfPoints()) &&
        id == std::floor(id);
    }
    if (!inRange)
    {
      problem << "level " << i << " has " << names::MorphTargetId << " values outside [0, "
              << next->GetNumberOfPoints() << ") or not integers";
      return problem.str();
    }
    // Ranks are compared as 64-bit integers: beyond 2^53 a double no longer holds every
    // integer (and 1e30 or an infinity would not convert).
    bool ranked = true;
    const double largestRank = 9007199254740992.0; // 2^53
    for (vtkIdType p = 0; p < rank->GetNumberOfTuples() && ranked; ++p)
    {
      const double r = rank->GetTuple1(p);
      ranked = r >= -1.0 && r <= largestRank && r == std::floor(r);
    }
    if (!ranked)
    {
      problem << "level " << i << " has " << names::CollapseRank
              << " values that are neither -1 nor a rank (an integer from 0 to 2^53)";
      return problem.str();
    }
    // MorphTarget is where the point MorphTargetId names is (the blends end on the one, the
    // exact counts and the correspondence use the other), up to 1e-6 of level i + 1's size.
    // (NaN or infinite values are reported as such by the geomorph.)
    const double tolerance = 1e-6 * next->GetLength();
    vtkIdType far = -1;
    for (vtkIdType p = 0; p < target->GetNumberOfTuples() && far < 0; ++p)
    {
      double x[3], y[3];
      target->GetTuple(p, x);
      next->GetPoint(static_cast<vtkIdType>(targetId->GetTuple1(p)), y);
      const double d2 = vtkMath::Distance2BetweenPoints(x, y);
      far = std::isfinite(d2) && d2 > tolerance * tolerance ? p : -1;
    }
    if (far >= 0)
    {
      problem << "level " << i << "'s " << names::MorphTarget << " of point " << far
              << " is not where its " << names::MorphTargetId << " point of level " << i + 1
              << " is";
      return problem.str();
    }
  }
  return std::string();
}

} // namespace meshlod
