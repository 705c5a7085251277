"""hdimesh: tet meshes and their boundary surfaces adapted together to a size field.

The boundary follows a meshfree (Hermite Diffuse Interpolation) model of the input surface, so
no CAD is needed. Meshes are numpy arrays held by :class:`TetMesh`; every call below runs the
same library code as the command-line tools (``adapt``, ``surfremesh``), with the GIL released.

    import hdimesh
    mesh = hdimesh.read("sphere.mesh")
    out = hdimesh.adapt(mesh, hsiz=0.1)
    print(hdimesh.quality(out, hsiz=0.1)["tets"]["min_qe"])
    hdimesh.write(out, "sphere.o.mesh")

Indices count from 0. Errors are ``ValueError`` (bad input: array shape, ids out of range, NaN,
an invalid mesh, a bad option; messages number elements from 1, as the files do) and
``OSError`` (a file that cannot be read or written).
"""

import collections
import collections.abc

import numpy as np

from . import _hdimesh

__all__ = [
    "TetMesh",
    "Violation",
    "read",
    "write",
    "adapt",
    "remesh_surface",
    "mesh_volume",
    "quality",
    "check",
    "from_meshio",
    "to_meshio",
]

_INDEX = np.int32

# (attribute, columns, rows it is per, or None for a list of ids)
_ARRAYS = (
    ("tets", 4, None),
    ("triangles", 3, None),
    ("edges", 2, None),
    ("vertex_refs", 1, "points"),
    ("tet_refs", 1, "tets"),
    ("triangle_refs", 1, "triangles"),
    ("edge_refs", 1, "edges"),
    ("ridges", 1, None),
    ("corners", 1, None),
    ("required_vertices", 1, None),
    ("required_edges", 1, None),
    ("required_triangles", 1, None),
    ("required_tets", 1, None),
)


