#!/usr/bin/python3
"""Anisotropic adaptation beside Mmg (issue 43): analytic metrics on the unit cube.

  bench/bench_metric.py [--adapt build/apps/adapt] [--mmg PATH/mmg3d_O3] [--cases layer,shock]
                        [--rounds 3] [--quick] [--work DIR]

The protocol. For each case of scripts/make_metric.py (layer: a layer across z = 0.5 of aspect
ratio 100; shock: the sphere |p| = 0.6, aspect ratio 25; their defaults, or with --quick sizes
4x larger and a 5^3 start cube, for a sanity run in seconds), both tools start from the same
structured cube (bench/metric_cube.py, 10^3 cubes of 6 tets) and run --rounds rounds (3); a round
evaluates the analytic metric at the current mesh's vertices, writes it as a tensor .sol (Medit
order m11 m12 m22 m13 m23 m33) and runs the tool on the current mesh with it, no gradation:
  hdimesh  ADAPT cur.mesh -sol met.sol -out next.mesh -hgrad -1
  Mmg      MMG -in cur.mesh -sol met.sol -out next.mesh -hgrad -1 -v 0   (with --mmg only)
Every tool runs as a child process (Popen, then os.wait4 on its pid): the child's own rusage
gives its CPU (user + system: the whole process, reading and writing included, i.e. the
RUSAGE_CHILDREN delta around it) and its peak resident set; wall time is perf_counter around it.
CPU and wall are summed over the rounds, the peak is the largest round's; this script's metric
evaluation and .sol writing between rounds count for no one.

After the last round the metric is evaluated at the final mesh's vertices and
scripts/metricstat.py (Mmg's anisotropic edge length and tet quality, independently computed)
measures the output. A table per case: tool, CPU s over the rounds, wall s, peak MB, the tets
after each round, % of edges with 1/sqrt2 <= L <= sqrt2, the longest edge, min and mean quality,
the tets of quality < 0.1, and tets inverted or flat. A tool that fails gets the row
"error: <first line of its stderr>" and the bench goes on. After each case a targets line, each
PASS/FAIL with its figure: hdimesh >= 95 % edges in range; hdimesh min quality >= Mmg's;
hdimesh CPU < Mmg's (the last two need both rows).
"""
import argparse, json, os, subprocess, sys, tempfile, time
from collections import namedtuple

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PY = '/usr/bin/python3'  # Debian's, with numpy
sys.path[:0] = [os.path.join(ROOT, 'scripts'), os.path.join(ROOT, 'bench')]
from make_metric import metric  # noqa: E402
from metric_cube import cube_mesh, write_mesh  # noqa: E402
from metricstat import write_sol  # noqa: E402
from meshstat import read_mesh  # noqa: E402

Usage = namedtuple('Usage', 'cpu wall rss')
CUBE = 10
QUICK_CUBE = 5
QUICK = {  # --quick: the fine sizes 4x the defaults, hmax 2x: about 10x fewer tets
    'layer': {'hmin': 0.004, 'hmax': 0.2},
    'shock': {'hmin': 0.008, 'htan': 0.1, 'hmax': 0.2},
}
IN_RANGE_TARGET = 95.0


class ToolError(Exception):
    pass


def run_child(cmd, stem):
    """Runs cmd as a child, stdout and stderr into stem.out / stem.err; its rusage and wall."""
    with open(stem + '.out', 'w') as out, open(stem + '.err', 'w') as err:
        start = time.perf_counter()
        try:
            proc = subprocess.Popen(cmd, stdout=out, stderr=err)
        except OSError as e:
            raise ToolError(str(e))
        _, status, ru = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        lines = [l.strip() for path in (stem + '.err', stem + '.out') for l in open(path) if l.strip()]
        raise ToolError(lines[0] if lines else 'exit code %d' % code)
    return Usage(ru.ru_utime + ru.ru_stime, wall, ru.ru_maxrss * 1024)


def tet_count(path):
    try:
        return len(read_mesh(path)[1])
    except (OSError, ValueError, IndexError, TypeError) as e:
        raise ToolError('%s: not a Medit ASCII tet mesh (%s)' % (path, e))


def write_metric(mesh, case, params, sol):
    try:
        V = read_mesh(mesh)[0]
    except (OSError, ValueError, IndexError, TypeError) as e:  # a tool's unreadable output is its error
        raise ToolError('%s: not a Medit ASCII tet mesh (%s)' % (mesh, e))
    write_sol(sol, metric(V, case, **params))


def command(tool, exe, cur, sol, nxt):
    if tool == 'hdimesh':
        return [exe, cur, '-sol', sol, '-out', nxt, '-hgrad', '-1']
    return [exe, '-in', cur, '-sol', sol, '-out', nxt, '-hgrad', '-1', '-v', '0']


