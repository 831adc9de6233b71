#include "vtkLODGeomorph.h"

#include "MeshLODGeomorphInternals.h"
#include "MeshLODHierarchy.h"
#include "MeshLODInputMesh.h"
#include "MeshLODSettings.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

vtkStandardNewMacro(vtkLODGeomorph);

namespace
{
constexpr const char* LevelOfDetailName = "LevelOfDetail";
// A pipeline time within this many levels of a level's time step is that level.
constexpr double LevelSnapTolerance = 1e-9;
// Between two levels whose triangles differ by edge flips (FlipEdges), the share of the interval
// that turns the flipped quads' diagonals, after the collapses.
constexpr double FlipShare = 0.25;
using meshlod::geomorph::HierarchyTime;

// The level of detail at pipeline time `time`, in [0, levels - 1]. The advertised time steps,
// i * timeScale, need not divide back to i (3 * 0.7 / 0.7 is 2.9999999999999996, whose floor is
// level 2 collapsed almost to level 3): a time that close to a level's is that level.
double LevelAtTime(double time, double timeScale, int levels)
{
  const double lod = std::min(std::max(time / timeScale, 0.0), static_cast<double>(levels - 1));
  const double nearest = std::round(lod);
  return std::abs(lod - nearest) <= LevelSnapTolerance ? nearest : lod;
}
} // namespace

//------------------------------------------------------------------------------
vtkLODGeomorph::vtkLODGeomorph()
  : Impl(new Internals)
{
}

vtkLODGeomorph::~vtkLODGeomorph() = default;

//------------------------------------------------------------------------------
void vtkLODGeomorph::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* const modes[] = { "Automatic", "MorphArrays", "NearestVertices" };
  os << indent << "LevelOfDetail: " << this->LevelOfDetail << "\n";
  os << indent << "UsePipelineTime: " << (this->UsePipelineTime ? "On" : "Off") << "\n";
  os << indent << "TimeScale: " << this->TimeScale << "\n";
  os << indent << "TargetNumberOfTriangles: " << this->TargetNumberOfTriangles << "\n";
  os << indent << "CollapseFraction: " << this->CollapseFraction << "\n";
  os << indent << "DropDegenerateTriangles: " << (this->DropDegenerateTriangles ? "On" : "Off")
     << "\n";
  os << indent << "Correspondence: " << modes[this->Correspondence] << "\n";
  os << indent << "MergeTolerance: " << this->MergeTolerance << "\n";
  os << indent << "NumberOfLevels: " << this->NumberOfLevels << "\n";
  os << indent << "ActualLevelOfDetail: " << this->ActualLevelOfDetail << "\n";
  os << indent << "ActualNumberOfTriangles: " << this->ActualNumberOfTriangles << "\n";
  os << indent << "ActualCorrespondence: " << modes[this->ActualCorrespondence] << "\n";
  os << indent << "NumberOfCorrespondenceBuilds: " << this->NumberOfCorrespondenceBuilds << "\n";
}

//------------------------------------------------------------------------------
int vtkLODGeomorph::FillInputPortInformation(int vtkNotUsed(port), vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  return 1;
}

//------------------------------------------------------------------------------
namespace
{
// With pipeline time the time is the level of detail, not a request for the hierarchy: an
// upstream with time of its own is asked for its first time step (or the start of its time
// range), whatever time was asked of it before (without this, a time asked while
// UsePipelineTime was off stayed in its request).
void AskForFirstTimeStep(vtkInformation* upstream)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (upstream->Has(SDDP::TIME_STEPS()) && upstream->Length(SDDP::TIME_STEPS()) > 0)
  {
    upstream->Set(SDDP::UPDATE_TIME_STEP(), upstream->Get(SDDP::TIME_STEPS())[0]);
  }
  else if (upstream->Has(SDDP::TIME_RANGE()) && upstream->Length(SDDP::TIME_RANGE()) > 0)
  {
    upstream->Set(SDDP::UPDATE_TIME_STEP(), upstream->Get(SDDP::TIME_RANGE())[0]);
  }
  else
  {
    upstream->Remove(SDDP::UPDATE_TIME_STEP());
  }
}
} // namespace