def _points(name, values):
    a = np.asarray(values, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{name} must have shape (n, 3), got {a.shape}")
    bad = ~np.isfinite(a).all(axis=1)
    if bad.any():
        raise ValueError(f"{name} row {int(np.argmax(bad))} is not finite (NaN or infinity)")
    return a


def _ids(name, values, columns, limit=None):
    a = np.asarray(values)
    if a.size == 0:
        a = a.reshape((0, columns) if columns > 1 else (0,))
    if a.dtype.kind not in "iu":
        if a.dtype.kind == "f" and np.all(np.isfinite(a)) and np.all(a == np.round(a)):
            a = a.astype(np.int64)
        else:
            raise ValueError(f"{name} must hold integers, got dtype {a.dtype}")
    want = (columns,) if columns > 1 else ()
    if a.ndim != 1 + len(want) or a.shape[1:] != want:
        shape = f"(m, {columns})" if columns > 1 else "(m,)"
        raise ValueError(f"{name} must have shape {shape}, got {a.shape}")
    if limit is not None and a.size:
        low, high = a.min(), a.max()
        if low < 0 or high >= limit:
            bad = int(np.argmax((a < 0) | (a >= limit)))
            row = bad // columns if columns > 1 else bad
            value = a.reshape(-1)[bad]
            raise ValueError(f"{name} row {row} refers to {value}, out of range [0, {limit})")
    return a


def _fields(fields, n):
    """Fields at n vertices: a dict name -> array of shape (n,) or (n, ...), finite."""
    if fields is None:
        return {}
    if not isinstance(fields, collections.abc.Mapping):
        raise TypeError(f"fields must be a dict of name -> array, got {type(fields).__name__}")
    out = {}
    for name, values in fields.items():
        a = np.asarray(values, dtype=np.float64)
        if a.ndim == 0 or a.shape[0] != n or int(np.prod(a.shape[1:])) < 1:
            raise ValueError(f"fields[{name!r}] must have shape ({n},) or ({n}, k), one value "
                             f"or row per vertex, got {a.shape}")
        bad = ~np.isfinite(a.reshape(n, -1)).all(axis=1)
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(f"fields[{name!r}] at vertex {i} is not finite: {a[i]}")
        out[str(name)] = a
    return out


class TetMesh:
    """A tet mesh, or a surface (triangles and no tets), as numpy arrays.

    points (n, 3) float64; tets (m, 4), triangles (k, 3), edges (e, 2) vertex ids; tet_refs,
    triangle_refs, edge_refs, vertex_refs one int per row; ridges and required_edges ids into
    edges, corners and required_vertices vertex ids, required_triangles and required_tets ids
    into triangles and tets. Tets are positive: det(v1-v0, v2-v0, v3-v0) > 0. The arrays are
    kept as given (no copy) when they already have the right type.

    ``fields``: a dict name -> float64 array at the vertices, (n,) or (n, ...): what
    :func:`adapt` carried onto this mesh (empty unless asked for). ``metric``: when
    :func:`adapt` was given a metric, the field at this mesh's vertices, (n, 6) in Medit's
    order; else None.
    """

    def __init__(self, points, tets=None, triangles=None, tet_refs=None, triangle_refs=None,
                 fields=None, **more):
        unknown = set(more) - {name for name, _, _ in _ARRAYS}
        if unknown:
            raise TypeError(f"TetMesh got unknown arrays {sorted(unknown)}")
        self.points = _points("points", points)
        given = dict(more, tets=tets, triangles=triangles, tet_refs=tet_refs,
                     triangle_refs=triangle_refs)
        n = len(self.points)
        for name, columns, per in _ARRAYS:
            value = given.get(name)
            limit = {"tets": n, "triangles": n, "edges": n, "corners": n,
                     "required_vertices": n}.get(name)
            if value is None:
                rows = len(getattr(self, per)) if per else 0
                value = np.zeros((rows, columns) if columns > 1 else (rows,), dtype=_INDEX)
            setattr(self, name, _ids(name, value, columns, limit))
        for name, _, per in _ARRAYS:
            if per and len(getattr(self, name)) != len(getattr(self, per)):
                raise ValueError(f"{name} has {len(getattr(self, name))} values for "
                                 f"{len(getattr(self, per))} {per}")
        for name, into in (("ridges", "edges"), ("required_edges", "edges"),
                           ("required_triangles", "triangles"), ("required_tets", "tets")):
            _ids(name, getattr(self, name), 1, len(getattr(self, into)))
        self.fields = _fields(fields, n)
        self.metric = None

    @classmethod
    def _from_native(cls, d):
        return cls(**d)

    def _native(self):
        return {name: getattr(self, name) for name in ("points",) + tuple(a for a, _, _ in _ARRAYS)}

    @property
    def is_surface(self):
        """True when the mesh has triangles and no tets."""
        return len(self.tets) == 0

    def __repr__(self):
        return (f"TetMesh({len(self.points)} points, {len(self.tets)} tets, "
                f"{len(self.triangles)} triangles)")


Violation = collections.namedtuple("Violation", "kind element message")
Violation.__str__ = lambda v: f"{v.kind} {v.element + 1}: {v.message}"


def read(path, fields=False):
    """Reads .mesh/.meshb (Medit), .msh (Gmsh 2.2, 4.1), or a surface (.obj .off .stl .ply).

    With ``fields=True`` (a .msh only), its $NodeData sections become the mesh's ``fields``,
    by name: (n,) for one component, else (n, k)."""
    d = _hdimesh.read(str(path), fields=bool(fields))
    names, arrays = d.pop("fields", ((), ()))
    mesh = TetMesh._from_native(d)
    mesh.fields = dict(zip(names, arrays))
    return mesh


def write(mesh, path):
    """Writes by extension: .mesh .meshb .msh .vtu, or the triangles to .obj .off .stl .ply.

    The mesh's ``fields`` go into a .msh as $NodeData (1, 3, 6 or 9 values per vertex) and
    into a .vtu as point data; the other formats hold none. Atomic: a failed write leaves no
    file."""
    mesh = _as_mesh(mesh)
    _hdimesh.write(mesh._native(), str(path), names=list(mesh.fields),
                   fields=[np.ascontiguousarray(a.reshape(len(a), -1))
                           for a in mesh.fields.values()])


def _as_mesh(mesh):
    if isinstance(mesh, TetMesh):
        return mesh
    if hasattr(mesh, "cells") and hasattr(mesh, "point_data"):  # a meshio.Mesh
        return from_meshio(mesh)
    raise TypeError(f"expected an hdimesh.TetMesh, got {type(mesh).__name__}")


def _number(name, value, default=0.0):
    if value is None:
        return default
    v = float(value)
    if not np.isfinite(v) or v <= 0:
        raise ValueError(f"{name} must be a positive number, got {value!r}")
    return v


def _vertex_sizes(sizes, points):
    """Sizes at `points`: an array (n,), or a callable evaluated once on all of them."""
    if sizes is None:
        return None
    values = sizes(np.array(points, dtype=np.float64)) if callable(sizes) else sizes
    a = np.asarray(values, dtype=np.float64).reshape(-1)
    if a.shape != (len(points),):
        raise ValueError(f"sizes must give one value per vertex ({len(points)}), got "
                         f"{np.asarray(values).shape}")
    bad = ~(np.isfinite(a) & (a > 0))
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"sizes[{i}] = {a[i]} is not a positive number")
    return a


