"""Runs MeshLODDemo on surfaces read from files (--input) and checks what it makes:

    check_demo_input.py <MeshLODDemo> <CheckDemoOutput> <work-directory>

A closed surface (a sampled sphere's isosurface, triangles only, no point data) is written as
.vtp, .vtk, .stl, .ply and .obj; for each, the demo must say it read that many triangles, and
its triangle-collapse files must pass CheckDemoOutput (9 levels, 2 frames per transition). The
same surface as triangle strips, a plane of quads and a 12-triangle cube must run too (the
demo counts their triangles: the octree's level counts were once computed from polygons, 0 for
strips, and counts below 1 stopped the demo). A missing file, an unknown extension and --input
given with --field must fail with their messages.
"""
import os
import re
import subprocess
import sys

from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkSphere
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D, vtkStripper, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkPlaneSource
from vtkmodules.vtkImagingHybrid import vtkSampleFunction
from vtkmodules.vtkIOGeometry import vtkOBJWriter, vtkSTLWriter
from vtkmodules.vtkIOLegacy import vtkPolyDataWriter
from vtkmodules.vtkIOPLY import vtkPLYWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

demo, check_output, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("CHECK failed:", what)


def run(*arguments):
    result = subprocess.run([demo, *arguments], capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


sphere = vtkSphere()
sphere.SetRadius(0.7)
sample = vtkSampleFunction()
sample.SetImplicitFunction(sphere)
sample.SetSampleDimensions(24, 24, 24)
sample.SetModelBounds(-1, 1, -1, 1, -1, 1)
contour = vtkFlyingEdges3D()
contour.SetInputConnection(sample.GetOutputPort())
contour.SetValue(0, 0.0)
contour.ComputeNormalsOff()
contour.ComputeGradientsOff()
contour.ComputeScalarsOff()
contour.Update()
surface = vtkPolyData()
surface.SetPoints(contour.GetOutput().GetPoints())
surface.SetPolys(contour.GetOutput().GetPolys())
triangles = surface.GetNumberOfPolys()

writers = {".vtp": vtkXMLPolyDataWriter, ".vtk": vtkPolyDataWriter, ".stl": vtkSTLWriter,
           ".ply": vtkPLYWriter, ".obj": vtkOBJWriter}
for extension, writer_class in writers.items():
    path = os.path.join(work, "sphere" + extension)
    writer = writer_class()
    writer.SetInputData(surface)
    writer.SetFileName(path)
    writer.Write()
    output = os.path.join(work, "out" + extension.replace(".", "_"))
    code, text = run(output, "--input", path, "--frames", "2", "--no-render")
    check(code == 0, "%s: the demo exits with 0 (%d):\n%s" % (extension, code, text))
    read = re.search(r"Read [^\n]*, (\d+) triangles", text)
    check(read is not None and int(read.group(1)) == triangles,
          "%s: read %s triangles, written %d" % (extension, read and read.group(1), triangles))
    check(not re.search(r"ERR\||WARN\||Warning:", text), "%s: no VTK error or warning:\n%s"
          % (extension, text))
    files = subprocess.run([check_output, output, "triangle_collapse", "9", "2"],
                           capture_output=True, text=True)
    check(files.returncode == 0, "%s: CheckDemoOutput:\n%s" % (extension, files.stdout))

# Strips, quads and a tiny solid: their triangles counted, both hierarchies made.
stripper = vtkStripper()
stripper.SetInputData(surface)
plane = vtkPlaneSource()
plane.SetResolution(30, 30)
cube = vtkCubeSource()
cube_triangles = vtkTriangleFilter()
cube_triangles.SetInputConnection(cube.GetOutputPort())
for name, algorithm, expected in (("strips", stripper, triangles), ("quads", plane, 1800),
                                  ("cube", cube_triangles, 12)):
    algorithm.Update()
    path = os.path.join(work, name + ".vtp")
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(algorithm.GetOutput())
    writer.SetFileName(path)
    writer.Write()
    output = os.path.join(work, "out_" + name)
    code, text = run(output, "--input", path, "--frames", "2", "--no-render")
    read = re.search(r"Read [^\n]*, (\d+) triangles", text)
    check(code == 0 and read is not None and int(read.group(1)) == expected,
          "%s: exit code %d, %s triangles read (%d expected):\n%s"
          % (name, code, read and read.group(1), expected, text))
    check(os.path.isfile(os.path.join(output, "vertex_cluster_octree.vtm")),
          "%s: the octree's hierarchy written" % name)

code, text = run(os.path.join(work, "none"), "--input", os.path.join(work, "missing.stl"))
check(code == 1 and "no such file" in text, "a missing file is refused: %d %s" % (code, text))
unknown = os.path.join(work, "sphere.xyz")
open(unknown, "w").close()
code, text = run(os.path.join(work, "none"), "--input", unknown)
check(code == 1 and "not a file type the demo reads" in text,
      "an unknown extension is refused: %d %s" % (code, text))
code, text = run(os.path.join(work, "none"), "--input", unknown, "--field", "gyroid")
check(code == 2 and "give one or the other" in text,
      "--input with --field is refused: %d %s" % (code, text))

print("%d checks failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
