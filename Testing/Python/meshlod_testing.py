"""What the Python tests share: checks that count and report failures without stopping the
script, the meshes' points and triangles as Python lists for exact comparisons, and what several
tests measure on a level (its edges, its points' finiteness, its MorphTargetId values). Each test
script imports it from its own folder (the first entry of sys.path) and ends with finish()."""

import math
import sys
from collections import Counter

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


def edge_counts(poly):
    """How many edges have 1, 2, 3, ... triangles (a Counter), and the Euler characteristic over
    the points in use."""
    corners = triangles_of(poly)
    edges = Counter()
    for t in range(0, len(corners), 3):
        a, b, c = corners[t:t + 3]
        for u, v in ((a, b), (b, c), (c, a)):
            edges[(min(u, v), max(u, v))] += 1
    euler = len(set(corners)) - len(edges) + len(corners) // 3
    return Counter(edges.values()), euler


def first_nonfinite_point(poly):
    """The id of the first point with a NaN or infinite coordinate, or -1."""
    for i in range(poly.GetNumberOfPoints()):
        if not all(math.isfinite(x) for x in poly.GetPoint(i)):
            return i
    return -1


def morph_target_ids(level):
    """The level's MorphTargetId values as a list, or None when it has no such array."""
    ids = level.GetPointData().GetArray("MorphTargetId")
    return None if ids is None else [int(ids.GetTuple1(k)) for k in range(ids.GetNumberOfTuples())]
