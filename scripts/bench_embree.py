#!/usr/bin/env python3
"""Embree (embreex, from PyPI) on the exact mesh and rays of raylab's BVH bench.

Not part of CI. Usage (a throw-away venv):
    python3 -m venv /tmp/embree-venv && /tmp/embree-venv/bin/pip install embreex numpy
    cargo bench -p raylab-renderer --bench bvh -- --export /tmp/knot-export
    /tmp/embree-venv/bin/python scripts/bench_embree.py /tmp/knot-export [repeats]
Prints build seconds and closest-hit Mrays/s per ray set (median of repeats),
single-threaded calls (embreex's run() casts rays one call per ray), and with
two Python threads each casting half of the rays (parallel only if embreex
releases the GIL).
"""
import sys, time, threading
import numpy as np
from embreex import rtcore_scene as rtcs
from embreex.mesh_construction import TriangleMesh

d = sys.argv[1]
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
load = lambda name, dt=np.float32: np.fromfile(f"{d}/{name}.bin", dtype=dt).reshape(-1, 3)
positions, triangles = load("positions"), load("triangles", np.int32)


def build():
    t = time.perf_counter()
    scene = rtcs.EmbreeScene()
    TriangleMesh(scene, positions, indices=triangles)
    # Embree builds lazily at the first query: include one ray.
    scene.run(np.zeros((1, 3), np.float32), np.ones((1, 3), np.float32))
    return scene, time.perf_counter() - t


builds = [build() for _ in range(max(1, min(repeats, 3)))]
scene = builds[-1][0]
print(f"embree: {len(triangles)} triangles, build {np.median([b[1] for b in builds]):.3f} s (median)")
for name in ["primary", "tiled", "incoherent"]:
    o, v = load(f"{name}_origins"), load(f"{name}_dirs")
    one, two = [], []
    for _ in range(repeats):
        t = time.perf_counter()
        ids = scene.run(o, v)
        one.append(time.perf_counter() - t)
        half = len(o) // 2
        parts = [(o[:half], v[:half]), (o[half:], v[half:])]
        threads = [threading.Thread(target=scene.run, args=p) for p in parts]
        t = time.perf_counter()
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        two.append(time.perf_counter() - t)
    hit = 100.0 * np.count_nonzero(ids >= 0) / len(ids)
    print(
        f"embree {name:>10}: 1 thread {len(o) / np.median(one) / 1e6:6.2f} Mrays/s, "
        f"2 threads {len(o) / np.median(two) / 1e6:6.2f} Mrays/s, hit {hit:.1f}%"
    )
