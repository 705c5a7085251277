#!/usr/bin/python3
"""A volume from a surface: our adapt beside TetGen and Gmsh on the same closed surfaces (issue 15).

  bench/compare_volume_peers.py [--build build] [--inputs sphere3k,sphere12k,fandisk,...]
                                [--remesh] [--threads 1,2]

Inputs: unit spheres meshed by Gmsh 2-D at h = 0.1 / 0.05 / 0.025 (sphere3k, sphere12k,
sphere48k; interior h = that h) and the raw OBJs of data/ (interior h = 2 % of the bounding box
diagonal). Tools:
  hdimesh  build/apps/adapt IN -o OUT.mesh --hsiz H --keep-surface --threads N (or without
           --keep-surface, --remesh), once for each N of --threads (1 and 2 by default); the
           outputs must be the same bytes (cmp), the row's figures are the first run's
  TetGen   tetgen -pYq1.414a(H^3/(6 sqrt 2))                 (serial; when `tetgen` is installed)
  Gmsh-1   Merge the STL, Surface Loop, Volume, MeshSizeMax = H, Delaunay, Optimize = 1, one
           thread                                                      (when `gmsh` is installed)
  Gmsh-10  the same with HXT, -nt 1; and a row `Gmsh-10 nt2` with -nt 2 (General.NumThreads 2,
           HXT's threaded run: its own output, so its own figures and checker verdict)
  Netgen   build/bench/netgen_volume IN.off OUT.mesh H: nglib, outward triangles, maxh = H, the
           default 3 optimization steps, serial               (when libnglib-dev was found by CMake)
Every tool runs as a child process (compare_peers.run_child: os.wait4 on its pid), so its own
rusage gives its CPU time (user + system) and wall time is perf_counter around it. Columns: the
CPU of the row's run, its wall under `wall 1t` or `wall 2t` (ours: both), the speed-up `1t/2t`
(ours: 1-thread wall / 2-thread wall; Gmsh-10 nt2: the -nt 1 row's wall / its own), and the
checker column, build/apps/meshstat's verdict (clean, or the count per kind; a peer's mesh may
break a rule of ours its format does not know, so read the kinds). Under our row a line says
whether the thread counts' outputs are byte-identical (a FAIL line when not); after each input
a targets line (issue 42): our 2-thread speed-up >= 1.8x and our 2-thread wall <= Gmsh HXT's
-nt 2 wall (the issue's target is on sphere48k; it is printed for every input).
Every output is scored here by one computation: Qe = 2 sqrt 6 rho / longest edge, dihedral
angles, and Qt of every edge against H; the figures are given over all tets and over the tets
with no boundary face whose smallest angle is under 10 degrees (a raw input triangle can force
a bad tet). For Netgen the note also gives the driver's own thread CPU time around
Ng_GenerateVolumeMesh alone.
Netgen's output changes with the order of the input points and with small changes of H, so it
gets the points in the order every other tool gets (Gmsh's for the spheres, the OBJ's otherwise)
and the same unrounded H.
"""
import argparse, json, os, shutil, subprocess, sys, tempfile

import numpy as np

import compare_peers

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPHERES = {'sphere3k': 0.1, 'sphere12k': 0.05, 'sphere48k': 0.025}
OBJS = ['fandisk', 'spot', 'rocker-arm', 'cheburashka']


def read_medit(path):
    """Vertices (n,3), tets (m,4) 0-based, of a Medit ASCII mesh."""
    sections, _ = compare_peers.read_medit(path)
    return sections['Vertices'][:, :3], sections['Tetrahedra'][:, :4].astype(np.int64) - 1


def read_obj(path):
    verts, faces = [], []
    for line in open(path):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == 'v':
            verts.append([float(x) for x in parts[1:4]])
        elif parts[0] == 'f':
            ids = [int(p.split('/')[0]) for p in parts[1:]]
            for k in range(1, len(ids) - 1):
                faces.append([ids[0], ids[k], ids[k + 1]])
    v = np.array(verts)
    f = np.array(faces) - 1
    return v, f


