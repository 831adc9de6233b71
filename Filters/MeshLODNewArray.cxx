#include "MeshLODNewArray.h"

#include "vtkAbstractArray.h"
#include "vtkInformation.h"

#include <cstring>

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
bool SameComponentNames(vtkAbstractArray* a, vtkAbstractArray* b)
{
  if (a->GetNumberOfComponents() != b->GetNumberOfComponents())
  {
    return false;
  }
  for (int k = 0; k < a->GetNumberOfComponents(); ++k)
  {
    const char* x = a->GetComponentName(k);
    const char* y = b->GetComponentName(k);
    if ((x == nullptr) != (y == nullptr) || (x != nullptr && std::strcmp(x, y) != 0))
    {
      return false;
    }
  }
  return true;
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
