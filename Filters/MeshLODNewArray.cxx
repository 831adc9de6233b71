#include "MeshLODNewArray.h"

#include "vtkAbstractArray.h"
#include "vtkInformation.h"

namespace meshlod
{
//------------------------------------------------------------------------------
void CopyArrayDescription(vtkAbstractArray* from, vtkAbstractArray* to)
{
  to->SetName(from->GetName());
  to->CopyComponentNames(from);
  if (from->HasInformation())
  {
    to->CopyInformation(from->GetInformation(), /*deep=*/1);
  }
  else if (to->HasInformation())
  {
    to->GetInformation()->Clear(); // (a recycled array's from its previous use)
  }
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkAbstractArray> NewArrayLike(vtkAbstractArray* like, vtkIdType tuples)
{
  auto array = vtk::TakeSmartPointer(like->NewInstance());
  array->SetNumberOfComponents(like->GetNumberOfComponents());
  CopyArrayDescription(like, array);
  array->SetNumberOfTuples(tuples);
  return array;
}
} // namespace meshlod