def write_stl(path, v, f):
    with open(path, 'w') as out:
        out.write('solid s\n')
        for a, b, c in f:
            n = np.cross(v[b] - v[a], v[c] - v[a])
            n = n / (np.linalg.norm(n) or 1.0)
            out.write(f'facet normal {n[0]!r} {n[1]!r} {n[2]!r}\nouter loop\n')
            for p in (v[a], v[b], v[c]):
                out.write(f'vertex {p[0]!r} {p[1]!r} {p[2]!r}\n')
            out.write('endloop\nendfacet\n')
        out.write('endsolid s\n')


def write_off(path, v, f):
    with open(path, 'w') as out:
        out.write(f'OFF\n{len(v)} {len(f)} 0\n')
        for p in v:
            out.write(f'{p[0]!r} {p[1]!r} {p[2]!r}\n')
        for a, b, c in f:
            out.write(f'3 {a} {b} {c}\n')


def gmsh_sphere(work, name, h):
    """A unit sphere surface meshed by Gmsh 2-D: vertices and outward triangles."""
    geo = os.path.join(work, name + '_surf.geo')
    msh = os.path.join(work, name + '_surf.mesh')
    with open(geo, 'w') as out:
        out.write(f'SetFactory("OpenCASCADE");\nSphere(1) = {{0, 0, 0, 1}};\n'
                  f'Mesh.MeshSizeMin = {h};\nMesh.MeshSizeMax = {h};\n'
                  'Mesh.MeshSizeFromCurvature = 0;\n')
    subprocess.run(['gmsh', geo, '-2', '-format', 'mesh', '-o', msh, '-v', '0'], check=True)
    text = '\n'.join(line.split('#', 1)[0] for line in open(msh)).split()
    i = text.index('Vertices')
    n = int(text[i + 1])
    v = np.array(text[i + 2:i + 2 + 4 * n], dtype=float).reshape(n, 4)[:, :3]
    i = text.index('Triangles')
    m = int(text[i + 1])
    f = np.array(text[i + 2:i + 2 + 4 * m], dtype=np.int64).reshape(m, 4)[:, :3] - 1
    # outward: the enclosed volume is positive
    vol = np.einsum('ij,ij->i', v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]])).sum()
    if vol < 0:
        f = f[:, [0, 2, 1]]
    used = np.unique(f)
    remap = -np.ones(len(v), dtype=np.int64)
    remap[used] = np.arange(len(used))
    return v[used], remap[f]


def score(points, tets, h, bad_triangle_keys):
    p = points
    a, b, c, d = (p[tets[:, k]] for k in range(4))
    vol = np.einsum('ij,ij->i', b - a, np.cross(c - a, d - a)) / 6.0
    faces = [(b, c, d), (a, d, c), (a, b, d), (a, c, b)]
    area = sum(0.5 * np.linalg.norm(np.cross(y - x, z - x), axis=1) for x, y, z in faces)
    edges = [(a, b), (a, c), (a, d), (b, c), (b, d), (c, d)]
    longest = np.sqrt(np.max([np.sum((y - x) ** 2, axis=1) for x, y in edges], axis=0))
    qe = 2 * np.sqrt(6) * (3 * vol / area) / longest
    # dihedral at each edge from the two face normals
    normals = [np.cross(y - x, z - x) for x, y, z in faces]
    normals = [n / np.linalg.norm(n, axis=1)[:, None] for n in normals]
    dihedral = []
    for i in range(4):
        for j in range(i + 1, 4):
            cos = -np.einsum('ij,ij->i', normals[i], normals[j])
            dihedral.append(np.degrees(np.arccos(np.clip(cos, -1, 1))))
    dihedral = np.array(dihedral).T
    # edges, once each
    e = np.concatenate([tets[:, [0, 1]], tets[:, [0, 2]], tets[:, [0, 3]], tets[:, [1, 2]],
                        tets[:, [1, 3]], tets[:, [2, 3]]])
    e.sort(axis=1)
    e = np.unique(e, axis=0)
    length = np.linalg.norm(p[e[:, 1]] - p[e[:, 0]], axis=1)
    qt = np.minimum(h / length, length / h)
    # tets holding a bad input triangle
    keep = np.ones(len(tets), dtype=bool)
    if bad_triangle_keys:
        for k, (x, y, z) in enumerate([(1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2)]):
            keys = np.sort(tets[:, [x, y, z]], axis=1)
            hits = np.array([tuple(r) in bad_triangle_keys for r in keys])
            keep &= ~hits

    def stats(mask):
        return {'tets': int(mask.sum()), 'min_qe': float(qe[mask].min()),
                'qe05': 100.0 * float((qe[mask] >= 0.5).mean()),
                'min_dih': float(dihedral[mask].min()), 'max_dih': float(dihedral[mask].max())}

    return stats(np.ones(len(tets), dtype=bool)), stats(keep), 100.0 * float((qt >= 0.66).mean()), \
        int((vol <= 0).sum())


