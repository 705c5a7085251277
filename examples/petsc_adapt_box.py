#!/usr/bin/python3
"""Adapts a labelled DMPlex box with hdimesh from petsc4py, as tests/petsc/adapt_box.c does in C.

    /usr/bin/python3 examples/petsc_adapt_box.py --lib build/apps/petsc/libhdimesh_petsc.so \
        [--metric iso|aniso] [-n 4] [--h 0.12] [--out box.vtu]

A unit box of n^3 cubes (6 tets each), faces labelled 'boundary' (sides 1..6, the inner plane
x = 0.5 as 7) and cells 'regions' (x < 0.5: 1, else 2), a DMPlex metric, then DMAdaptMetric with
-dm_adaptor hdimesh. Checks PETSc's DMPlexCheck, the volume, the labels and the edge lengths in
the metric; exits non-zero on failure. The library is --lib or $HDIMESH_PETSC_LIB.
"""
import argparse
import math
import os
import sys

import numpy as np
import petsc4py

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("--lib", default=os.environ.get("HDIMESH_PETSC_LIB"),
                    help="libhdimesh_petsc.so (default: $HDIMESH_PETSC_LIB)")
parser.add_argument("--metric", choices=["iso", "aniso"], default="iso")
parser.add_argument("-n", type=int, default=4, help="cubes per side")
parser.add_argument("--h", type=float, default=0.12, help="the metric's size at x = 0.5")
parser.add_argument("--out", help="write the adapted mesh with meshio (e.g. box.vtu)")
args, petsc_args = parser.parse_known_args()
if not args.lib or not os.path.isfile(args.lib):
    sys.exit("petsc_adapt_box.py: give libhdimesh_petsc.so with --lib or HDIMESH_PETSC_LIB"
             f" (got {args.lib!r})")

# petsc4py 3.18 wraps no DMGenerateRegister: the plugin registers 'hdimesh' when PETSc loads it.
petsc4py.init([sys.argv[0], "-dll_append", os.path.abspath(args.lib)] + petsc_args)
from petsc4py import PETSc  # noqa: E402  (after init, so the options above are seen)

ANISO = args.metric == "aniso"


def sizes_at(x):
    """The metric's sizes at x: h finer towards x = 0; aniso: 3 times longer across x."""
    hx = args.h * (0.6 + 0.8 * x[0])
    return np.array([hx, 3 * hx if ANISO else hx, 3 * hx if ANISO else hx])


def create_box(n):
    """n^3 cubes, Kuhn's split (conforming between cubes), each tet as Plex wants it."""
    g = np.linspace(0.0, 1.0, n + 1)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    coords = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    vid = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)  # noqa: E731
    perms = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    cells = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                for p in perms:
                    ijk = [i, j, k]
                    tet = [vid(*ijk)]
                    for d in p:
                        ijk[d] += 1
                        tet.append(vid(*ijk))
                    cells.append(tet)
    cells = np.array(cells, dtype=PETSc.IntType)
    # Plex wants the first face to see the fourth vertex on its negative side.
    a, b, c, d = (coords[cells[:, s]] for s in range(4))
    pos = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) > 0
    cells[pos, 0], cells[pos, 1] = cells[pos, 1], cells[pos, 0].copy()
    return PETSc.DMPlex().createFromCellList(3, cells, coords, interpolate=True,
                                             comm=PETSc.COMM_WORLD)


def face_value(x):
    """The side a face lies on (1..6), 7 on the plane x = 0.5, else -1."""
    for d in range(3):
        if abs(x[d]) < 1e-10:
            return 2 * d + 1
        if abs(x[d] - 1) < 1e-10:
            return 2 * d + 2
    return 7 if abs(x[0] - 0.5) < 1e-10 else -1


def centroid(dm, p):
    return dm.computeCellGeometryFVM(p)[1]


def label(dm):
    dm.createLabel("boundary")
    dm.createLabel("regions")
    bd, rg = dm.getLabel("boundary"), dm.getLabel("regions")
    for f in range(*dm.getHeightStratum(1)):
        value = face_value(centroid(dm, f))
        if value > 0:
            bd.setValue(f, value)
    for c in range(*dm.getHeightStratum(0)):
        rg.setValue(c, 1 if centroid(dm, c)[0] < 0.5 else 2)


def create_metric(dm):
    """A P1 metric filled per vertex through its DM's local section (one rank)."""
    dm.metricSetIsotropic(not ANISO)
    metric = dm.metricCreate()
    ms = metric.getDM().getSection()
    cs, xyz = dm.getCoordinateSection(), dm.getCoordinatesLocal().getArray(readonly=True)
    m = metric.getArray()
    for v in range(*dm.getDepthStratum(0)):
        xo, mo = cs.getOffset(v), ms.getOffset(v)
        s = sizes_at(xyz[xo:xo + 3])
        if ANISO:
            m[mo:mo + 9] = np.diag(1 / s**2).ravel()  # full 3x3 tensor, row-major
        else:
            m[mo] = 1 / s[0]**2
    return metric


