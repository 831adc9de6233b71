#include "vtkTriangleCollapseDecimation.h"

#include "Core/FreshMemory.h"
#include "Core/LevelCentering.h"
#include "Core/LevelData.h"
#include "Core/LevelEdgeFlips.h"
#include "Core/TriangleCollapse.h"
#include "MeshLODHierarchy.h"
#include "MeshLODInputMesh.h"
#include "MeshLODSettings.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>
#include <utility>

vtkStandardNewMacro(vtkTriangleCollapseDecimation);

namespace
{
// Progress shares: validation, the collapses, building the output, measuring.
// A level's estimated error counts as a jump above ErrorJumpFactor times what the fall in its
// triangle count explains, measured from at least ErrorJumpFloor of the bounding diagonal.
constexpr double ErrorJumpFactor = 8.0;
constexpr double ErrorJumpFloor = 1e-4;
constexpr double CollapseStart = 0.05;
constexpr double CollapseEnd = 0.85;
constexpr double MeasureStart = 0.9;

// The curvature method's fits read the original points from the input itself (alive until
// the run ends) instead of a copy of them; the engine copies them when they are stored
// otherwise, or when point ids are not 64-bit (the engine reads the map as long long).
void LetFitsReadInputPoints(
  const meshlod::InputMesh& mesh, meshlod::TriangleCollapseOptions& options)
{
  vtkPoints* inputPoints = mesh.Source->GetPoints();
  vtkDataArray* coordinates = inputPoints ? inputPoints->GetData() : nullptr;
  if constexpr (std::is_same<vtkIdType, long long>::value)
  {
    if (options.Method == meshlod::CollapseMethod::Curvature && coordinates &&
      coordinates->GetNumberOfComponents() == 3)
    {
      if (auto* floats = vtkFloatArray::FastDownCast(coordinates))
      {
        options.InputPointsFloat = floats->GetPointer(0);
      }
      else if (auto* doubles = vtkDoubleArray::FastDownCast(coordinates))
      {
        options.InputPointsDouble = doubles->GetPointer(0);
      }
      // Through the map to the input's points, unless it is the identity (as it mostly is).
      // (The same type here: the cast only lets the discarded branch compile.)
      bool identity = true;
      for (std::size_t i = 0; i < mesh.SourcePointIds.size() && identity; ++i)
      {
        identity = mesh.SourcePointIds[i] == static_cast<vtkIdType>(i);
      }
      options.InputPointIds =
        identity ? nullptr : reinterpret_cast<const long long*>(mesh.SourcePointIds.data());
    }
  }
}

// The triangle count of each level of a mesh of inputTriangles triangles.
std::vector<std::int64_t> LevelTargets(
  const std::vector<double>& reductions, std::int64_t inputTriangles)
{
  std::vector<std::int64_t> targets;
  for (const double r : reductions)
  {
    // Reductions that round to the same count on a small mesh give one level.
    const auto target = static_cast<std::int64_t>(std::floor((1.0 - r) * inputTriangles));
    if (targets.empty() ? target < inputTriangles : target < targets.back())
    {
      targets.push_back(target);
    }
  }
  return targets;
}

// A level whose estimated error jumps far beyond what its triangle count explains (on a
// smooth surface the error grows about as the count falls) was made of collapses that had
// only costly choices left: a broken input (a locked seam, non-manifold parts) forced by the
// count. Reported, not prevented: nothing tells such a level from a healthy coarse one before
// it is made.
class ErrorJumpWatch
{
public:
  ErrorJumpWatch(double diagonal, std::int64_t inputTriangles)
    : Diagonal(diagonal)
    , PreviousTriangles(inputTriangles)
  {
  }

  // The levels in order, from level 1.
  void AddLevel(double error, std::int64_t triangles)
  {
    ++this->LevelIndex;
    const double reference = std::max(this->PreviousError, ErrorJumpFloor * this->Diagonal);
    const double explained = static_cast<double>(this->PreviousTriangles) /
      static_cast<double>(std::max<std::int64_t>(1, triangles));
    // (Not level 1: a noisy input's first collapses already move vertices by its noise.)
    if (this->JumpLevel < 0 && this->LevelIndex > 1 &&
      error > ErrorJumpFactor * explained * reference)
    {
      this->JumpLevel = this->LevelIndex;
      this->JumpError = error;
      this->JumpPrevious = this->PreviousError;
    }
    this->PreviousError = error;
    this->PreviousTriangles = triangles;
  }

