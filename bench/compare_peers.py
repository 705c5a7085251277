#!/usr/bin/python3
"""Our adapt beside TetGen, Mmg and Gmsh on the paper's benchmark: speed on one core (issue 40).

  bench/compare_peers.py [--build build] [--cases CDE] [--threads 1,2] [--mmg PATH/mmg3d]

The protocol. For each case of the three-cylinder field (C, D and E by default; A and B on
request), starting from data/sphere480.mesh:
  hdimesh  build/apps/adapt --bench-field X -v 1 (the default) --threads N, one run for each N of
           --threads (1 and 2 by default, in that order); the outputs must be the same bytes
           (cmp), the rows' figures are those of the first run
  TetGen   `tetgen -rq1.4mQ` iterated (Q only silences it): before each round the size at every
           node of the current mesh is re-evaluated from the field and written as a .mtr (TetGen
           adapts to sizes at nodes only); rounds until the tet count changes by less than 2 %
           between two rounds, at most 8
  Mmg      (with --mmg) `mmg3d IN -sol S -out OUT -v -1` iterated the same way, the field's
           sizes at the current mesh's vertices written as a Medit .sol (SolAtVertices, one
           scalar); Mmg's defaults otherwise (hausd 0.01, hgrad 1.3)
  Gmsh     the unit sphere (OpenCASCADE) meshed in 3D with the same field as a MathEval
           background field, one thread
Every tool runs as a child process (subprocess.Popen, then os.wait4 on its pid), so the child's
own rusage gives its CPU time (user + system) and its peak resident set (ru_maxrss, KiB on
Linux), whole process for everyone: reading, setting up, meshing and writing. Wall time is
perf_counter around the child. For the iterated peers CPU and wall are summed over the rounds
and the peak is the largest round's; the field evaluation and the .mtr/.sol writing between
rounds (this script's Python) count for no one. TetGen is serial; Gmsh runs its default 3-D
algorithm on one thread (its HXT, the threaded one, is in compare_volume_peers.py). Our adapt at
-v 1 also computes its quality tables of the input and the output, which its CPU includes (-v 2
would add a summary of the whole mesh after every optimization sweep).

Columns: output tets, CPU s, the wall time of each thread count (`wall 1t`, `wall 2t`: a serial
peer fills the first only) and the speed-up (`1t/2t`, first over last), tets per CPU-second,
microseconds of CPU per output tet, peak RSS in bytes per output tet, and the output measured by
our meshstat against the same field (min Qe, % Qe >= 0.5, % Qt >= 0.66), the largest distance of
a boundary vertex to the unit sphere, the rounds of the iterated peers (* when the cap came
first) and our checker's verdict (meshstat's: clean, or the count per kind; a peer's mesh may
break a rule of ours its format does not know, so read the kinds). Under our row, one line per
further thread count: its CPU, peak and whether its output is byte-identical to the first's (a
FAIL line when not). Under our row, the stage split of adapt's own CPU (its `cpu:` line) and the
refinement rate: the most tets after a refinement pass (adapt's `refinement:` line) per
CPU-second of the refine stage. That count is not the splitting's alone: a pass's count follows
its splits, the projection of the new boundary vertices and the repair of bad tets around them
(optimization), while the refine stage's CPU is the splitting only.

After each case a targets line, each PASS/FAIL with its figure: ours >= 100k tets/CPU-s;
refinement >= 2M tets/CPU-s; min Qe >= 0.3, >= 99 % Qe >= 0.5, >= 99 % Qt >= 0.66; on C our
1-thread wall <= TetGen's iterated wall; on E our peak <= 100 B/tet; on C, D and E (issue 42)
our 2-thread speed-up (1-thread wall / 2-thread wall) >= 1.8x and our 2-thread wall <= TetGen's.
After all cases, when C and E both ran, our us/tet on E within 20 % of C's.

TetGen and Gmsh rows appear only when `tetgen` / `gmsh` are installed (Debian packages of those
names); Mmg's only with --mmg (build Mmg from its repository: cmake -DUSE_SCOTCH=OFF
-DUSE_ELAS=OFF -DUSE_VTK=OFF, target mmg3d).
"""
import argparse, itertools, json, os, re, shutil, subprocess, sys, tempfile, time
from collections import namedtuple

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INPUT = os.path.join(ROOT, 'data/sphere480.mesh')
CASES = {'A': (0.03, 0.03), 'B': (0.01, 0.01), 'C': (0.03, 0.3), 'D': (0.01, 0.3), 'E': (0.01, 0.7)}
DMAX = 1.0 / 3.0
MAX_ROUNDS = 8        # the iterated peers' cap
CONVERGED = 0.02      # ... and their stop: tet count changed by less than this between rounds
MEDIT_WIDTH = {'Vertices': 4, 'Triangles': 4, 'Tetrahedra': 5}

