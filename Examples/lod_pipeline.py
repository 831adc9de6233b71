"""Levels of detail of an isosurface, and the smooth meshes between them, in one VTK pipeline:
vtkSampleFunction -> vtkFlyingEdges3D -> vtkTriangleCollapseDecimation (the levels) ->
vtkLODGeomorph (time i is level i; time i + f moves level i the fraction f of the way to level
i + 1, with level i's triangles).

    /usr/bin/python3 lod_pipeline.py [output-prefix]

writes <prefix>.vtm (the levels; open it in ParaView; their files go into <prefix>/) and
<prefix>_<time>.vtp for a few times. Exits with 1 when a file cannot be written.
"""
import os
import sys

import meshlod
from vtkmodules.vtkCommonDataModel import vtkSphere
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkImagingHybrid import vtkSampleFunction
from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataWriter, vtkXMLPolyDataWriter


def write_succeeded(writer):
    """vtkXMLWriter.Write returns 1 even where it could not write the file; its error code
    tells."""
    return writer.Write() == 1 and writer.GetErrorCode() == 0


first = sys.argv[1] if len(sys.argv) > 1 else ""
if len(sys.argv) > 2 or first.startswith("-"):
    helping = first in ("-h", "--help")
    print("usage: %s [output-prefix]\nwrites <prefix>.vtm (the levels, files in <prefix>/) and "
          "<prefix>_<time>.vtp; the prefix defaults to lod" % sys.argv[0],
          file=sys.stdout if helping else sys.stderr)
    sys.exit(0 if helping else 2)
prefix = first or "lod"
# The levels' files go into <prefix>/, which the writer would fail to make without a word in
# its error code (a file of that name, say).
try:
    os.makedirs(prefix, exist_ok=True)
except OSError as error:
    print("cannot create the folder %s: %s" % (prefix, error), file=sys.stderr)
    sys.exit(1)
shape = vtkSphere()  # radius 0.5: its isosurface at 0 in a 50^3 volume over [-1, 1]^3
volume = vtkSampleFunction()
volume.SetImplicitFunction(shape)
surface = vtkFlyingEdges3D()
surface.SetInputConnection(volume.GetOutputPort())
surface.SetValue(0, 0.0)
levels = meshlod.vtkTriangleCollapseDecimation()  # levels 1-4 keep 38%, 14%, 5.3%, 2%
levels.SetInputConnection(surface.GetOutputPort())
levels.SetNumberOfLevels(4)
levels.SetTargetReduction(0.98)
level_writer = vtkXMLMultiBlockDataWriter()
level_writer.SetInputConnection(levels.GetOutputPort())
level_writer.SetFileName(prefix + ".vtm")
written = write_succeeded(level_writer)

geomorph = meshlod.vtkLODGeomorph()
geomorph.SetInputConnection(levels.GetOutputPort())
mesh_writer = vtkXMLPolyDataWriter()
mesh_writer.SetInputConnection(geomorph.GetOutputPort())
for time in ("0", "0.5", "1", "2.25", "4"):
    geomorph.UpdateTimeStep(float(time))  # as a ParaView animation asks; the writer keeps it
    mesh_writer.SetFileName(prefix + "_" + time + ".vtp")
    written = write_succeeded(mesh_writer) and written
    print("time", time, ":", geomorph.GetOutput().GetNumberOfPolys(), "triangles")
if not written:
    print("cannot write the files of %s" % prefix, file=sys.stderr)
sys.exit(0 if written else 1)
