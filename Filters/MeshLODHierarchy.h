// The LOD hierarchy output shared by vtkTriangleCollapseDecimation and vtkVertexClusterOctree,
// and read by vtkLODGeomorph.
//
// Layout: a vtkMultiBlockDataSet, block i = level i as vtkPolyData named "Level i"; block 0 is
// the validated input, each next level has fewer triangles. Every level carries:
// - point data: every input point-data array. Floating-point arrays are interpolated with the
//   weights the algorithm gives (e.g. barycentric at a collapse point, or a cluster average);
//   integer arrays (ids, labels, categories) are not interpolated: they take the value of the
//   parent with the largest weight. A 3-component array that is the point data's Normals
//   attribute is renormalised after interpolation.
// - cell data: the input's cell data of the level-0 triangle each triangle descends from
//   (triangles keep their identity through collapses and re-indexing).
// - field data: LevelIndex (int), NumberOfTriangles (vtkIdType), EstimatedError (double, the
//   algorithm's own estimate in world units), and, when measured, MeasuredHausdorff and
//   MeasuredRMS (double, world units, surface distance to level 0 by MeshLODSurfaceDistance);
//   plus the input's field-data arrays, shared, except those named like the level arrays
//   above or TextureAtlasLevel (left out even where the level has none).
// Every level except the coarsest also carries the correspondence to the next level:
// - MorphTargetId (32-bit int): the point of level i+1 this point becomes. Chaining it maps any
//   point of level 0 to its point in any coarser level.
// - MorphTarget (3 components, the points' type): the position of that point.
// - CollapseRank (32-bit int): the order in which the point moves when only part of the
//   transition i -> i+1 is applied (points sharing a rank move together, as one collapse);
//   -1 when the point keeps its position and merges with nothing.
#ifndef MeshLODHierarchy_h
#define MeshLODHierarchy_h

#include "Core/LevelZeroView.h"
#include "Core/LevelData.h"
#include "vtkFiltersMeshLODModule.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkFieldData;
class vtkInformation;
class vtkMultiBlockDataSet;
class vtkObject;
class vtkPolyData;

namespace meshlod
{
struct InputMesh;

/// Names of the arrays and blocks of a hierarchy, in one place.
namespace names
{
constexpr const char* MorphTarget = "MorphTarget";
constexpr const char* MorphTargetId = "MorphTargetId";
constexpr const char* CollapseRank = "CollapseRank";
constexpr const char* LevelIndex = "LevelIndex";
constexpr const char* NumberOfTriangles = "NumberOfTriangles";
constexpr const char* EstimatedError = "EstimatedError";
constexpr const char* MeasuredHausdorff = "MeasuredHausdorff";
constexpr const char* MeasuredRMS = "MeasuredRMS";
// Field data of a level whose TCoords address a texture of its own (vtkVertexClusterOctree's
// baked atlases): the index of that texture. Such coordinates mean nothing on another level's
// texture, so a geomorph never blends them.
constexpr const char* TextureAtlasLevel = "TextureAtlasLevel";
} // namespace names

VTKFILTERSMESHLOD_EXPORT std::string LevelBlockName(int level);

/// Whether `name` is one of the field-data arrays the layout gives each level (LevelIndex,
/// NumberOfTriangles, EstimatedError, MeasuredHausdorff, MeasuredRMS, TextureAtlasLevel): what
/// describes that level only, as opposed to the input's field data every level carries.
VTKFILTERSMESHLOD_EXPORT bool IsLevelFieldName(const char* name);

/// Adds to `to` the arrays of `from`, shared, but those IsLevelFieldName names and those whose
/// name `to` already has (unnamed arrays too: no name to clash with): the input's metadata, which
/// every level and a geomorph's output carry as VTK filters pass field data on.
VTKFILTERSMESHLOD_EXPORT void PassMetadata(vtkFieldData* from, vtkFieldData* to);

/// Warn on `caller` when the input has point-data arrays named like the hierarchy's own
/// (MorphTarget, MorphTargetId, CollapseRank): the levels carry the filter's arrays under those
/// names instead.
VTKFILTERSMESHLOD_EXPORT void WarnAboutReservedNames(vtkPolyData* input, vtkObject* caller);

/// Builds the output multiblock level by level, so that the algorithm can free its own copy of
/// a level as soon as it is handed over.
class VTKFILTERSMESHLOD_EXPORT HierarchyBuilder
{
public:
  HierarchyBuilder();
  ~HierarchyBuilder();
  HierarchyBuilder(const HierarchyBuilder&) = delete;
  HierarchyBuilder& operator=(const HierarchyBuilder&) = delete;

  /// Level 0 from the validated input. Shares the input's points, cells and arrays when the
  /// input needed no cleaning. `precision` (vtkAlgorithm::DesiredOutputPrecision) is the type
  /// of every level's points: DEFAULT_PRECISION the input's when it is float or double (else
  /// double), SINGLE_PRECISION float, DOUBLE_PRECISION double.
  void SetLevelZero(const InputMesh& input, int precision);

  /// Level 0 of an empty input (no points or no polygons): no points and no cells, the
  /// input's point- and cell-data arrays without tuples, and the level field data. The
  /// hierarchy of an empty input is this one level, so that a downstream vtkLODGeomorph
  /// produces an empty mesh too instead of reporting a hierarchy without levels.
  void SetEmptyLevelZero(vtkPolyData* input, int precision);

  /// Append the next level: builds its polydata and adds the morph arrays to the level before.
  /// Consumes `level`: each of its arrays is released once converted, so that a level's plain
  /// arrays and its VTK arrays are not all alive at the peak of memory.
  void AppendLevel(LevelData&& level);

  /// Level 0's points and triangles, to be read in place (LevelCentering, LevelEdgeFlips): its
  /// points are copied into `copy` when they are neither float nor double.
  LevelZeroView GetLevelZeroView(std::vector<double>& copy) const;

  /// Number of levels so far (level 0 included).
  int GetNumberOfLevels() const;
  vtkPolyData* GetLevel(int level) const;

  /// Measure every level against level 0 with MeshLODSurfaceDistance (LevelErrorSamples area
  /// samples per surface, as many vertices at most) and store MeasuredHausdorff / MeasuredRMS in
  /// the levels' field data.
  void MeasureLevelErrors();
  static constexpr std::int64_t LevelErrorSamples = 10000;

  /// Move the levels into `output` (cleared first), block i named "Level i".
  void Finish(vtkMultiBlockDataSet* output);

private:
  struct Internals;
  Internals* Impl;
};

/// Port information for a filter whose output port 0 is a hierarchy.
VTKFILTERSMESHLOD_EXPORT int FillHierarchyOutputPortInformation(vtkInformation* info);

/// Checks a hierarchy has the layout above (for vtkLODGeomorph and the tests): returns an empty
/// string when it does, otherwise what is wrong.
VTKFILTERSMESHLOD_EXPORT std::string CheckHierarchyLayout(
  vtkMultiBlockDataSet* hierarchy, bool requireMorphData);

} // namespace meshlod

#endif
