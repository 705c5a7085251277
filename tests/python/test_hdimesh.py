"""The Python module against the app and against bad input (run by CTest: python_module).

Environment: PYTHONPATH holds the built package, HDIMESH_DATA the data/ folder, HDIMESH_ADAPT
the adapt app.
"""
import itertools
import os
import subprocess
import threading
import time

import numpy as np
import pytest

import hdimesh

DATA = os.environ.get("HDIMESH_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))
ADAPT = os.environ.get("HDIMESH_ADAPT", "adapt")
SPHERE = os.path.join(DATA, "sphere480.mesh")
ICOSPHERE = os.path.join(DATA, "icosphere320.obj")


def one_tet():
    #      3
    #      |
    #      0 --- 1     positive: det(v1-v0, v2-v0, v3-v0) > 0
    #     /
    #    2 (y)
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    tets = np.array([[0, 1, 2, 3]])
    triangles = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return points, tets, triangles


def same_mesh(a, b):
    for name in ("points", "tets", "triangles", "tet_refs", "triangle_refs"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


# --- data and files

def test_numpy_round_trip(tmp_path):
    mesh = hdimesh.read(SPHERE)
    assert mesh.points.shape[1] == 3 and mesh.tets.shape[1] == 4 and len(mesh.tets) > 0
    path = tmp_path / "copy.mesh"
    hdimesh.write(mesh, path)
    same_mesh(mesh, hdimesh.read(path))
    # arrays of the right type are held as given, not copied
    points, tets, triangles = one_tet()
    m = hdimesh.TetMesh(points, tets.astype(np.int32), triangles)
    assert m.points is points or np.shares_memory(m.points, points)
    assert hdimesh.check(m) == []


def test_meshio_round_trip(tmp_path):
    meshio = pytest.importorskip("meshio")
    mesh = hdimesh.read(SPHERE)
    same_mesh(mesh, hdimesh.from_meshio(hdimesh.to_meshio(mesh)))
    # a file meshio writes, read by us; ours, read by meshio
    meshio.write(tmp_path / "by_meshio.mesh", hdimesh.to_meshio(mesh))
    same_mesh(mesh, hdimesh.read(tmp_path / "by_meshio.mesh"))
    hdimesh.write(mesh, tmp_path / "ours.vtu")
    back = meshio.read(tmp_path / "ours.vtu")
    assert np.allclose(back.points, mesh.points)
    assert np.array_equal(back.cells_dict["tetra"], mesh.tets)


def test_surface_read_write(tmp_path):
    surface = hdimesh.read(ICOSPHERE)
    assert surface.is_surface and len(surface.triangles) == 320
    hdimesh.write(surface, tmp_path / "copy.off")
    again = hdimesh.read(tmp_path / "copy.off")
    corners = lambda m: np.sort(np.sort(m.points[m.triangles].reshape(-1, 9), axis=1), axis=0)
    assert np.allclose(corners(again), corners(surface), atol=1e-6)  # OFF: OpenMesh writes floats


# --- the library calls

def test_adapt_matches_the_app(tmp_path):
    """The paper's case A on sphere480: the same mesh as `adapt --bench-field A`."""
    out = tmp_path / "app.mesh"
    subprocess.run([ADAPT, SPHERE, "-o", str(out), "--bench-field", "A", "-v", "0"], check=True)
    app = hdimesh.read(out)
    ours = hdimesh.adapt(hdimesh.read(SPHERE), bench_field="A")
    same_mesh(app, ours)
    a = hdimesh.quality(app, bench_field="A")
    b = hdimesh.quality(ours, bench_field="A")
    assert a == b
    assert b["tets"] == len(ours.tets) and b["min_qe"] > 0.3 and b["percent_qt_ge_066"] > 99
    assert hdimesh.check(ours) == []


def test_threads_give_the_same_mesh():
    """threads= reaches the engine; the mesh is the same for any count, as the app's."""
    sphere = hdimesh.read(SPHERE)
    one = hdimesh.adapt(sphere, bench_field="A", threads=1)
    for threads in (2, 3, None):
        same_mesh(one, hdimesh.adapt(sphere, bench_field="A", threads=threads))
    with pytest.raises(ValueError, match="threads must be at least 1"):
        hdimesh.adapt(sphere, bench_field="A", threads=0)


def test_mesh_volume_threads_give_the_same_mesh():
    """threads= reaches the volume-from-surface path: the same mesh for any count."""
    surface = hdimesh.read(ICOSPHERE)
    one = hdimesh.mesh_volume(surface.points, surface.triangles, hsiz=0.15, threads=1)
    assert len(one.tets) > 0 and hdimesh.check(one) == []
    for threads in (2, 3, None):
        same_mesh(one, hdimesh.mesh_volume(surface.points, surface.triangles, hsiz=0.15,
                                           threads=threads))
    with pytest.raises(ValueError, match="threads must be at least 1"):
        hdimesh.mesh_volume(surface.points, surface.triangles, hsiz=0.15, threads=0)


def test_bounds_alone_keep_the_input_sizes_as_the_app(tmp_path):
    """Only hausd and hmax given: the tet mesh keeps its own sizes within them, as `adapt`."""
    out = tmp_path / "app.mesh"
    subprocess.run([ADAPT, SPHERE, "-o", str(out), "--hausd", "0.01", "--hmax", "0.3", "-v", "0"],
                   check=True)
    ours = hdimesh.adapt(hdimesh.read(SPHERE), hausd=0.01, hmax=0.3)
    same_mesh(hdimesh.read(out), ours)
    assert hdimesh.check(ours) == []


def test_callable_sizes_in_batches():
    calls = []

    def size(points):
        calls.append(len(points))
        return 0.12 + 0.08 * np.abs(points[:, 0])

    mesh = hdimesh.read(SPHERE)
    out = hdimesh.adapt(mesh, sizes=size)
    assert hdimesh.check(out) == []
    assert len(calls) <= 8 and min(calls) > 100, calls  # batches, never a point at a time
    assert hdimesh._conformity(out, size, 0, 0) >= 0.99
    # an array at the vertices is the same field, sampled once
    once = hdimesh.adapt(mesh, sizes=size(mesh.points), size_rounds=1)
    assert len(once.tets) > len(mesh.tets)


def test_progress_and_gil_released():
    mesh = hdimesh.read(SPHERE)
    stages = []
    result = {}
    worker = threading.Thread(
        target=lambda: result.update(mesh=hdimesh.adapt(mesh, hsiz=0.06,
                                                        progress=lambda s, n: stages.append(s))))
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1  # runs only while adapt has let go of the GIL
        time.sleep(0.001)
    worker.join()
    assert ticks >= 20, ticks
    assert "pass 1" in stages and stages[-1] == "optimize", stages
    assert hdimesh.check(result["mesh"]) == []


def test_progress_can_stop_a_run():
    def stop(stage, tets):
        if stage == "pass 2":
            raise KeyboardInterrupt("stopped by the caller")

    with pytest.raises(KeyboardInterrupt, match="stopped by the caller"):
        hdimesh.adapt(hdimesh.read(SPHERE), hsiz=0.1, progress=stop)


def test_remesh_surface_and_mesh_volume():
    surface = hdimesh.read(ICOSPHERE)
    v, f = hdimesh.remesh_surface(surface.points, surface.triangles, hsiz=0.15, ridge_angle=60)
    assert v.shape[1] == 3 and f.shape[1] == 3 and len(f) > 320
    radius = np.linalg.norm(v, axis=1)
    assert radius.max() - radius.min() < 0.05
    v2, f2, r2 = hdimesh.remesh_surface(surface.points, surface.triangles, hsiz=0.15,
                                        refs=np.full(320, 7))
    assert set(np.unique(r2)) == {7}
    solid = hdimesh.mesh_volume(v, f, hsiz=0.15)
    assert len(solid.tets) > 0 and hdimesh.check(solid) == []
    q = hdimesh.quality(solid, hsiz=0.15)
    assert q["min_qe"] > 0.2 and q["tets"] == len(solid.tets)


def test_mesh_volume_repairs_a_hole_unless_strict():
    surface = hdimesh.read(ICOSPHERE)
    open_faces = surface.triangles[1:]  # a 3-edge hole
    solid = hdimesh.mesh_volume(surface.points, open_faces, hsiz=0.2)
    assert len(solid.tets) > 0 and hdimesh.check(solid) == []
    with pytest.raises(ValueError, match="the surface is open: 1 boundary loop"):
        hdimesh.mesh_volume(surface.points, open_faces, hsiz=0.2, strict=True)


def test_check_names_violations():
    points, tets, triangles = one_tet()
    inverted = hdimesh.TetMesh(points, tets[:, [1, 0, 2, 3]], triangles)
    found = hdimesh.check(inverted)
    assert found and any(v.element == 0 for v in found), found


# --- bad input: a clear exception, never a crash

@pytest.mark.parametrize("make, pattern", [
    (lambda p, t, f: hdimesh.TetMesh(p[:, :2], t, f), r"points must have shape \(n, 3\)"),
    (lambda p, t, f: hdimesh.TetMesh(np.where(p == 1, np.nan, p), t, f), "not finite"),
    (lambda p, t, f: hdimesh.TetMesh(p, t + 1, f), "out of range"),
    (lambda p, t, f: hdimesh.TetMesh(p, t[:, :3], f), r"tets must have shape \(m, 4\)"),
    (lambda p, t, f: hdimesh.TetMesh(p, t * 0.5, f), "integers"),
    (lambda p, t, f: hdimesh.TetMesh(p, t, f, tet_refs=[1, 2]), "tet_refs has 2 values"),
    (lambda p, t, f: hdimesh.adapt(hdimesh.TetMesh(p, t[:, [1, 0, 2, 3]], f), hsiz=0.5),
     "negative volume"),
    (lambda p, t, f: hdimesh.adapt(hdimesh.TetMesh(p, t, f), hsiz=-1), "hsiz must be a positive"),
    (lambda p, t, f: hdimesh.adapt(hdimesh.TetMesh(p, t, f), hsiz=0.5, sizes=[1, 1, 1, 1]),
     "only one of"),
    (lambda p, t, f: hdimesh.adapt(hdimesh.TetMesh(p, t, f), sizes=[1, 1]),
     "one value per vertex"),
    (lambda p, t, f: hdimesh.adapt(hdimesh.TetMesh(p, t, f), sizes=[1, 1, -1, 1]),
     r"sizes\[2\]"),
    (lambda p, t, f: hdimesh.adapt(hdimesh.TetMesh(p, t, f), sizes=lambda x: np.zeros(len(x))),
     r"sizes\[0\]"),
    (lambda p, t, f: hdimesh.adapt(hdimesh.TetMesh(p, t, f)), "no size field"),
    (lambda p, t, f: hdimesh.mesh_volume(p, f[:3], hsiz=0.3), "open|boundary"),
    (lambda p, t, f: hdimesh.remesh_surface(p, f, hsiz=0.3, ridge_angle=500), "ridge_angle"),
])
def test_bad_input(make, pattern):
    points, tets, triangles = one_tet()
    with pytest.raises(ValueError, match=pattern):
        make(points, tets, triangles)


def test_bad_files(tmp_path):
    with pytest.raises(OSError, match="no_such.mesh"):
        hdimesh.read(tmp_path / "no_such.mesh")
    bad = tmp_path / "bad.mesh"
    bad.write_text("MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n")
    with pytest.raises(ValueError, match="bad.mesh"):
        hdimesh.read(bad)
    with pytest.raises(OSError):
        hdimesh.write(hdimesh.TetMesh(*one_tet()), tmp_path / "no_dir" / "x.mesh")
    with pytest.raises(TypeError):
        hdimesh.adapt({"points": np.zeros((4, 3))}, hsiz=1)


# --- fields carried through adapt

def linear(points):
    return 1 + 2 * points[:, 0] - points[:, 1] + 3 * points[:, 2]


def test_adapt_carries_linear_fields_exactly():
    mesh = hdimesh.read(SPHERE)
    u = linear(mesh.points)
    grad = np.stack([u, 2 * u, -u], axis=1)
    out = hdimesh.adapt(mesh, hsiz=0.3, fields={"u": u, "grad": grad, "t": grad[:, :, None]})
    assert sorted(out.fields) == ["grad", "t", "u"]
    n = len(out.points)
    assert out.fields["u"].shape == (n,)
    assert out.fields["grad"].shape == (n, 3)
    assert out.fields["t"].shape == (n, 3, 1)  # the trailing shape as given
    expected = linear(out.points)
    assert np.max(np.abs(out.fields["u"] - expected)) <= 1e-12
    assert np.max(np.abs(out.fields["grad"] - np.stack([expected, 2 * expected, -expected],
                                                       axis=1))) <= 1e-12
    # opt-in: without fields, the same mesh and none carried
    plain = hdimesh.adapt(mesh, hsiz=0.3)
    assert plain.fields == {}
    same_mesh(plain, out)


def test_meshio_point_data_carried():
    pytest.importorskip("meshio")
    m = hdimesh.to_meshio(hdimesh.read(SPHERE))
    m.point_data["u"] = linear(m.points)
    assert np.array_equal(hdimesh.from_meshio(m, fields=True).fields["u"], m.point_data["u"])
    out = hdimesh.adapt(m, hsiz=0.3, fields=m.point_data)  # a meshio.Mesh in, as from_meshio
    back = hdimesh.to_meshio(out)
    assert np.max(np.abs(back.point_data["u"] - linear(back.points))) <= 1e-12


@pytest.mark.parametrize("fields, pattern", [
    ({"u": [1.0, 2.0]}, r"fields\['u'\] must have shape \(4,\)"),
    ({"u": np.zeros((4, 0))}, r"fields\['u'\] must have shape"),
    ({"u": [1.0, np.nan, 0.0, 0.0]}, r"fields\['u'\] at vertex 1 is not finite"),
    ({"v": [[0, 0], [0, 0], [np.inf, 0], [0, 0]]}, r"fields\['v'\] at vertex 2 is not finite"),
])
def test_bad_fields(fields, pattern):
    with pytest.raises(ValueError, match=pattern):
        hdimesh.adapt(hdimesh.TetMesh(*one_tet()), hsiz=0.5, fields=fields)


def test_fields_need_a_tet_input():
    points, _, triangles = one_tet()
    with pytest.raises(ValueError, match="fields need a tet mesh"):
        hdimesh.adapt(hdimesh.TetMesh(points, triangles=triangles), hsiz=0.5,
                      fields={"u": np.zeros(4)})
    with pytest.raises(TypeError, match="fields must be a dict"):
        hdimesh.adapt(hdimesh.TetMesh(*one_tet()), hsiz=0.5, fields=[np.zeros(4)])


def test_fields_through_gmsh_node_data(tmp_path):
    mesh = hdimesh.read(SPHERE)
    u = linear(mesh.points)
    out = hdimesh.adapt(mesh, hsiz=0.4, fields={"u": u, "v": np.stack([u, u, -u], axis=1)})
    hdimesh.write(out, tmp_path / "out.msh")
    back = hdimesh.read(tmp_path / "out.msh", fields=True)
    assert sorted(back.fields) == ["u", "v"]
    assert np.array_equal(back.fields["u"], out.fields["u"])
    assert np.array_equal(back.fields["v"], out.fields["v"])
    assert hdimesh.read(tmp_path / "out.msh").fields == {}  # opt-in
    hdimesh.write(mesh, tmp_path / "plain.msh")
    with pytest.raises(ValueError, match=r"plain.msh:\d+: no \$NodeData section"):
        hdimesh.read(tmp_path / "plain.msh", fields=True)
    with pytest.raises(ValueError, match=r"read from a \.msh"):
        hdimesh.read(SPHERE, fields=True)


# --- anisotropic metrics

def box(n):
    """The unit cube cut into n³ cells of 6 tets each (Kuhn), with its boundary triangles."""
    g = np.linspace(0, 1, n + 1)
    points = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)
    corner = np.arange((n + 1) ** 3).reshape(n + 1, n + 1, n + 1)[:-1, :-1, :-1].reshape(-1)
    step = np.array([(n + 1) ** 2, n + 1, 1])
    tets = np.concatenate([np.stack([corner, corner + step[a], corner + step[a] + step[b],
                                     corner + step.sum()], axis=1)
                           for a, b, _ in itertools.permutations(range(3))])
    p = points[tets]
    flip = np.linalg.det(p[:, 1:] - p[:, :1]) < 0
    tets[flip] = tets[flip][:, [1, 0, 2, 3]]
    faces = np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 3, 2]], tets[:, [0, 1, 3]],
                            tets[:, [0, 2, 1]]])
    _, inverse, count = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True,
                                  return_counts=True)
    return hdimesh.TetMesh(points, tets, faces[count[inverse.reshape(-1)] == 1])