def bad_triangles(v, f, max_angle_deg=10.0):
    """Sorted vertex triples of input triangles with an angle under max_angle_deg."""
    keys = set()
    for tri in f:
        pa, pb, pc = v[tri[0]], v[tri[1]], v[tri[2]]
        angles = []
        for x, y, z in ((pa, pb, pc), (pb, pc, pa), (pc, pa, pb)):
            u, w = y - x, z - x
            cos = np.dot(u, w) / (np.linalg.norm(u) * np.linalg.norm(w) + 1e-300)
            angles.append(np.degrees(np.arccos(np.clip(cos, -1, 1))))
        if min(angles) < max_angle_deg:
            keys.add(tuple(sorted(int(x) for x in tri)))
    return keys


def timed(cmd, log, cwd=None):
    """cmd as a child (compare_peers.run_child), its output into the file log: its Usage."""
    return compare_peers.run_child(cmd, log, cwd=cwd)


def checker(build, path):
    """meshstat's verdict on a mesh: clean, or the count per kind."""
    out = subprocess.run([f'{build}/apps/meshstat', path, '--json'], capture_output=True, text=True)
    try:
        q = json.loads(out.stdout[:out.stdout.rfind('}') + 1])
    except ValueError:
        return 'unreadable'
    if q['clean']:
        return 'clean'
    return out.stderr.splitlines()[0].rstrip() if out.stderr else f"{q['violations']} violations"


def run_ours(build, work, name, v, f, h, keep, threads):
    """adapt once for each thread count: the first output, the first Usage and a note of the
    walls by thread count and the counts whose output differs from the first's."""
    obj = os.path.join(work, name + '.obj')
    with open(obj, 'w') as out:
        for p in v:
            out.write(f'v {p[0]!r} {p[1]!r} {p[2]!r}\n')
        for a, b, c in f:
            out.write(f'f {a + 1} {b + 1} {c + 1}\n')
    runs, differ = {}, []
    for n in threads:
        out = os.path.join(work, f'{name}_ours_{n}t.mesh')
        cmd = [f'{build}/apps/adapt', obj, '-o', out, '--hsiz', repr(h), '-v', '0',
               '--threads', str(n)]
        if keep:
            cmd.append('--keep-surface')
        runs[n] = timed(cmd, os.path.join(work, f'{name}_ours_{n}t.log'))
        if n != threads[0] and subprocess.run(['cmp', '-s', first, out]).returncode != 0:
            differ.append(n)
        if n == threads[0]:
            first = out
    return first, runs[threads[0]], {'walls': {n: u.wall for n, u in runs.items()},
                                     'cpus': {n: u.cpu for n, u in runs.items()}, 'differ': differ}


def run_tetgen(work, name, v, f, h):
    off = os.path.join(work, name + '_tg.off')
    write_off(off, v, f)
    vol = h ** 3 / (6 * np.sqrt(2))
    usage = timed(['tetgen', f'-pYq1.414a{vol:.6g}gQ', off], os.path.join(work, name + '_tg.log'),
                  cwd=work)
    return os.path.join(work, name + '_tg.1.mesh'), usage, {'walls': {1: usage.wall}}


