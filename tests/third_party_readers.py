#!/usr/bin/python3
"""Third-party readers agree with our writers, and our reader with Gmsh's own files.

usage: third_party_readers.py MESHCONVERT DATA_DIR

1. meshconvert writes data/sphere480.mesh (refs varied by meshio first) as .mesh, .meshb, .msh (2.2 and 4.1, ASCII and
   binary) and .vtu; meshio (Debian's python3-meshio) reads each and must find the same
   points (bitwise), tet and triangle counts and refs as it finds in the original file.
2. The gmsh CLI reads each .msh and re-saves it; meshio must find the same counts and refs.
3. Gmsh meshes a box (physical groups on volume and faces) in 2.2/4.1 ASCII/binary;
   meshconvert reads them (which rejects any tet that is not positive in our numbering) and
   writes .mesh; counts and refs must match what meshio reads from Gmsh's file.
4. The app's error contract: a bad file gives exit code 1, one stderr line naming file and
   line, and no output file.

Installs nothing: the test command installs python3-meshio and gmsh beforehand.
"""

import os
import shutil
import subprocess
import sys
import tempfile
import warnings

import numpy as np

warnings.filterwarnings("ignore")
import meshio  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def run(cmd):
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit("command failed: %s\n%s%s" % (" ".join(cmd), result.stdout, result.stderr))
    return result


def cells_and_refs(mesh, ref_key):
    """{cell type: (connectivity, refs)} for tetra and triangle blocks, blocks concatenated."""
    out = {}
    for i, block in enumerate(mesh.cells):
        if block.type not in ("tetra", "triangle"):
            continue
        refs = np.asarray(mesh.cell_data[ref_key][i]).astype(np.int64)
        conn, old = out.get(block.type, (np.zeros((0, block.data.shape[1]), np.int64), np.zeros(0, np.int64)))
        out[block.type] = (np.vstack([conn, block.data.astype(np.int64)]), np.concatenate([old, refs]))
    return out


def sorted_rows(conn, refs, points=None):
    """Cells as sorted rows (ref, vertex ids) or, given points, (ref, vertex coordinates): the
    coordinate form does not depend on the node numbering (gmsh renumbers nodes on saving)."""
    if points is None:
        rows = np.hstack([refs[:, None].astype(np.float64), conn.astype(np.float64)])
    else:
        rows = np.hstack([refs[:, None].astype(np.float64), points[conn].reshape(len(conn), -1)])
    return rows[np.lexsort(rows.T[::-1])]


def compare(name, reference, mesh, ref_key, same_order, renumbered=False):
    """Same points, cells and refs; `renumbered`: node order may differ (compare by coordinates)."""
    ref_cells = cells_and_refs(reference, "medit:ref")
    got = cells_and_refs(mesh, ref_key)
    check(mesh.points.shape == reference.points.shape, "%s: %s points, expected %s" % (name, mesh.points.shape, reference.points.shape))
    if mesh.points.shape == reference.points.shape:
        same_points = np.array_equal(mesh.points, reference.points) if not renumbered else np.array_equal(
            np.unique(mesh.points, axis=0), np.unique(reference.points, axis=0))
        check(same_points, "%s: coordinates differ" % name)
    for cell_type in ("tetra", "triangle"):
        want_conn, want_refs = ref_cells[cell_type]
        if cell_type not in got:
            check(False, "%s: no %s cells" % (name, cell_type))
            continue
        conn, refs = got[cell_type]
        check(len(conn) == len(want_conn), "%s: %d %s, expected %d" % (name, len(conn), cell_type, len(want_conn)))
        if len(conn) != len(want_conn):
            continue
        if same_order:
            check(np.array_equal(conn, want_conn) and np.array_equal(refs, want_refs), "%s: %s or refs differ" % (name, cell_type))
        elif renumbered:
            check(np.array_equal(sorted_rows(conn, refs, mesh.points), sorted_rows(want_conn, want_refs, reference.points)),
                  "%s: %s or refs differ (by coordinates)" % (name, cell_type))
        else:
            check(np.array_equal(sorted_rows(conn, refs), sorted_rows(want_conn, want_refs)), "%s: %s or refs differ (as sets)" % (name, cell_type))
    print("ok  %-16s %d points, %s" % (name, len(mesh.points), ", ".join("%d %s" % (len(got[t][0]), t) for t in sorted(got))))