# Medit's order m11 m12 m22 m13 m23 m33: the lower triangle row by row
_MEDIT_ROWS, _MEDIT_COLS = [0, 1, 1, 2, 2, 2], [0, 0, 1, 0, 1, 2]


def _vertex_metrics(metric, points):
    """Metrics at `points` as an (n, 6) array in Medit's order: an (n, 6) or (n, 3, 3) array,
    or a callable evaluated once on all of them. The row count, finiteness and positive
    definiteness are checked by the library (naming the vertex)."""
    if metric is None:
        return None
    values = metric(np.array(points, dtype=np.float64)) if callable(metric) else metric
    a = np.asarray(values, dtype=np.float64)
    if a.ndim == 3 and a.shape[1:] == (3, 3):
        scale = np.abs(a).max(axis=(1, 2), initial=0.0)
        # NaN compares False here: the library names it as not finite
        bad = np.abs(a - a.transpose(0, 2, 1)).max(axis=(1, 2), initial=0.0) > 1e-10 * scale
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(f"metric[{i}] (vertex {i + 1}) is not symmetric: {a[i].tolist()}")
        a = a[:, _MEDIT_ROWS, _MEDIT_COLS]
    elif a.ndim != 2 or a.shape[1] != 6:
        raise ValueError(f"metric must have shape (n, 6) (Medit's order m11 m12 m22 m13 m23 "
                         f"m33) or (n, 3, 3), got {a.shape}")
    return np.ascontiguousarray(a)


def _metric_matrices(m6):
    """(n, 6) in Medit's order to (n, 3, 3)."""
    m = np.empty((len(m6), 3, 3))
    m[:, _MEDIT_ROWS, _MEDIT_COLS] = m6
    m[:, _MEDIT_COLS, _MEDIT_ROWS] = m6
    return m


def _edges(mesh):
    t = mesh.tets
    edges = np.concatenate([t[:, [a, b]] for a, b in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3),
                                                       (2, 3))])
    return np.unique(np.sort(edges, axis=1), axis=0)


def _metric_conformity(mesh, metric, hmin, hmax):
    """Share of edges whose length in a callable metric (at their midpoints, one call, sizes
    bounded to [hmin, hmax]) lies in [0.66, 1/0.66]."""
    edges = _edges(mesh)
    p, q = mesh.points[edges[:, 0]], mesh.points[edges[:, 1]]
    lam, vec = np.linalg.eigh(_metric_matrices(_vertex_metrics(metric, (p + q) / 2)))
    lam = np.clip(lam, 1 / hmax**2 if hmax else 0, 1 / hmin**2 if hmin else np.inf)
    e = np.einsum("nji,nj->ni", vec, q - p)
    length = np.sqrt(np.einsum("ni,ni->n", lam * e, e))
    return float(np.mean(np.minimum(length, 1 / length) >= 0.66))


def _conformity(mesh, sizes, hmin, hmax):
    """Share of edges with Qt >= 0.66 against a callable at the edge midpoints (one call)."""
    edges = _edges(mesh)
    p, q = mesh.points[edges[:, 0]], mesh.points[edges[:, 1]]
    h = _vertex_sizes(sizes, (p + q) / 2)
    h = np.clip(h, hmin if hmin else 0, hmax if hmax else np.inf)
    length = np.linalg.norm(p - q, axis=1)
    qt = np.minimum(h / length, length / h)
    return float(np.mean(qt >= 0.66))


