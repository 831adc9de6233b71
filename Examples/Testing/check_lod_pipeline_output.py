"""Checks the files of the example pipelines (LODPipeline.cxx, lod_pipeline.py):

    check_lod_pipeline_output.py <prefix> [<other-prefix>]

<prefix>.vtm has levels "Level 0".."Level 4" with strictly fewer triangles each, level k keeping
0.02^(k/4) of the input's (up to 4 triangles fewer); <prefix>_<time>.vtp has the triangles of
level floor(time), LevelOfDetail = time, and at a whole time the points of that level. With a
second prefix, both sets of files hold the same meshes (the C++ and the Python pipeline agree).
"""
import math
import sys

from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet
from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader, vtkXMLPolyDataReader

TIMES = ("0", "0.5", "1", "2.25", "4")
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("CHECK failed:", what)


def read_mesh(path):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def mesh_of(poly):
    ids = poly.GetPolys().GetConnectivityArray()
    return ([poly.GetPoint(i) for i in range(poly.GetNumberOfPoints())],
            [int(ids.GetTuple1(i)) for i in range(ids.GetNumberOfTuples())])


def check_files(prefix):
    reader = vtkXMLMultiBlockDataReader()
    reader.SetFileName(prefix + ".vtm")
    reader.Update()
    levels = reader.GetOutput()
    n = levels.GetNumberOfBlocks()
    check(n == 5, "%s.vtm: %d levels" % (prefix, n))
    if n != 5:
        return
    counts = [levels.GetBlock(i).GetNumberOfPolys() for i in range(5)]
    check(counts[0] > 4000, "level 0 has %d triangles" % counts[0])
    for k in range(5):
        name = levels.GetMetaData(k).Get(vtkCompositeDataSet.NAME())
        check(name == "Level %d" % k, "block %d named %r" % (k, name))
        target = math.floor(counts[0] * 0.02 ** (k / 4) + 1e-9)
        check(target - 4 <= counts[k] <= target, "level %d: %d for %d" % (k, counts[k], target))
        if k > 0:
            check(counts[k] < counts[k - 1], "level %d has fewer triangles" % k)
    for time in TIMES:
        mesh = read_mesh("%s_%s.vtp" % (prefix, time))
        level = levels.GetBlock(int(float(time)))
        check(mesh.GetNumberOfPolys() == level.GetNumberOfPolys(), "triangles at time " + time)
        lod = mesh.GetFieldData().GetArray("LevelOfDetail")
        check(lod is not None and lod.GetValue(0) == float(time), "LevelOfDetail at time " + time)
        if float(time).is_integer():
            check(mesh_of(mesh) == mesh_of(level), "time %s is level %s" % (time, time))


def check_same(prefix, other):
    for time in TIMES:
        a = read_mesh("%s_%s.vtp" % (prefix, time))
        b = read_mesh("%s_%s.vtp" % (other, time))
        check(mesh_of(a) == mesh_of(b), "%s and %s differ at time %s" % (prefix, other, time))


check_files(sys.argv[1])
if len(sys.argv) > 2:
    check_files(sys.argv[2])
    check_same(sys.argv[1], sys.argv[2])
if failures:
    print(len(failures), "check(s) failed")
    sys.exit(1)
print("checked", " and ".join(sys.argv[1:]))
