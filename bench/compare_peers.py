#!/usr/bin/python3
"""Our adapt beside TetGen and Gmsh on the paper's benchmark (issue 4's comparison table).

  bench/compare_peers.py [--build build] [--cases AC] [--tetgen-iterations 4]

For each case of the three-cylinder field, starting from data/sphere480.mesh:
  hdimesh  build/apps/adapt --bench-field X
  TetGen   `tetgen -rqmgQ` repeated: the size at every node is re-evaluated from the field
           and written as a .mtr before each run (TetGen adapts to sizes at nodes only)
  Gmsh     the unit sphere (OpenCASCADE) meshed in 3D with the same field as a MathEval
           background field
Every output is measured by our meshstat against the same field (tet shape, sizes), and by
the largest distance of a boundary vertex to the unit sphere. TetGen and Gmsh rows appear
only when `tetgen` / `gmsh` are installed (Debian packages of those names).
"""
import argparse, json, os, shutil, subprocess, sys, tempfile, time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASES = {'A': (0.03, 0.03), 'B': (0.01, 0.01), 'C': (0.03, 0.3), 'D': (0.01, 0.3), 'E': (0.01, 0.7)}
DMAX = 1.0 / 3.0


def field(p, case):
    """The benchmark field (method.md §2), vectorized over an (n,3) array."""
    dmin, r = CASES[case]
    h = np.full(len(p), DMAX)
    x, y, z = p[:, 0], p[:, 1], p[:, 2]
    for rho in (np.hypot(y, z), np.hypot(x, z), np.hypot(x, y)):
        d = np.abs(rho - r)
        h = np.minimum(h, np.minimum((1 - d) * dmin + d * DMAX, DMAX))
    return h


def gmsh_expression(case):
    dmin, r = CASES[case]
    terms = []
    for rho in ('Sqrt(y*y+z*z)', 'Sqrt(x*x+z*z)', 'Sqrt(x*x+y*y)'):
        d = f'Fabs({rho}-{r})'
        terms.append(f'Min((1-{d})*{dmin}+{d}*{DMAX},{DMAX})')
    return f'Min({terms[0]},Min({terms[1]},{terms[2]}))'


def read_medit_sections(path):
    """Vertices, tetrahedra (0-based) and boundary-triangle vertex ids of a Medit ASCII mesh."""
    text = '\n'.join(line.split('#', 1)[0] for line in open(path))
    tokens = text.split()
    out, i = {}, 0
    while i < len(tokens):
        key = tokens[i]
        width = {'Vertices': 4, 'Triangles': 4, 'Tetrahedra': 5, 'Edges': 3, 'Corners': 1,
                 'Ridges': 1, 'RequiredVertices': 1, 'RequiredEdges': 1,
                 'RequiredTriangles': 1}.get(key)
        if width:
            n = int(tokens[i + 1])
            out[key] = np.array(tokens[i + 2:i + 2 + n * width], dtype=float).reshape(n, width)
            i += 2 + n * width
        else:
            i += 1
    return out


def boundary_deviation(path):
    """Largest | |x| - 1 | over vertices of faces used by exactly one tet."""
    s = read_medit_sections(path)
    tets = s['Tetrahedra'][:, :4].astype(np.int64) - 1
    faces = np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 2, 3]], tets[:, [0, 1, 3]], tets[:, [0, 1, 2]]])
    faces.sort(axis=1)
    uniq, counts = np.unique(faces, axis=0, return_counts=True)
    boundary = np.unique(uniq[counts == 1])
    p = s['Vertices'][boundary, :3]
    return float(np.max(np.abs(np.linalg.norm(p, axis=1) - 1.0)))


def measure(build, path, case):
    out = subprocess.run([f'{build}/apps/meshstat', path, '--bench-field', case, '--json'],
                         capture_output=True, text=True)
    text = out.stdout[:out.stdout.rfind('}') + 1]
    return json.loads(text)


def verdict(tool, q):
    """Our checker's verdict on our output. Peers' .mesh files list interior faces among their
    Triangles (TetGen) or omit refs, which our strict checker reports, so it is not shown."""
    if tool != 'hdimesh':
        return '-'
    return 'clean' if q['clean'] else f"{q['violations']} violations"