  // A warning on `caller` about the first level whose error jumped, if one did. With
  // `piecesMayVanish` (PreserveTopology off) the warning names the other cause.
  void WarnIfJumped(vtkObject* caller, bool piecesMayVanish) const
  {
    if (this->JumpLevel > 0)
    {
      std::ostringstream jump;
      jump << "Level " << this->JumpLevel << "'s estimated error, " << this->JumpError << " ("
           << (this->Diagonal > 0.0 ? 100.0 * this->JumpError / this->Diagonal : 0.0)
           << "% of the bounding diagonal), is ";
      if (this->JumpPrevious > 0.0)
      {
        jump << this->JumpError / this->JumpPrevious << " times the level before's";
      }
      else
      {
        jump << "where the level before's was 0";
      }
      vtkWarningWithObjectMacro(caller,
        << jump.str()
        << ", far more than its triangle count explains: its last collapses had only "
           "costly choices left, and it may be badly distorted. Inputs with locked "
           "seams or non-manifold parts do this when pushed to a low count; ask for "
           "a smaller TargetReduction."
          << (piecesMayVanish
                 ? " (With PreserveTopology off, a closed piece that vanishes at that level "
                   "raises its estimated error to about the piece's size, as it should: then "
                   "the level is not distorted.)"
                 : ""));
    }
  }

private:
  double Diagonal;
  double PreviousError = 0.0;
  std::int64_t PreviousTriangles;
  int LevelIndex = 0;
  int JumpLevel = -1;
  double JumpError = 0.0;
  double JumpPrevious = 0.0;
};
} // namespace

//------------------------------------------------------------------------------
vtkTriangleCollapseDecimation::vtkTriangleCollapseDecimation() = default;
vtkTriangleCollapseDecimation::~vtkTriangleCollapseDecimation() = default;

//------------------------------------------------------------------------------
vtkMultiBlockDataSet* vtkTriangleCollapseDecimation::GetHierarchy()
{
  return vtkMultiBlockDataSet::SafeDownCast(this->GetOutputDataObject(0));
}

int vtkTriangleCollapseDecimation::FillInputPortInformation(int, vtkInformation* info)
{
  return meshlod::FillSurfaceInputPortInformation(info);
}

int vtkTriangleCollapseDecimation::FillOutputPortInformation(int, vtkInformation* info)
{
  return meshlod::FillHierarchyOutputPortInformation(info);
}

const char* vtkTriangleCollapseDecimation::GetMethodAsString() const
{
  return this->Method == QUADRIC ? "Quadric" : "Curvature";
}

const char* vtkTriangleCollapseDecimation::GetOperatorAsString() const
{
  return this->Operator == TRIANGLES ? "Triangles" : "TrianglesAndEdges";
}

const char* vtkTriangleCollapseDecimation::GetCurvatureCostAsString() const
{
  return this->CurvatureCost == FIT_DEVIATION ? "FitDeviation" : "Weight";
}

const char* vtkTriangleCollapseDecimation::GetScheduleAsString() const
{
  return this->Schedule == GREEDY ? "Greedy" : "IndependentSets";
}

const char* vtkTriangleCollapseDecimation::GetPlacementAsString() const
{
  return this->Placement == PAPER_CANDIDATES ? "PaperCandidates" : "Regularized";
}

const char* vtkTriangleCollapseDecimation::GetPlaneWeightsAsString() const
{
  return this->PlaneWeights == UNIFORM_WEIGHTS ? "Uniform" : "Area";
}

void vtkTriangleCollapseDecimation::AddLevelReduction(double reduction)
{
  this->LevelReductions.push_back(reduction);
  this->Modified();
}

void vtkTriangleCollapseDecimation::RemoveAllLevelReductions()
{
  if (!this->LevelReductions.empty())
  {
    this->LevelReductions.clear();
    this->Modified();
  }
}

double vtkTriangleCollapseDecimation::GetLevelReduction(int i) const
{
  return i >= 0 && i < this->GetNumberOfLevelReductions() ? this->LevelReductions[i] : 0.0;
}

