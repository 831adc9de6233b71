"""What the Python tests share: checks that count and report failures without stopping the
script, and the meshes' points and triangles as Python lists for exact comparisons. Each test
script imports it from its own folder (the first entry of sys.path) and ends with finish()."""

import sys

failures = []
checks = [0]


def check(condition, what):
    """Records a failed check (and prints it); the script goes on to the next."""
    checks[0] += 1
    if not condition:
        failures.append(what)
        print("CHECK failed:", what)


def finish():
    """Prints the count of failed checks and exits non-zero if there were any."""
    print("%d of %d checks failed" % (len(failures), checks[0]))
    sys.exit(1 if failures else 0)


def points_of(poly):
    return [poly.GetPoint(i) for i in range(poly.GetNumberOfPoints())]


def triangles_of(poly):
    """The point ids of the cells, flat: three per triangle."""
    ids = poly.GetPolys().GetConnectivityArray()
    return [int(ids.GetTuple1(i)) for i in range(ids.GetNumberOfTuples())]


def same_mesh(a, b):
    return points_of(a) == points_of(b) and triangles_of(a) == triangles_of(b)
