#!/usr/bin/env python3
"""Hostile files through every app: mutants of small valid inputs in each format the apps read
(.mesh, .meshb, .msh 2.2/4.1 ASCII and binary, .sol, OBJ, OFF, STL, PLY).

Each mutant is one of: bytes flipped, the file truncated, a block of it repeated, or a number
replaced by -1, 1e308, nan or 2^32. Every app that reads the format runs on it, with a time limit.
An app may accept or refuse a mutant; it must not crash or hang, a refusal is an "app: error:"
line and leaves no output file, and an acceptance writes its output.

usage: fuzz_apps.py APPS_DIR WORK_DIR [--mutants N] [--seed S] [--timeout SECONDS]
"""

import argparse
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys

NUMBER = re.compile(rb"-?\d+(\.\d+)?([eE][-+]?\d+)?")
HOSTILE_NUMBERS = [b"-1", b"1e308", b"nan", b"4294967296"]


def cube_mesh():
    """[0,1]^3 as 2x2x2 Kuhn cubes (48 tets), its 48 boundary triangles, Medit ASCII."""
    n = 2
    vid = lambda i, j, k: 1 + i + (n + 1) * (j + (n + 1) * k)
    points = [(i / n, j / n, k / n) for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)]
    kuhn = [(0, 1, 3, 7), (0, 3, 2, 7), (0, 2, 6, 7), (0, 6, 4, 7), (0, 4, 5, 7), (0, 5, 1, 7)]
    tets = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                corner = lambda b: vid(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1))
                for t in kuhn:
                    tets.append(tuple(corner(b) for b in t))
    # orient positive, then collect the unshared faces outward
    def vol(t):
        a, b, c, d = (points[v - 1] for v in t)
        u = [b[x] - a[x] for x in range(3)]
        v = [c[x] - a[x] for x in range(3)]
        w = [d[x] - a[x] for x in range(3)]
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                u[2] * (v[0] * w[1] - v[1] * w[0]))
    tets = [t if vol(t) > 0 else (t[0], t[1], t[3], t[2]) for t in tets]
    faces = {}
    for t in tets:
        for f in ((t[1], t[2], t[3]), (t[0], t[3], t[2]), (t[0], t[1], t[3]), (t[0], t[2], t[1])):
            faces.setdefault(tuple(sorted(f)), []).append(f)
    boundary = [fs[0] for fs in faces.values() if len(fs) == 1]
    out = ["MeshVersionFormatted 2", "Dimension 3", "Vertices", str(len(points))]
    out += ["%g %g %g 0" % p for p in points]
    out += ["Triangles", str(len(boundary))] + ["%d %d %d 1" % f for f in boundary]
    out += ["Tetrahedra", str(len(tets))] + ["%d %d %d %d 1" % t for t in tets]
    out += ["End", ""]
    return "\n".join(out).encode(), len(points)


def octahedron():
    points = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    return points, faces


def surface_files():
    points, faces = octahedron()
    obj = "".join("v %g %g %g\n" % p for p in points) + "".join(
        "f %d %d %d\n" % tuple(v + 1 for v in f) for f in faces)
    off = "OFF\n%d %d 0\n" % (len(points), len(faces)) + "".join(
        "%g %g %g\n" % p for p in points) + "".join("3 %d %d %d\n" % f for f in faces)
    stl = "solid octahedron\n" + "".join(
        "facet normal 0 0 0\nouter loop\n" + "".join("vertex %g %g %g\n" % points[v] for v in f) +
        "endloop\nendfacet\n" for f in faces) + "endsolid octahedron\n"
    ply = ("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
           "property float z\nelement face %d\nproperty list uchar int vertex_indices\n"
           "end_header\n" % (len(points), len(faces)) + "".join("%g %g %g\n" % p for p in points) +
           "".join("3 %d %d %d\n" % f for f in faces))
    return {".obj": obj.encode(), ".off": off.encode(), ".stl": stl.encode(), ".ply": ply.encode()}


