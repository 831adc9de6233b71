#include "MeshLODInputArrays.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkVariant.h"

#include <cmath>
#include <sstream>
#include <string>

namespace meshlod
{
namespace
{
// Indices of the arrays of `data` whose tuple count is not `count`, in increasing order.
std::vector<int> MismatchedArrays(vtkFieldData* data, vtkIdType count)
{
  std::vector<int> indices;
  for (int i = 0; i < data->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* array = data->GetAbstractArray(i);
    if (array != nullptr && array->GetNumberOfTuples() != count)
    {
      indices.push_back(i);
    }
  }
  return indices;
}

// The arrays' names for a message (an unnamed array by its index), then remove them.
std::string RemoveArrays(vtkFieldData* data, const std::vector<int>& indices)
{
  std::ostringstream names;
  for (size_t i = 0; i < indices.size(); ++i)
  {
    const char* name = data->GetAbstractArray(indices[i])->GetName();
    names << (i ? ", " : "");
    if (name)
    {
      names << '"' << name << '"';
    }
    else
    {
      names << "unnamed array " << indices[i];
    }
  }
  for (auto i = indices.rbegin(); i != indices.rend(); ++i)
  {
    data->RemoveArray(*i); // highest index first: the others keep theirs
  }
  return names.str();
}
} // namespace

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> DropMismatchedArrays(vtkPolyData* input, vtkAlgorithm* caller)
{
  const std::vector<int> points =
    MismatchedArrays(input->GetPointData(), input->GetNumberOfPoints());
  const std::vector<int> cells = MismatchedArrays(input->GetCellData(), input->GetNumberOfCells());
  if (points.empty() && cells.empty())
  {
    return input;
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(input);
  // A shallow copy shares the arrays but has field data of its own, so removing is safe.
  if (!points.empty())
  {
    vtkWarningWithObjectMacro(caller,
      "Ignoring point-data arrays whose number of tuples is not the number of points ("
        << input->GetNumberOfPoints() << "): " << RemoveArrays(copy->GetPointData(), points)
        << ".");
  }
  if (!cells.empty())
  {
    vtkWarningWithObjectMacro(caller,
      "Ignoring cell-data arrays whose number of tuples is not the number of cells ("
        << input->GetNumberOfCells() << "): " << RemoveArrays(copy->GetCellData(), cells)
        << ".");
  }
  return copy;
}

//------------------------------------------------------------------------------
void PointDataAgreement::Prepare() const
{
  this->Prepared = true;
  vtkPointData* pointData = this->PointData;
  for (int i = 0; i < pointData->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* any = pointData->GetAbstractArray(i);
    vtkDataArray* array = pointData->GetArray(i);
    if (any == nullptr || any == pointData->GetGlobalIds() || any == pointData->GetPedigreeIds())
    {
      continue;
    }
    if (array == nullptr)
    {
      this->Others.push_back(any); // strings, variants: equal values agree
      continue;
    }
    this->Arrays.push_back(array);
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      // The finite range: one infinite value would make every pair agree.
      double range[2];
      array->GetFiniteRange(range, c);
      const double width = range[1] - range[0];
      this->Tolerances.push_back(std::isfinite(width) && width > 0.0 ? 1e-6 * width : 0.0);
    }
  }
}

bool PointDataAgreement::operator()(Id a, Id b) const
{
  if (!this->Prepared)
  {
    this->Prepare();
  }
  size_t k = 0;
  for (vtkDataArray* array : this->Arrays)
  {
    for (int c = 0; c < array->GetNumberOfComponents(); ++c, ++k)
    {
      const double difference = array->GetComponent(a, c) - array->GetComponent(b, c);
      // Written so that NaN values (which never agree with anything) keep the points apart.
      if (!(std::abs(difference) <= this->Tolerances[k]))
      {
        return false;
      }
    }
  }
  for (vtkAbstractArray* array : this->Others)
  {
    const vtkIdType nc = array->GetNumberOfComponents();
    for (vtkIdType c = 0; c < nc; ++c)
    {
      if (!(array->GetVariantValue(a * nc + c) == array->GetVariantValue(b * nc + c)))
      {
        return false;
      }
    }
  }
  return true;
}

} // namespace meshlod