Usage = namedtuple('Usage', 'cpu wall rss')  # CPU s (user + sys), wall s, peak RSS bytes
Run = namedtuple('Run', 'path usage rounds extra')


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


# --- running a child -------------------------------------------------------------------------

def run_child(cmd, log, cwd=None):
    """Runs cmd as a child, its output into the file log; its own rusage and the wall time."""
    with open(log, 'w') as out:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT)
        _, status, ru = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        with open(log) as f:
            tail = f.read()[-2000:]
        raise subprocess.CalledProcessError(proc.returncode, cmd, output=tail)
    return Usage(ru.ru_utime + ru.ru_stime, wall, ru.ru_maxrss * 1024)


def add(total, u):
    """Usage over rounds: CPU and wall summed, the largest peak."""
    return Usage(total.cpu + u.cpu, total.wall + u.wall, max(total.rss, u.rss))


def iterate(round_, tets_before):
    """Calls round_(k) -> (tets, Usage) until the tets change by < CONVERGED between rounds or
    MAX_ROUNDS ran; returns the rounds (a str, '*' when the cap came first) and the usage."""
    total, previous = Usage(0.0, 0.0, 0), tets_before
    for k in range(1, MAX_ROUNDS + 1):
        tets, u = round_(k)
        total = add(total, u)
        if abs(tets - previous) < CONVERGED * previous:
            return str(k), total
        previous = tets
    return f'{MAX_ROUNDS}*', total


# --- Medit files ---------------------------------------------------------------------------

def read_medit(path, keys=('Vertices', 'Tetrahedra')):
    """The sections `keys` of a Medit ASCII mesh (one entity per line) as float arrays, and the
    entity count of every section of MEDIT_WIDTH."""
    sections, counts = {}, {}
    with open(path) as f:
        for line in f:
            words = line.split('#', 1)[0].split()
            if not words or words[0] not in MEDIT_WIDTH:
                continue
            key = words[0]
            while len(words) < 2:
                words += next(f).split('#', 1)[0].split()
            n = counts[key] = int(words[1])
            rows = itertools.islice(f, n)
            if key in keys:
                width = MEDIT_WIDTH[key]
                sections[key] = np.loadtxt(rows, ndmin=2).reshape(n, width) if n else np.zeros((0, width))
            else:
                for _ in rows:
                    pass
    return sections, counts


def boundary_faces(tets):
    """The faces used by exactly one of the (n,4) 0-based tets, as the tet lists them: outward
    when the tets are positive (b c d, a d c, a b d, a c b)."""
    faces = np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 3, 2]], tets[:, [0, 1, 3]],
                            tets[:, [0, 2, 1]]])
    ids = np.sort(faces, axis=1)
    if ids.max(initial=0) < 1 << 21:  # one int64 key a face: a much faster unique
        keys = (ids[:, 0] << 42) | (ids[:, 1] << 21) | ids[:, 2]
        _, first, counts = np.unique(keys, return_index=True, return_counts=True)
    else:
        _, first, counts = np.unique(ids, axis=0, return_index=True, return_counts=True)
    return faces[first[counts == 1]]


def boundary_deviation(path):
    """Largest | |x| - 1 | over vertices of faces used by exactly one tet."""
    s, _ = read_medit(path)
    boundary = np.unique(boundary_faces(s['Tetrahedra'][:, :4].astype(np.int64) - 1))
    p = s['Vertices'][boundary, :3]
    return float(np.max(np.abs(np.linalg.norm(p, axis=1) - 1.0)))


