#include "vtkVertexClusterOctree.h"

#include "Core/ClusterTree.h"
#include "Core/FreshMemory.h"
#include "Core/LevelCentering.h"
#include "Core/OctreeClustering.h"
#include "Core/SpatialOrder.h"
#include "Core/TextureAtlas.h"
#include "Core/Vector3.h"
#include "MeshLODHierarchy.h"
#include "MeshLODInputMesh.h"
#include "MeshLODSettings.h"
#include "MeshLODTextureBaking.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <limits>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkVertexClusterOctree);

namespace
{
using meshlod::Id;
using meshlod::InvalidId;

// The octree halves the input's bounding cube at most ClusterTree::AxisBits times along each
// axis, so its finest cells are 2^-AxisBits of the cube's side. Where the input's edges are
// mostly shorter than that (a small part beside a far outlier), many vertices share a finest
// cell and cannot be clustered apart: nothing merges there at any epsilon. Said in a warning
// (the median length of up to 10,000 edges, spread over the input: an outlier's long edges
// would raise a mean).
void WarnIfFinerThanOctree(const meshlod::TriangleMesh& mesh, vtkAlgorithm* caller)
{
  const Id nt = mesh.GetNumberOfTriangles();
  if (nt == 0)
  {
    return;
  }
  double lo[3], hi[3];
  mesh.GetBounds(lo, hi);
  const double side = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] });
  const double finest = std::ldexp(side, -meshlod::ClusterTree::AxisBits);
  const Id step = std::max<Id>(1, nt / 10000);
  std::vector<double> lengths;
  for (Id t = 0; t < nt; t += step)
  {
    const Id* tri = mesh.Triangle(t);
    lengths.push_back(std::sqrt(meshlod::Distance2(mesh.Point(tri[0]), mesh.Point(tri[1]))));
  }
  auto middle = lengths.begin() + lengths.size() / 2;
  std::nth_element(lengths.begin(), middle, lengths.end());
  const double median = *middle;
  if (median < finest)
  {
    vtkWarningWithObjectMacro(caller,
      "The input's edges (" << median << " long, the median) are shorter than the octree's finest "
                            << "cells (" << finest << ", 2^-" << meshlod::ClusterTree::AxisBits
                            << " of the bounding box's largest side, " << side
                            << "): vertices that share a cell cannot be clustered apart, so "
                               "such parts hardly simplify. A far outlier (a stray triangle) "
                               "makes the box that large: remove it, or simplify the parts "
                               "separately.");
  }
}

// One level to make: by epsilon (world units) or by triangle count.

struct LevelRequest
{
  bool ByCount = false;
  double Epsilon = 0.0;
  vtkIdType Count = 0;
};

// Mark `level`'s TCoords as addressing texture `texture` of output port 1 (see
// names::TextureAtlasLevel: a geomorph keeps them unblended).
void MarkAtlasLevel(vtkPolyData* level, int texture)
{
  vtkNew<vtkIntArray> mark;
  mark->SetName(meshlod::names::TextureAtlasLevel);
  mark->InsertNextValue(texture);
  level->GetFieldData()->AddArray(mark);
}

// Area-weighted point normals of a mesh (unit length; zero where every triangle is degenerate).
std::vector<float> PointNormals(const meshlod::TriangleMesh& mesh)
{
  std::vector<double> sum(3 * static_cast<size_t>(mesh.GetNumberOfPoints()), 0.0);
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    const Id* tri = mesh.Triangle(t);
    double n[3];
    mesh.AreaVector(t, n);
    for (int k = 0; k < 3; ++k)
    {
      for (int i = 0; i < 3; ++i)
      {
        sum[3 * static_cast<size_t>(tri[k]) + i] += n[i];
      }
    }
  }
  std::vector<float> normals(sum.size(), 0.0f);
  for (size_t p = 0; p < sum.size() / 3; ++p)
  {
    const double length = std::sqrt(
      sum[3 * p] * sum[3 * p] + sum[3 * p + 1] * sum[3 * p + 1] + sum[3 * p + 2] * sum[3 * p + 2]);
    for (int i = 0; i < 3 && length > 0.0; ++i)
    {
      normals[3 * p + i] = static_cast<float>(sum[3 * p + i] / length);
    }
  }
  return normals;
}

// Points of a level that were split for the texture atlas: split point -> level point, and the
// first split point of each level point. Both empty when the level was not split.
struct SplitMap
{
  std::vector<Id> SplitToPoint;
  std::vector<Id> FirstSplit;
  Id Point(Id split) const
  {
    return this->SplitToPoint.empty() ? split : this->SplitToPoint[split];
  }
  Id First(Id point) const { return this->FirstSplit.empty() ? point : this->FirstSplit[point]; }
  Id Count(Id points) const
  {
    return this->SplitToPoint.empty() ? points : static_cast<Id>(this->SplitToPoint.size());
  }
};

