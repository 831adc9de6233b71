// Input validation of the data arrays (see MeshLODInputMesh.h for the whole policy).
#ifndef MeshLODInputArrays_h
#define MeshLODInputArrays_h

#include "Core/TriangleMesh.h"
#include "vtkSmartPointer.h"

#include <vector>

class vtkAbstractArray;
class vtkAlgorithm;
class vtkDataArray;
class vtkPointData;
class vtkPolyData;

namespace meshlod
{
/// The input itself when every point-data array has one tuple per point and every cell-data
/// array one per cell; otherwise a shallow copy without the arrays that do not (reading past
/// their end would give garbage), with a warning naming them.
vtkSmartPointer<vtkPolyData> DropMismatchedArrays(vtkPolyData* input, vtkAlgorithm* caller);

/// Whether points id `a` and `b` carry the same point data: every array but the global and pedigree
/// ids (twins differ there by construction), each component within 1e-6 of its range (exact for
/// integers in practice), equal values for strings and variants. Coincident points whose data
/// differ are an attribute seam (a cube's split normals, a texture's wrap): merging them would lose
/// it.
class PointDataAgreement
{
public:
  explicit PointDataAgreement(vtkPointData* pointData)
    : PointData(pointData)
  {
  }
  bool operator()(Id a, Id b) const;

private:
  // The arrays and their tolerances, found at the first comparison: most inputs have no
  // coincident boundary points, and the ranges cost a pass over every array.
  void Prepare() const;
  vtkPointData* PointData;
  mutable bool Prepared = false;
  mutable std::vector<vtkDataArray*> Arrays;
  mutable std::vector<double> Tolerances; // per array, per component
  mutable std::vector<vtkAbstractArray*> Others; // arrays of strings or variants
};

} // namespace meshlod

#endif
