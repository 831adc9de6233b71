// Private to vtkLODGeomorph: what the filter keeps between executions (per-level caches, the
// exact-count topology) and how it produces each kind of output mesh. The VTK class itself
// (settings, pipeline passes) is vtkLODGeomorph.cxx.
#ifndef MeshLODGeomorphInternals_h
#define MeshLODGeomorphInternals_h

#include "vtkLODGeomorph.h"

#include "Core/CollapseSchedule.h"
#include "Core/EdgeMerge.h"
#include "MeshLODBlend.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkMultiBlockDataSet;

namespace meshlod
{
namespace geomorph
{
// The merged topology of the nearest-vertex mode, for one set of short edges.
struct MergedTopology
{
  std::vector<std::uint8_t> ShortEdges;
  std::vector<Id> Source; // output point -> level point
  vtkSmartPointer<vtkCellArray> Cells;
  vtkSmartPointer<vtkCellData> CellData;
  double WarnedTolerance = -1.0; // the MergeTolerance last warned about as too large
};

// Everything the filter keeps about one level between executions (valid while the input is
// unchanged). Built lazily: only the levels and modes actually asked for pay.
struct LevelCache
{
  vtkPolyData* Poly = nullptr; // the input's block, or Checked
  // A shallow copy of the block without the data arrays whose tuple count is not its number of
  // points or cells (a geomorph would read past their end); null when it has none.
  vtkSmartPointer<vtkPolyData> Checked;
  std::vector<Id> TargetIds; // MorphTargetId, with morph data
  // With morph data: the next level's point data at this level's points (each point's values
  // where it goes, gathered once), so that every frame blends two arrays row by row instead of
  // gathering from the next level at random. Kept for the level last blended only.
  vtkSmartPointer<vtkPointData> TargetData;

  // Triangles of the level (exact count, nearest vertices, dropping degenerate triangles).
  bool TrianglesRead = false;
  bool AllTriangles = false;
  std::vector<Id> Triangles;

  // The next level's edge flips against the images of this level's triangles (a hierarchy
  // made with FlipEdges; MeshLODGeomorphFlips.cxx): per lone flipped quad, a, b, c, d (the
  // old diagonal (a, b), the new (c, d)) and the next level's triangles (c, a, d), (d, b, c).
  bool FlipsFound = false;
  std::vector<Id> FlipQuads;
  // The morph's triangles and their cell data (the same at every fraction), built at its first
  // frame.
  vtkSmartPointer<vtkCellArray> FlipCells;
  vtkSmartPointer<vtkCellData> FlipCellData;

  std::unique_ptr<meshlod::CollapseSchedule> Schedule; // exact count
  // Level point -> schedule point, for a level split per texture square (its copies of a point
  // welded into one); empty when the schedule's points are the level's.
  std::vector<Id> ScheduleIds;

  bool HasCorrespondence = false; // nearest vertices: this level -> the next one
  std::vector<Id> Partner;
  meshlod::EdgeList Edges;
  double Diagonal = 0.0;
  MergedTopology Merged;
};

// The latest exact-count topology, reused while only CollapseFraction changes.
struct ExactTopology
{
  int Level = -1;
  Id Steps = -1;
  std::vector<Id> Source;          // output point -> level point
  std::vector<std::uint8_t> State; // per output point: 0 still, 1 next collapse, 2 settled
  vtkSmartPointer<vtkCellArray> Cells;
  vtkSmartPointer<vtkCellData> CellData;
};


/// Latest modification time over the hierarchy and its levels (their points, cells, arrays).
vtkMTimeType HierarchyTime(vtkMultiBlockDataSet* input);

/// The level's polygons as triangles; false when a cell is not a triangle or the level has
/// vertices, lines or strips.
bool ReadTriangles(vtkPolyData* poly, std::vector<Id>& triangles);
} // namespace geomorph
} // namespace meshlod

struct vtkLODGeomorph::Internals
{
  // The output arrays of the last update, reused by the next one once the output lets go of
  // them (see meshlod::ArrayPool).
  meshlod::ArrayPool Pool;

  // What the caches were built for.
  vtkMultiBlockDataSet* Input = nullptr;
  vtkMTimeType InputTime = 0;
  int RequestedCorrespondence = -1;
  std::string Problem; // empty when the input is a valid hierarchy

  int Mode = MORPH_ARRAYS; // resolved correspondence
  std::vector<meshlod::geomorph::LevelCache> Levels;
  meshlod::geomorph::ExactTopology Exact;

  std::string Prepare(vtkMultiBlockDataSet* input, int requested, vtkLODGeomorph* self);
  bool EnsureTriangles(vtkLODGeomorph* self, int level, const char* purpose);
  bool EnsureSchedule(vtkLODGeomorph* self, int level);
  bool EnsureCorrespondence(vtkLODGeomorph* self, int level);

  // LevelCache::TargetData of the level, gathered on first use (and dropped for every other
  // level: one level's worth of memory).
  vtkPointData* TargetData(int level);
  void ProduceLevel(int level, vtkPolyData* output);
  bool ProducePartialCollapse(vtkLODGeomorph* self, int level, double t, vtkPolyData* output);
  // Whether level + 1 has lone flipped quads against the images of level's triangles (found
  // once); the morph across them at fraction t (MeshLODGeomorphFlips.cxx).
  bool EnsureFlips(int level);
  void BuildFlipCells(int level);
  void ProduceFlipMorph(int level, double t, vtkPolyData* output);
  bool ProduceNearestBlend(vtkLODGeomorph* self, int level, double t, vtkPolyData* output);
  bool ProduceExactCount(
    vtkLODGeomorph* self, vtkIdType count, double fraction, vtkPolyData* output, double& lod);
  // ProduceExactCount's and ProduceNearestBlend's steps (MeshLODGeomorphInternals.cxx).
  bool ProduceWholeLevelFor(vtkLODGeomorph* self, vtkIdType count, double fraction,
    vtkPolyData* output, double& lod, int& level);
  void ProduceSteps(
    int level, meshlod::Id steps, meshlod::Id nextStep, double fraction, vtkPolyData* output);
  void MergeShortEdges(vtkLODGeomorph* self, int level, std::vector<std::uint8_t>& shortEdge);
  void BuildExactTopology(int level, meshlod::Id steps, meshlod::Id nextStep);
  void WarnIfMergedTooFar(vtkLODGeomorph* self, int level);
};

#endif