// The level handed to the hierarchy builder, its points split as `split` says (the points of
// the previous level as `previous` says).
meshlod::LevelData ToLevelData(meshlod::ClusterLevel& level,
  const SplitMap& previous,
  Id previousPoints,
  const SplitMap& split,
  const meshlod::TextureAtlas* atlas)
{
  meshlod::LevelData data;
  data.EstimatedError = level.EstimatedError;
  data.LevelZeroTriangle = std::move(level.LevelZeroTriangle);
  if (!atlas && previous.SplitToPoint.empty())
  {
    // Nothing split: hand the arrays over as they are.
    data.Mesh = std::move(level.Mesh);
    data.Sources.Offsets = std::move(level.SourceOffsets);
    data.Sources.Parents = std::move(level.SourceParents);
    data.Sources.Weights = std::move(level.SourceWeights);
    data.Target = std::move(level.Target);
    data.Rank = std::move(level.Rank);
    return data;
  }
  const Id points = level.Mesh.GetNumberOfPoints();
  const Id splitPoints = split.Count(points);
  data.Mesh.Points.resize(3 * static_cast<size_t>(splitPoints));
  for (Id q = 0; q < splitPoints; ++q)
  {
    std::copy_n(level.Mesh.Point(split.Point(q)), 3, data.Mesh.Point(q));
  }
  data.Mesh.Triangles = atlas ? atlas->CornerPoint : level.Mesh.Triangles;
  data.Sources.Clear();
  std::vector<Id> parents;
  for (Id q = 0; q < splitPoints; ++q)
  {
    const Id j = split.Point(q);
    parents.clear();
    for (Id i = level.SourceOffsets[j]; i < level.SourceOffsets[j + 1]; ++i)
    {
      parents.push_back(previous.First(level.SourceParents[i]));
    }
    data.Sources.Add(parents.data(),
      level.SourceWeights.data() + level.SourceOffsets[j],
      static_cast<int>(parents.size()));
  }
  data.Target.resize(previousPoints);
  data.Rank.resize(previousPoints);
  for (Id r = 0; r < previousPoints; ++r)
  {
    const Id p = previous.Point(r);
    data.Target[r] = split.First(level.Target[p]);
    data.Rank[r] = level.Rank[p];
  }
  return data;
}

// The colour source for baking: the input texture at its texture coordinates, else a colour
// array (ColorArrayName, else the scalars). False, with the reason in `problem`, when neither
// can be used.
bool InitializeBaker(meshlod::TextureBaker& baker,
  const meshlod::InputMesh& in,
  vtkDataArray* inputTCoords,
  vtkImageData* texture,
  const char* colorArrayName,
  std::string& problem)
{
  bool ready = false;
  if (texture && inputTCoords)
  {
    ready = baker.InitializeFromTexture(in.Source, inputTCoords, texture, problem);
  }
  else
  {
    vtkDataArray* colors = colorArrayName ? in.Source->GetPointData()->GetArray(colorArrayName)
                                          : in.Source->GetPointData()->GetScalars();
    if (colors == nullptr)
    {
      const bool other = colorArrayName &&
        in.Source->GetPointData()->GetAbstractArray(colorArrayName) != nullptr;
      problem = !colorArrayName
        ? std::string("the input has neither texture coordinates with a texture on port 1 "
                      "nor colour scalars")
        : std::string(other ? "the input's point array " : "the input has no point array ") +
          "named " + colorArrayName + (other ? " is not numeric (a data array)" : "");
    }
    else
    {
      ready = baker.InitializeFromColors(in.Source, colors, problem);
    }
  }
  return ready;
}

// Block b of the textures output holds the texture of level b: named as that level's block.
void NameTextureBlocks(vtkMultiBlockDataSet* textures)
{
  for (unsigned int b = 0; b < textures->GetNumberOfBlocks(); ++b)
  {
    textures->GetMetaData(b)->Set(
      vtkCompositeDataSet::NAME(), meshlod::LevelBlockName(static_cast<int>(b)).c_str());
  }
}

// The normals array of an output level: each point (split as `split` says) takes the normal of
// its level point.
void SetLevelNormals(vtkPolyData* poly,
  const std::string& normalsName,
  const std::vector<float>& normals,
  const SplitMap& split)
{
  vtkNew<vtkFloatArray> array;
  array->SetName(normalsName.c_str());
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(poly->GetNumberOfPoints());
  for (vtkIdType q = 0; q < poly->GetNumberOfPoints(); ++q)
  {
    array->SetTypedTuple(
      q, normals.data() + 3 * static_cast<size_t>(split.Point(static_cast<Id>(q))));
  }
  poly->GetPointData()->SetNormals(array);
}

