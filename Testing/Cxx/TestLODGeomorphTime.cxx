// vtkLODGeomorph driven by the pipeline time: published time steps, the same mesh as the
// explicit LevelOfDetail, DATA_TIME_STEP, a downstream filter asking for time, and an upstream
// hierarchy that has no time and runs only once.
#include "vtkLODGeomorph.h"

#include "MeshLODHierarchyChecks.h"
#include "MeshLODTestCheck.h"
#include "MeshLODTestHierarchies.h"
#include "MeshLODTestMeshes.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkMultiBlockDataSetAlgorithm.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTestErrorObserver.h"
#include "vtkTriangleFilter.h"

#include <limits>
#include <vector>

namespace
{
using namespace meshlod;
using testing::SameMesh;
using SDDP = vtkStreamingDemandDrivenPipeline;

// A pipeline source handing out a fixed hierarchy and counting its executions.
class HierarchySource : public vtkMultiBlockDataSetAlgorithm
{
public:
  static HierarchySource* New();
  vtkTypeMacro(HierarchySource, vtkMultiBlockDataSetAlgorithm);
  vtkSmartPointer<vtkMultiBlockDataSet> Hierarchy;
  int Executions = 0;
  std::vector<double> TimeSteps; // published when not empty
  double RequestedTime = -1.0;   // the time of the last execution, -1 when none was asked
  int RequestedPiece = -1, RequestedPieces = -1; // the piece request of the last execution

protected:
  HierarchySource() { this->SetNumberOfInputPorts(0); }
  int RequestInformation(
    vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkInformation* info = out->GetInformationObject(0);
    if (!this->TimeSteps.empty())
    {
      const double range[2] = { this->TimeSteps.front(), this->TimeSteps.back() };
      info->Set(
        SDDP::TIME_STEPS(), this->TimeSteps.data(), static_cast<int>(this->TimeSteps.size()));
      info->Set(SDDP::TIME_RANGE(), range, 2);
    }
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    ++this->Executions;
    vtkInformation* info = out->GetInformationObject(0);
    this->RequestedTime =
      info->Has(SDDP::UPDATE_TIME_STEP()) ? info->Get(SDDP::UPDATE_TIME_STEP()) : -1.0;
    this->RequestedPiece = info->Get(SDDP::UPDATE_PIECE_NUMBER());
    this->RequestedPieces = info->Get(SDDP::UPDATE_NUMBER_OF_PIECES());
    vtkMultiBlockDataSet::GetData(out)->ShallowCopy(this->Hierarchy);
    return 1;
  }
};
vtkStandardNewMacro(HierarchySource);

} // namespace