def adapt(mesh, hsiz=None, sizes=None, hmin=None, hmax=None, hgrad=None, hausd=None,
          threads=None, verbose=0, progress=None, bench_field=None, nosurf=False,
          noinsert=False, noswap=False, nomove=False, optim=False, no_optimize=False,
          keep_surface=False, strict=False, max_passes=40, size_rounds=4, ridge_angle=45.0,
          no_ridges=False, fields=None, metric=None):
    """Adapts a tet mesh and its boundary to a size field; returns a new TetMesh.

    Given a surface (a TetMesh with triangles and no tets), remeshes it to the size and fills
    the volume it bounds, as :func:`mesh_volume` does.

    The size: ``hsiz`` (constant), ``sizes`` (an array with one value per input vertex, or a
    callable taking an (n, 3) array of points and returning (n,) sizes), or ``bench_field``
    (the paper's case "A" to "E"); ``hmin``/``hmax`` bound it, ``hgrad`` (> 1) bounds the size
    ratio between neighbours. A callable is evaluated in batches, never once per point: at the
    vertices of the mesh, which is then adapted to those sizes; repeated on the result (at most
    ``size_rounds`` times, as Mmg users iterate) until 99 % of the edges conform to the
    callable at their midpoints. ``hausd`` bounds the boundary's distance to the input. As
    with the app, a tet mesh given no size but ``hausd``, ``hmin``, ``hmax`` or ``hgrad`` keeps
    its own sizes within them.

    ``metric`` (instead of a size; a tet input only): an anisotropic field, a symmetric
    positive definite M per input vertex (an edge e has length sqrt(eᵀ M e) in it, the
    isotropic size h is h⁻² I): an (n, 6) array in Medit's order (m11 m12 m22 m13 m23 m33),
    an (n, 3, 3) array (symmetric to a relative 1e-10), or a callable taking an (n, 3) array
    of points and returning either. It is sampled at the input's vertices and interpolated
    log-Euclidean between them; a callable is sampled again on the result, as for ``sizes``,
    until 99 % of the edges have a length in [0.66, 1.5] in it at their midpoints (at most
    ``size_rounds`` times). ``hmin``/``hmax`` bound its sizes in every direction, ``hgrad``
    grades it. The result's ``metric`` is then the field at its vertices, (m, 6) in Medit's
    order (the app's OUT.sol), where the next round can start.

    The switches are the app's: ``nosurf`` (keep the boundary, only split and projected),
    ``noinsert`` (no vertex inserted or removed), ``noswap``, ``nomove``, ``optim`` (optimize only, keep the sizes),
    ``no_optimize``, ``keep_surface`` (a surface input's triangles are the boundary, exactly),
    ``strict`` (refuse a defective input instead of repairing it: a tet input's triangles
    that are not the tets' boundary; a surface input's degenerate, duplicated or crossing
    triangles, pinched vertices, holes and tiny shells), ``ridge_angle`` (degrees) and ``no_ridges`` for the boundary's features.
    ``verbose``: 0 silent, 1 summary, 2 a row per pass (on stdout).
    ``progress(stage, tets)`` is called after each refinement pass and as the surface pass and
    the final optimization start; an exception it raises stops the run.

    ``threads``: threads the run uses (None: the cores present); the output is the same bytes
    for any count (the work is cut into pieces set by the mesh, never by the thread count).

    ``fields``: a dict name -> array at the input's vertices, (n,) or (n, k) (any trailing
    shape), e.g. a meshio mesh's ``point_data``; carried onto the result (P1 in the input tet
    of each new vertex's region, extrapolated from the nearest tet outside the input: linear
    fields are exact) as ``result.fields``, with the same names and trailing shapes. A tet
    input only. The input may also be a ``meshio.Mesh`` (read by :func:`from_meshio`).
    """
    mesh = _as_mesh(mesh)
    carried = _fields(fields, len(mesh.points))
    if carried and mesh.is_surface:
        raise ValueError("fields need a tet mesh input, not a surface")
    if threads is not None and int(threads) < 1:
        raise ValueError(f"threads must be at least 1, got {threads}")
    if progress is not None and not callable(progress):
        raise TypeError("progress must be callable")
    if sum(x is not None for x in (hsiz, sizes, bench_field)) > 1:
        raise ValueError("give only one of hsiz, sizes and bench_field")
    if metric is not None and any(x is not None for x in (hsiz, sizes, bench_field)):
        raise ValueError("give either metric or one of hsiz, sizes and bench_field")
    hmin_v, hmax_v = _number("hmin", hmin), _number("hmax", hmax)
    if not 0 < float(ridge_angle) < 180:
        raise ValueError(f"ridge_angle must lie in (0, 180) degrees, got {ridge_angle!r}")
    if hgrad is not None and not float(hgrad) > 1:
        raise ValueError(f"hgrad must be larger than 1, got {hgrad!r}")
    if bench_field is not None and bench_field not in tuple("ABCDE"):
        raise ValueError(f"bench_field is one of 'A' to 'E', got {bench_field!r}")
    args = dict(hsiz=_number("hsiz", hsiz), bench_field=bench_field or "", hmin=hmin_v,
                hmax=hmax_v, hgrad=float(hgrad) if hgrad is not None else 0.0,
                hausd=_number("hausd", hausd), verbose=int(verbose), progress=progress,
                nosurf=bool(nosurf), noinsert=bool(noinsert), noswap=bool(noswap),
                nomove=bool(nomove), optim=bool(optim), no_optimize=bool(no_optimize),
                keep_surface=bool(keep_surface), strict=bool(strict),
                max_passes=int(max_passes), ridge_angle=float(ridge_angle),
                no_ridges=bool(no_ridges), threads=int(threads) if threads is not None else 0)

    def once(m, vertex_sizes, fields, metrics=None):
        flat = [np.ascontiguousarray(a.reshape(len(a), -1)) for a in fields.values()]
        d = _hdimesh.adapt(m._native(), sizes=vertex_sizes, fields=flat, metrics=metrics,
                           **args)
        out = d.pop("fields")
        output_metric = d.pop("metric", None)
        result = TetMesh._from_native(d)
        result.fields = {name: a.reshape((len(a),) + fields[name].shape[1:])
                         for name, a in zip(fields, out)}
        result.metric = output_metric
        return result

    if metric is not None:
        current = once(mesh, None, carried, _vertex_metrics(metric, mesh.points))
        rounds = int(size_rounds) if callable(metric) else 1
        for _ in range(1, max(1, rounds)):
            if _metric_conformity(current, metric, hmin_v, hmax_v) >= 0.99:
                break
            current = once(current, None, current.fields,
                           _vertex_metrics(metric, current.points))
        return current
    if not callable(sizes):
        return once(mesh, _vertex_sizes(sizes, mesh.points), carried)
    if mesh.is_surface:
        return mesh_volume(mesh.points, mesh.triangles, sizes=sizes, hmin=hmin, hmax=hmax,
                           hgrad=hgrad, hausd=hausd, verbose=verbose, progress=progress,
                           threads=threads)
    current = mesh
    for _ in range(max(1, int(size_rounds))):
        current = once(current, _vertex_sizes(sizes, current.points), carried)
        carried = current.fields
        if _conformity(current, sizes, hmin_v, hmax_v) >= 0.99:
            break
    return current