def write_medit(path, vertices, tets):
    """A Medit mesh of (n,3) vertices and (m,4) 0-based tets, its boundary as Triangles: the
    tets turned positive first, so the triangles face outward."""
    a, b, c, d = (vertices[tets[:, k]] for k in range(4))
    negative = np.einsum('ij,ij->i', b - a, np.cross(c - a, d - a)) < 0
    tets = np.where(negative[:, None], tets[:, [0, 2, 1, 3]], tets)
    tris = boundary_faces(tets)
    with open(path, 'w') as f:
        f.write('MeshVersionFormatted 2\nDimension 3\n')
        f.write(f'Vertices\n{len(vertices)}\n')
        np.savetxt(f, np.column_stack([vertices, np.zeros(len(vertices))]), fmt='%.17g %.17g %.17g %d')
        f.write(f'Triangles\n{len(tris)}\n')
        np.savetxt(f, np.column_stack([tris + 1, np.zeros(len(tris), dtype=np.int64)]), fmt='%d')
        f.write(f'Tetrahedra\n{len(tets)}\n')
        np.savetxt(f, np.column_stack([tets + 1, np.zeros(len(tets), dtype=np.int64)]), fmt='%d')
        f.write('End\n')


def write_sol(path, sizes):
    """A Medit .sol of one scalar per vertex (Mmg's isotropic sizes)."""
    with open(path, 'w') as f:
        f.write(f'MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n{len(sizes)}\n1 1\n')
        np.savetxt(f, sizes, fmt='%.17g')
        f.write('End\n')


# --- the tools -----------------------------------------------------------------------------

CPU_LINE = re.compile(r'cpu:\s+total ([\d.]+) s = surface ([\d.]+) \+ refine ([\d.]+) \+ '
                      r'project ([\d.]+) \+ optimize ([\d.]+) \+ other (-?[\d.]+)')


def parse_adapt_log(text):
    """adapt -v 1's stage split (its cpu: line) and the refinement's output: the most tets
    after a refinement pass (its refinement: line), which the final optimization then reduces."""
    cpu = CPU_LINE.search(text)
    stages = dict(zip(('total', 'surface', 'refine', 'project', 'optimize', 'other'),
                      map(float, cpu.groups()))) if cpu else None
    refined = re.search(r'refinement: (\d+) passes, (\d+) tets at most', text)
    return {'stages': stages, 'refine_tets': int(refined.group(2)) if refined else None}


def run_ours(build, case, work, threads):
    """adapt once for each thread count: the first run's Run, its extra holding every run's
    Usage by thread count ('walls') and the counts whose output differs from the first's."""
    runs, differ = {}, []
    for n in threads:
        out = os.path.join(work, f'ours_{case}_{n}t.mesh')
        log = os.path.join(work, f'ours_{case}_{n}t.log')
        runs[n] = run_child([f'{build}/apps/adapt', INPUT, '-o', out, '--bench-field', case, '-v',
                             '1', '--threads', str(n)], log)
        if n == threads[0]:
            first, first_log = out, log
        elif subprocess.run(['cmp', '-s', first, out]).returncode != 0:
            differ.append(n)
    with open(first_log) as f:
        extra = parse_adapt_log(f.read())
    extra.update(threads=runs, differ=differ)
    return Run(first, runs[threads[0]], '-', extra)


def read_tetgen(base):
    """Vertices (n,3) and 0-based tets (m,4) of TetGen's base.node / base.ele."""
    node = np.loadtxt(base + '.node', skiprows=1, comments='#', ndmin=2)
    ele = np.loadtxt(base + '.ele', skiprows=1, comments='#', ndmin=2, dtype=np.int64)
    first = int(node[:, 0].min())
    return node[:, 1:4], ele[:, 1:5] - first


def tetgen_count(base):
    with open(base + '.ele') as f:
        return int(f.readline().split()[0])


