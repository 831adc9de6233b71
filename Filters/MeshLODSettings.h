// Checks and printing of filter settings shared by the MeshLOD filters.
#ifndef MeshLODSettings_h
#define MeshLODSettings_h

#include "vtkAlgorithm.h"
#include "vtkObject.h"

#include <cmath>
#include <initializer_list>
#include <utility>

namespace meshlod
{
/// vtkSetClampMacro lets NaN through (every comparison with NaN is false), and a NaN setting
/// reaches the algorithms as a garbage index or threshold. Returns false, with an error naming
/// the first NaN setting, when there is one.
inline bool SettingsAreNumbers(
  vtkObject* caller, std::initializer_list<std::pair<const char*, double>> settings)
{
  for (const auto& setting : settings)
  {
    if (std::isnan(setting.second))
    {
      vtkErrorWithObjectMacro(caller,
        << setting.first << " is NaN; set a number in its documented range.");
      return false;
    }
  }
  return true;
}

/// The name of a vtkAlgorithm::DesiredOutputPrecision value, for PrintSelf.
inline const char* PrecisionName(int precision)
{
  return precision == vtkAlgorithm::SINGLE_PRECISION ? "SINGLE_PRECISION"
    : precision == vtkAlgorithm::DOUBLE_PRECISION    ? "DOUBLE_PRECISION"
                                                     : "DEFAULT_PRECISION";
}

} // namespace meshlod

#endif
