#!/usr/bin/python3
"""Independent checker of a tet mesh against an anisotropic metric (issue 43).

  metricstat.py MESH.mesh MET.sol [--json]     edge lengths and tet qualities in the metric
  metricstat.py --selftest                     checks the rules on known tets (exit 1 on failure)

MESH: Medit ASCII .mesh (Vertices, Tetrahedra; read by scripts/meshstat.py). MET: Medit ASCII .sol,
SolAtVertices with one solution, either type 3 (symmetric tensor, the 6 values per vertex in
Medit's file order m11 m12 m22 m13 m23 m33, the order Mmg reads) or type 1 (an isotropic size h,
taken as the metric h^-2 I).

The rules are Mmg's (git MmgTools/mmg, src/mmg3d/inlined_functions_3d_private.h):
  edge length, MMG5_lenedgCoor_ani: for the edge e = b - a with the metrics Ma, Mb at its ends,
      da = eᵀ Ma e, db = eᵀ Mb e (each clamped at 0);
      L = sqrt((da + db) / 2)                                  when |da - db| < 0.05,
      L = (sqrt(da) + sqrt(db) + 4 sqrt((da + db) / 2)) / 6    otherwise (Simpson's rule with the
      midpoint's squared length taken as the mean of the ends').
    Every unique tet edge is measured (Mmg's length histogram, MMG3D_computePrilen, skips only
    tets whose four vertices are all ridge points, tags this checker does not have). For a
    scalar .sol whose h varies along an edge this is the tensor rule on h^-2 I, not Mmg's
    isotropic one (MMG5_lenedgCoor_iso); for a constant h both give |e| / h.
  tet quality, MMG5_caltet_ani, normalized as Mmg prints it (times MMG3D_ALPHAD = 12 sqrt(3)):
      M = the arithmetic mean of the 4 vertex tensors (MMG5_moymet, in src/mmg3d/anisosiz_3d.c;
      Mmg leaves out ridge vertices, unknown here), V6 = 6 * signed volume,
      S = sum over the 6 edges of eᵀ M e,
      Q = 12 sqrt(3) * sqrt(det M) * V6 / S^(3/2)     (1 for a regular tet of the metric).
    Mmg gives 0 to a tet with V6 <= 0; here the mesh's majority orientation counts as positive
    (Medit files from different tools may orient all tets the other way) and a tet of the other
    sign, or flat, gets 0 and is counted as inverted.
Histogram bins of the lengths are Mmg's: 0, 0.3, 0.6, 0.7071, 0.9, 1.3, 1.4142, 2, 5, inf.
"""
import argparse, json, math, os, sys, tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from meshstat import read_mesh  # noqa: E402  (same reader as the isotropic checker)

ALPHAD = 12.0 * math.sqrt(3.0)
LENGTH_BINS = [0.0, 0.3, 0.6, 0.7071, 0.9, 1.3, 1.4142, 2.0, 5.0, np.inf]
QUALITY_THRESHOLDS = [0.1, 0.2, 0.3, 0.5]
CHUNK = 1 << 20  # edges or tets per vectorized block: bounds the temporaries' memory
# Our components, per vertex: m11 m12 m13 m22 m23 m33 (Mmg's in-memory order).
FILE_TO_OURS = [0, 1, 3, 2, 4, 5]  # Medit file order m11 m12 m22 m13 m23 m33 -> ours


def read_sol(path, n_vertices):
    """The metric at the vertices, (n, 6) in our order, from a tensor or scalar Medit .sol."""
    tokens = open(path).read().split()
    if 'SolAtVertices' not in tokens:
        raise ValueError('%s: no SolAtVertices section' % path)
    i = tokens.index('SolAtVertices')
    n, nsol = int(tokens[i + 1]), int(tokens[i + 2])
    if nsol != 1:
        raise ValueError('%s: %d solutions, expected one metric' % (path, nsol))
    kind = int(tokens[i + 3])
    if n != n_vertices:
        raise ValueError('%s: %d values for %d vertices' % (path, n, n_vertices))
    width = {1: 1, 3: 6}.get(kind)
    if width is None:
        raise ValueError('%s: solution type %d, expected 1 (scalar) or 3 (tensor)' % (path, kind))
    values = np.array(tokens[i + 4:i + 4 + n * width], dtype=np.float64)
    if values.size != n * width:
        raise ValueError('%s: SolAtVertices truncated' % path)
    if kind == 1:
        m = np.zeros((n, 6))
        inv = values ** -2.0
        m[:, 0] = m[:, 3] = m[:, 5] = inv
        return m
    return values.reshape(n, 6)[:, FILE_TO_OURS]


