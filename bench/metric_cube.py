#!/usr/bin/python3
"""The start mesh of bench_metric.py: the unit cube [0,1]^3 as a structured tet mesh.

  bench/metric_cube.py N OUT.mesh      N^3 cubes, each cut into 6 tets around its diagonal
                                       (0,0,0)-(1,1,1) (Kuhn), so neighbouring cubes' faces match

Medit ASCII: every tet positively oriented ((b-a).((c-a)x(d-a)) > 0, as Mmg writes), ref 1; the
boundary triangles outward, with refs 1..6 for the faces x=0, x=1, y=0, y=1, z=0, z=1.
"""
import itertools, sys

import numpy as np


def cube_mesh(n):
    """(vertices (m,3), tets (k,4), triangles (f,3), triangle refs (f,)), indices from 0."""
    g = np.arange(n + 1)
    X, Y, Z = np.meshgrid(g, g, g, indexing='ij')
    V = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1) / float(n)

    def vid(i, j, k):
        return (i * (n + 1) + j) * (n + 1) + k

    c = np.arange(n)
    I, J, K = (a.ravel() for a in np.meshgrid(c, c, c, indexing='ij'))
    tets = []
    for perm in itertools.permutations(range(3)):
        # the path 000 -> +e_p0 -> +e_p1 -> 111 along the cube's edges
        steps = [np.zeros(3, int)]
        for axis in perm:
            s = steps[-1].copy()
            s[axis] = 1
            steps.append(s)
        tets.append(np.stack([vid(I + s[0], J + s[1], K + s[2]) for s in steps], axis=1))
    T = np.concatenate(tets)
    a, b, cc, d = (V[T[:, k]] for k in range(4))
    negative = np.einsum('ij,ij->i', b - a, np.cross(cc - a, d - a)) < 0
    T[negative] = T[negative][:, [0, 2, 1, 3]]

    faces = np.concatenate([T[:, [1, 2, 3]], T[:, [0, 3, 2]], T[:, [0, 1, 3]], T[:, [0, 2, 1]]])
    key = np.sort(faces, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    F = faces[counts[inverse.ravel()] == 1]  # those faces of a positive tet point outward
    P = V[F]
    refs = np.zeros(len(F), dtype=np.int64)
    for axis in range(3):
        for side in (0, 1):
            on = np.all(P[:, :, axis] == side, axis=1)
            refs[on] = 2 * axis + side + 1
    return V, T, F, refs


def write_mesh(path, V, T, F, refs):
    with open(path, 'w') as f:
        f.write('MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n%d\n' % len(V))
        np.savetxt(f, np.column_stack([V, np.zeros(len(V))]), fmt='%.17g %.17g %.17g %d')
        f.write('\nTriangles\n%d\n' % len(F))
        np.savetxt(f, np.column_stack([F + 1, refs]), fmt='%d')
        f.write('\nTetrahedra\n%d\n' % len(T))
        np.savetxt(f, np.column_stack([T + 1, np.ones(len(T), dtype=np.int64)]), fmt='%d')
        f.write('\nEnd\n')


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    write_mesh(sys.argv[2], *cube_mesh(int(sys.argv[1])))