def run_tetgen(case, work):
    s, _ = read_medit(INPUT)
    base = os.path.join(work, f'tg_{case}')
    with open(base + '.node', 'w') as f:
        f.write(f"{len(s['Vertices'])} 3 0 0\n")
        np.savetxt(f, np.column_stack([np.arange(1, len(s['Vertices']) + 1), s['Vertices'][:, :3]]),
                   fmt='%d %.17g %.17g %.17g')
    with open(base + '.ele', 'w') as f:
        f.write(f"{len(s['Tetrahedra'])} 4 0\n")
        np.savetxt(f, np.column_stack([np.arange(1, len(s['Tetrahedra']) + 1),
                                       s['Tetrahedra'][:, :4].astype(np.int64)]), fmt='%d')
    names = [base]

    def round_(k):
        name = names[-1]
        nodes = np.loadtxt(name + '.node', skiprows=1, comments='#', ndmin=2)[:, 1:4]
        np.savetxt(name + '.mtr', field(nodes, case), header=f'{len(nodes)} 1', comments='')
        usage = run_child(['tetgen', '-rq1.4mQ', name], f'{base}.log', cwd=work)
        names.append(f'{base}.{k}')
        return tetgen_count(names[-1]), usage

    rounds, usage = iterate(round_, len(s['Tetrahedra']))
    out = base + '_out.mesh'
    write_medit(out, *read_tetgen(names[-1]))
    return Run(out, usage, rounds, None)


def run_mmg(mmg, case, work):
    paths = [INPUT]
    _, counts = read_medit(INPUT, keys=())

    def round_(k):
        s, _ = read_medit(paths[-1], keys=('Vertices',))
        sol = os.path.join(work, f'mmg_{case}.{k}.in.sol')
        write_sol(sol, field(s['Vertices'][:, :3], case))
        out = os.path.join(work, f'mmg_{case}.{k}.mesh')
        usage = run_child([mmg, paths[-1], '-sol', sol, '-out', out, '-v', '-1'],
                          os.path.join(work, f'mmg_{case}.log'))
        paths.append(out)
        return read_medit(out, keys=())[1]['Tetrahedra'], usage

    rounds, usage = iterate(round_, counts['Tetrahedra'])
    return Run(paths[-1], usage, rounds, None)


def run_gmsh(case, work):
    geo = os.path.join(work, f'gmsh_{case}.geo')
    out = os.path.join(work, f'gmsh_{case}.mesh')
    with open(geo, 'w') as f:
        f.write('SetFactory("OpenCASCADE");\nSphere(1) = {0, 0, 0, 1};\n'
                f'Field[1] = MathEval;\nField[1].F = "{gmsh_expression(case)}";\n'
                'Background Field = 1;\n'
                'Mesh.MeshSizeExtendFromBoundary = 0;\nMesh.MeshSizeFromPoints = 0;\n'
                'Mesh.MeshSizeFromCurvature = 0;\nMesh.Optimize = 1;\nGeneral.NumThreads = 1;\n')
    usage = run_child(['gmsh', geo, '-3', '-format', 'mesh', '-o', out, '-v', '0'],
                      os.path.join(work, f'gmsh_{case}.log'))
    return Run(out, usage, '-', None)


# --- measuring and reporting ----------------------------------------------------------------

def measure(build, path, case):
    out = subprocess.run([f'{build}/apps/meshstat', path, '--bench-field', case, '--json'],
                         capture_output=True, text=True)
    text = out.stdout[:out.stdout.rfind('}') + 1]
    q = json.loads(text)
    if not q['clean'] and out.stderr:  # format_violations: its first line, the count per kind
        q['kinds'] = out.stderr.splitlines()[0].rstrip()
    return q


def verdict(q):
    """Our checker's verdict: clean, or the count per kind (a peer's mesh may lack refs our
    strict checker asks for; the kinds tell that from a broken mesh)."""
    return 'clean' if q['clean'] else q.get('kinds') or f"{q['violations']} violations"


def figures(run, q, threads):
    """The speed and memory figures of one row; walls by thread count (a serial peer's under the
    first count only)."""
    tets, u = q['tets'], run.usage
    walls = {n: r.wall for n, r in (run.extra or {}).get('threads', {threads[0]: u}).items()}
    return {'tets': tets, 'cpu': u.cpu, 'wall': u.wall, 'walls': walls, 'rate': tets / u.cpu,
            'us_per_tet': 1e6 * u.cpu / tets, 'bytes_per_tet': u.rss / tets,
            'min_qe': q['min_qe'], 'qe05': q['percent_qe_ge_05'], 'qt066': q['percent_qt_ge_066']}


