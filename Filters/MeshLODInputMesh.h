// Input validation shared by every MeshLOD filter: a vtkPolyData in, a clean core
// TriangleMesh out, plus the bookkeeping to carry point and cell data back to VTK.
//
// Policy (documented in every filter's class comment):
// - No points or no polygons/strips: "empty", the filter produces an empty output, no error.
// - Polygons with more than three points and triangle strips are triangulated with
//   vtkTriangleFilter (cell data is copied to each resulting triangle; the GlobalIds attribute
//   as a plain array of that name, since the triangles of one cell share its id).
// - Vertices and lines are ignored, with a warning.
// - NaN or infinite coordinates of a point a triangle uses: an error naming the first such
//   point, no output (an unused point, finite or not, is dropped like any unused point).
// - A point id outside [0, number of points) in a polygon or strip: an error naming the cell,
//   no output.
// - Point- or cell-data arrays whose tuple count is not the number of points or cells are
//   ignored, with a warning naming them (reading past their end would give garbage).
// - More than 2^31 - 1 points or triangles: an error (the core uses 32-bit ids).
// - A bounding-box diagonal above 1e30, or above 0 and below 1e-30: an error from the filters
//   that square lengths (CheckInputDiagonal). A diagonal of exactly 0 (all points at one place)
//   is no error: nothing there is squared out of range.
// - Triangles that repeat a point id are dropped; a triangle with the same three points as an
//   earlier one is dropped (both with a warning giving the count).
// - Points on boundary or non-manifold edges that coincide up to rounding (at most 1e-12 of the
//   bounding diagonal apart, or 64 double-precision epsilons of the largest coordinate) and carry
//   the same point data (MeshLODInputArrays.h) are merged: this stitches triangle soups such as
//   STL files and seams duplicated by rounding (as parametric sources make them). Coincident
//   points inside
//   closed manifold regions are left alone: merging them would create a non-manifold vertex.
//   Coincident points whose point data differ are an attribute seam and stay apart (warning):
//   the sides of the seam then simplify separately, as with vtkQuadricDecimation; running
//   vtkCleanPolyData first joins them (it merges coincident points whatever their data).
//   Points used by no triangle are dropped.
// - Triangles whose orientation disagrees with their part's (the triangles joined by manifold
//   edges) are flipped, each orientable part keeping the orientation most of its triangles had
//   (with a warning giving the count); a non-orientable part is left as it is.
// - Non-manifold edges (more than two triangles) and vertices (several fans) are kept and
//   reported in the topology; the algorithms lock them (they never move or merge).
// - Composite data (a multiblock of surfaces) is an error naming what to do instead
//   (SurfaceInput). Integer points are read as numbers; every level's points are double
//   (HierarchyBuilder), float and double inputs keep their type.
#ifndef MeshLODInputMesh_h
#define MeshLODInputMesh_h

#include "Core/TriangleMesh.h"
#include "vtkFiltersMeshLODModule.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <vector>

class vtkAbstractArray;
class vtkAlgorithm;
class vtkCellArray;
class vtkInformation;
class vtkInformationVector;
class vtkPolyData;

namespace meshlod
{
struct VTKFILTERSMESHLOD_EXPORT InputMesh
{
  TriangleMesh Mesh;
  TriangleTopology Topology;
  /// The polydata whose point and cell data the ids below refer to: the input itself, or its
  /// triangulated copy.
  vtkSmartPointer<vtkPolyData> Source;
  std::vector<vtkIdType> SourcePointIds; // core vertex -> point of Source
  std::vector<vtkIdType> SourceCellIds;  // core triangle -> cell of Source
  /// True when the core mesh is exactly the input's polys: same point ids, same triangles in
  /// the same order, every point used. Level 0 can then share the input's arrays.
  bool SameAsInput = false;

