#!/usr/bin/python3
"""The coupled adaptation's table (issue 16): adapt on Gmsh tet meshes of real surfaces, beside
surfremesh on the same surfaces, refining (1 % of the diagonal) and coarsening (4 %).

  bench/bench_coupled.py --volumes DIR --surfaces DIR [--build build] [--models fandisk,...]
                         [--fractions 0.01,0.04] [--extra "--nosurf"] [--round-trip 0.01,0.04]
                         [--mmg PATH/mmg3d] [--threads 1,2]

For each model X, DIR/X.msh is the tet mesh and DIR/X.obj its input surface. Boundary columns
come from scripts/surfstat.py against the input surface, volume columns from
scripts/meshstat.py --hsiz h; CPU is adapt's own "cpu: total" (parse, read and write excluded);
the checker column is adapt --check's verdict on its output (volume/check/check.h).
adapt runs once for each thread count of --threads (1 and 2 by default, `--threads N`), each a
child process (os.wait4 on its pid) timed by perf_counter: the `wall 1t` and `wall 2t` columns and
the speed-up `1t/2t` (first count's wall over the last's); the other columns are the first run's.
Under an adapt row, a line: the speed-up against issue 42's 1.8x and whether the outputs are
byte-identical (cmp), PASS/FAIL each. With --mmg, Mmg
runs on the same tet mesh (converted to Medit by meshconvert) with -hsiz h, its defaults
otherwise; its CPU is the whole process's (user + system, reading and writing included).
"""
import argparse, json, os, re, resource, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PY = '/usr/bin/python3'  # Debian's, with numpy and scipy


def boundary_obj(mesh_path, obj_path):
    """The Triangles section of a Medit ASCII mesh, as an OBJ."""
    tokens = open(mesh_path).read().split()
    i, points, tris = 0, [], []
    while i < len(tokens):
        key = tokens[i]
        if key == 'Vertices':
            n = int(tokens[i + 1]); i += 2
            points = [tokens[i + 4 * k:i + 4 * k + 3] for k in range(n)]; i += 4 * n
        elif key == 'Triangles':
            n = int(tokens[i + 1]); i += 2
            tris = [tokens[i + 4 * k:i + 4 * k + 3] for k in range(n)]; i += 4 * n
        elif key in ('Tetrahedra',):
            n = int(tokens[i + 1]); i += 2 + 5 * n
        elif key in ('Edges',):
            n = int(tokens[i + 1]); i += 2 + 3 * n
        elif key in ('Ridges', 'Corners', 'RequiredVertices', 'RequiredEdges'):
            n = int(tokens[i + 1]); i += 2 + n
        else:
            i += 1
    with open(obj_path, 'w') as out:
        for p in points: out.write('v %s %s %s\n' % tuple(p))
        for t in tris: out.write('f %s %s %s\n' % tuple(t))