def run_tool(tool, exe, case, params, start, rounds, work):
    """The rounds of one tool on one case: (final mesh, Usage summed, tets after each round)."""
    cur, total, tets = start, Usage(0.0, 0.0, 0), []
    for k in range(1, rounds + 1):
        stem = os.path.join(work, '%s_%s.%d' % (tool, case, k))
        sol = stem + '.in.sol'
        write_metric(cur, case, params, sol)
        nxt = stem + '.mesh'
        u = run_child(command(tool, exe, cur, sol, nxt), stem)
        if not os.path.exists(nxt):
            raise ToolError('no output %s' % nxt)
        total = Usage(total.cpu + u.cpu, total.wall + u.wall, max(total.rss, u.rss))
        tets.append(tet_count(nxt))
        cur = nxt
    return cur, total, tets


def measure(mesh, case, params):
    """metricstat's figures of mesh against the analytic metric at its vertices."""
    sol = mesh[:-len('.mesh')] + '.final.sol'
    write_metric(mesh, case, params, sol)
    out = subprocess.run([PY, os.path.join(ROOT, 'scripts/metricstat.py'), mesh, sol, '--json'],
                         capture_output=True, text=True)
    if out.returncode != 0:
        # the checker's last line is its exception's message
        raise ToolError('metricstat: ' + (out.stderr.strip().splitlines() or ['failed'])[-1])
    return json.loads(out.stdout)


HEADER = ('| case | tool | CPU s | wall s | peak MB | tets by round | % L in [0.71, 1.41] | L max '
          '| Q min | Q mean | Q < 0.1 | inverted |\n|---|---|---|---|---|---|---|---|---|---|---|---|')


def row(case, tool, r):
    if 'error' in r:
        return '| %s | %s | error: %s |' % (case, tool, r['error'])
    u, s = r['usage'], r['stat']
    return '| %s | %s | %.2f | %.2f | %.0f | %s | %.2f | %.3g | %.4f | %.4f | %d | %d |' % (
        case, tool, u.cpu, u.wall, u.rss / 2 ** 20, ' / '.join(str(t) for t in r['tets']),
        s['percent_in_range'], s['length_max'], s['quality_min'], s['quality_mean'],
        s['quality_below']['0.1'], s['inverted'])


def targets_line(case, results):
    ours, mmg = results.get('hdimesh', {}), results.get('Mmg', {})
    ok_ours, ok_mmg = 'stat' in ours, 'stat' in mmg

    def check(name, ok, shown):
        return '%s: %s (%s)' % (name, 'PASS' if ok else 'FAIL', shown)

    parts = [check('hdimesh >= %g %% edges in range' % IN_RANGE_TARGET,
                   ok_ours and ours['stat']['percent_in_range'] >= IN_RANGE_TARGET,
                   '%.2f %%' % ours['stat']['percent_in_range'] if ok_ours else 'no run')]
    if ok_mmg:
        q = mmg['stat']['quality_min']
        parts.append(check('hdimesh min Q >= Mmg\'s %.4f' % q,
                           ok_ours and ours['stat']['quality_min'] >= q,
                           '%.4f' % ours['stat']['quality_min'] if ok_ours else 'no run'))
        c = mmg['usage'].cpu
        parts.append(check('hdimesh CPU < Mmg\'s %.2f s' % c, ok_ours and ours['usage'].cpu < c,
                           '%.2f s' % ours['usage'].cpu if ok_ours else 'no run'))
    else:
        parts.append('Mmg comparisons: n/a (no Mmg row)')
    return 'targets %s: %s' % (case, ' | '.join(parts))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--adapt', default=os.path.join(ROOT, 'build/apps/adapt'), help='our adapt binary')
    ap.add_argument('--mmg', help='mmg3d binary (Mmg 5.x); without it, no Mmg row')
    ap.add_argument('--cases', default='layer,shock')
    ap.add_argument('--rounds', type=int, default=3)
    ap.add_argument('--quick', action='store_true', help='4x larger sizes, a 5^3 start cube')
    ap.add_argument('--work', help='directory for the meshes and logs (default: a new temporary one)')
    args = ap.parse_args()
    work = args.work or tempfile.mkdtemp(prefix='bench_metric_')
    os.makedirs(work, exist_ok=True)
    start = os.path.join(work, 'cube.mesh')
    write_mesh(start, *cube_mesh(QUICK_CUBE if args.quick else CUBE))
    tools = [('hdimesh', args.adapt)] + ([('Mmg', args.mmg)] if args.mmg else [])

    print(HEADER, flush=True)
    lines = []
    for case in args.cases.split(','):
        params = QUICK[case] if args.quick else {}
        results = {}
        for tool, exe in tools:
            try:
                final, usage, tets = run_tool(tool, exe, case, params, start, args.rounds, work)
                results[tool] = {'usage': usage, 'tets': tets, 'stat': measure(final, case, params)}
            except ToolError as e:
                results[tool] = {'error': str(e)}
            print(row(case, tool, results[tool]), flush=True)
        lines.append(targets_line(case, results))
    print()
    for line in lines:
        print(line)
    print('outputs in %s (start mesh cube.mesh, %d tets)' % (work, tet_count(start)))


if __name__ == '__main__':
    main()
