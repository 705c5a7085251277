#!/usr/bin/python3
"""Checks an adapted data/box_with_ball.msh (a ball of ref 2, centre (0.2, 0.1, 0), radius 0.6,
inside the box [-1, 1]^3 of ref 1): both materials kept at their volumes, and the interface
triangles on the sphere with the surface remesher's shape targets.

usage: interface_check.py OUT.mesh  (exit 1 naming what fails)
"""
import sys

import numpy as np

CENTRE, RADIUS = np.array([0.2, 0.1, 0.0]), 0.6


def read_medit(path):
    tokens = open(path).read().split()
    sections, i = {}, 0
    widths = {"Vertices": 4, "Triangles": 4, "Tetrahedra": 5}
    while i < len(tokens):
        name = tokens[i]
        if name in widths:
            n, w = int(tokens[i + 1]), widths[name]
            sections[name] = np.array(tokens[i + 2:i + 2 + n * w], float).reshape(n, w)
            i += 2 + n * w
        else:
            i += 1
    return sections


def triangle_shape(x):
    """Per triangle: the smallest angle in degrees, and Qe = 2 sqrt(3) inradius / longest."""
    e = [x[:, 1] - x[:, 0], x[:, 2] - x[:, 1], x[:, 0] - x[:, 2]]
    lengths = np.stack([np.linalg.norm(v, axis=1) for v in e], 1)
    angles = []
    for k in range(3):
        u, v = e[k], -e[(k + 2) % 3]
        cos = (u * v).sum(1) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
        angles.append(np.degrees(np.arccos(np.clip(cos, -1, 1))))
    s = lengths.sum(1) / 2
    area = np.sqrt(np.maximum(s * (s - lengths[:, 0]) * (s - lengths[:, 1]) * (s - lengths[:, 2]), 0))
    return np.min(angles, axis=0), 2 * np.sqrt(3) * (area / s) / lengths.max(1)


def main():
    mesh = read_medit(sys.argv[1])
    points = mesh["Vertices"][:, :3]
    tets = mesh["Tetrahedra"][:, :4].astype(int) - 1
    refs = mesh["Tetrahedra"][:, 4].astype(int)
    failures = []
    x = points[tets]
    volume = np.abs(np.einsum("ij,ij->i", x[:, 1] - x[:, 0],
                              np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 0]))) / 6
    ball = volume[refs == 2].sum()
    exact = 4 / 3 * np.pi * RADIUS ** 3
    if sorted(set(refs.tolist())) != [1, 2]:
        failures.append("tet refs %s, not [1, 2]" % sorted(set(refs.tolist())))
    # (the ball is a polyhedron inscribed in its sphere: a little less than its volume)
    if abs(ball - exact) > 0.02 * exact or abs(volume.sum() - 8) > 1e-9:
        failures.append("ball volume %.6f (sphere %.6f), total %.9f" % (ball, exact, volume.sum()))
    triangles = mesh["Triangles"][:, :3].astype(int) - 1
    t = points[triangles]
    on_box = np.zeros(len(t), bool)
    for axis in range(3):
        for side in (-1, 1):
            on_box |= np.all(np.abs(t[:, :, axis] - side) < 1e-12, axis=1)
    interface = t[~on_box]
    off = np.abs(np.linalg.norm(interface - CENTRE, axis=2) - RADIUS).max()
    angle, qe = triangle_shape(interface)
    share = 100 * (qe >= 0.7).mean()
    print("%d interface triangles: vertices within %.3g of the sphere, min angle %.2f, "
          "Qe >= 0.7 %.2f %%; ball volume %.6f (sphere %.6f)"
          % (len(interface), off, angle.min(), share, ball, exact))
    if off > 1e-3:
        failures.append("an interface vertex %.3g off the sphere" % off)
    if angle.min() < 20 or share < 99:
        failures.append("interface shape: min angle %.2f, Qe >= 0.7 %.2f %%" % (angle.min(), share))
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