def main():
    meshconvert, data_dir = sys.argv[1], sys.argv[2]
    work = tempfile.mkdtemp(prefix="hdimesh_third_party_")
    # sphere480 with varied refs (its own are all 1), written by meshio itself
    sphere = meshio.read(os.path.join(data_dir, "sphere480.mesh"))
    refs = []
    for block in sphere.cells:
        count = len(block.data)
        refs.append(np.arange(count) % 3 + 1 if block.type == "tetra" else np.arange(count) % 4 + 10)
    sphere.cell_data = {"medit:ref": refs}
    source = os.path.join(work, "sphere_refs.mesh")
    meshio.write(source, sphere, file_format="medit")
    reference = meshio.read(source)

    # 1. our outputs through meshio
    outputs = [
        ("out.mesh", [], "medit:ref", True),
        ("out.meshb", [], "medit:ref", True),
        ("out22.msh", ["--msh-version", "2.2"], "gmsh:physical", True),
        ("out22b.msh", ["--msh-version", "2.2", "--binary"], "gmsh:physical", True),
        ("out41.msh", [], "gmsh:physical", False),
        ("out41b.msh", ["--binary"], "gmsh:physical", False),
        ("out.vtu", [], "ref", True),
    ]
    for name, flags, ref_key, same_order in outputs:
        path = os.path.join(work, name)
        run([meshconvert, source, path] + flags)
        compare(name, reference, meshio.read(path), ref_key, same_order)

    # 2. the gmsh CLI reads our .msh files and re-saves them
    for name, _, _, _ in outputs:
        if not name.endswith(".msh"):
            continue
        resaved = os.path.join(work, "gmsh_" + name)
        result = run(["gmsh", os.path.join(work, name), "-0", "-format", "msh41", "-o", resaved])
        check("Error" not in result.stdout + result.stderr, "gmsh reports an error on %s" % name)
        compare("gmsh(" + name + ")", reference, meshio.read(resaved), "gmsh:physical", False, renumbered=True)

    # 3. Gmsh's own meshes through our reader
    geo = os.path.join(work, "box.geo")
    with open(geo, "w") as f:
        f.write('SetFactory("OpenCASCADE");\nBox(1) = {0, 0, 0, 1, 1, 1};\n'
                "Physical Volume(7) = {1};\nPhysical Surface(3) = {1, 2, 3};\n"
                "Physical Surface(4) = {4, 5, 6};\nMesh.MeshSizeMax = 0.25;\n")
    for fmt, binary in (("msh22", False), ("msh22", True), ("msh41", False), ("msh41", True)):
        name = "gmsh_box_%s%s" % (fmt, "b" if binary else "")
        msh = os.path.join(work, name + ".msh")
        run(["gmsh", geo, "-3", "-format", fmt, "-o", msh] + (["-bin"] if binary else []))
        ours = os.path.join(work, name + ".mesh")
        run([meshconvert, msh, ours])  # reads, checks (positive tets, closed boundary), writes
        theirs = meshio.read(msh)
        ref_cells = cells_and_refs(theirs, "gmsh:physical")
        back = cells_and_refs(meshio.read(ours), "medit:ref")
        for cell_type in ("tetra", "triangle"):
            want_conn, want_refs = ref_cells[cell_type]
            conn, refs = back[cell_type]
            check(len(conn) == len(want_conn), "%s: %d %s, Gmsh wrote %d" % (name, len(conn), cell_type, len(want_conn)))
            check(sorted(refs.tolist()) == sorted(want_refs.tolist()), "%s: %s refs differ" % (name, cell_type))
        check(set(back["triangle"][1].tolist()) == {3, 4} and set(back["tetra"][1].tolist()) == {7},
              "%s: physical groups did not become refs" % name)
        print("ok  %-16s Gmsh's mesh read: %d tetra, %d triangle" % (name, len(back["tetra"][0]), len(back["triangle"][0])))

    # 4. error contract of the app
    bad = os.path.join(work, "bad.mesh")
    with open(bad, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 nan 0 0\nEnd\n")
    target = os.path.join(work, "never_written.mesh")
    result = subprocess.run([meshconvert, bad, target], capture_output=True, text=True)
    lines = result.stderr.strip().splitlines()
    check(result.returncode == 1, "meshconvert on a bad file: exit code %d, expected 1" % result.returncode)
    check(len(lines) == 1 and lines[0].startswith("meshconvert: error: " + bad + ":5:"),
          "meshconvert on a bad file: stderr %r" % result.stderr)
    check(not os.path.exists(target), "meshconvert left an output file after an error")
    print("ok  error contract:", lines[0] if lines else "")

    if failures:
        print("%d failure(s); files kept in %s" % (len(failures), work))
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("all third-party checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