def surfstat(obj, ref, h):
    out = subprocess.run([PY, os.path.join(ROOT, 'scripts/surfstat.py'), obj, '--ref', ref,
                          '--hsiz', repr(h), '--json'], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def meshstat(mesh, h):
    out = subprocess.run([PY, os.path.join(ROOT, 'scripts/meshstat.py'), mesh, '--hsiz', repr(h),
                          '--json'], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def cpu_of(stdout):
    m = re.search(r'^cpu:\s+total\s+([0-9.]+)', stdout, re.M)
    return float(m.group(1)) if m else float('nan')


def print_volume_row(name, v, s, cpu, checker, threads, walls=None):
    """One row of a tet mesh: v from meshstat, s from surfstat of its boundary; walls by thread
    count (adapt's rows only)."""
    walls = walls or {}
    cells = ' | '.join('%.2f s' % walls[n] if n in walls else '—' for n in threads)
    if len(threads) > 1:
        cells += ' | ' + ('%.2fx' % (walls[threads[0]] / walls[threads[-1]])
                          if threads[0] in walls and threads[-1] in walls else '—')
    print('| %s | %d | %.3f | %.2f | %.2f | %d | %.1f° | %.1f | %.2f | %.2e | %.2f s | %s | %s |' % (
        name, v['n_tets'], v['Qe_min'], v['pct_Qe_ge_0.5'], v['pct_Qt_ge_0.66'], s['n_faces'],
        s['min_angle'], s['pct_Qe_ge_07'], s['pct_Qt_ge_066'], s['hausdorff_rel'], cpu, cells,
        checker), flush=True)


def run_timed(cmd, stem):
    """cmd as a child, its stdout and stderr into stem.out / stem.err: (return code, stdout,
    stderr, wall s), the wall by perf_counter around os.wait4 on its pid."""
    with open(stem + '.out', 'w') as out, open(stem + '.err', 'w') as err:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, stdout=out, stderr=err)
        _, status, _ = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
    with open(stem + '.out') as out, open(stem + '.err') as err:
        return os.waitstatus_to_exitcode(status), out.read(), err.read(), wall


def adapt_row(a, tag, vol, ref, h, out):
    """Runs adapt on vol at size h into out, once per thread count of a.threads (the first
    run's output at out), and prints its row and its threads line; False when it failed."""
    walls, differ = {}, []
    for n in a.threads:
        path = out if n == a.threads[0] else '%s_%dt.mesh' % (out[:-5], n)
        code, stdout, stderr, walls[n] = run_timed(
            [os.path.join(a.build, 'apps/adapt'), vol, '--hsiz', repr(h), '-o', path, '--check',
             '--threads', str(n)] + a.extra.split(), '%s_%dt' % (out[:-5], n))
        if code != 0:
            print('| adapt %s | failed with --threads %d: %s |' % (tag, n, stderr.strip()[-200:]))
            return False
        if n == a.threads[0]:
            run_stdout = stdout
        elif subprocess.run(['cmp', '-s', out, path]).returncode != 0:
            differ.append(n)
    obj = out[:-5] + '_boundary.obj'
    boundary_obj(out, obj)
    v, s = meshstat(out, h), surfstat(obj, ref, h)
    checker = 'clean' if 'check output: clean' in run_stdout else 'VIOLATIONS'
    print_volume_row('adapt ' + tag, v, s, cpu_of(run_stdout), checker, a.threads, walls)
    if len(a.threads) > 1:
        notes = []
        if 1 in walls and 2 in walls:
            x = walls[1] / walls[2]
            notes.append('2-thread speed-up %.2f / %.2f s = %.2fx >= 1.8x %s' % (
                walls[1], walls[2], x, 'PASS' if x >= 1.8 else 'FAIL'))
        same = ', '.join('%dt' % n for n in a.threads)
        notes.append('outputs at %s byte-identical (cmp) PASS' % same if not differ else
                     'FAIL: output at %s differs from %dt (cmp)' % (
                         ', '.join('%dt' % n for n in differ), a.threads[0]))
        print('|  | threads: %s |' % '; '.join(notes), flush=True)
    if s['euler'] != s['ref_topology']['euler'] or s['components'] != s['ref_topology']['components']:
        print('|  | topology changed: euler %d, components %d |' % (s['euler'], s['components']))
    return True


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def mmg_row(a, tag, vol, ref, h, work, stem):
    """Runs Mmg (a.mmg) on vol at size h and prints its row in adapt's columns."""
    medit = os.path.join(work, stem + '_input.mesh')
    if not os.path.exists(medit):
        subprocess.run([os.path.join(a.build, 'apps/meshconvert'), vol, medit],
                       capture_output=True, check=True)
    out = os.path.join(work, stem + '_mmg.mesh')
    before = children_cpu()
    run = subprocess.run([a.mmg, medit, '-out', out, '-hsiz', repr(h)], capture_output=True,
                         text=True)
    cpu = children_cpu() - before
    if run.returncode != 0:
        print('| mmg %s | failed: %s |' % (tag, run.stdout.strip()[-200:]))
        return
    obj = out[:-5] + '_boundary.obj'
    boundary_obj(out, obj)
    print_volume_row('Mmg ' + tag, meshstat(out, h), surfstat(obj, ref, h), cpu, '—', a.threads)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--volumes', required=True)
    ap.add_argument('--surfaces', required=True)
    ap.add_argument('--build', default=os.path.join(ROOT, 'build'))
    ap.add_argument('--models', default='fandisk,rocker-arm,spot,cheburashka')
    ap.add_argument('--fractions', default='0.01,0.04')
    ap.add_argument('--extra', default='', help='more adapt flags')
    ap.add_argument('--no-surfremesh', action='store_true')
    ap.add_argument('--keep', help='directory to keep the outputs in')
    ap.add_argument('--mmg', help='an mmg3d executable: its rows beside adapt\'s')
    ap.add_argument('--round-trip', default='',
                    help='F1,F2: also adapt the F1 output to F2 (e.g. 0.01,0.04; its Hausdorff '
                         'is to the original input)')
    ap.add_argument('--threads', default='1,2',
                    help="adapt's thread counts, one run each (the first's output is the row's)")
    a = ap.parse_args()
    try:
        a.threads = [int(n) for n in a.threads.split(',')]
    except ValueError:
        a.threads = []
    if not a.threads or min(a.threads) < 1 or len(set(a.threads)) != len(a.threads):
        sys.exit('--threads: distinct counts >= 1, e.g. 1,2')
    walls = ''.join(' wall %dt |' % n for n in a.threads)
    speedup = ' %dt/%dt |' % (a.threads[0], a.threads[-1]) if len(a.threads) > 1 else ''
    dashes = '---|' * (len(a.threads) + (len(a.threads) > 1))
    trip = [float(f) for f in a.round_trip.split(',')] if a.round_trip else None
    work = a.keep or tempfile.mkdtemp(prefix='bench_coupled_')
    os.makedirs(work, exist_ok=True)
    print('| run | tets | min Qe | % Qe >= 0.5 | % Qt >= 0.66 | bd triangles | bd min angle | '
          'bd % Qe >= 0.7 | bd % Qt >= 0.66 | Hausdorff / diag | CPU |' + walls + speedup +
          ' checker |')
    print('|---|---|---|---|---|---|---|---|---|---|---|' + dashes + '---|')
    for model in a.models.split(','):
        vol = os.path.join(a.volumes, model + '.msh')
        ref = os.path.join(a.surfaces, model + '.obj')
        ref_stat = surfstat(ref, ref, 1.0)
        diag = ref_stat['bbox_diag']
        for frac in [float(f) for f in a.fractions.split(',')]:
            h = frac * diag
            tag = '%s %g %%' % (model, 100 * frac)
            out = os.path.join(work, '%s_%g.mesh' % (model, frac))
            if a.mmg: mmg_row(a, tag, vol, ref, h, work, '%s_%g' % (model, frac))
            if not adapt_row(a, tag, vol, ref, h, out): continue
            if trip and frac == trip[0]:
                # the round trip: this output adapted again, to the second size
                adapt_row(a, '%s %g %% -> %g %%' % (model, 100 * trip[0], 100 * trip[1]), out, ref,
                          trip[1] * diag, os.path.join(work, '%s_%g_%g.mesh' % (model, *trip)))
            if a.no_surfremesh: continue
            sobj = os.path.join(work, '%s_%g_surfremesh.obj' % (model, frac))
            srun = subprocess.run(['bash', '-c', 'TIMEFORMAT=%U+%S; time ' + ' '.join(
                [os.path.join(a.build, 'apps/surfremesh'), ref, '--hsiz', repr(h), '-o', sobj])],
                capture_output=True, text=True)
            cpu = sum(float(x) for x in srun.stderr.strip().splitlines()[-1].split('+'))
            s = surfstat(sobj, ref, h)
            print('| surfremesh %s | — | — | — | — | %d | %.1f° | %.1f | %.2f | %.2e | %.2f s |%s — |' % (
                tag, s['n_faces'], s['min_angle'], s['pct_Qe_ge_07'], s['pct_Qt_ge_066'],
                s['hausdorff_rel'], cpu, ' — |' * (len(a.threads) + (len(a.threads) > 1))),
                flush=True)


if __name__ == '__main__':
    sys.exit(main())
