#!/usr/bin/python3
"""The Python module's overhead: dynmesh.flip on NumPy arrays against the C++ call on the same
mesh, in one run, at several sizes (a worsened torus grid; 1000 x 1000 is 1M vertices).

usage: flip_overhead.py FLIP_OVERHEAD_BENCH [--sizes 250,500,1000] [--repeats 3] [--work DIR]
(the module from PYTHONPATH or the set-up's .pth; FLIP_OVERHEAD_BENCH is the C++ program
bench/python/flip_overhead_bench.cpp builds)

For each size: the same arrays go to dynmesh.flip (timed whole: arrays to mesh, flip_all, faces
back to an array, the report dict) and, through an OFF file written here with the same corner
order, to the C++ program, which times SurfaceMesh::from_soup, flip_all and to_soup apart.
Both must make the same number of flips. Every time is the fastest of --repeats runs (the
machine's noise is one-sided). Printed: the Python call, the C++ call (flip_all on
the built mesh), their ratio (the goal: <= 1.2 at 1M vertices), and the ratio against the whole
C++ sequence a caller with arrays runs (from_soup + flip_all + to_soup).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import dynmesh


def torus_grid(n, R=3.0, r=1.0):
    u, w = np.meshgrid(np.arange(n) * 2 * np.pi / n, np.arange(n) * 2 * np.pi / n, indexing="ij")
    v = np.stack([(R + r * np.cos(w)) * np.cos(u), (R + r * np.cos(w)) * np.sin(u), r * np.sin(w)], -1)
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    a, b = i * n + j, ((i + 1) % n) * n + j
    c, d = ((i + 1) % n) * n + (j + 1) % n, i * n + (j + 1) % n
    f = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return v.reshape(-1, 3), f


def write_off(path, v, f):
    with open(path, "w") as out:
        out.write("OFF\n%d %d 0\n" % (len(v), len(f)))
        np.savetxt(out, v, fmt="%.17g")
        np.savetxt(out, np.hstack([np.full((len(f), 1), 3), f]), fmt="%d")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bench")
    ap.add_argument("--sizes", default="250,500,1000")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--work", default=None)
    a = ap.parse_args()
    work = a.work or tempfile.mkdtemp(prefix="flip_overhead_")
    print("dynmesh %s (%s)" % (dynmesh.__version__, dynmesh.__file__))
    print("%9s %9s %10s %10s %8s %12s %11s" % ("vertices", "flips", "python s", "C++ flip s", "ratio",
                                                "C++ arrays s", "ratio"))
    rows = []
    for n in (int(s) for s in a.sizes.split(",")):
        v, f = torus_grid(n)
        f, _ = dynmesh.worsen(v, f, rounds=2, seed=1)
        path = os.path.join(work, "torus_%d.off" % n)
        write_off(path, v, f)
        cpp = json.loads(subprocess.run([a.bench, path, str(a.repeats)], check=True, capture_output=True,
                                        text=True).stdout)
        os.remove(path)
        python = float("inf")
        for _ in range(a.repeats):
            t0 = time.perf_counter()
            faces, report = dynmesh.flip(v, f)
            python = min(python, time.perf_counter() - t0)
        if report["flips"] != cpp["flips"] or len(faces) != cpp["faces"]:
            sys.exit("flip_overhead: not the same work: %d flips in Python, %d in C++" % (report["flips"], cpp["flips"]))
        whole = cpp["seconds_from_arrays"] + cpp["seconds_flip"] + cpp["seconds_faces"]
        rows.append((len(v), report["flips"], python, cpp["seconds_flip"], whole))
        print("%9d %9d %10.3f %10.3f %8.3f %12.3f %11.3f" % (len(v), report["flips"], python, cpp["seconds_flip"],
                                                             python / cpp["seconds_flip"], whole, python / whole))
    big = rows[-1]
    print("at %d vertices: dynmesh.flip %.3f s, C++ flip_all %.3f s: ratio %.3f (goal <= 1.2); "
          "against from_soup + flip_all + to_soup %.3f s: ratio %.3f" % (big[0], big[2], big[3], big[2] / big[3], big[4],
                                                                          big[2] / big[4]))


if __name__ == "__main__":
    main()
