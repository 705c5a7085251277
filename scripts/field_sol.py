#!/usr/bin/env python3
"""Fields at a Medit mesh's vertices for adapt --field, and their check after the transfer.

  field_sol.py make MESH OUT.sol     three solutions: a linear scalar, a linear vector and the
                                     smooth scalar sin(2x) cos(3y) + z^2
  field_sol.py check MESH FIELD.sol  the carried solutions against the same functions at MESH's
                                     vertices: prints each one's max error; exits 1 when the
                                     linear ones are off by more than --tolerance (1e-12)
  field_sol.py check-msh OUT.msh     the same for a Gmsh 4.1 ASCII file's $NodeData field1,
                                     field2, field3 at its own nodes
An ASCII .mesh only (Vertices section); no numpy needed.
"""
import math
import sys


def vertices(path):
    tokens = open(path).read().split()
    i = tokens.index('Vertices')
    n = int(tokens[i + 1])
    v = tokens[i + 2:i + 2 + 4 * n]
    return [(float(v[4 * k]), float(v[4 * k + 1]), float(v[4 * k + 2])) for k in range(n)]


def linear(p):
    return 0.7 + 1.3 * p[0] - 2.1 * p[1] + 0.4 * p[2]


def vector(p):
    return [c - 2 * p[c] + p[(c + 1) % 3] for c in range(3)]


def smooth(p):
    return math.sin(2 * p[0]) * math.cos(3 * p[1]) + p[2] * p[2]


def make(mesh, out):
    with open(out, 'w') as f:
        points = vertices(mesh)
        f.write('MeshVersionFormatted 2\n\nDimension 3\n\nSolAtVertices\n%d\n3 1 2 1\n' % len(points))
        for p in points:
            f.write(' '.join(repr(x) for x in [linear(p)] + vector(p) + [smooth(p)]) + '\n')
        f.write('\nEnd\n')


def gmsh(path):
    """A Gmsh 4.1 ASCII file's nodes by tag and its $NodeData by name, rows by node tag."""
    lines = open(path).read().split('\n')
    points, data, i = {}, {}, 0
    while i < len(lines):
        if lines[i] == '$Nodes':
            i += 2
            while lines[i] != '$EndNodes':
                n = int(lines[i].split()[3])
                for k in range(n):
                    points[int(lines[i + 1 + k])] = [float(x) for x in lines[i + 1 + n + k].split()]
                i += 1 + 2 * n
        elif lines[i] == '$NodeData':
            name = lines[i + 2].strip('"') if int(lines[i + 1]) else ''
            j = i + 2 + int(lines[i + 1])
            j += 1 + int(lines[j])
            n = int(lines[j + 3])
            rows = [lines[j + 1 + int(lines[j]) + k].split() for k in range(n)]
            data[name] = {int(r[0]): [float(x) for x in r[1:]] for r in rows}
            i = j
        i += 1
    return points, data


def check_msh(path, tolerance):
    points, data = gmsh(path)
    if sorted(data) != ['field1', 'field2', 'field3'] or any(len(d) != len(points) for d in data.values()):
        print('layout differs: %d nodes, $NodeData %s' % (len(points), sorted(data)))
        return 1
    errors = [max(max(abs(a - b) for a, b in zip(data[name][t], f(p))) for t, p in points.items())
              for name, f in (('field1', lambda p: [linear(p)]), ('field2', vector),
                              ('field3', lambda p: [smooth(p)]))]
    print('nodes %d  linear max error %.3g  vector max error %.3g  smooth max error %.3g'
          % ((len(points),) + tuple(errors)))
    return 0 if max(errors[:2]) <= tolerance else 1


def check(mesh, sol, tolerance):
    points = vertices(mesh)
    tokens = open(sol).read().split()
    i = tokens.index('SolAtVertices')
    n = int(tokens[i + 1])
    if n != len(points) or tokens[i + 2:i + 6] != ['3', '1', '2', '1']:
        print('layout differs: %s vertices, types %s' % (n, tokens[i + 2:i + 6]))
        return 1
    values = [float(x) for x in tokens[i + 6:i + 6 + 5 * n]]
    e_linear = e_vector = e_smooth = 0.0
    for k, p in enumerate(points):
        row = values[5 * k:5 * k + 5]
        e_linear = max(e_linear, abs(row[0] - linear(p)))
        e_vector = max(e_vector, max(abs(a - b) for a, b in zip(row[1:4], vector(p))))
        e_smooth = max(e_smooth, abs(row[4] - smooth(p)))
    print('vertices %d  linear max error %.3g  vector max error %.3g  smooth max error %.3g'
          % (n, e_linear, e_vector, e_smooth))
    return 0 if max(e_linear, e_vector) <= tolerance else 1


if __name__ == '__main__':
    args = sys.argv[1:]
    tolerance = 1e-12
    if '--tolerance' in args:
        k = args.index('--tolerance')
        tolerance = float(args[k + 1])
        del args[k:k + 2]
    if len(args) == 3 and args[0] == 'make':
        make(args[1], args[2])
    elif len(args) == 3 and args[0] == 'check':
        sys.exit(check(args[1], args[2], tolerance))
    elif len(args) == 2 and args[0] == 'check-msh':
        sys.exit(check_msh(args[1], tolerance))
    else:
        sys.exit(__doc__)