// The texture coordinates of an output level: the texel of each triangle corner in `atlas`, on
// the point the atlas gives that corner.
void SetLevelTCoords(vtkPolyData* poly,
  const std::string& tcoordsName,
  const meshlod::TriangleMesh& mesh,
  const meshlod::TextureAtlas& atlas)
{
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName(tcoordsName.c_str());
  tcoords->SetNumberOfComponents(2);
  tcoords->SetNumberOfTuples(poly->GetNumberOfPoints());
  for (Id t = 0; t < mesh.GetNumberOfTriangles(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Id q = atlas.CornerPoint[3 * static_cast<size_t>(t) + k];
      const Id* texel = atlas.CornerTexel.data() + 6 * static_cast<size_t>(t) + 2 * k;
      tcoords->SetTypedComponent(q, 0, static_cast<float>(atlas.U(texel[0])));
      tcoords->SetTypedComponent(q, 1, static_cast<float>(atlas.U(texel[1])));
    }
  }
  poly->GetPointData()->SetTCoords(tcoords);
  // The atlas splits points into copies that share their point data: a GlobalIds attribute,
  // which promises one point per id, stays as a plain array of the same name.
  if (poly->GetPointData()->GetGlobalIds())
  {
    poly->GetPointData()->SetActiveAttribute(-1, vtkDataSetAttributes::GLOBALIDS);
  }
}
} // namespace

//------------------------------------------------------------------------------
vtkVertexClusterOctree::vtkVertexClusterOctree()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