def run_gmsh(work, name, v, f, h, algorithm, nt=1):
    """Gmsh on nt threads: the geo file sets General.NumThreads too, as it is read after the
    command line's -nt and would override it."""
    stl = os.path.join(work, name + '_gm.stl')
    if not os.path.exists(stl):
        write_stl(stl, v, f)
    geo = os.path.join(work, f'{name}_gm{algorithm}_nt{nt}.geo')
    out = os.path.join(work, f'{name}_gm{algorithm}_nt{nt}.mesh')
    with open(geo, 'w') as g:
        g.write(f'Merge "{stl}";\nSurface Loop(1) = {{1}};\nVolume(1) = {{1}};\n'
                f'Mesh.MeshSizeMax = {h};\nMesh.Algorithm3D = {algorithm};\n'
                f'Mesh.Optimize = 1;\nGeneral.NumThreads = {nt};\n')
    usage = timed(['gmsh', geo, '-3', '-format', 'mesh', '-o', out, '-v', '0', '-nt', str(nt)],
                  os.path.join(work, f'{name}_gm{algorithm}_nt{nt}.log'))
    return out, usage, {'walls': {nt: usage.wall}}


def run_netgen(binary, work, name, v, f, h):
    off = os.path.join(work, name + '_ng.off')
    write_off(off, v, f)
    out = os.path.join(work, name + '_ng.mesh')
    log = os.path.join(work, name + '_ng.log')
    usage = timed([binary, off, out, repr(h)], log, cwd=work)
    with open(log, errors='replace') as text:
        meshing = [line.split()[1] for line in text if line.startswith('seconds ')]
    note = f'Ng_GenerateVolumeMesh {float(meshing[-1]):.2f} s' if meshing else ''
    return out, usage, {'walls': {1: usage.wall}, 'note': note}