LAYER = np.diag([1 / 0.5**2, 1 / 0.5**2, 1 / 0.05**2])
LAYER6 = LAYER[[0, 1, 1, 2, 2, 2], [0, 0, 1, 0, 1, 2]]  # Medit's order m11 m12 m22 m13 m23 m33


def test_metric_forms_give_the_same_mesh():
    mesh = box(3)
    n = len(mesh.points)
    as_rows = hdimesh.adapt(mesh, metric=np.tile(LAYER6, (n, 1)))
    as_matrices = hdimesh.adapt(mesh, metric=np.tile(LAYER, (n, 1, 1)))
    calls = []
    as_callable = hdimesh.adapt(
        mesh, metric=lambda x: calls.append(len(x)) or np.tile(LAYER, (len(x), 1, 1)),
        size_rounds=1)
    assert calls == [n]  # one batch at the input's vertices
    same_mesh(as_rows, as_matrices)
    same_mesh(as_rows, as_callable)
    assert np.array_equal(as_rows.points, as_callable.points)
    assert not hdimesh.check(as_rows)
    assert as_rows.metric.shape == (len(as_rows.points), 6)
    assert np.allclose(as_rows.metric, LAYER6, rtol=1e-9)  # a constant metric stays itself
    # anisotropic: the tets are flat across z
    z_extent = [np.ptp(as_rows.points[t][:, 2]) for t in as_rows.tets[:200]]
    x_extent = [np.ptp(as_rows.points[t][:, 0]) for t in as_rows.tets[:200]]
    assert np.median(x_extent) > 3 * np.median(z_extent)
    # the next round starts from result.metric; no metric given: none returned
    again = hdimesh.adapt(as_rows, metric=as_rows.metric)
    assert again.metric.shape == (len(again.points), 6)
    assert hdimesh.adapt(mesh, hsiz=0.5).metric is None