def run_ours(build, case, work):
    out = os.path.join(work, f'ours_{case}.mesh')
    start = time.perf_counter()
    subprocess.run([f'{build}/apps/adapt', os.path.join(ROOT, 'data/sphere480.mesh'), '-o', out,
                    '--bench-field', case, '-v', '0'], check=True)
    return out, time.perf_counter() - start


def run_tetgen(case, work, iterations):
    s = read_medit_sections(os.path.join(ROOT, 'data/sphere480.mesh'))
    base = os.path.join(work, f'tg_{case}')
    with open(base + '.node', 'w') as f:
        f.write(f"{len(s['Vertices'])} 3 0 0\n")
        for i, v in enumerate(s['Vertices'], 1):
            f.write(f'{i} {v[0]!r} {v[1]!r} {v[2]!r}\n')
    with open(base + '.ele', 'w') as f:
        f.write(f"{len(s['Tetrahedra'])} 4 0\n")
        for i, t in enumerate(s['Tetrahedra'].astype(int), 1):
            f.write(f'{i} {t[0]} {t[1]} {t[2]} {t[3]}\n')
    name, seconds = base, 0.0
    for k in range(1, iterations + 1):
        nodes = np.loadtxt(name + '.node', skiprows=1, comments='#')[:, 1:4]
        np.savetxt(name + '.mtr', field(nodes, case), header=f'{len(nodes)} 1', comments='')
        start = time.perf_counter()
        subprocess.run(['tetgen', '-rqmgQ', name], check=True, cwd=work, stdout=subprocess.DEVNULL)
        seconds += time.perf_counter() - start
        name = f'{base}.{k}' if k == 1 else f'{name.rsplit(".", 1)[0]}.{k}'
    return name + '.mesh', seconds


def run_gmsh(case, work):
    geo = os.path.join(work, f'gmsh_{case}.geo')
    out = os.path.join(work, f'gmsh_{case}.mesh')
    with open(geo, 'w') as f:
        f.write('SetFactory("OpenCASCADE");\nSphere(1) = {0, 0, 0, 1};\n'
                f'Field[1] = MathEval;\nField[1].F = "{gmsh_expression(case)}";\n'
                'Background Field = 1;\n'
                'Mesh.MeshSizeExtendFromBoundary = 0;\nMesh.MeshSizeFromPoints = 0;\n'
                'Mesh.MeshSizeFromCurvature = 0;\nMesh.Optimize = 1;\nGeneral.NumThreads = 1;\n')
    start = time.perf_counter()
    subprocess.run(['gmsh', geo, '-3', '-format', 'mesh', '-o', out, '-v', '0'], check=True)
    return out, time.perf_counter() - start


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--cases', default='AC')
    ap.add_argument('--tetgen-iterations', type=int, default=4)
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix='hdimesh_peers_')
    runners = [('hdimesh', lambda c: run_ours(args.build, c, work))]
    if shutil.which('tetgen'):
        runners.append((f'TetGen x{args.tetgen_iterations}', lambda c: run_tetgen(c, work, args.tetgen_iterations)))
    if shutil.which('gmsh'):
        runners.append(('Gmsh', lambda c: run_gmsh(c, work)))
    print(f"{'case':<5}{'tool':<12}{'tets':>10}{'time s':>9}{'tets/s':>10}{'min Qe':>8}"
          f"{'Qe>=0.5':>9}{'Qt>=0.66':>10}{'too long':>10}{'max|r-1|':>10}  checker")
    for case in args.cases:
        for tool, run in runners:
            try:
                path, seconds = run(case)
            except subprocess.CalledProcessError as e:
                print(f'{case:<5}{tool:<12} failed: {e}')
                continue
            q = measure(args.build, path, case)
            print(f"{case:<5}{tool:<12}{q['tets']:>10}{seconds:>9.2f}{q['tets'] / seconds:>10.0f}"
                  f"{q['min_qe']:>8.3f}{q['percent_qe_ge_05']:>8.2f}%{q['percent_qt_ge_066']:>9.2f}%"
                  f"{q['percent_too_long']:>9.2f}%{boundary_deviation(path):>10.1e}  {verdict(tool, q)}",
                  flush=True)
    shutil.rmtree(work)


if __name__ == '__main__':
    main()
