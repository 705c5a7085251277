#!/usr/bin/python3
"""Helper of the Mmg drop-in tests (tests/cmake/mmg_cli.cmake), on Medit ASCII files.

  mmg_cli_check.py medit IN.obj OUT.mesh       an OBJ surface as a Medit .mesh (Mmg's format)
  mmg_cli_check.py sol MESH OUT.sol SIZE [--tensor]   a constant size per vertex of MESH (.sol,
                                               type 1; --tensor: an isotropic metric, type 3)
  mmg_cli_check.py check MESH [--tets] [--max-edge H] [--min-edge H] [--at-most-vertices-of IN]
                               [--same-vertices-as IN [--unmoved]]

check: indices in range, every element non-degenerate (tets all of one orientation), a closed
conforming boundary (every triangle edge in two triangles; with --tets every tet face in two tets
or a boundary triangle, and every boundary triangle a tet face), then the flags' bounds on the
edge lengths and the vertex count. Prints one summary line; exit 1 with the reason otherwise.
"""
import argparse
import sys
from collections import Counter


def read_medit(path):
    import numpy as np  # here: `medit` and `sol` run without paying for it
    tok = open(path).read().split()
    out = {}
    i = 0
    sizes = {'Vertices': 4, 'Triangles': 4, 'Tetrahedra': 5, 'Edges': 3, 'Corners': 1,
             'Ridges': 1, 'RequiredVertices': 1, 'RequiredEdges': 1, 'RequiredTriangles': 1}
    while i < len(tok):
        key = tok[i]
        i += 1
        if key in ('MeshVersionFormatted', 'Dimension'):
            i += 1
        elif key in sizes:
            n = int(tok[i])
            i += 1
            w = sizes[key]
            out[key] = np.array(tok[i:i + n * w], float).reshape(n, w)
            i += n * w
        elif key == 'End':
            break
        else:
            sys.exit(f'{path}: unexpected keyword {key}')
    return out


def fail(message):
    print('FAIL:', message)
    sys.exit(1)


def check(args):
    import numpy as np
    mesh = read_medit(args.mesh)
    points = mesh['Vertices'][:, :3]
    tris = mesh.get('Triangles', np.zeros((0, 4)))[:, :3].astype(int) - 1
    tets = mesh.get('Tetrahedra', np.zeros((0, 5)))[:, :4].astype(int) - 1
    n = len(points)
    for name, cells in (('triangle', tris), ('tet', tets)):
        if len(cells) and (cells.min() < 0 or cells.max() >= n):
            fail(f'a {name} vertex index out of range')
    if args.tets and len(tets) == 0:
        fail('no tets')
    if len(tris) == 0:
        fail('no boundary triangles')
    area = np.linalg.norm(np.cross(points[tris[:, 1]] - points[tris[:, 0]],
                                   points[tris[:, 2]] - points[tris[:, 0]]), axis=1)
    if area.min() <= 0:
        fail('a degenerate triangle')
    tri_edges = Counter()
    for t in tris:
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            tri_edges[(min(a, b), max(a, b))] += 1
    if any(c != 2 for c in tri_edges.values()):
        fail('the boundary is not closed and manifold')
    edges = set(tri_edges)
    if len(tets):
        p = points[tets]
        vol = np.einsum('ij,ij->i', np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                        p[:, 3] - p[:, 0])
        if not (np.all(vol > 0) or np.all(vol < 0)):
            fail(f'tets of both orientations or flat ({np.sum(vol > 0)} positive, '
                 f'{np.sum(vol < 0)} negative)')
        faces = Counter()
        for t in tets:
            for f in ((t[0], t[1], t[2]), (t[0], t[1], t[3]), (t[0], t[2], t[3]),
                      (t[1], t[2], t[3])):
                faces[tuple(sorted(f))] += 1
            for a in range(4):
                for b in range(a + 1, 4):
                    edges.add((min(t[a], t[b]), max(t[a], t[b])))
        boundary = {tuple(sorted(t)) for t in tris}
        if any(c > 2 for c in faces.values()):
            fail('a face in three or more tets')
        if {f for f, c in faces.items() if c == 1} != boundary:
            fail('the tets\' boundary faces are not the boundary triangles')
    e = np.array(sorted(edges))
    length = np.linalg.norm(points[e[:, 0]] - points[e[:, 1]], axis=1)
    print(f'vertices {n} triangles {len(tris)} tets {len(tets)} '
          f'edge length min {length.min():.4g} max {length.max():.4g}')
    if args.max_edge is not None and length.max() > args.max_edge:
        fail(f'an edge of {length.max():.4g} is longer than {args.max_edge}')
    if args.min_edge is not None and length.min() < args.min_edge:
        fail(f'an edge of {length.min():.4g} is shorter than {args.min_edge}')
    if args.same_vertices_as:  # -noinsert: as many; with -nomove, the same points
        before = read_medit(args.same_vertices_as)['Vertices'][:, :3]
        if n != len(before):
            fail(f'{n} vertices, the input has {len(before)}')
        if args.unmoved and not np.array_equal(np.unique(points, axis=0),
                                                np.unique(before, axis=0)):
            fail('a vertex moved')
    if args.at_most_vertices_of:
        before = len(read_medit(args.at_most_vertices_of)['Vertices'])
        if n > before:
            fail(f'{n} vertices, more than the input\'s {before}')
    print('VALID')


def medit(args):
    points, tris = [], []
    for line in open(args.obj):
        s = line.split()
        if s and s[0] == 'v':
            points.append(s[1:4])
        elif s and s[0] == 'f':
            tris.append([w.split('/')[0] for w in s[1:4]])
    with open(args.out, 'w') as out:
        out.write(f'MeshVersionFormatted 2\nDimension 3\nVertices\n{len(points)}\n')
        out.writelines(' '.join(p) + ' 0\n' for p in points)
        out.write(f'Triangles\n{len(tris)}\n')
        out.writelines(' '.join(t) + ' 1\n' for t in tris)
        out.write('End\n')


def sol(args):
    n = len(read_medit(args.mesh)['Vertices'])
    with open(args.out, 'w') as out:
        out.write(f'MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n{n}\n1 '
                  f'{3 if args.tensor else 1}\n')
        m = 1 / args.size**2  # the metric of an isotropic size, as Mmg's -A reads it
        value = f'{m} 0 {m} 0 0 {m}' if args.tensor else f'{args.size}'
        out.writelines(value + '\n' for _ in range(n))
        out.write('End\n')


parser = argparse.ArgumentParser()
sub = parser.add_subparsers(dest='command', required=True)
c = sub.add_parser('check')
c.add_argument('mesh')
c.add_argument('--tets', action='store_true')
c.add_argument('--max-edge', type=float)
c.add_argument('--min-edge', type=float)
c.add_argument('--at-most-vertices-of')
c.add_argument('--same-vertices-as')
c.add_argument('--unmoved', action='store_true')
c.set_defaults(run=check)
m = sub.add_parser('medit')
m.add_argument('obj')
m.add_argument('out')
m.set_defaults(run=medit)
s = sub.add_parser('sol')
s.add_argument('mesh')
s.add_argument('out')
s.add_argument('size', type=float)
s.add_argument('--tensor', action='store_true')
s.set_defaults(run=sol)
args = parser.parse_args()
args.run(args)