def targets_line(name, rows, threads):
    """Issue 42's targets on one input, each PASS/FAIL with its figures."""
    ours = rows.get('hdimesh')
    if not ours or not {1, 2} <= set(ours['walls']):
        return f'targets {name}: no hdimesh 1- and 2-thread runs (--threads 1,2)'
    w1, w2 = ours['walls'][1], ours['walls'][2]
    parts = [compare_peers.check('2-thread speed-up', w1 / w2 >= 1.8,
                                 f'{w1:.2f} / {w2:.2f} s = {w1 / w2:.2f}x >= 1.8x')]
    gmsh = rows.get('Gmsh-10 nt2')
    if gmsh:
        wall = gmsh['walls'][2]
        parts.append(compare_peers.check('2-thread wall', w2 <= wall,
                                         f'{w2:.2f} s <= Gmsh HXT -nt 2 {wall:.2f} s'))
    return f'targets {name}: ' + '; '.join(parts)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--inputs', default='sphere3k,sphere12k,fandisk,spot,rocker-arm,cheburashka')
    ap.add_argument('--remesh', action='store_true', help='let adapt remesh the surface first')
    ap.add_argument('--threads', default='1,2',
                    help="adapt's thread counts, one run each; the first gives the row's figures")
    args = ap.parse_args()
    threads = compare_peers.parse_thread_counts(args.threads)
    columns = sorted(set(threads) | {1, 2})  # the wall columns: ours, and Gmsh HXT's -nt 1 and 2
    work = tempfile.mkdtemp(prefix='hdimesh_volpeers_')
    have_gmsh = shutil.which('gmsh') is not None
    netgen = os.path.abspath(os.path.join(args.build, 'bench', 'netgen_volume'))
    walls = ''.join(f"{f'wall {n}t':>8}" for n in columns)
    print(f"{'input':<12}{'tool':<12}{'tets':>9}{'cpu s':>8}{walls}{'1t/2t':>7}{'tets/s':>9}"
          f"{'min Qe':>8}{'Qe>=.5':>8}{'dihedral':>13}{'Qt>=.66':>8}   "
          f"{'without bad-triangle tets':<37}checker")
    for name in args.inputs.split(','):
        if name in SPHERES:
            if not have_gmsh:
                continue
            h = SPHERES[name]
            v, f = gmsh_sphere(work, name, h)
        else:
            v, f = read_obj(os.path.join(ROOT, 'data', name + '.obj'))
            h = 0.02 * float(np.linalg.norm(v.max(axis=0) - v.min(axis=0)))
        bad = bad_triangles(v, f)
        runners = [('hdimesh', lambda: run_ours(args.build, work, name, v, f, h, not args.remesh,
                                                threads))]
        if shutil.which('tetgen'):
            runners.append(('TetGen', lambda: run_tetgen(work, name, v, f, h)))
        if have_gmsh:
            runners.append(('Gmsh-1', lambda: run_gmsh(work, name, v, f, h, 1)))
            runners.append(('Gmsh-10', lambda: run_gmsh(work, name, v, f, h, 10)))
            runners.append(('Gmsh-10 nt2', lambda: run_gmsh(work, name, v, f, h, 10, nt=2)))
        if os.access(netgen, os.X_OK):
            runners.append(('Netgen', lambda: run_netgen(netgen, work, name, v, f, h)))
        rows = {}
        for tool, run in runners:
            try:
                path, usage, extra = run()
            except (subprocess.CalledProcessError, OSError) as e:
                message = (getattr(e, 'output', '') or '').strip().splitlines()
                print(f'{name:<12}{tool:<12} failed: {message[-1] if message else e}', flush=True)
                continue
            rows[tool] = extra
            seconds = usage.cpu
            points, tets = read_medit(path)
            if not len(tets):  # a broken run may write no tets: nothing to score
                print(f'{name:<12}{tool:<12} no tets in its output; checker: '
                      f'{checker(args.build, path)}', flush=True)
                continue
            if len(tets) and (np.einsum('ij,ij->i', points[tets[:, 1]] - points[tets[:, 0]],
                                        np.cross(points[tets[:, 2]] - points[tets[:, 0]],
                                                 points[tets[:, 3]] - points[tets[:, 0]])) < 0).mean() > 0.5:
                tets = tets[:, [0, 2, 1, 3]]  # a tool writing negative tets
            # the bad input triangles, in the output's numbering (matched by position)
            index = {tuple(np.round(p, 12)): i for i, p in enumerate(points)}
            bad_out = set()
            for key in bad:
                ids = [index.get(tuple(np.round(v[k], 12))) for k in key]
                if None not in ids:
                    bad_out.add(tuple(sorted(ids)))
            all_, clean, qt, negative = score(points, tets, h, bad_out)
            rate = all_['tets'] / seconds if seconds > 0 else float('inf')
            notes = ([f'{negative} non-positive'] if negative else []) + \
                ([extra['note']] if extra.get('note') else [])
            note = f"  ({'; '.join(notes)})" if notes else ''
            walls = ''.join(f"{extra['walls'][n]:>8.2f}" if n in extra['walls'] else f"{'-':>8}"
                            for n in columns)
            if tool == 'Gmsh-10 nt2' and 'Gmsh-10' in rows:
                extra['speedup'] = rows['Gmsh-10']['walls'][1] / extra['walls'][2]
            elif len(threads) > 1 and len(extra['walls']) > 1:
                extra['speedup'] = extra['walls'][threads[0]] / extra['walls'][threads[-1]]
            speedup = f"{extra['speedup']:>6.2f}x" if 'speedup' in extra else f"{'-':>7}"
            without = (f"min Qe {clean['min_qe']:.3f}, {clean['qe05']:.1f}%, "
                       f"dih >= {clean['min_dih']:.1f}")
            print(f"{name:<12}{tool:<12}{all_['tets']:>9}{seconds:>8.2f}{walls}{speedup}"
                  f"{rate:>9.0f}"
                  f"{all_['min_qe']:>8.3f}{all_['qe05']:>7.1f}%"
                  f"{all_['min_dih']:>6.1f}-{all_['max_dih']:<6.1f}{qt:>7.1f}%   "
                  f"{without:<37}{checker(args.build, path)}{note}", flush=True)
            for n in extra.get('differ', None) or []:
                print(f'{name:<12}hdimesh {n}t FAIL: output differs from {threads[0]}t (cmp)',
                      flush=True)
            if tool == 'hdimesh' and len(threads) > 1 and not extra['differ']:
                cpus = ', '.join(f"{n}t {extra['cpus'][n]:.2f} s" for n in threads)
                print(f"{name:<12}hdimesh outputs at {', '.join(f'{n}t' for n in threads)}: "
                      f'byte-identical (cmp); CPU {cpus}', flush=True)
        print(targets_line(name, rows, threads), flush=True)
    shutil.rmtree(work)


if __name__ == '__main__':
    main()