vtkVertexClusterOctree::~vtkVertexClusterOctree()
{
  this->SetColorArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkVertexClusterOctree::AddEpsilonValue(double epsilon)
{
  this->EpsilonValues.push_back(epsilon);
  this->Modified();
}

void vtkVertexClusterOctree::RemoveAllEpsilonValues()
{
  if (!this->EpsilonValues.empty())
  {
    this->EpsilonValues.clear();
    this->Modified();
  }
}

int vtkVertexClusterOctree::GetNumberOfEpsilonValues() const
{
  return static_cast<int>(this->EpsilonValues.size());
}

double vtkVertexClusterOctree::GetEpsilonValue(int i) const
{
  return (i >= 0 && i < this->GetNumberOfEpsilonValues()) ? this->EpsilonValues[i] : 0.0;
}

void vtkVertexClusterOctree::AddTargetTriangleCount(vtkIdType count)
{
  this->TargetTriangleCounts.push_back(count);
  this->Modified();
}

void vtkVertexClusterOctree::RemoveAllTargetTriangleCounts()
{
  if (!this->TargetTriangleCounts.empty())
  {
    this->TargetTriangleCounts.clear();
    this->Modified();
  }
}

int vtkVertexClusterOctree::GetNumberOfTargetTriangleCounts() const
{
  return static_cast<int>(this->TargetTriangleCounts.size());
}

vtkIdType vtkVertexClusterOctree::GetTargetTriangleCount(int i) const
{
  return (i >= 0 && i < this->GetNumberOfTargetTriangleCounts()) ? this->TargetTriangleCounts[i]
                                                                 : 0;
}

double vtkVertexClusterOctree::GetLevelEpsilon(int level) const
{
  return (level >= 1 && level <= static_cast<int>(this->LevelEpsilons.size()))
    ? this->LevelEpsilons[level - 1]
    : 0.0;
}

//------------------------------------------------------------------------------
// The search meets a count within 0.2%; a level off by more than 2% of the count is reported
// with its likely cause (see the class documentation), and so is one that repeats the level
// before.
void vtkVertexClusterOctree::WarnIfCountMissed(
  int level, vtkIdType asked, vtkIdType reached, vtkIdType previous)
{
  if (std::abs(reached - asked) <= std::max<vtkIdType>(2, asked / 50))
  {
    if (reached == previous)
    {
      // Met within the tolerance, but by the very cut of the level before (small counts).
      vtkWarningMacro("Level " << level << ": asked for " << asked << " triangles, reached "
                               << reached << ", the count of level " << level - 1
                               << ": no cut of the cluster tree lies between them (counts move "
                                  "in steps of whole clusters), so the two levels are the same.");
    }
    return;
  }
  if (asked >= previous)
  {
    vtkWarningMacro("Level " << level << ": asked for " << asked
                             << " triangles, at least the " << previous << " of level "
                             << level - 1 << " (a level never refines); it has " << reached
                             << ".");
  }
  else if (reached < asked)
  {
    vtkWarningMacro("Level " << level << ": asked for " << asked << " triangles, reached "
                             << reached
                             << ": the smallest epsilon that merges enough merges more at once "
                                "(levels cut one octree, so counts move in steps of whole "
                                "clusters); a smaller MaximumCellSize keeps more.");
  }
  else
  {
    vtkWarningMacro("Level " << level << ": asked for " << asked << " triangles, reached "
                             << reached
                             << ": the epsilon search found none that keeps fewer ("
                             << (this->PreserveTopology
                                    ? "clusters that would flip triangles, pinch edges, break "
                                      "a thin part or close a handle are split again, and a "
                                      "level that still closes a handle is not taken, which on "
                                      "a rough or noisy "
                                      "surface or along thin tubes adds many triangles back: "
                                      "vtkTriangleCollapseDecimation reaches such counts and "
                                      "keeps the topology, PreserveTopology off lifts the "
                                      "repairs but lets levels fold where the surface is rough; "
                                    : "")
                             << "curves of "
                                "non-manifold edges shorten only so far, and the vertices where "
                                "they meet or end, bow ties and separate components do not "
                                "merge), or none that keeps fewer at an error near that of this "
                                "count (a level a quarter or more above its target may keep up "
                                "to a tenth more triangles than the fewest found, half more "
                                "at under a quarter of the error, or up to four times as many "
                                "at under a tenth of the error times the square root of the "
                                "count, for a smaller "
                                "epsilon).");
  }
}

//------------------------------------------------------------------------------
void vtkVertexClusterOctree::SetTextureConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkVertexClusterOctree::SetTextureData(vtkImageData* texture)
{
  this->SetInputData(1, texture);
}

vtkMultiBlockDataSet* vtkVertexClusterOctree::GetHierarchy()
{
  return vtkMultiBlockDataSet::SafeDownCast(this->GetOutputDataObject(0));
}

vtkMultiBlockDataSet* vtkVertexClusterOctree::GetTextures()
{
  return vtkMultiBlockDataSet::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkVertexClusterOctree::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return meshlod::FillSurfaceInputPortInformation(info);
}

int vtkVertexClusterOctree::FillOutputPortInformation(int, vtkInformation* info)
{
  return meshlod::FillHierarchyOutputPortInformation(info);
}

int vtkVertexClusterOctree::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->Superclass::RequestUpdateExtent(request, inputVector, outputVector);
  if (vtkInformation* textureInfo = inputVector[1]->GetInformationObject(0))
  {
    meshlod::RequestWholeInput(textureInfo);
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkVertexClusterOctree::CheckSettings()
{
  if (!meshlod::SettingsAreNumbers(this,
        { { "Epsilon", this->Epsilon }, { "EpsilonFactor", this->EpsilonFactor },
          { "MaximumCellSize", this->MaximumCellSize },
          { "BoundaryWeight", this->BoundaryWeight } }))
  {
    return false;
  }
  if (this->LevelMode == EPSILON_LIST)
  {
    if (this->EpsilonValues.empty())
    {
      vtkErrorMacro("LevelMode is EPSILON_LIST but no epsilon value was added "
                    "(AddEpsilonValue).");
      return false;
    }
    for (size_t i = 0; i < this->EpsilonValues.size(); ++i)
    {
      const double e = this->EpsilonValues[i];
      if (!std::isfinite(e) || e < 0.0 || (i > 0 && e <= this->EpsilonValues[i - 1]))
      {
        vtkErrorMacro("Epsilon value " << i << " (" << e
                                       << ") is invalid: the values must be finite, not "
                                          "negative and strictly increasing, one per level.");
        return false;
      }
    }
  }
  if (this->LevelMode == TARGET_TRIANGLE_COUNTS)
  {
    if (this->TargetTriangleCounts.empty())
    {
      vtkErrorMacro("LevelMode is TARGET_TRIANGLE_COUNTS but no count was added "
                    "(AddTargetTriangleCount).");
      return false;
    }
    for (size_t i = 0; i < this->TargetTriangleCounts.size(); ++i)
    {
      const vtkIdType n = this->TargetTriangleCounts[i];
      if (n < 1 || (i > 0 && n >= this->TargetTriangleCounts[i - 1]))
      {
        vtkErrorMacro("Target triangle count " << i << " (" << n
                                               << ") is invalid: the counts must be at least 1 "
                                                  "and strictly decreasing, one per level.");
        return false;
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
namespace
{
// Whether `level` is `previous` again: the same points, each its own target, and as many
// triangles (the octree repeats a level whose epsilon merges nothing more).
bool RepeatsLevel(const meshlod::ClusterLevel& level, const meshlod::ClusterLevel& previous)
{
  const Id points = previous.Mesh.GetNumberOfPoints();
  if (level.Mesh.GetNumberOfPoints() != points ||
    level.Mesh.GetNumberOfTriangles() != previous.Mesh.GetNumberOfTriangles() ||
    level.Target.size() != static_cast<size_t>(points))
  {
    return false;
  }
  for (Id p = 0; p < points; ++p)
  {
    if (level.Target[p] != p)
    {
      return false;
    }
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
// The levels after level 0, RequestData's second half: the octree of the input, then each
// requested level made, checked against its request and handed to the hierarchy with its
// normals, texture atlas and baked texture. (Nested in the filter so that it reads the filter's
// settings and warns in its name.)
struct vtkVertexClusterOctree::LevelMaker
{
  vtkVertexClusterOctree* Self;
  meshlod::InputMesh& In;
  meshlod::HierarchyBuilder& Builder;
  meshlod::TextureBaker& Baker;
  vtkDataArray* InputTCoords; // null when the input has none
  vtkMultiBlockDataSet* Output;
  vtkMultiBlockDataSet* Textures;

  // False when the execution was aborted: RequestData then returns at once.
  bool MakeLevels();
  // The levels LevelMode asks for (epsilons in world units).
  std::vector<LevelRequest> Requests(double unit) const;
  meshlod::OctreeClusteringOptions ClusteringOptions(double unit) const;
  // Level i + 1, for request i, with the warnings it calls for (`previousTriangles`: level
  // i's count); false when it would keep no triangle.
  bool MakeLevel(meshlod::OctreeClustering& clustering,
    const std::vector<LevelRequest>& requests,
    size_t i,
    vtkIdType previousTriangles,
    meshlod::ClusterLevel& level);
  // The texture atlas of level i + 1 (i from 0), and its points split as the atlas splits them.
  SplitMap BuildAtlas(
    const meshlod::ClusterLevel& level, size_t i, meshlod::TextureAtlas& atlas) const;
};

//------------------------------------------------------------------------------
int vtkVertexClusterOctree::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* texture = inputVector[1]->GetNumberOfInformationObjects() > 0
    ? vtkImageData::GetData(inputVector[1])
    : nullptr;
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(outputVector, 0);
  vtkMultiBlockDataSet* textures = vtkMultiBlockDataSet::GetData(outputVector, 1);
  output->Initialize();
  textures->Initialize();
  this->LevelEpsilons.clear();
  vtkPolyData* input = nullptr;
  if (!meshlod::SurfaceInput(inputVector[0], this, input))
  {
    return 0;
  }
  if (!this->CheckSettings())
  {
    return 0;
  }

  meshlod::InputMesh in;
  const meshlod::InputStatus status = meshlod::ReadInputMesh(input, this, in);
  if (status == meshlod::InputStatus::Invalid)
  {
    return 0;
  }
  if (status == meshlod::InputStatus::Empty)
  {
    // One empty level, not none: see HierarchyBuilder::SetEmptyLevelZero.
    meshlod::HierarchyBuilder empty;
    empty.SetEmptyLevelZero(input, this->OutputPointsPrecision);
    empty.Finish(output);
    if (this->BakeTexture)
    {
      textures->SetNumberOfBlocks(1); // block i for level i: level 0 has no texture to bake
    }
    return 1;
  }
  meshlod::WarnAboutReservedNames(input, this);
  // Cluster errors and their thresholds are kept in single precision (4 bytes a node): beyond
  // about 1e38 they overflow and nothing merges (every level was the input again), below 1e-38
  // they vanish. A diagonal (the unit of RelativeUnits) is held well inside that range.
  if (!meshlod::CheckInputDiagonal(in.Mesh.BoundingDiagonal(), this,
        "the cluster errors (single precision)"))
  {
    return 0;
  }

  WarnIfFinerThanOctree(in.Mesh, this);

  meshlod::TextureBaker baker;
  vtkDataArray* inputTCoords = in.Source->GetPointData()->GetTCoords();
  if (this->BakeTexture)
  {
    std::string problem;
    if (!InitializeBaker(baker, in, inputTCoords, texture, this->ColorArrayName, problem))
    {
      vtkErrorMacro("BakeTexture is on but "
        << problem
        << ". Connect a texture, name a colour "
           "array (SetColorArrayName) or turn BakeTexture off.");
      return 0;
    }
  }

  meshlod::HierarchyBuilder builder;
  builder.SetLevelZero(in, this->OutputPointsPrecision);
  // The source ids were only needed for level 0.
  meshlod::Release(in.SourcePointIds);
  meshlod::Release(in.SourceCellIds);
  if (this->BakeTexture)
  {
    textures->SetBlock(0, texture && inputTCoords ? texture : nullptr);
    if (texture && inputTCoords)
    {
      MarkAtlasLevel(builder.GetLevel(0), 0);
    }
  }
  this->UpdateProgress(0.1);

  LevelMaker levels{ this, in, builder, baker, inputTCoords, output, textures };
  if (!levels.MakeLevels())
  {
    return 1;
  }

  if (this->MeasureLevelErrors)
  {
    builder.MeasureLevelErrors();
  }
  builder.Finish(output);
  if (this->BakeTexture)
  {
    NameTextureBlocks(textures);
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkVertexClusterOctree::LevelMaker::MakeLevels()
{
  vtkVertexClusterOctree* self = this->Self;
  meshlod::InputMesh& in = this->In;
  meshlod::HierarchyBuilder& builder = this->Builder;
  const double unit = self->RelativeUnits ? in.Mesh.BoundingDiagonal() : 1.0;
  const std::vector<LevelRequest> requests = this->Requests(unit);
  const meshlod::OctreeClusteringOptions options = this->ClusteringOptions(unit);
  // A mesh whose ids are scattered is clustered renumbered in space (SpatialOrder.h; level 0 is
  // built already, the baker reads the input itself), and each level is numbered back when it
  // is handed over, after its flips (which read the clustering's own ids).
  meshlod::SpatialRenumbering order;
  order.ApplyIfScattered(in.Mesh, in.Topology);
  // The clustering asks the topology only which edges are boundaries.
  in.Topology.KeepBoundaryFlagsOnly();
  meshlod::OctreeClustering clustering(in.Mesh, in.Topology, options);
  clustering.BuildTree();
  self->UpdateProgress(0.4);
  if (self->GetAbortExecute())
  {
    return false;
  }

  vtkDataArray* inputNormals = in.Source->GetPointData()->GetNormals();
  const std::string normalsName =
    inputNormals && inputNormals->GetName() ? inputNormals->GetName() : "Normals";
  vtkDataArray* inputTCoords = this->InputTCoords;
  const std::string tcoordsName =
    inputTCoords && inputTCoords->GetName() ? inputTCoords->GetName() : "TCoords";
  // An input array that is not the attribute but has the name the new one gets is replaced.
  const struct
  {
    bool Made;
    const std::string& Name;
    vtkAbstractArray* Attribute;
  } madeArrays[] = { { self->ComputeNormals, normalsName, inputNormals },
    { self->BakeTexture, tcoordsName, inputTCoords } };
  for (const auto& made : madeArrays)
  {
    vtkAbstractArray* same = in.Source->GetPointData()->GetAbstractArray(made.Name.c_str());
    if (made.Made && same != nullptr && same != made.Attribute)
    {
      vtkWarningWithObjectMacro(self,
        "The input's point-data array \"" << made.Name
                                          << "\" is replaced on the simplified levels by the "
                                             "new one of that name; rename it to keep it.");
    }
  }
  meshlod::LevelCentering centering;
  std::vector<double> levelZeroPoints; // only if its points are neither float nor double
  meshlod::LevelZeroCorrespondence levelZero;
  if (self->CenterOnInput)
  {
    levelZero.Reset(builder.GetLevelZeroView(levelZeroPoints));
    centering.SetLevelZero(levelZero);
  }
  SplitMap previous;
  Id previousPoints = in.Mesh.GetNumberOfPoints();
  // Level i + 1 (request i) centred, given its normals and texture and handed to the hierarchy;
  // false when the execution was aborted.
  auto emit = [&](meshlod::ClusterLevel& level, size_t i) -> bool
  {
    order.NumberBack(level.LevelZeroTriangle, level.SourceParents, level.Target, level.Rank);
    if (self->CenterOnInput)
    {
      levelZero.Advance(level.Target);
      centering.Apply(level.Mesh, level.SourceOffsets, level.SourceParents, level.SourceWeights);
    }
    meshlod::TextureAtlas atlas;
    SplitMap split;
    if (self->BakeTexture)
    {
      split = this->BuildAtlas(level, i, atlas);
    }
    const std::vector<float> normals =
      self->ComputeNormals ? PointNormals(level.Mesh) : std::vector<float>();
    builder.AppendLevel(
      ToLevelData(level, previous, previousPoints, split, self->BakeTexture ? &atlas : nullptr));
    vtkPolyData* poly = builder.GetLevel(builder.GetNumberOfLevels() - 1);

    if (self->ComputeNormals)
    {
      SetLevelNormals(poly, normalsName, normals, split);
    }
    if (self->BakeTexture)
    {
      SetLevelTCoords(poly, tcoordsName, level.Mesh, atlas);
      // The baking reports the second half of this level's share of the progress.
      const double half = 0.25 / requests.size();
      const double start = 0.4 + half * (2 * i + 1);
      vtkSmartPointer<vtkImageData> texture = this->Baker.Bake(level.Mesh, atlas,
        [&](double fraction)
        {
          self->UpdateProgress(start + half * fraction);
          return !self->GetAbortExecute();
        });
      if (texture == nullptr)
      {
        this->Output->Initialize();
        this->Textures->Initialize();
        return false;
      }
      this->Textures->SetBlock(static_cast<unsigned int>(i + 1), texture);
      MarkAtlasLevel(poly, static_cast<int>(i + 1));
    }

    previousPoints = static_cast<Id>(poly->GetNumberOfPoints());
    previous = std::move(split);
    self->UpdateProgress(0.4 + 0.5 * (i + 1) / requests.size());
    if (self->GetAbortExecute())
    {
      this->Output->Initialize();
      this->Textures->Initialize();
      return false;
    }
    return true;
  };
  // With FlipEdges a level waits for the next one before it is flipped and handed over: a flip
  // is refused where the next level would merge its two triangles into one triangle twice
  // (OctreeClustering::FlipEdges), which only the next level's clusters tell. A level that
  // repeats the one before (an epsilon that merges nothing more) waits with it, so that all of
  // them get the same flips, those the next different level allows (no jump between them).
  std::vector<std::pair<meshlod::ClusterLevel, size_t>> waiting; // level, request
  const auto handOver = [&](const meshlod::ClusterLevel* next) -> bool
  {
    for (auto& held : waiting)
    {
      clustering.FlipEdges(held.first, next);
      if (!emit(held.first, held.second))
      {
        return false;
      }
    }
    waiting.clear();
    return true;
  };
  vtkIdType previousTriangles = builder.GetLevel(0)->GetNumberOfPolys();
  for (size_t i = 0; i < requests.size(); ++i)
  {
    meshlod::ClusterLevel level;
    if (!this->MakeLevel(clustering, requests, i, previousTriangles, level))
    {
      break;
    }
    previousTriangles = static_cast<vtkIdType>(level.Mesh.GetNumberOfTriangles());
    if (!self->FlipEdges)
    {
      if (!emit(level, i))
      {
        return false;
      }
      continue;
    }
    if (!waiting.empty() && !RepeatsLevel(level, waiting.back().first) && !handOver(&level))
    {
      return false;
    }
    waiting.emplace_back(std::move(level), i);
  }
  return handOver(nullptr);
}

//------------------------------------------------------------------------------
std::vector<LevelRequest> vtkVertexClusterOctree::LevelMaker::Requests(double unit) const
{
  const vtkVertexClusterOctree* self = this->Self;
  std::vector<LevelRequest> requests;
  // An epsilon that overflows (Epsilon * EpsilonFactor^i * diagonal past the largest double)
  // is the largest double: an infinite one would also merge the nodes refused or over a limit,
  // whose threshold is infinite (a sphere kept at 12 triangles by every finite epsilon
  // vanished, and MaximumPointsPerCell 1 merged points).
  auto finite = [](double epsilon)
  { return std::min(epsilon, std::numeric_limits<double>::max()); };
  switch (self->LevelMode)
  {
    case EPSILON_LIST:
      for (const double e : self->EpsilonValues)
      {
        requests.push_back({ false, finite(e * unit), 0 });
      }
      break;
    case TARGET_TRIANGLE_COUNTS:
      for (const vtkIdType n : self->TargetTriangleCounts)
      {
        requests.push_back({ true, 0.0, n });
      }
      break;
    default:
      for (int i = 0; i < self->NumberOfLevels; ++i)
      {
        const double epsilon = self->Epsilon * std::pow(self->EpsilonFactor, i) * unit;
        // (Multiplied in this order, a product may overflow on the way though it does not.)
        requests.push_back({ false,
          finite(std::isinf(epsilon) ? self->Epsilon * unit * std::pow(self->EpsilonFactor, i)
                                     : epsilon),
          0 });
      }
  }
  return requests;
}

//------------------------------------------------------------------------------
meshlod::OctreeClusteringOptions vtkVertexClusterOctree::LevelMaker::ClusteringOptions(
  double unit) const
{
  const vtkVertexClusterOctree* self = this->Self;
  meshlod::OctreeClusteringOptions options;
  options.MaximumCellSize = self->MaximumCellSize * unit;
  options.MaximumPointsPerCell = self->MaximumPointsPerCell;
  options.RepresentativeIterations = self->RepresentativeIterations;
  options.PreserveTopology = self->PreserveTopology;
  options.BoundaryWeight = self->BoundaryWeight;
  options.OrderFlatClusters = self->LevelMode == TARGET_TRIANGLE_COUNTS;
  return options;
}

//------------------------------------------------------------------------------
bool vtkVertexClusterOctree::LevelMaker::MakeLevel(meshlod::OctreeClustering& clustering,
  const std::vector<LevelRequest>& requests,
  size_t i,
  vtkIdType previousTriangles,
  meshlod::ClusterLevel& level)
{
  vtkVertexClusterOctree* self = this->Self;
  // (A count above the input's asks for no change; clamped so that it fits the core's ids.)
  const Id count =
    static_cast<Id>(std::min<vtkIdType>(requests[i].Count, this->In.Mesh.GetNumberOfTriangles()));
  const bool made = requests[i].ByCount ? clustering.MakeLevelForTriangleCount(count, level)
                                        : clustering.MakeLevel(requests[i].Epsilon, level);
  if (!made)
  {
    vtkWarningWithObjectMacro(self,
      "Level " << i + 1 << " would keep no triangle; the hierarchy stops at level " << i << ".");
    return false;
  }
  // (An epsilon below the previous level's is raised to it.)
  const double asked = std::max(
    requests[i].Epsilon, self->LevelEpsilons.empty() ? 0.0 : self->LevelEpsilons.back());
  self->LevelEpsilons.push_back(level.Epsilon);
  if (requests[i].ByCount)
  {
    self->WarnIfCountMissed(static_cast<int>(i + 1), requests[i].Count,
      static_cast<vtkIdType>(level.Mesh.GetNumberOfTriangles()), previousTriangles);
  }
  else if (level.Epsilon < asked)
  {
    vtkWarningWithObjectMacro(self,
      "Level " << i + 1 << ": epsilon " << requests[i].Epsilon
               << " (in world units) closes a handle of the surface (its genus would change); "
                  "the level is cut at epsilon "
               << level.Epsilon << ", the largest found that keeps every handle.");
  }
  else if (static_cast<vtkIdType>(level.Mesh.GetNumberOfTriangles()) == previousTriangles)
  {
    // Kept (level i answers epsilon i), but said: a repeated level is rarely what was meant.
    vtkWarningWithObjectMacro(self,
      "Level " << i + 1 << " keeps the " << previousTriangles << " triangles of level " << i
               << ": its epsilon (" << requests[i].Epsilon
               << " in world units) merges nothing more: a larger EpsilonFactor or larger "
                  "epsilon values give coarser levels, unless nothing left may merge (with "
                  "PreserveTopology on a closed piece keeps at least a tetrahedron and vanishes "
                  "only within twice the epsilon of the level's other triangles; locked "
                  "non-manifold vertices never merge).");
  }
  return true;
}

//------------------------------------------------------------------------------
SplitMap vtkVertexClusterOctree::LevelMaker::BuildAtlas(
  const meshlod::ClusterLevel& level, size_t i, meshlod::TextureAtlas& atlas) const
{
  const vtkVertexClusterOctree* self = this->Self;
  meshlod::BuildTextureAtlas(level.Mesh, self->TextureResolution, atlas);
  if (atlas.Resolution > atlas.RequestedResolution)
  {
    vtkWarningWithObjectMacro(self,
      "Level " << i + 1 << " has " << level.Mesh.GetNumberOfTriangles()
               << " triangles, too many for a " << atlas.RequestedResolution
               << "^2 texture; its texture has " << atlas.Resolution << "^2 texels.");
  }
  SplitMap split;
  split.SplitToPoint = atlas.SplitPoints;
  split.FirstSplit.assign(level.Mesh.GetNumberOfPoints(), InvalidId);
  for (Id q = static_cast<Id>(atlas.SplitPoints.size()) - 1; q >= 0; --q)
  {
    split.FirstSplit[atlas.SplitPoints[q]] = q;
  }
  return split;
}

//------------------------------------------------------------------------------
void vtkVertexClusterOctree::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* const modes[] = { "GeometricEpsilon", "EpsilonList", "TargetTriangleCounts" };
  os << indent << "LevelMode: " << modes[this->LevelMode] << "\n";
  os << indent << "NumberOfLevels: " << this->NumberOfLevels << "\n";
  os << indent << "Epsilon: " << this->Epsilon << "\n";
  os << indent << "EpsilonFactor: " << this->EpsilonFactor << "\n";
  os << indent << "EpsilonValues:";
  for (const double e : this->EpsilonValues)
  {
    os << " " << e;
  }
  os << "\n" << indent << "TargetTriangleCounts:";
  for (const vtkIdType n : this->TargetTriangleCounts)
  {
    os << " " << n;
  }
  os << "\n";
  os << indent << "RelativeUnits: " << (this->RelativeUnits ? "On" : "Off") << "\n";
  os << indent << "MaximumCellSize: " << this->MaximumCellSize << "\n";
  os << indent << "MaximumPointsPerCell: " << this->MaximumPointsPerCell << "\n";
  os << indent << "RepresentativeIterations: " << this->RepresentativeIterations << "\n";
  os << indent << "PreserveTopology: " << (this->PreserveTopology ? "On" : "Off") << "\n";
  os << indent << "FlipEdges: " << (this->FlipEdges ? "On" : "Off") << "\n";
  os << indent << "CenterOnInput: " << (this->CenterOnInput ? "On" : "Off") << "\n";
  os << indent << "BoundaryWeight: " << this->BoundaryWeight << "\n";
  os << indent << "ComputeNormals: " << (this->ComputeNormals ? "On" : "Off") << "\n";
  os << indent << "MeasureLevelErrors: " << (this->MeasureLevelErrors ? "On" : "Off") << "\n";
  os << indent << "OutputPointsPrecision: " << meshlod::PrecisionName(this->OutputPointsPrecision)
     << "\n";
  os << indent << "BakeTexture: " << (this->BakeTexture ? "On" : "Off") << "\n";
  os << indent << "TextureResolution: " << this->TextureResolution << "\n";
  os << indent << "ColorArrayName: " << (this->ColorArrayName ? this->ColorArrayName : "(none)")
     << "\n";
}