  vtkIdType IgnoredVerts = 0;
  vtkIdType IgnoredLines = 0;
  vtkIdType MergedPoints = 0;
  vtkIdType DegenerateTriangles = 0;
  vtkIdType DuplicateTriangles = 0;
  vtkIdType FlippedTriangles = 0; // re-oriented for a consistent orientation
  vtkIdType UnusedPoints = 0;
};

enum class InputStatus
{
  Valid,
  Empty,
  Invalid,
};

/// Input port 0 of the hierarchy filters: a vtkPolyData, and composite data too, so that the
/// filter sees it and says what to do (SurfaceInput) instead of the pipeline running it block by
/// block, which nested hierarchies inside a hierarchy.
VTKFILTERSMESHLOD_EXPORT int FillSurfaceInputPortInformation(vtkInformation* info);

/// In RequestUpdateExtent, for an input the filter needs whole whatever piece it is asked for
/// (vtkVertexClusterOctree's texture, vtkLODGeomorph's hierarchy): piece 0 of 1, no ghost
/// levels, the whole extent of structured data. Otherwise the piece request reaches it (an image
/// source then makes part of the texture; an image filter upstream can crash on it, a reader of
/// a saved hierarchy hands out some of its blocks).
VTKFILTERSMESHLOD_EXPORT void RequestWholeInput(vtkInformation* inputInfo);

/// The vtkPolyData on `port`, or nullptr; false, with an error on `caller`, when it is composite
/// data (a multiblock of surfaces: one filter simplifies one surface).
VTKFILTERSMESHLOD_EXPORT bool SurfaceInput(
  vtkInformationVector* port, vtkAlgorithm* caller, vtkPolyData*& input);

/// Validate and convert. Errors and warnings are reported on `caller` (its observers see them
/// like any VTK error); on Invalid the caller must produce no output.
VTKFILTERSMESHLOD_EXPORT InputStatus ReadInputMesh(
  vtkPolyData* input, vtkAlgorithm* caller, InputMesh& result);

/// The first cell of `cells` (may be null) whose offsets break vtkCellArray's layout (offsets
/// from 0 to the connectivity's size, never decreasing), or -1. Check it before anything reads
/// the cells.
VTKFILTERSMESHLOD_EXPORT vtkIdType FirstCellWithBadOffset(vtkCellArray* cells);

/// The first cell of `cells` (may be null) that refers to a point id outside
/// [0, numberOfPoints), or -1. Every id is read (a data array's cached range can miss values
/// edited in place).
VTKFILTERSMESHLOD_EXPORT vtkIdType FirstCellWithBadId(
  vtkCellArray* cells, vtkIdType numberOfPoints);

/// The bounding-box diagonals the filters accept. Their collapse costs and cluster errors hold
/// squared areas (and the octree's single-precision thresholds): outside this range they
/// overflow or vanish, and the levels came out silently wrong (a sphere scaled by 1e200 or
/// 1e-200 got another collapse order and a measured error of 1e-51 times its own).
constexpr double MinimumInputDiagonal = 1e-30;
constexpr double MaximumInputDiagonal = 1e30;

/// Whether `diagonal` (0 for a single point) is in range; when not, an error on `caller`
/// naming the range and what does not hold outside it (`what`).
VTKFILTERSMESHLOD_EXPORT bool CheckInputDiagonal(
  double diagonal, vtkAlgorithm* caller, const char* what);

/// Prepare the memory of a freshly sized array (standard memory layout) that the caller is about
/// to write in full, as Core/FreshMemory.h describes; other arrays are left alone.
VTKFILTERSMESHLOD_EXPORT void PrepareForWriting(vtkAbstractArray* array);

/// Triangles as a vtkCellArray built in one go (32-bit storage, which halves its memory).
VTKFILTERSMESHLOD_EXPORT vtkSmartPointer<vtkCellArray> MakeTriangleCells(
  const Id* triangles, Id numberOfTriangles);

/// f(offsets, connectivity) on the cell array's typed arrays, whichever storage (32 or 64 bits)
/// it has (include vtkCellArray.h to use it).
template <typename CellArray, typename F>
auto WithCellStorage(CellArray* cells, F&& f)
{
  return cells->IsStorage64Bit()
    ? f(cells->GetOffsetsArray64(), cells->GetConnectivityArray64())
    : f(cells->GetOffsetsArray32(), cells->GetConnectivityArray32());
}

} // namespace meshlod

#endif