def write_sol(path, metric):
    """Writes (n, 6) tensors in our order as a Medit type-3 .sol (file order)."""
    m = np.asarray(metric)[:, FILE_TO_OURS]  # the swap of m13 and m22 is its own inverse
    with open(path, 'w') as f:
        f.write('MeshVersionFormatted 2\n\nDimension 3\n\nSolAtVertices\n%d\n1 3\n' % len(m))
        np.savetxt(f, m, fmt='%.17g')
        f.write('\nEnd\n')


def quadratic(m, e):
    """eᵀ M e for rows of tensors m (k, 6) in our order and vectors e (k, 3)."""
    x, y, z = e[:, 0], e[:, 1], e[:, 2]
    return (m[:, 0] * x * x + m[:, 3] * y * y + m[:, 5] * z * z
            + 2.0 * (m[:, 1] * x * y + m[:, 2] * x * z + m[:, 4] * y * z))


def unique_edges(T):
    """The unique edges (k, 2) of tets T (m, 4), each once, smaller index first."""
    pairs = np.concatenate([T[:, [a, b]] for a, b in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))])
    pairs.sort(axis=1)
    n = int(T.max()) + 1
    code = np.unique(pairs[:, 0] * n + pairs[:, 1])
    return np.stack([code // n, code % n], axis=1)


def edge_lengths(V, M, E):
    """Mmg's anisotropic length (MMG5_lenedgCoor_ani) of every edge E (k, 2)."""
    out = np.empty(len(E))
    for s in range(0, len(E), CHUNK):
        a, b = E[s:s + CHUNK, 0], E[s:s + CHUNK, 1]
        e = V[b] - V[a]
        da = np.maximum(quadratic(M[a], e), 0.0)
        db = np.maximum(quadratic(M[b], e), 0.0)
        mid = np.sqrt(0.5 * (da + db))
        out[s:s + CHUNK] = np.where(np.abs(da - db) < 0.05, mid,
                                    (np.sqrt(da) + np.sqrt(db) + 4.0 * mid) / 6.0)
    return out


def det6(m):
    return (m[:, 0] * (m[:, 3] * m[:, 5] - m[:, 4] * m[:, 4])
            - m[:, 1] * (m[:, 1] * m[:, 5] - m[:, 2] * m[:, 4])
            + m[:, 2] * (m[:, 1] * m[:, 4] - m[:, 2] * m[:, 3]))


def tet_qualities(V, M, T):
    """Mmg's anisotropic quality (MMG5_caltet_ani times 12 sqrt(3)) of every tet, and the number
    of tets against the majority orientation (or flat), whose quality is 0."""
    q = np.empty(len(T))
    vol6 = np.empty(len(T))
    for s in range(0, len(T), CHUNK):
        t = T[s:s + CHUNK]
        a, b, c, d = (V[t[:, k]] for k in range(4))
        ab, ac, ad = b - a, c - a, d - a
        vol6[s:s + CHUNK] = np.einsum('ij,ij->i', ab, np.cross(ac, ad))
        mm = (M[t[:, 0]] + M[t[:, 1]] + M[t[:, 2]] + M[t[:, 3]]) * 0.25
        rap = sum(quadratic(mm, e) for e in (ab, ac, ad, c - b, d - b, d - c))
        det = det6(mm)
        with np.errstate(invalid='ignore', divide='ignore'):
            cal = ALPHAD * np.sqrt(np.maximum(det, 0.0)) * np.abs(vol6[s:s + CHUNK]) / (rap * np.sqrt(rap))
        q[s:s + CHUNK] = np.where((det < 1e-200) | (rap <= 0.0), 0.0, cal)
    sign = 1.0 if np.count_nonzero(vol6 > 0) >= np.count_nonzero(vol6 < 0) else -1.0
    bad = sign * vol6 <= 0.0
    q[bad] = 0.0
    return q, int(np.count_nonzero(bad))


def measure(V, T, M):
    """The report's figures as a dict."""
    L = edge_lengths(V, M, unique_edges(T))
    q, inverted = tet_qualities(V, M, T)
    hist, _ = np.histogram(L, bins=LENGTH_BINS)
    lo, hi = 1.0 / math.sqrt(2.0), math.sqrt(2.0)
    return {
        'vertices': int(len(np.unique(T))), 'tets': int(len(T)), 'edges': int(len(L)),
        'length_min': float(L.min()), 'length_max': float(L.max()), 'length_mean': float(L.mean()),
        'percent_in_range': 100.0 * float(np.count_nonzero((L >= lo) & (L <= hi))) / len(L),
        'length_bins': [b if np.isfinite(b) else 'inf' for b in LENGTH_BINS],
        'length_histogram': [int(x) for x in hist],
        'quality_min': float(q.min()), 'quality_mean': float(q.mean()),
        'quality_below': {str(t): int(np.count_nonzero(q < t)) for t in QUALITY_THRESHOLDS},
        'inverted': inverted,
    }


def print_report(r):
    print('vertices %d  tets %d  edges %d' % (r['vertices'], r['tets'], r['edges']))
    print('length in the metric  min %.4g  mean %.4g  max %.4g' % (r['length_min'], r['length_mean'], r['length_max']))
    print('edges with 1/sqrt2 <= L <= sqrt2  %.2f %%' % r['percent_in_range'])
    bins = r['length_bins']
    for k, count in enumerate(r['length_histogram']):
        print('  %6s <= L < %-6s  %10d  %6.2f %%' % (bins[k], bins[k + 1], count, 100.0 * count / r['edges']))
    print('quality in the metric  min %.4f  mean %.4f' % (r['quality_min'], r['quality_mean']))
    print('  ' + '  '.join('Q < %s: %d' % (t, c) for t, c in r['quality_below'].items()))
    print('inverted or flat tets  %d' % r['inverted'])


# ---------------------------------------------------------------------------------------------
# self-test

REGULAR = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, math.sqrt(3) / 2, 0.0],
                    [0.5, math.sqrt(3) / 6, math.sqrt(2.0 / 3.0)]])