def remesh_surface(vertices, faces, hsiz=None, hausd=None, ridge_angle=45.0, refs=None,
                   hmin=None, hmax=None, hgrad=None, sizes=None, no_ridges=False,
                   iterations=8, verbose=0):
    """Remeshes a triangle surface on its own HDI model; returns (vertices, faces).

    Ridges sharper than ``ridge_angle`` degrees, corners, open boundaries and refs are kept.
    The size: ``hsiz``, ``sizes`` (one per input vertex, or a callable on an (n, 3) array),
    or curvature-adaptive with ``hausd``; none: curvature-adaptive with hausd 0.002 x the
    diagonal, at most twice the input's mean edge length. With ``refs`` (one per face) given,
    returns (vertices, faces, refs).
    """
    vertices = _points("vertices", vertices)
    faces = _ids("faces", faces, 3, len(vertices))
    face_refs = None if refs is None else _ids("refs", refs, 1)
    if face_refs is not None and len(face_refs) != len(faces):
        raise ValueError(f"refs has {len(face_refs)} values for {len(faces)} faces")
    if sum(x is not None for x in (hsiz, sizes, hausd)) > 1:
        raise ValueError("give at most one of hsiz, sizes and hausd")
    if not 0 < float(ridge_angle) < 180:
        raise ValueError(f"ridge_angle must lie in (0, 180) degrees, got {ridge_angle!r}")
    surface = TetMesh(vertices, triangles=faces, triangle_refs=face_refs)
    v, f, r = _hdimesh.remesh_surface(
        surface._native(), hsiz=_number("hsiz", hsiz), hausd=_number("hausd", hausd),
        ridge_angle=float(ridge_angle), no_ridges=bool(no_ridges), hmin=_number("hmin", hmin),
        hmax=_number("hmax", hmax), hgrad=float(hgrad) if hgrad is not None else 1.3,
        sizes=_vertex_sizes(sizes, vertices), iterations=int(iterations), verbose=int(verbose))
    return (v, f) if refs is None else (v, f, r)


