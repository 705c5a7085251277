#!/usr/bin/python3
"""Analytic anisotropic metrics on the unit cube [0,1]^3, at a mesh's vertices, as a tensor .sol.

  make_metric.py MESH.mesh --case layer|shock [--hmin H] [--htan H] [--hmax H] [--delta D] -o MET.sol

The .sol is Medit ASCII, SolAtVertices, one solution of type 3 (symmetric tensor), the 6 values
per vertex in Medit's order m11 m12 m22 m13 m23 m33 (what Mmg reads). Every metric is
M = R diag(h1^-2, h2^-2, h3^-2) Rᵀ, R's columns the principal directions, h the sizes along them.

layer   a boundary-layer-like refinement across the plane z = 0.5, which cuts the cube's four side
        faces (so the boundary must be remeshed anisotropically too). With d = |z - 0.5|:
            h_x = h_y = hmax,   h_z = hmin + (hmax - hmin) (1 - exp(-d / delta)),
        R = I. Defaults hmin 0.001, hmax 0.1 (aspect ratio 100 at the plane), delta 1.5: h_z
        grows from the plane about like a layer of growth ratio 1 + (hmax - hmin)/delta = 1.066
        (it is 0.029 at the faces z = 0, 1). Its metric volume, the integral of sqrt(det M), is
        1.11e4, i.e. about 94k regular tets of unit edges (6 sqrt(2) per unit of metric volume);
        an adapted mesh holds more (Mmg: about 1.3x), so ~120-125k tets are expected.
shock   a shock along the sphere |p| = 0.6 (centre at the corner (0,0,0): an eighth of it in the
        cube, cutting the faces x = 0, y = 0, z = 0). With d = | |p| - 0.6 |, n = p / |p|, and the
        profile s(a, b) = a + (b - a) (1 - exp(-d / delta)):
            h_n = s(hmin, hmax) along n,   h_t = s(htan, hmax) in the two tangential directions,
        i.e. M = h_n^-2 n nᵀ + h_t^-2 (I - n nᵀ). Defaults hmin 0.002, htan 0.05 (aspect ratio 25
        at the shock), hmax 0.1, delta 0.7 (a growth ratio 1.14 of h_n away from the shock):
        metric volume 1.12e4, ~95k unit tets, ~120-125k expected. At p = 0, the corner where n is
        undefined, n is taken as x (one vertex; its sizes are 0.058 and 0.079 there).
"""
import argparse, os, sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from meshstat import read_mesh  # noqa: E402
from metricstat import write_sol  # noqa: E402

DEFAULTS = {  # case: its parameters' defaults
    'layer': {'hmin': 0.001, 'hmax': 0.1, 'delta': 1.5},
    'shock': {'hmin': 0.002, 'htan': 0.05, 'hmax': 0.1, 'delta': 0.7},
}
SHOCK_RADIUS = 0.6


def profile(d, a, b, delta):
    """a at d = 0, tending to b with the distance d (scale delta)."""
    return a + (b - a) * (1.0 - np.exp(-d / delta))


def from_directions(n, hn, ht):
    """(k, 6) tensors, our order m11 m12 m13 m22 m23 m33: size hn along unit n, ht across."""
    a, b = hn ** -2.0, ht ** -2.0
    out = np.empty((len(n), 6))
    for col, (i, j) in enumerate(((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))):
        out[:, col] = (a - b) * n[:, i] * n[:, j] + (b if i == j else 0.0)
    return out


def layer(P, hmin, hmax, delta, **_):
    hz = profile(np.abs(P[:, 2] - 0.5), hmin, hmax, delta)
    n = np.zeros_like(P)
    n[:, 2] = 1.0
    return from_directions(n, hz, np.full(len(P), hmax))


def shock(P, hmin, htan, hmax, delta, **_):
    r = np.linalg.norm(P, axis=1)
    n = np.zeros_like(P)
    n[:, 0] = 1.0
    inside = r > 0
    n[inside] = P[inside] / r[inside, None]
    d = np.abs(r - SHOCK_RADIUS)
    return from_directions(n, profile(d, hmin, hmax, delta), profile(d, htan, hmax, delta))


CASES = {'layer': layer, 'shock': shock}


def metric(P, case, **overrides):
    """The case's tensors at the points P (k, 3), our order; overrides replace defaults."""
    params = dict(DEFAULTS[case])
    params.update({k: v for k, v in overrides.items() if v is not None})
    return CASES[case](P, **params)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('mesh')
    ap.add_argument('--case', required=True, choices=sorted(CASES))
    ap.add_argument('--hmin', type=float, help='the smallest size (across the layer or the shock)')
    ap.add_argument('--htan', type=float, help='shock: the tangential size at the shock')
    ap.add_argument('--hmax', type=float, help='the size far from the feature')
    ap.add_argument('--delta', type=float, help='the distance scale of the sizes\' growth')
    ap.add_argument('-o', required=True, metavar='MET.sol')
    args = ap.parse_args()
    V = read_mesh(args.mesh)[0]
    extra = {'htan': args.htan} if args.case == 'shock' else {}
    write_sol(args.o, metric(V, args.case, hmin=args.hmin, hmax=args.hmax, delta=args.delta, **extra))


if __name__ == '__main__':
    main()