//------------------------------------------------------------------------------
int vtkLODGeomorph::RequestInformation(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** vtkNotUsed(inputVector), vtkInformationVector* outputVector)
{
  // Without pipeline time the filter is transparent to time: the executive has already copied
  // the input's time steps, if any, to the output.
  if (!this->UsePipelineTime)
  {
    return 1;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  if (this->GetNumberOfInputConnections(0) == 0)
  {
    return 1;
  }
  // The time steps are the levels, which only the data knows: bring the input up to date now
  // (the data pass then finds it up to date and does not run it again).
  int producerPort = 0;
  if (vtkAlgorithm* producer = this->GetInputAlgorithm(0, 0, producerPort))
  {
    producer->UpdateInformation();
    AskForFirstTimeStep(producer->GetOutputInformation(producerPort));
    producer->Update(producerPort);
  }
  auto* input = vtkMultiBlockDataSet::SafeDownCast(this->GetInputDataObject(0, 0));
  const int levels = input ? static_cast<int>(input->GetNumberOfBlocks()) : 0;
  bool allLevels = levels > 0;
  for (int i = 0; i < levels && allLevels; ++i)
  {
    allLevels = vtkPolyData::SafeDownCast(input->GetBlock(static_cast<unsigned int>(i))) != nullptr;
  }
  if (!allLevels || std::isnan(this->TimeScale))
  {
    return 1; // no time steps for what RequestData refuses (and reports: a block that is not a
              // level, a NaN TimeScale)
  }
  std::vector<double> times(levels);
  for (int i = 0; i < levels; ++i)
  {
    times[i] = i * this->TimeScale;
  }
  const double range[2] = { 0.0, times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), levels);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

//------------------------------------------------------------------------------
int vtkLODGeomorph::RequestUpdateExtent(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* vtkNotUsed(outputVector))
{
  // The blend needs the whole hierarchy, whatever piece is asked for (the piece is produced
  // whole or empty in RequestData). With pipeline time, the time is the level of detail and is
  // not passed upstream.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo)
  {
    meshlod::RequestWholeInput(inInfo);
  }
  if (this->UsePipelineTime && inInfo)
  {
    AskForFirstTimeStep(inInfo);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkLODGeomorph::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  auto* input = vtkMultiBlockDataSet::GetData(inputVector[0], 0);
  auto* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  this->ActualNumberOfTriangles = 0;
  this->ActualLevelOfDetail = -1.0; // until a level of detail is produced
  Internals& impl = *this->Impl;

  // 1. The input, validated once per change of the hierarchy or of the correspondence mode.
  const vtkMTimeType inputTime = input ? HierarchyTime(input) : 0;
  if (input != impl.Input || inputTime != impl.InputTime ||
    this->Correspondence != impl.RequestedCorrespondence)
  {
    impl.Input = input;
    impl.InputTime = inputTime;
    impl.RequestedCorrespondence = this->Correspondence;
    impl.Problem = impl.Prepare(input, this->Correspondence, this);
  }
  if (!impl.Problem.empty())
  {
    vtkErrorMacro(
      "Invalid LOD hierarchy: " << impl.Problem << ". The input must be a "
                                << "vtkMultiBlockDataSet of vtkPolyData levels, finest first.");
    this->NumberOfLevels = 0;
    return 1;
  }
  const bool pipelineTime =
    this->UsePipelineTime && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  if (!meshlod::SettingsAreNumbers(this,
        { { "LevelOfDetail",
            pipelineTime || this->TargetNumberOfTriangles >= 0 ? 0.0 : this->LevelOfDetail },
          { "TimeScale", this->TimeScale },
          { "CollapseFraction", this->CollapseFraction },
          { "MergeTolerance", this->MergeTolerance },
          { "The requested time (UPDATE_TIME_STEP)",
            pipelineTime ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())
                         : 0.0 } }))
  {
    return 1; // an empty output
  }
  const int n = static_cast<int>(impl.Levels.size());
  this->NumberOfLevels = n;
  this->ActualCorrespondence = impl.Mode;
  // The whole mesh is piece 0; the other pieces of a request in pieces are empty, so that the
  // pieces together hold it once.
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) &&
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) > 0)
  {
    return 1;
  }

  // 2. The level of detail: the pipeline time, or the explicit setting.
  double lod = this->LevelOfDetail;
  if (pipelineTime)
  {
    const double time = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    lod = LevelAtTime(time, this->TimeScale, n);
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), time);
  }
  else if (lod > n - 1 && this->TargetNumberOfTriangles < 0) // (an exact count overrides it)
  {
    // All the digits: 4.000000000000001 must not read "4 is beyond the coarsest level 4".
    std::ostringstream asked;
    asked << std::setprecision(17) << lod;
    vtkWarningMacro("LevelOfDetail " << asked.str() << " is beyond the coarsest level " << n - 1
                                     << "; producing level " << n - 1 << ".");
    lod = n - 1;
  }

  // 3. The mesh.
  this->UpdateProgress(0.0);
  int dataLevel = 0;
  if (!this->Produce(lod, output, dataLevel))
  {
    output->Initialize();
    return 1;
  }
  this->ActualLevelOfDetail = lod;
  vtkNew<vtkDoubleArray> lodArray;
  lodArray->SetName(LevelOfDetailName);
  lodArray->InsertNextValue(lod);
  output->GetFieldData()->AddArray(lodArray);
  // The field data of the level whose point data the output has, less what the layout gives
  // each level (its index, count and errors describe that level, not this mesh) but for
  // TextureAtlasLevel: the output's TCoords address that level's baked texture.
  vtkFieldData* levelData = impl.Levels[dataLevel].Poly->GetFieldData();
  meshlod::PassMetadata(levelData, output->GetFieldData());
  if (vtkAbstractArray* atlas = levelData->GetAbstractArray(meshlod::names::TextureAtlasLevel))
  {
    output->GetFieldData()->AddArray(atlas);
  }
  this->ActualNumberOfTriangles = output->GetNumberOfPolys();
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
// False when it failed or was stopped.
bool vtkLODGeomorph::Produce(double& lod, vtkPolyData* output, int& dataLevel)
{
  Internals& impl = *this->Impl;
  if (this->TargetNumberOfTriangles >= 0)
  {
    // (Its L is kept below the next level wherever the output has this level's point data.)
    const bool done = impl.ProduceExactCount(
      this, this->TargetNumberOfTriangles, this->CollapseFraction, output, lod);
    dataLevel = std::max(0, std::min(static_cast<int>(std::floor(lod)),
                              static_cast<int>(impl.Levels.size()) - 1));
    return done;
  }
  const int n = static_cast<int>(impl.Levels.size());
  int level = static_cast<int>(std::floor(lod));
  double t = lod - level;
  if (level >= n - 1)
  {
    level = n - 1;
    t = 0.0;
  }
  lod = level + t;
  dataLevel = level;
  if (t == 0.0)
  {
    impl.ProduceLevel(level, output);
    return true;
  }
  if (impl.Mode == MORPH_ARRAYS && impl.EnsureFlips(level))
  {
    // The collapses in the first part of the interval, the flips in the rest (see the header).
    constexpr double collapses = 1.0 - FlipShare;
    if (t >= collapses)
    {
      impl.ProduceFlipMorph(level, (t - collapses) / FlipShare, output);
      dataLevel = level + 1; // (on the next level's points, with its arrays)
      return true;
    }
    return impl.ProducePartialCollapse(this, level, t / collapses, output);
  }
  return impl.Mode == MORPH_ARRAYS ? impl.ProducePartialCollapse(this, level, t, output)
                                   : impl.ProduceNearestBlend(this, level, t, output);
}