def mutate(data, rng):
    kind = rng.randrange(4)
    if kind == 0:  # bytes flipped
        data = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            at = rng.randrange(len(data))
            data[at] = rng.choice(b"09-.e \n$#\x00\x7f\xff") if rng.random() < 0.5 else rng.randrange(256)
        return bytes(data)
    if kind == 1:  # truncated
        return data[:rng.randrange(len(data))]
    if kind == 2:  # a block repeated
        a = rng.randrange(len(data))
        b = min(len(data), a + rng.randint(1, 400))
        return data[:b] + data[a:b] + data[b:]
    numbers = list(NUMBER.finditer(data))  # a number replaced
    if not numbers:
        return data
    for _ in range(rng.randint(1, 3)):
        m = rng.choice(numbers)
        data = data[:m.start()] + rng.choice(HOSTILE_NUMBERS) + data[m.end():]
        numbers = list(NUMBER.finditer(data))
    return data


def run_one(job):
    app, args, output, timeout = job
    if output and os.path.exists(output):
        os.remove(output)
    try:
        result = subprocess.run([app] + args, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "hang (over %g s)" % timeout
    name = os.path.basename(app)
    err = result.stderr.decode(errors="replace").strip().splitlines()
    if result.returncode < 0:
        return "crash (signal %d)" % -result.returncode
    if output is None:  # meshstat: exit 1 is also its verdict on a mesh it could read
        if result.returncode == 0 or b"check: " in result.stdout:
            return None
        output = ""
    if result.returncode == 0:
        return None if os.path.exists(output) else "exit 0 without an output file"
    if output and os.path.exists(output):
        return "exit %d but left %s" % (result.returncode, output)
    errors = [line for line in err if line.startswith(name + ": error: ")]
    if len(errors) != 1:
        return "exit %d without one '%s: error:' line: %r" % (result.returncode, name, err[:3])
    return None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("apps")
    parser.add_argument("work")
    parser.add_argument("--mutants", type=int, default=200, help="mutants per format")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=30.0)
    args = parser.parse_args()
    app = lambda name: os.path.join(args.apps, name)
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    work = lambda name: os.path.join(args.work, name)

    # the valid sources, each format written by the apps themselves where they write it
    cube, cube_vertices = cube_mesh()
    with open(work("cube.mesh"), "wb") as f:
        f.write(cube)
    sources = {"cube.mesh": cube}
    for name, flags in [("cube.meshb", []), ("cube22.msh", ["--msh-version", "2.2"]),
                        ("cube22b.msh", ["--msh-version", "2.2", "--binary"]),
                        ("cube41.msh", []), ("cube41b.msh", ["--binary"])]:
        subprocess.run([app("meshconvert"), work("cube.mesh"), work(name)] + flags, check=True)
        with open(work(name), "rb") as f:
            sources[name] = f.read()
    sources["cube.sol"] = ("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n%d\n1 1\n" %
                           cube_vertices + "0.6\n" * cube_vertices + "End\n").encode()
    for ext, data in surface_files().items():
        sources["octahedron" + ext] = data

    def commands(name, path, tag):
        out = lambda ext: work("out_%s%s" % (tag, ext))
        if name.endswith(".sol"):
            return [(app("adapt"), [work("cube.mesh"), "--sol", path, "-o", out(".mesh"), "-v", "0"],
                     out(".mesh"))]
        jobs = [(app("adapt"), [path, "-o", out(".mesh"), "--hsiz", "0.6", "-v", "0"], out(".mesh"))]
        if name.startswith("octahedron") or name.endswith(".mesh"):
            jobs.append((app("surfremesh"), [path, "-o", out(".obj"), "--hsiz", "0.6", "-v", "0"],
                         out(".obj")))
        if name.startswith("cube"):
            jobs.append((app("meshconvert"), [path, out(".msh")], out(".msh")))
            jobs.append((app("meshstat"), [path], None))
        return jobs

    rng = random.Random(args.seed)
    jobs, origin = [], []
    for name, data in sources.items():
        base, ext = os.path.splitext(name)
        for k in range(args.mutants):
            tag = "%s_%d" % (base, k)
            path = work("m_%s%s" % (tag, ext))
            with open(path, "wb") as f:
                f.write(mutate(data, rng))
            for job in commands(name, path, tag):
                jobs.append(job + (args.timeout,))
                origin.append(path)

    failures = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        for (job, path), problem in zip(zip(jobs, origin), pool.map(run_one, jobs)):
            if problem:
                failures += 1
                print("FAIL %s on %s: %s" % (os.path.basename(job[0]), path, problem))
    print("%d runs on %d mutants of %d sources: %d failures" %
          (len(jobs), args.mutants * len(sources), len(sources), failures))
    if failures == 0:
        shutil.rmtree(args.work, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