def header(threads):
    walls = ''.join(f"{f'wall {n}t':>9}" for n in threads)
    speedup = f"{f'{threads[0]}t/{threads[-1]}t':>7}" if len(threads) > 1 else ''
    return (f"{'case':<5}{'tool':<9}{'tets':>10}{'CPU s':>9}{walls}{speedup}{'tets/CPU-s':>11}"
            f"{'us/tet':>8}{'B/tet':>7}{'min Qe':>8}{'Qe>=0.5':>9}{'Qt>=0.66':>10}{'max|r-1|':>10}"
            f"{'rounds':>7}  checker")


def speedup(f, threads):
    """The first thread count's wall over the last's, None when either is missing."""
    a, b = f['walls'].get(threads[0]), f['walls'].get(threads[-1])
    return a / b if len(threads) > 1 and a and b else None


def row(case, tool, f, run, q, deviation, threads):
    walls = ''.join(f"{f['walls'][n]:>9.2f}" if n in f['walls'] else f"{'-':>9}" for n in threads)
    s = speedup(f, threads)
    walls += (f'{s:>6.2f}x' if s else f"{'-':>7}") if len(threads) > 1 else ''
    return (f"{case:<5}{tool:<9}{f['tets']:>10}{f['cpu']:>9.2f}{walls}{f['rate']:>11.0f}"
            f"{f['us_per_tet']:>8.2f}{f['bytes_per_tet']:>7.0f}{f['min_qe']:>8.3f}{f['qe05']:>8.2f}%"
            f"{f['qt066']:>9.2f}%{deviation:>10.1e}{run.rounds:>7}  {verdict(q)}")


def thread_lines(f, extra, threads):
    """Under our row: each further thread count's CPU and peak, and whether its output is the
    first's bytes."""
    lines = []
    for n in threads[1:]:
        u = extra['threads'][n]
        same = n not in extra['differ']
        lines.append(f"     hdimesh {n}t: CPU {u.cpu:.2f} s, wall {u.wall:.2f} s, peak "
                     f"{u.rss / f['tets']:.0f} B/tet; output "
                     + (f'byte-identical to {threads[0]}t (cmp)' if same else
                        f'FAIL: differs from {threads[0]}t (cmp)'))
    return lines


def stage_line(extra):
    """Our stage split and refinement rate, or why they are missing."""
    st, tets = extra['stages'], extra['refine_tets']
    if not st:
        return '     hdimesh stages: no cpu: line in adapt -v 1 output'
    text = (f"     hdimesh CPU in adapt(): surface {st['surface']:.2f} + refine {st['refine']:.2f}"
            f" + project {st['project']:.2f} + optimize {st['optimize']:.2f} + other {st['other']:.2f}"
            f" = {st['total']:.2f} s")
    if tets and st['refine'] > 0:
        extra['refine_rate'] = tets / st['refine']
        text += f"; refinement {tets} tets / {st['refine']:.2f} s = {extra['refine_rate']:.3g} tets/CPU-s"
    return text


def check(name, ok, shown):
    return f"{name} {shown} {'PASS' if ok else 'FAIL'}"


