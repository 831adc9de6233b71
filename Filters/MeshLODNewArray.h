// New output arrays shaped like an input array: the same class, name and number of components,
// and what vtkDataSetAttributes::CopyAllocate carries over too, the component names and the
// array's information (units, for instance). ParaView shows a three-component array with named
// components as "Velocity_Vx"; a level built with bare NewInstance() showed "Velocity_0".
#ifndef MeshLODNewArray_h
#define MeshLODNewArray_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

class vtkAbstractArray;

namespace meshlod
{
/// Gives `to` the name, component names and information of `from` (the information's cached
/// ranges left out, as vtkAbstractArray::CopyInformation does); `to` keeps its values. VTK 9.1
/// cannot take component names away (CopyComponentNames of an array without any leaves them),
/// so `to` must have no component names or the same ones as `from` (SameComponentNames).
void CopyArrayDescription(vtkAbstractArray* from, vtkAbstractArray* to);

/// Whether `a` and `b` have the same component names (none counts as a name of its own).
bool SameComponentNames(vtkAbstractArray* a, vtkAbstractArray* b);

/// A new array of `like`'s class and number of components with `tuples` tuples (values not
/// set) and `like`'s description (CopyArrayDescription).
vtkSmartPointer<vtkAbstractArray> NewArrayLike(vtkAbstractArray* like, vtkIdType tuples);
} // namespace meshlod

#endif
