"""MeshLOD: levels of detail for triangle meshes, with smooth transitions between them.

The classes are VTK algorithms and plug into any VTK pipeline::

    import meshlod
    from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D

    hierarchy = meshlod.vtkTriangleCollapseDecimation()
    hierarchy.SetInputConnection(contour.GetOutputPort())
"""

# The wrapped classes derive from these VTK modules: import them first so that the base classes
# are known to Python.
from vtkmodules import vtkCommonCore, vtkCommonDataModel, vtkCommonExecutionModel  # noqa: F401

from .vtkFiltersMeshLOD import *  # noqa: F401,F403