def targets_line(case, results, threads):
    """Issue 40's targets on one case, each PASS/FAIL with its figure."""
    ours = results.get((case, 'hdimesh'))
    if not ours:
        return f'targets {case}: no hdimesh row'
    f, extra = ours
    parts = [check('rate', f['rate'] >= 1e5, f"{f['rate']:.0f} >= 100000 tets/CPU-s")]
    rate = extra.get('refine_rate')
    parts.append(check('refinement', rate is not None and rate >= 2e6,
                       f"{rate:.3g} >= 2e6 tets/CPU-s" if rate else 'unknown'))
    parts.append(check('min Qe', f['min_qe'] >= 0.3, f"{f['min_qe']:.3f} >= 0.3"))
    parts.append(check('Qe>=0.5', f['qe05'] >= 99.0, f"{f['qe05']:.2f}% >= 99%"))
    parts.append(check('Qt>=0.66', f['qt066'] >= 99.0, f"{f['qt066']:.2f}% >= 99%"))
    tetgen = results.get((case, 'TetGen'))
    if case == 'C' and tetgen:
        wall = tetgen[0]['wall']
        parts.append(check('1-thread wall', f['wall'] <= wall,
                           f"{f['wall']:.2f} s <= TetGen {wall:.2f} s"))
    if case in 'CDE' and 1 in f['walls'] and 2 in f['walls']:
        s = f['walls'][1] / f['walls'][2]
        parts.append(check('2-thread speed-up', s >= 1.8,
                           f"{f['walls'][1]:.2f} / {f['walls'][2]:.2f} s = {s:.2f}x >= 1.8x"))
        if tetgen:
            wall = tetgen[0]['wall']
            parts.append(check('2-thread wall', f['walls'][2] <= wall,
                               f"{f['walls'][2]:.2f} s <= TetGen {wall:.2f} s"))
    elif case in 'CDE':
        parts.append('2-thread targets: no 1- and 2-thread runs (--threads 1,2)')
    if case == 'E':
        parts.append(check('peak', f['bytes_per_tet'] <= 100,
                           f"{f['bytes_per_tet']:.0f} <= 100 B/tet"))
    return f'targets {case}: ' + '; '.join(parts)


def scaling_line(results):
    """Our us/tet from C to E within 20 %, when both ran."""
    c, e = results.get(('C', 'hdimesh')), results.get(('E', 'hdimesh'))
    if not (c and e):
        return None
    a, b = c[0]['us_per_tet'], e[0]['us_per_tet']
    change = (b - a) / a
    return 'targets C->E: ' + check('us/tet', abs(change) <= 0.2,
                                    f'{a:.2f} -> {b:.2f} ({100 * change:+.1f}%, within 20%)')


def parse_thread_counts(text):
    """--threads '1,2' -> [1, 2]; exits with a usage line unless distinct counts >= 1."""
    try:
        threads = [int(n) for n in text.split(',')]
    except ValueError:
        threads = []
    if not threads or min(threads) < 1 or len(set(threads)) != len(threads):
        sys.exit('--threads: distinct counts >= 1, e.g. 1,2')
    return threads


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--cases', default='CDE')
    ap.add_argument('--threads', default='1,2',
                    help="adapt's thread counts, one run each; the first gives the row's figures")
    ap.add_argument('--mmg', help="Mmg's mmg3d executable (a bench-only peer)")
    ap.add_argument('--keep', action='store_true', help='keep the work directory')
    args = ap.parse_args()
    if any(c not in CASES for c in args.cases):
        sys.exit(f'--cases: letters of {"".join(CASES)}')
    threads = parse_thread_counts(args.threads)
    work = tempfile.mkdtemp(prefix='hdimesh_peers_')
    runners = [('hdimesh', lambda c: run_ours(args.build, c, work, threads))]
    if shutil.which('tetgen'):
        runners.append(('TetGen', lambda c: run_tetgen(c, work)))
    if args.mmg:
        runners.append(('Mmg', lambda c: run_mmg(args.mmg, c, work)))
    if shutil.which('gmsh'):
        runners.append(('Gmsh', lambda c: run_gmsh(c, work)))
    print(header(threads), flush=True)
    results = {}
    for case in args.cases:
        for tool, run in runners:
            try:
                r = run(case)
            except (subprocess.CalledProcessError, OSError) as e:
                print(f'{case:<5}{tool:<9} failed: {e}', getattr(e, 'output', '') or '', flush=True)
                continue
            q = measure(args.build, r.path, case)
            f = figures(r, q, threads)
            results[(case, tool)] = (f, r.extra or {})
            print(row(case, tool, f, r, q, boundary_deviation(r.path), threads), flush=True)
            if tool == 'hdimesh':
                print(stage_line(r.extra), flush=True)
                for line in thread_lines(f, r.extra, threads):
                    print(line, flush=True)
        print(targets_line(case, results, threads), flush=True)
    line = scaling_line(results)
    if line:
        print(line)
    if args.keep:
        print(f'outputs in {work}')
    else:
        shutil.rmtree(work)


if __name__ == '__main__':
    main()