def test_callable_metric_is_resampled_on_the_result():
    calls = []
    out = hdimesh.adapt(box(3), metric=lambda x: calls.append(len(x)) or np.tile(
        LAYER6, (len(x), 1)), size_rounds=2)
    assert len(calls) >= 2 and calls[0] == 64  # the input, then the result (and its edges)
    assert out.metric.shape == (len(out.points), 6)


def test_metric_carries_fields():
    mesh = box(3)
    out = hdimesh.adapt(mesh, metric=np.tile(LAYER6, (len(mesh.points), 1)),
                        fields={"u": linear(mesh.points)})
    assert np.max(np.abs(out.fields["u"] - linear(out.points))) <= 1e-12


def bad_metric(i, value):
    m = np.tile(LAYER, (64, 1, 1))
    m[i] = value
    return m


@pytest.mark.parametrize("metric, pattern", [
    (bad_metric(5, [[4, 1, 0], [0, 4, 0], [0, 0, 400]]),
     r"metric\[5\] \(vertex 6\) is not symmetric"),
    (bad_metric(7, np.diag([4, np.nan, 400])), r"metric at vertex 8 is not finite"),
    (bad_metric(9, np.diag([4, -4, 400])), r"metric at vertex 10 is not positive definite"),
    (np.tile(LAYER6, (63, 1)), r"378 metric values for 64 vertices"),
    (np.tile(LAYER6[:5], (64, 1)), r"metric must have shape \(n, 6\)"),
    (lambda x: np.zeros((len(x), 3)), r"metric must have shape"),
])
def test_bad_metric(metric, pattern):
    with pytest.raises(ValueError, match=pattern):
        hdimesh.adapt(box(3), metric=metric)


def test_metric_refusals():
    mesh = box(3)
    m = np.tile(LAYER6, (len(mesh.points), 1))
    for other in ({"hsiz": 0.3}, {"sizes": np.ones(len(mesh.points))}, {"bench_field": "A"}):
        with pytest.raises(ValueError, match="either metric or one of"):
            hdimesh.adapt(mesh, metric=m, **other)
    surface = hdimesh.TetMesh(mesh.points, triangles=mesh.triangles)
    with pytest.raises(ValueError, match="anisotropic metrics need a tet mesh input"):
        hdimesh.adapt(surface, metric=m)