int TestLODGeomorphTime(int, char*[])
{
  testing::CollapseHierarchyOptions options;
  options.MaximumLevels = 4;
  options.MaximumFraction = 0.5;
  vtkNew<HierarchySource> source;
  source->Hierarchy = testing::MakeCollapseHierarchy(testing::MakeIcosphere(3), options);
  MESHLOD_CHECK_EQ(source->Hierarchy->GetNumberOfBlocks(), 4u);

  vtkNew<vtkLODGeomorph> timed;
  timed->SetInputConnection(source->GetOutputPort());
  timed->SetTimeScale(2.0);

  // One time step per level, level i at i * TimeScale.
  timed->UpdateInformation();
  vtkInformation* outInfo = timed->GetOutputInformation(0);
  MESHLOD_CHECK(outInfo->Has(SDDP::TIME_STEPS()));
  MESHLOD_CHECK_EQ(outInfo->Length(SDDP::TIME_STEPS()), 4);
  if (outInfo->Length(SDDP::TIME_STEPS()) == 4)
  {
    const double* steps = outInfo->Get(SDDP::TIME_STEPS());
    MESHLOD_CHECK_EQ(steps[0], 0.0);
    MESHLOD_CHECK_EQ(steps[3], 6.0);
  }
  MESHLOD_CHECK_EQ(outInfo->Get(SDDP::TIME_RANGE())[1], 6.0);

  // Without a time request, LevelOfDetail rules.
  timed->SetLevelOfDetail(1.25);
  timed->Update();
  MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), 1.25);

  // The explicit setting, for comparison.
  vtkNew<vtkLODGeomorph> explicitLod;
  explicitLod->SetInputConnection(source->GetOutputPort());
  explicitLod->UsePipelineTimeOff();

  for (const double time : { 0.0, 1.3, 2.0, 3.7, 5.9, 6.0 })
  {
    timed->UpdateTimeStep(time);
    vtkPolyData* byTime = timed->GetOutput();
    MESHLOD_CHECK_EQ(byTime->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), time);
    MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), time / 2.0);
    explicitLod->SetLevelOfDetail(time / 2.0);
    explicitLod->Update();
    MESHLOD_CHECK(SameMesh(byTime, explicitLod->GetOutput()));
  }
  // Every published time step gives its level exactly, also where i * TimeScale / TimeScale
  // rounds below i (3 * 0.7 / 0.7 is 2.9999999999999996: level 2 almost collapsed to level 3
  // came out instead of level 3).
  timed->SetTimeScale(0.7);
  timed->UpdateInformation();
  MESHLOD_CHECK_EQ(outInfo->Length(SDDP::TIME_STEPS()), 4);
  for (int i = 0; i < outInfo->Length(SDDP::TIME_STEPS()); ++i)
  {
    timed->UpdateTimeStep(outInfo->Get(SDDP::TIME_STEPS())[i]);
    MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), static_cast<double>(i));
    MESHLOD_CHECK(SameMesh(timed->GetOutput(),
      vtkPolyData::SafeDownCast(source->Hierarchy->GetBlock(static_cast<unsigned int>(i)))));
  }
  timed->SetTimeScale(2.0);

  // Beyond the range: clamped silently to the coarsest level.
  timed->UpdateTimeStep(9.0);
  MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), 3.0);
  MESHLOD_CHECK_EQ(timed->GetOutput()->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), 9.0);
  // A time that is not a number: an error, an empty output, and no level of detail reported
  // (the last one used to stay).
  {
    vtkNew<vtkTest::ErrorObserver> errors;
    timed->AddObserver(vtkCommand::ErrorEvent, errors);
    timed->UpdateTimeStep(std::numeric_limits<double>::quiet_NaN());
    MESHLOD_CHECK(errors->GetError());
    MESHLOD_CHECK_EQ(timed->GetOutput()->GetNumberOfPolys(), 0);
    MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), -1.0);
    timed->RemoveObserver(errors);
  }

  // A time-unaware filter downstream asking for a time.
  vtkNew<vtkTriangleFilter> downstream;
  downstream->SetInputConnection(timed->GetOutputPort());
  downstream->UpdateTimeStep(2.5);
  explicitLod->SetLevelOfDetail(1.25);
  explicitLod->Update();
  MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), 1.25);
  MESHLOD_CHECK(SameMesh(downstream->GetOutput(), explicitLod->GetOutput()));

  // The upstream ran once: its time request was never set, so it never re-ran for time.
  MESHLOD_CHECK_EQ(source->Executions, 1);
  MESHLOD_CHECK(!source->GetOutputInformation(0)->Has(SDDP::UPDATE_TIME_STEP()));

  // Pieces: the hierarchy is asked for whole (piece 0 of 1) whatever piece is asked for, and
  // runs no more for it; the whole mesh is piece 0, the other pieces are empty.
  {
    vtkNew<vtkLODGeomorph> pieces;
    pieces->SetInputConnection(source->GetOutputPort());
    pieces->UsePipelineTimeOff();
    pieces->SetLevelOfDetail(1.5);
    pieces->Update();
    vtkNew<vtkPolyData> whole;
    whole->DeepCopy(pieces->GetOutput());
    const int runs = source->Executions;
    pieces->UpdatePiece(1, 3, 1);
    MESHLOD_CHECK_EQ(pieces->GetOutput()->GetNumberOfPoints(), 0);
    MESHLOD_CHECK_EQ(pieces->GetNumberOfLevels(), 4);
    MESHLOD_CHECK_EQ(source->RequestedPiece, 0);
    MESHLOD_CHECK_EQ(source->RequestedPieces, 1);
    pieces->UpdatePiece(0, 3, 1);
    MESHLOD_CHECK(SameMesh(pieces->GetOutput(), whole));
    MESHLOD_CHECK_EQ(source->Executions, runs);
    MESHLOD_CHECK(!source->GetOutputInformation(0)->Has(SDDP::UPDATE_TIME_STEP()));
  }

  // An exact count ignores the time.
  timed->SetTargetNumberOfTriangles(1000);
  timed->UpdateTimeStep(4.0);
  MESHLOD_CHECK_EQ(timed->GetOutput()->GetNumberOfPolys(), 1000);
  timed->SetTargetNumberOfTriangles(-1);

  // UsePipelineTime off: no time published, the time request ignored.
  timed->UsePipelineTimeOff();
  timed->SetLevelOfDetail(0.5);
  timed->UpdateTimeStep(4.0);
  MESHLOD_CHECK(!timed->GetOutputInformation(0)->Has(SDDP::TIME_STEPS()));
  MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), 0.5);

  // A new hierarchy upstream: the time steps follow its number of levels.
  options.MaximumLevels = 2;
  source->Hierarchy = testing::MakeCollapseHierarchy(testing::MakeIcosphere(2), options);
  source->Modified();
  timed->UsePipelineTimeOn();
  timed->UpdateInformation();
  MESHLOD_CHECK_EQ(timed->GetOutputInformation(0)->Length(SDDP::TIME_STEPS()), 2);
  MESHLOD_CHECK_EQ(source->Executions, 2);
  timed->UpdateTimeStep(1.0);
  MESHLOD_CHECK_EQ(timed->GetActualLevelOfDetail(), 0.5);
  MESHLOD_CHECK_EQ(timed->GetNumberOfLevels(), 2);
  MESHLOD_CHECK_EQ(source->Executions, 2);

  // An upstream with time steps of its own. With pipeline time, the levels are the time steps
  // and the upstream is asked for its first; without, the filter is transparent to time.
  vtkNew<HierarchySource> temporal;
  temporal->Hierarchy = source->Hierarchy;
  temporal->TimeSteps = { 10.0, 20.0, 30.0 };
  vtkNew<vtkLODGeomorph> transparent;
  transparent->SetInputConnection(temporal->GetOutputPort());
  transparent->UpdateTimeStep(1.0);
  MESHLOD_CHECK_EQ(transparent->GetOutputInformation(0)->Length(SDDP::TIME_STEPS()), 2);
  MESHLOD_CHECK_EQ(temporal->RequestedTime, 10.0);
  transparent->UsePipelineTimeOff();
  transparent->SetLevelOfDetail(0.25);
  transparent->UpdateTimeStep(20.0);
  MESHLOD_CHECK_EQ(transparent->GetOutputInformation(0)->Length(SDDP::TIME_STEPS()), 3);
  MESHLOD_CHECK_EQ(temporal->RequestedTime, 20.0);
  MESHLOD_CHECK_EQ(transparent->GetActualLevelOfDetail(), 0.25);
  MESHLOD_CHECK_EQ(
    transparent->GetOutput()->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), 20.0);
  // Back to pipeline time: the first time step again, not the 20 asked while it was off.
  transparent->UsePipelineTimeOn();
  transparent->UpdateTimeStep(0.5);
  MESHLOD_CHECK_EQ(temporal->RequestedTime, 10.0);
  MESHLOD_CHECK_EQ(transparent->GetActualLevelOfDetail(), 0.5);
  return testing::Result();
}
