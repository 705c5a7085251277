#!/usr/bin/env python3
"""The analysts' loop: solve, a metric from the solution, adapt, carry the solution over.

    examples/solve_adapt_transfer.py [--rounds 3]

The "solver" is a stand-in: u = tanh((z - 0.5) / δ), a boundary layer across z = 0.5 in the
unit cube, computed exactly at the vertices. Its Hessian-like size across the layer (small
where u bends, larger along it) makes an anisotropic metric; adapt() then meshes to it and
carries u (fields=) onto the new vertices, which is the next solve's restart. Each round
prints the tets and how far the carried u is from the exact one at the new vertices.
"""
import argparse
import itertools

import numpy as np

import hdimesh

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--rounds", type=int, default=3)
parser.add_argument("--delta", type=float, default=0.02, help="the layer's width δ")
args = parser.parse_args()
delta, h_along, h_min = args.delta, 0.1, 0.005


def box(n):
    """The unit cube cut into n³ cells of 6 tets each, with its boundary triangles."""
    g = np.linspace(0, 1, n + 1)
    points = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)
    corner = np.arange((n + 1) ** 3).reshape(n + 1, n + 1, n + 1)[:-1, :-1, :-1].reshape(-1)
    step = np.array([(n + 1) ** 2, n + 1, 1])
    tets = np.concatenate([np.stack([corner, corner + step[a], corner + step[a] + step[b],
                                     corner + step.sum()], axis=1)
                           for a, b, _ in itertools.permutations(range(3))])
    p = points[tets]
    flip = np.linalg.det(p[:, 1:] - p[:, :1]) < 0
    tets[flip] = tets[flip][:, [1, 0, 2, 3]]
    faces = np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 3, 2]], tets[:, [0, 1, 3]],
                            tets[:, [0, 2, 1]]])
    _, inverse, count = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True,
                                  return_counts=True)
    return hdimesh.TetMesh(points, tets, faces[count[inverse.reshape(-1)] == 1])


def solve(points, restart=None):
    """The stand-in solver: the exact u (a real one would start from `restart`)."""
    return np.tanh((points[:, 2] - 0.5) / delta)


def metric(points, u):
    """diag(h_along⁻², h_along⁻², h_z⁻²), h_z from u's second variation across the layer:
    |u_z| / δ = (1 - u²) / δ², equidistributing an interpolation error of 0.25."""
    h_z = np.clip(np.sqrt(0.25 / ((1 - u**2) / delta**2 + 1e-30)), h_min, h_along)
    m = np.zeros((len(points), 3, 3))
    m[:, 0, 0] = m[:, 1, 1] = h_along**-2
    m[:, 2, 2] = h_z**-2
    return m


mesh = box(6)
u = solve(mesh.points)
print(f"start: {len(mesh.tets)} tets")
for k in range(1, args.rounds + 1):
    mesh = hdimesh.adapt(mesh, metric=metric(mesh.points, u), fields={"u": u}, hgrad=2.0)
    restart = mesh.fields["u"]
    error = np.max(np.abs(restart - solve(mesh.points)))
    print(f"round {k}: {len(mesh.tets)} tets, transferred u's max error {error:.3g}")
    u = solve(mesh.points, restart)
assert not hdimesh.check(mesh), "the adapted mesh is valid"