//------------------------------------------------------------------------------
int vtkTriangleCollapseDecimation::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(outputVector);
  output->Initialize();
  // Every after-execution count is reset first, so that a run that fails or ends early reports
  // none of the run before.
  this->NumberOfLevelsProduced = 0;
  this->ActualReduction = 0.0;
  this->NumberOfSwaps = 0;
  this->NumberOfFlips = 0;
  vtkPolyData* input = nullptr;
  if (!meshlod::SurfaceInput(inputVector[0], this, input))
  {
    return 0;
  }

  // Settings first.
  if (!this->CheckSettings())
  {
    return 0;
  }

  meshlod::InputMesh mesh;
  const meshlod::InputStatus status = meshlod::ReadInputMesh(input, this, mesh);
  if (status == meshlod::InputStatus::Invalid)
  {
    return 0;
  }
  if (status == meshlod::InputStatus::Empty)
  {
    // One empty level, not none: see HierarchyBuilder::SetEmptyLevelZero.
    meshlod::HierarchyBuilder empty;
    empty.SetEmptyLevelZero(input, this->OutputPointsPrecision);
    this->NumberOfLevelsProduced = 1;
    empty.Finish(output);
    return 1;
  }
  const double diagonal = mesh.Mesh.BoundingDiagonal();
  if (!meshlod::CheckInputDiagonal(diagonal, this, "the collapse costs (squared areas)"))
  {
    return 0;
  }
  meshlod::WarnAboutReservedNames(input, this);
  this->UpdateProgress(CollapseStart);

  meshlod::TriangleCollapseOptions options = this->CollapseOptions();
  LetFitsReadInputPoints(mesh, options);
  const std::int64_t inputTriangles = mesh.Mesh.GetNumberOfTriangles();
  options.LevelTargets = LevelTargets(this->LevelReductionsToMake(), inputTriangles);

  meshlod::HierarchyBuilder builder;
  builder.SetLevelZero(mesh, this->OutputPointsPrecision);
  // Level 0 as the output holds it (the engine takes the mesh over below), for the passes that
  // look at each level through it.
  const bool throughLevelZero = this->CenterOnInput || this->FlipEdges;
  std::vector<double> levelZeroPoints; // only if its points are neither float nor double
  meshlod::LevelZeroCorrespondence levelZero;
  if (throughLevelZero)
  {
    levelZero.Reset(builder.GetLevelZeroView(levelZeroPoints));
  }
  meshlod::LevelCentering centering;
  if (this->CenterOnInput)
  {
    centering.SetLevelZero(levelZero);
  }
  meshlod::LevelEdgeFlips flips;
  vtkIdType flipCount = 0; // NumberOfFlips once the run has finished (an aborted one has none)
  if (this->FlipEdges)
  {
    flips.SetLevelZero(levelZero);
  }
  // The maps to the source were for level 0, but for the point map when the curvature method's
  // fits read the input's points through it (12 bytes per input triangle alive to the end of
  // the run otherwise).
  meshlod::Release(mesh.SourceCellIds);
  if (options.InputPointIds == nullptr)
  {
    meshlod::Release(mesh.SourcePointIds);
  }
  ErrorJumpWatch jumps(diagonal, mesh.Mesh.GetNumberOfTriangles());
  meshlod::TriangleCollapseCallbacks callbacks;
  std::vector<meshlod::Id> flipped;
  callbacks.EmitLevel = [&](meshlod::LevelData& level, meshlod::LevelRetriangulation& changed) {
    jumps.AddLevel(level.EstimatedError, level.Mesh.GetNumberOfTriangles());
    if (throughLevelZero)
    {
      levelZero.Advance(level.Target);
    }
    if (this->CenterOnInput)
    {
      centering.Apply(
        level.Mesh, level.Sources.Offsets, level.Sources.Parents, level.Sources.Weights);
    }
    if (this->FlipEdges)
    {
      // The collapses go on from the flipped triangles, so that the geomorph from this level
      // ends on the next level's triangles before its flips (see vtkLODGeomorph).
      flipped.clear();
      flipCount += flips.Apply(level.Mesh, level.EstimatedError, &flipped);
      std::sort(flipped.begin(), flipped.end()); // (each triangle once: one sweep flips it once)
      flipped.erase(std::unique(flipped.begin(), flipped.end()), flipped.end());
      for (const meshlod::Id j : flipped)
      {
        changed.Triangles.push_back(level.LevelZeroTriangle[j]);
        const meshlod::Id* corners = level.Mesh.Triangle(j);
        changed.Corners.insert(changed.Corners.end(), corners, corners + 3);
      }
    }
    builder.AppendLevel(std::move(level));
  };
  callbacks.Progress = [this](double fraction) {
    this->UpdateProgress(CollapseStart + (CollapseEnd - CollapseStart) * fraction);
    return !this->GetAbortExecute();
  };
  // Level 0 is built: the engine takes over the mesh and its topology instead of copying them.
  const meshlod::TriangleCollapseResult result = meshlod::RunTriangleCollapse(
    std::move(mesh.Mesh), std::move(mesh.Topology), options, callbacks);
  if (result.Aborted)
  {
    return 1; // aborted: the output stays empty
  }
  this->WarnIfTargetMissed(options, result);
  jumps.WarnIfJumped(this, !this->PreserveTopology);
  if (this->ComputeLevelError)
  {
    this->UpdateProgress(MeasureStart);
    builder.MeasureLevelErrors();
  }
  this->NumberOfLevelsProduced = builder.GetNumberOfLevels();
  this->NumberOfSwaps = result.Swaps;
  this->NumberOfFlips = flipCount;
  this->ActualReduction = inputTriangles > 0
    ? 1.0 - static_cast<double>(result.FinalTriangles) / static_cast<double>(inputTriangles)
    : 0.0;
  builder.Finish(output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkTriangleCollapseDecimation::CheckSettings()
{
  if (!meshlod::SettingsAreNumbers(this,
        { { "TriangleCostFactor", this->TriangleCostFactor },
          { "TargetReduction", this->TargetReduction }, { "LevelFraction", this->LevelFraction },
          { "MaximumError", this->MaximumError }, { "CurvatureWeight", this->CurvatureWeight },
          { "AngleWeight", this->AngleWeight }, { "ValenceWeight", this->ValenceWeight },
          { "BoundaryWeight", this->BoundaryWeight },
          { "AreaNormalization", this->AreaNormalization },
          { "MaximumNormalDeviation", this->MaximumNormalDeviation } }))
  {
    return false;
  }
  if (this->Method == CURVATURE &&
    std::abs(this->CurvatureWeight + this->AngleWeight + this->ValenceWeight - 1.0) > 1e-6)
  {
    vtkErrorMacro("CurvatureWeight + AngleWeight + ValenceWeight must be 1, not "
      << this->CurvatureWeight + this->AngleWeight + this->ValenceWeight << ".");
    return false;
  }
  const std::vector<double>& reductions = this->LevelReductions;
  for (size_t i = 0; i < reductions.size(); ++i)
  {
    if (!(reductions[i] > 0.0 && reductions[i] < 1.0) ||
      (i > 0 && reductions[i] <= reductions[i - 1]))
    {
      vtkErrorMacro("Level reductions must lie in (0, 1) and increase strictly; reduction "
        << i << " is " << reductions[i] << ".");
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
std::vector<double> vtkTriangleCollapseDecimation::LevelReductionsToMake() const
{
  std::vector<double> reductions = this->LevelReductions;
  if (reductions.empty())
  {
    // Geometric spacing of the kept fraction: keep_k = (1 - TargetReduction)^(k / N).
    const double coarsest = 1.0 - this->TargetReduction;
    for (int k = 1; k <= this->NumberOfLevels; ++k)
    {
      reductions.push_back(1.0 - std::pow(coarsest, static_cast<double>(k) / this->NumberOfLevels));
    }
  }
  return reductions;
}

//------------------------------------------------------------------------------
meshlod::TriangleCollapseOptions vtkTriangleCollapseDecimation::CollapseOptions() const
{
  meshlod::TriangleCollapseOptions options;
  options.Method = this->Method == QUADRIC ? meshlod::CollapseMethod::Quadric
                                           : meshlod::CollapseMethod::Curvature;
  options.Schedule = this->Schedule == GREEDY ? meshlod::CollapseSchedule::Greedy
                                              : meshlod::CollapseSchedule::IndependentSets;
  options.Operator = this->Operator == TRIANGLES ? meshlod::CollapseOperator::Triangles
                                                 : meshlod::CollapseOperator::TrianglesAndEdges;
  options.Placement = this->Placement == PAPER_CANDIDATES
    ? meshlod::CollapsePlacement::PaperCandidates
    : meshlod::CollapsePlacement::Regularized;
  options.UniformPlaneWeights = this->PlaneWeights == UNIFORM_WEIGHTS;
  options.AreaNormalization = this->AreaNormalization;
  options.PartitionedGreedy = this->PartitionedGreedy;
  options.TriangleCostFactor = this->TriangleCostFactor;
  options.MaximumError = this->MaximumError;
  options.LevelFraction = this->LevelFraction;
  options.CurvatureWeight = this->CurvatureWeight;
  options.AngleWeight = this->AngleWeight;
  options.ValenceWeight = this->ValenceWeight;
  options.CurvatureRanking = this->CurvatureCost == FIT_DEVIATION
    ? meshlod::CurvatureCost::FitDeviation
    : meshlod::CurvatureCost::Weight;
  options.BoundaryWeight = this->BoundaryWeight;
  options.MaximumNormalDeviation = this->MaximumNormalDeviation;
  options.PreserveTopology = this->PreserveTopology;
  options.MaximumFitPoints = this->MaximumFitPoints;
  return options;
}

//------------------------------------------------------------------------------
// A run that stops early emits the coarsest mesh it reached as a level of its own (see
// Collapser::FinishRun), so the level count alone does not tell a missed target: the last
// level must also be within one collapse (3 triangles) of the coarsest target.
// (No targets at all, as with TargetReduction 0: only level 0, nothing missed.)
void vtkTriangleCollapseDecimation::WarnIfTargetMissed(
  const meshlod::TriangleCollapseOptions& options, const meshlod::TriangleCollapseResult& result)
{
  const std::int64_t coarsestTarget =
    options.LevelTargets.empty() ? result.FinalTriangles : options.LevelTargets.back();
  if (result.TargetsReached < static_cast<int>(options.LevelTargets.size()) ||
    result.FinalTriangles > coarsestTarget + 3)
  {
    std::ostringstream levels;
    if (result.TargetsReached < static_cast<int>(options.LevelTargets.size()))
    {
      levels << "Reached " << result.TargetsReached << " of " << options.LevelTargets.size()
             << " level targets: the coarsest level";
    }
    else
    {
      levels << "The coarsest level";
    }
    std::ostringstream why;
    if (result.ErrorLimited)
    {
      why << "MaximumError reached";
    }
    else
    {
      why << "no legal collapse left";
      if (this->PreserveTopology && result.FinalPieces > 1)
      {
        why << "; each of its " << result.FinalPieces
            << " connected pieces keeps at least a tetrahedron, or a triangle if open, while "
               "PreserveTopology is on";
      }
    }
    vtkWarningMacro(<< levels.str() << " has " << result.FinalTriangles
                    << " triangles, short of its target of " << coarsestTarget << " ("
                    << why.str() << ").");
  }
}

//------------------------------------------------------------------------------
void vtkTriangleCollapseDecimation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << this->GetMethodAsString() << "\n";
  os << indent << "Schedule: " << this->GetScheduleAsString() << "\n";
  os << indent << "Operator: " << this->GetOperatorAsString() << "\n";
  os << indent << "Placement: " << this->GetPlacementAsString() << "\n";
  os << indent << "PlaneWeights: " << this->GetPlaneWeightsAsString() << "\n";
  os << indent << "AreaNormalization: " << this->AreaNormalization << "\n";
  os << indent << "PartitionedGreedy: " << (this->PartitionedGreedy ? "On" : "Off") << "\n";
  os << indent << "TriangleCostFactor: " << this->TriangleCostFactor << "\n";
  os << indent << "TargetReduction: " << this->TargetReduction << "\n";
  os << indent << "NumberOfLevels: " << this->NumberOfLevels << "\n";
  os << indent << "LevelReductions:";
  for (const double r : this->LevelReductions)
  {
    os << " " << r;
  }
  os << (this->LevelReductions.empty() ? " (none)\n" : "\n");
  os << indent << "LevelFraction: " << this->LevelFraction << "\n";
  os << indent << "MaximumError: " << this->MaximumError << "\n";
  os << indent << "CurvatureWeight: " << this->CurvatureWeight << "\n";
  os << indent << "AngleWeight: " << this->AngleWeight << "\n";
  os << indent << "ValenceWeight: " << this->ValenceWeight << "\n";
  os << indent << "CurvatureCost: " << this->GetCurvatureCostAsString() << "\n";
  os << indent << "BoundaryWeight: " << this->BoundaryWeight << "\n";
  os << indent << "MaximumNormalDeviation: " << this->MaximumNormalDeviation << "\n";
  os << indent << "PreserveTopology: " << (this->PreserveTopology ? "On" : "Off") << "\n";
  os << indent << "MaximumFitPoints: " << this->MaximumFitPoints << "\n";
  os << indent << "CenterOnInput: " << (this->CenterOnInput ? "On" : "Off") << "\n";
  os << indent << "FlipEdges: " << (this->FlipEdges ? "On" : "Off") << "\n";
  os << indent << "ComputeLevelError: " << (this->ComputeLevelError ? "On" : "Off") << "\n";
  os << indent << "OutputPointsPrecision: " << meshlod::PrecisionName(this->OutputPointsPrecision)
     << "\n";
  os << indent << "NumberOfLevelsProduced: " << this->NumberOfLevelsProduced << "\n";
  os << indent << "ActualReduction: " << this->ActualReduction << "\n";
  os << indent << "NumberOfSwaps: " << this->NumberOfSwaps << "\n";
  os << indent << "NumberOfFlips: " << this->NumberOfFlips << "\n";
}