def plex_check(dm):
    """DMPlexCheck: petsc4py 3.18 has no checkSymmetry() etc., DMSetFromOptions runs them."""
    opts = PETSc.Options()
    opts["dm_plex_check_all"] = None
    try:
        dm.setFromOptions()
    finally:
        opts.delValue("dm_plex_check_all")


def check_adapted(dm):
    """Labels where they belong, the volume kept, edges within [1/sqrt2, sqrt2] of the metric."""
    plex_check(dm)
    if not (dm.hasLabel("boundary") and dm.hasLabel("regions")):
        raise RuntimeError("labels lost")
    bd, rg = dm.getLabel("boundary"), dm.getLabel("regions")
    cStart, cEnd = dm.getHeightStratum(0)
    eStart, eEnd = dm.getDepthStratum(1)
    dm.createLabel("outer")
    dm.markBoundaryFaces("outer", 1)
    outer = dm.getLabel("outer")
    volume, bad = 0.0, 0
    for c in range(cStart, cEnd):
        vol, x, _ = dm.computeCellGeometryFVM(c)
        volume += vol
        bad += rg.getValue(c) != (1 if x[0] < 0.5 else 2)
    if bad:
        raise RuntimeError(f"{bad} cells in the wrong region")
    if abs(volume - 1) > 1e-10:
        raise RuntimeError(f"volume {volume}, not 1")
    seen = set()
    for f in range(*dm.getHeightStratum(1)):
        value, expect = bd.getValue(f), face_value(centroid(dm, f))
        bad += value != expect or (outer.getValue(f) == 1 and expect < 0)
        seen.add(value)
    if bad:
        raise RuntimeError(f"{bad} faces labelled wrongly")
    if not set(range(1, 8)) <= seen:
        raise RuntimeError(f"no face keeps value(s) {sorted(set(range(1, 8)) - seen)}")
    cs, xyz = dm.getCoordinateSection(), dm.getCoordinatesLocal().getArray(readonly=True)
    in_range = 0
    for e in range(eStart, eEnd):
        _, v0, v1 = dm.getTransitiveClosure(e)[0]  # the edge, then its two vertices
        a = xyz[cs.getOffset(v0):cs.getOffset(v0) + 3]
        b = xyz[cs.getOffset(v1):cs.getOffset(v1) + 3]
        lm = np.linalg.norm((b - a) / sizes_at(centroid(dm, e)))
        in_range += 1 / math.sqrt(2) <= lm <= math.sqrt(2)
    share = 100.0 * in_range / (eEnd - eStart)
    PETSc.Sys.Print(f"adapted ({args.metric}): {cEnd - cStart} tets, {share:.1f} % of "
                    f"{eEnd - eStart} edges in [1/sqrt2, sqrt2]")
    if in_range < 0.75 * (eEnd - eStart):
        raise RuntimeError("too few edges in range")


def to_numpy(dm):
    """(points, tets, regions) of a one-rank tet DMPlex, tets positively oriented."""
    vStart, vEnd = dm.getDepthStratum(0)
    cStart, cEnd = dm.getHeightStratum(0)
    cs, xyz = dm.getCoordinateSection(), dm.getCoordinatesLocal().getArray(readonly=True)
    points = np.array([xyz[cs.getOffset(v):cs.getOffset(v) + 3] for v in range(vStart, vEnd)])
    tets = np.array([[p - vStart for p in dm.getTransitiveClosure(c)[0] if vStart <= p < vEnd]
                     for c in range(cStart, cEnd)])
    a, b, c, d = (points[tets[:, s]] for s in range(4))
    neg = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) < 0
    tets[neg, 0], tets[neg, 1] = tets[neg, 1], tets[neg, 0].copy()  # Plex lists them inward
    regions = np.array([dm.getLabel("regions").getValue(c) for c in range(cStart, cEnd)])
    return points, tets, regions


def main():
    dm = create_box(args.n)
    plex_check(dm)
    label(dm)
    metric = create_metric(dm)
    PETSc.Options()["dm_adaptor"] = "hdimesh"
    adapted = dm.adaptMetric(metric, bdLabel="boundary", rgLabel="regions")
    check_adapted(adapted)
    points, tets, regions = to_numpy(adapted)
    PETSc.Sys.Print(f"numpy: points {points.shape}, tets {tets.shape}, regions "
                    f"{np.bincount(regions)[1:].tolist()}")
    if args.out:
        import meshio
        meshio.write(args.out, meshio.Mesh(points, [("tetra", tets)],
                                           cell_data={"regions": [regions]}))
    for obj in (metric, adapted, dm):
        obj.destroy()


if __name__ == "__main__":
    try:
        main()
    except (PETSc.Error, RuntimeError) as err:
        print(f"petsc_adapt_box.py: FAILED: {err}", file=sys.stderr)
        sys.exit(1)