def write_mesh(path, V, T):
    with open(path, 'w') as f:
        f.write('MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n' % len(V))
        for p in V:
            f.write('%.17g %.17g %.17g 0\n' % tuple(p))
        f.write('Tetrahedra\n%d\n' % len(T))
        for t in T:
            f.write('%d %d %d %d 0\n' % tuple(np.asarray(t) + 1))
        f.write('End\n')


def selftest():
    """Known answers through the files (so the .sol component order is tested too)."""
    failures = []

    def expect(name, got, want, tol=1e-12):
        ok = abs(got - want) <= tol * max(1.0, abs(want))
        print('%-58s %.15g  %s' % (name, got, 'ok' if ok else 'FAIL (want %.15g)' % want))
        if not ok:
            failures.append(name)

    def run(V, file_rows=None, sizes=None):
        """file_rows: per vertex, the 6 values as the file lists them (Medit order), written by
        hand here so that a reader swapping components fails."""
        rows = file_rows if file_rows is not None else [[h] for h in sizes]
        with tempfile.TemporaryDirectory() as d:
            write_mesh(os.path.join(d, 't.mesh'), V, [[0, 1, 2, 3]])
            with open(os.path.join(d, 't.sol'), 'w') as f:
                f.write('MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n%d\n1 %d\n'
                        % (len(rows), 1 if file_rows is None else 3))
                f.write(''.join(' '.join('%.17g' % x for x in row) + '\n' for row in rows) + 'End\n')
            Vr, Tr, _ = read_mesh(os.path.join(d, 't.mesh'))
            return measure(Vr, Tr, read_sol(os.path.join(d, 't.sol'), len(Vr)))

    identity = np.tile([1.0, 0, 1.0, 0, 0, 1.0], (4, 1))  # file order m11 m12 m22 m13 m23 m33
    r = run(REGULAR, identity)
    expect('regular tet, identity: quality', r['quality_min'], 1.0)
    expect('regular tet, identity: min length', r['length_min'], 1.0)
    expect('regular tet, identity: max length', r['length_max'], 1.0)
    r = run(REGULAR[[0, 2, 1, 3]], identity)
    expect('regular tet, other orientation: quality', r['quality_min'], 1.0)

    stretched = REGULAR * [1.0, 1.0, 100.0]
    r = run(stretched, np.tile([1.0, 0, 1.0, 0, 0, 1e-4], (4, 1)))
    expect('z*100 tet, diag(1,1,1e-4): quality', r['quality_min'], 1.0)
    expect('z*100 tet, diag(1,1,1e-4): max length', r['length_max'], 1.0)

    # A rotated anisotropic metric, every component distinct: the regular tet mapped by
    # F = R diag(1, 3, 7) is regular in M = F^-T F^-1, whose m13 != m22 (a swapped read fails).
    c, s = math.cos(0.3), math.sin(0.3)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    F = R @ np.diag([1.0, 3.0, 7.0])
    Finv = np.linalg.inv(F)
    Mfull = Finv.T @ Finv
    m = [Mfull[0, 0], Mfull[0, 1], Mfull[1, 1], Mfull[0, 2], Mfull[1, 2], Mfull[2, 2]]  # file order
    r = run(REGULAR @ F.T, np.tile(m, (4, 1)))
    expect('regular tet mapped by R diag(1,3,7), its metric: quality', r['quality_min'], 1.0, 1e-10)
    expect('regular tet mapped by R diag(1,3,7), its metric: max length', r['length_max'], 1.0, 1e-10)

    r = run(REGULAR, sizes=[0.25] * 4)
    expect('regular tet, scalar h = 0.25: min length (= 1/h)', r['length_min'], 4.0)
    expect('regular tet, scalar h = 0.25: max length (= 1/h)', r['length_max'], 4.0)
    expect('regular tet, scalar h = 0.25: quality', r['quality_min'], 1.0)

    # Different ends: da = 1, db = 4 (|da - db| >= 0.05): Simpson's (1 + 2 + 4 sqrt(2.5)) / 6.
    r = run(REGULAR, sizes=[1.0, 0.5, 1.0, 1.0])
    expect('h = 1 and 0.5 at the ends of an edge: max length', r['length_max'], (3 + 4 * math.sqrt(2.5)) / 6)
    # write_sol and read_sol round trip
    with tempfile.TemporaryDirectory() as d:
        ours = np.tile([Mfull[0, 0], Mfull[0, 1], Mfull[0, 2], Mfull[1, 1], Mfull[1, 2], Mfull[2, 2]], (2, 1))
        write_sol(os.path.join(d, 'm.sol'), ours)
        expect('write_sol then read_sol: largest difference',
               float(np.abs(read_sol(os.path.join(d, 'm.sol'), 2) - ours).max()), 0.0)
    print('selftest: %s' % ('FAIL: ' + ', '.join(failures) if failures else 'all passed'))
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('mesh', nargs='?')
    ap.add_argument('sol', nargs='?')
    ap.add_argument('--json', action='store_true', help='print the figures as one JSON object')
    ap.add_argument('--selftest', action='store_true')
    args = ap.parse_args()
    if args.selftest:
        return selftest()
    if not args.sol:
        ap.error('MESH and MET.sol are needed')
    V, T, _ = read_mesh(args.mesh)
    r = measure(V, T, read_sol(args.sol, len(V)))
    if args.json:
        print(json.dumps(r))
    else:
        print_report(r)
    return 0


if __name__ == '__main__':
    sys.exit(main())