def mesh_volume(vertices, faces, hsiz=None, hausd=None, sizes=None, hmin=None, hmax=None,
                hgrad=None, refs=None, keep_surface=False, strict=False, verbose=0,
                progress=None, threads=None):
    """Fills the volume a closed surface bounds with tets; returns a TetMesh.

    The surface is repaired first (coincident points merged, degenerate and duplicated faces
    dropped, pinched vertices split, holes up to 10 local sizes around closed, tiny shells
    dropped; ``strict=True`` refuses instead); what stays open, non-manifold or
    non-orientable raises ValueError naming it. It is then remeshed to the size (unless
    ``keep_surface``), checked (crossing faces raise ValueError), filled and optimized. Nested shells make voids, disjoint ones separate
    regions with tet refs 1, 2, ... ``sizes`` is an array (one per input vertex) or a callable
    evaluated on the input vertices.

    ``threads``: threads the run uses (None: the cores present), as :func:`adapt`; the output
    is the same bytes for any count.
    """
    if threads is not None and int(threads) < 1:
        raise ValueError(f"threads must be at least 1, got {threads}")
    vertices = _points("vertices", vertices)
    faces = _ids("faces", faces, 3, len(vertices))
    surface = TetMesh(vertices, triangles=faces, triangle_refs=refs)
    if sizes is not None and (hsiz is not None or hausd is not None):
        raise ValueError("give only one of hsiz, sizes and hausd")
    if hsiz is None and hausd is None and sizes is None and not keep_surface:
        raise ValueError("no size: give hsiz, sizes or hausd (or keep_surface=True)")
    return adapt(surface, hsiz=hsiz, sizes=_vertex_sizes(sizes, vertices), hmin=hmin,
                 hmax=hmax, hgrad=hgrad, hausd=hausd, keep_surface=keep_surface,
                 strict=strict, verbose=verbose, progress=progress, threads=threads)


def quality(mesh, hsiz=None, sizes=None, bench_field=None):
    """The quality report (the app's --stats JSON) as a dict: counts, Qe, dihedral angles and,
    with a size (``hsiz``, ``sizes`` per vertex or a callable, or ``bench_field``), the
    conformity Qt of every edge."""
    mesh = _as_mesh(mesh)
    if sum(x is not None for x in (hsiz, sizes, bench_field)) > 1:
        raise ValueError("give only one of hsiz, sizes and bench_field")
    import json
    return json.loads(_hdimesh.quality(mesh._native(), hsiz=_number("hsiz", hsiz),
                                       sizes=_vertex_sizes(sizes, mesh.points),
                                       bench_field=bench_field or ""))


def check(mesh):
    """The mesh checker's violations, a list of Violation(kind, element, message); empty when
    the mesh is valid (positive tets, consistent faces, a closed oriented boundary equal to
    the triangles, volume conserved)."""
    mesh = _as_mesh(mesh)
    return [Violation(*v) for v in _hdimesh.check(mesh._native())]


def from_meshio(m, fields=False):
    """A TetMesh from a meshio.Mesh: its tetra and triangle cells, refs from the cell data
    "medit:ref" or "gmsh:physical" when present; with ``fields=True``, its point data as the
    mesh's ``fields`` (to carry through :func:`adapt` with ``fields=mesh.fields``)."""
    tets, triangles, tet_refs, triangle_refs = [], [], [], []
    key = next((k for k in ("medit:ref", "gmsh:physical", "ref") if k in m.cell_data), None)
    for i, block in enumerate(m.cells):
        refs = m.cell_data[key][i] if key else np.zeros(len(block.data), dtype=_INDEX)
        if block.type == "tetra":
            tets.append(block.data)
            tet_refs.append(refs)
        elif block.type == "triangle":
            triangles.append(block.data)
            triangle_refs.append(refs)
    cat = (lambda parts, cols: np.concatenate(parts) if parts
           else np.zeros((0, cols) if cols > 1 else (0,), dtype=_INDEX))
    return TetMesh(m.points, tets=cat(tets, 4), triangles=cat(triangles, 3),
                   tet_refs=cat(tet_refs, 1), triangle_refs=cat(triangle_refs, 1),
                   fields=dict(m.point_data) if fields else None)


def to_meshio(mesh):
    """A meshio.Mesh with tetra and triangle cells and their refs as "medit:ref", and the
    mesh's ``fields`` as point data."""
    import meshio
    mesh = _as_mesh(mesh)
    cells, refs = [], []
    for kind, data, ref in (("tetra", mesh.tets, mesh.tet_refs),
                            ("triangle", mesh.triangles, mesh.triangle_refs)):
        if len(data):
            cells.append((kind, data))
            refs.append(ref)
    return meshio.Mesh(mesh.points, cells, cell_data={"medit:ref": refs},
                       point_data=dict(mesh.fields))
