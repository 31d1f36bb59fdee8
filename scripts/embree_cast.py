#!/usr/bin/env python3
"""Embree's side of scripts/bench-vs-embree.sh.

  embree_cast.py cast EXPORT_DIR --threads N [--runs 5] [--no-robust]
      Loads what `raylab bench SCENE --export EXPORT_DIR` wrote, builds Embree's
      BVH over it with embreex (timed: the scene commit) and casts the primary
      and incoherent rays for their closest hits on N threads, median of --runs
      casts; prints one JSON object.

  embree_cast.py report ROUNDS_DIR --out FILE.json
      Reads the rounds the shell script recorded (raylab-K.json, embree-1-K.json,
      embree-all-K.json), prints the medians side by side with the ratios and
      both hit fractions, writes them as JSON; exits 1 when the hit fractions
      disagree by more than HIT_TOLERANCE.

Threads: embreex's EmbreeDevice takes no configuration string and the Embree
4.4 it ships reads no ~/.embree4 file, so "threads=N" cannot be passed. Embree
builds with TBB, which uses every CPU of the process's affinity mask, so with
--threads N this process first restricts itself to N CPUs of its mask (as
`taskset` would) before Embree starts: the build and the casts both run on N
threads. The casts are embreex's `scene.run` (rtcIntersect1 per ray, the GIL
released) on N Python threads over chunks of rays.
"""

import argparse
import glob
import json
import os
import statistics
import sys
import time
from concurrent.futures import ThreadPoolExecutor

# Hit fractions must agree to this many percentage points.
HIT_TOLERANCE_PP = 0.1


def pin_to(threads):
    """Restrict this process to `threads` CPUs of its affinity mask; returns them."""
    allowed = sorted(os.sched_getaffinity(0))
    if threads > len(allowed):
        sys.exit(f"--threads {threads}: only {len(allowed)} CPUs are available")
    chosen = set(allowed[:threads])
    os.sched_setaffinity(0, chosen)
    return sorted(chosen)


def load(export_dir):
    import numpy as np

    with open(os.path.join(export_dir, "manifest.json")) as f:
        manifest = json.load(f)

    def array(name, dtype, width):
        data = np.fromfile(os.path.join(export_dir, name), dtype=dtype)
        return data.reshape(-1, width)

    vertices = array(manifest["vertices_file"], "<f4", 3)
    triangles = array(manifest["triangles_file"], "<u4", 3)
    assert len(vertices) == manifest["vertices"] and len(triangles) == manifest["triangles"]
    rays = {}
    for name in ("primary", "incoherent"):
        spec = manifest.get(name)
        if spec:
            r = array(spec["file"], "<f4", 6)
            assert len(r) == spec["count"], name
            rays[name] = (np.ascontiguousarray(r[:, :3]), np.ascontiguousarray(r[:, 3:]))
    return manifest, vertices, triangles, rays


def build(manifest, vertices, triangles, robust):
    """Embree's scene, one triangle geometry per exported object; the seconds
    embreex spends copying the arrays in, and the seconds of the commit (the
    BVH build, on this process's CPUs)."""
    import numpy as np
    from embreex import rtcore_scene
    from embreex.mesh_construction import TriangleMesh

    start = time.perf_counter()
    scene = rtcore_scene.EmbreeScene(robust=robust)
    for g in manifest["geometries"]:
        v0, t0 = g["first_vertex"], g["first_triangle"]
        v = np.ascontiguousarray(vertices[v0 : v0 + g["vertices"]])
        t = (triangles[t0 : t0 + g["triangles"]].astype(np.int64) - v0).astype(np.int32)
        TriangleMesh(scene, v, t)
    copied = time.perf_counter()
    # embreex commits the scene (builds the BVH) on the first run.
    scene.run(np.zeros((1, 3), np.float32), np.ones((1, 3), np.float32))
    built = time.perf_counter()
    return scene, copied - start, built - copied


def cast(scene, origins, dirs, t_max, threads, pool):
    """Closest hit of every ray on `threads` threads: (seconds, hits)."""
    n = len(origins)
    start = time.perf_counter()
    if threads == 1:
        hits = int((scene.run(origins, dirs, dists=t_max) >= 0).sum())
    else:
        chunk = max(4096, n // (threads * 32))
        spans = [(a, min(a + chunk, n)) for a in range(0, n, chunk)]
        counts = pool.map(
            lambda s: int((scene.run(origins[s[0] : s[1]], dirs[s[0] : s[1]], dists=t_max) >= 0).sum()),
            spans,
        )
        hits = sum(counts)
    return time.perf_counter() - start, hits


def cmd_cast(args):
    cpus = pin_to(args.threads)
    import embreex.rtcore

    manifest, vertices, triangles, rays = load(args.export_dir)
    if manifest["t_min"] != 0.0:
        sys.exit("embreex casts from t = 0 only; this export has another t_min")
    scene, copy_s, build_s = build(manifest, vertices, triangles, not args.no_robust)
    out = {
        "embree": repr(embreex.rtcore.EmbreeDevice()).split(":")[-1].strip(),
        "threads": args.threads,
        "cpus": cpus,
        "robust": not args.no_robust,
        "triangles": int(len(triangles)),
        "copy_in_seconds": copy_s,
        "build_seconds": build_s,
    }
    with ThreadPoolExecutor(max_workers=args.threads) as pool:
        for name, (origins, dirs) in rays.items():
            runs = [cast(scene, origins, dirs, manifest["t_max"], args.threads, pool) for _ in range(args.runs)]
            seconds, hits = sorted(runs)[len(runs) // 2]
            out[name] = {
                "rays": len(origins),
                "hit_fraction": hits / max(1, len(origins)),
                "mrays_per_second": len(origins) / seconds / 1e6,
            }
    print(json.dumps(out, indent=1))


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def cmd_report(args):
    def rounds(prefix):
        found = []
        for path in sorted(glob.glob(os.path.join(args.rounds_dir, prefix + "-*.json"))):
            with open(path) as f:
                found.append(json.load(f))
        if not found:
            sys.exit(f"no {prefix}-*.json in {args.rounds_dir}")
        return found

    raylab, one, every = rounds("raylab"), rounds("embree-1"), rounds("embree-all")
    threads = raylab[0]["threads"]

    def ray(cast, n):
        return lambda r: (r.get(cast) or {}).get(n, {}).get("mrays_per_second")

    def emb(cast):
        return lambda r: (r.get(cast) or {}).get("mrays_per_second")

    # (figure, raylab's value per round, Embree's per round, True when higher is better);
    # round k of each list ran back to back (raylab, then Embree on 1 thread, then on all).
    rows = [
        ("BVH build s, all threads", [r["mesh_bvh_build_seconds"] for r in raylab],
         [r["build_seconds"] for r in every], False),
        ("BVH build s, 1 thread", [r["mesh_bvh_build_seconds_one_thread"] for r in raylab],
         [r["build_seconds"] for r in one], False),
    ]
    for cast in ("primary", "incoherent"):
        rows.append((f"{cast} Mrays/s, 1 thread", list(map(ray(cast, "one"), raylab)),
                     list(map(emb(cast), one)), True))
        rows.append((f"{cast} Mrays/s, {threads} threads", list(map(ray(cast, "all"), raylab)),
                     list(map(emb(cast), every)), True))

    # raylab's batches of the same rays (World::intersect_batch: packets of sixteen
    # for the coherent primary rays (4×4 tiles), interleaved rays for the incoherent ones),
    # against Embree's one-ray-at-a-time casts above.
    for cast in ("primary", "incoherent"):
        if raylab[0].get(f"{cast}_batched"):
            rows.append((f"{cast} batched, 1 thread", list(map(ray(f"{cast}_batched", "one"), raylab)),
                         list(map(emb(cast), one)), True))
            rows.append((f"{cast} batched, {threads} thr", list(map(ray(f"{cast}_batched", "all"), raylab)),
                         list(map(emb(cast), every)), True))

    def ratio(a, b):
        return a / b if a is not None and b else None

    def fmt(v, digits=4):
        return "–" if v is None else f"{v:.{digits}g}" if abs(v) < 1 else f"{v:.{digits - 1}f}"

    r0, e0 = raylab[0], every[0]
    print(f"raylab vs Embree {e0['embree']} (embreex, {'robust' if e0['robust'] else 'not robust'}) on "
          f"{r0['scene']}, {r0['width']}×{r0['height']} rays, {threads} threads; medians of "
          f"{len(raylab)} rounds of raylab → Embree on 1 thread → Embree on {threads}")
    print(f"  {'':<32}{'raylab':>10}{'Embree':>10}{'raylab/Embree':>15}   each round's own ratio")
    for name, a, b, _ in rows:
        each = ", ".join(fmt(ratio(x, y), 3) for x, y in zip(a, b)) if len(a) > 1 else ""
        print(f"  {name:<32}{fmt(median(a)):>10}{fmt(median(b)):>10}"
              f"{fmt(ratio(median(a), median(b)), 3):>15}   {each}")
    print("  (Mrays/s: a ratio above 1 is raylab faster; build seconds: below 1 is raylab faster)")

    hits, agree = {}, True
    for cast in ("primary", "incoherent"):
        if not r0.get(cast) or not e0.get(cast):
            continue
        ours = r0[cast]["all"]["hit_fraction"]
        theirs = [e0[cast]["hit_fraction"], one[0][cast]["hit_fraction"]]
        diff = max(abs(ours - t) for t in theirs) * 100
        ok = diff <= HIT_TOLERANCE_PP
        agree &= ok
        hits[cast] = {"raylab": ours, "embree": theirs[0], "embree_1_thread": theirs[1],
                      "difference_pp": diff, "agree": ok}
        print(f"  {cast + ' hit fraction':<32}{100 * ours:>9.4f}%{100 * theirs[0]:>9.4f}%"
              f"   Δ {diff:.4f} pp {'ok' if ok else 'DISAGREE'}")

    report = {
        "scene": r0["scene"], "triangles": r0["triangles"], "width": r0["width"],
        "height": r0["height"], "threads": threads, "rounds": len(raylab),
        "embree": e0["embree"], "embree_robust": e0["robust"],
        "medians": [{"figure": n, "raylab": median(a), "embree": median(b),
                     "ratio_raylab_over_embree": ratio(median(a), median(b)),
                     "ratios_per_round": [ratio(x, y) for x, y in zip(a, b)],
                     "higher_is_better": h} for n, a, b, h in rows],
        "hit_fractions": hits,
        "raw": {"raylab": raylab, "embree_1_thread": one, "embree_all_threads": every},
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(report, f, indent=1)
    print(f"  JSON: {args.out}")
    if not agree:
        print(f"hit fractions differ by more than {HIT_TOLERANCE_PP} percentage points", file=sys.stderr)
        sys.exit(1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    c = sub.add_parser("cast", help="build Embree's BVH and cast the exported rays")
    c.add_argument("export_dir")
    c.add_argument("--threads", type=int, required=True)
    c.add_argument("--runs", type=int, default=5)
    c.add_argument("--no-robust", action="store_true", help="without RTC_SCENE_FLAG_ROBUST")
    c.set_defaults(run=cmd_cast)
    r = sub.add_parser("report", help="medians of the recorded rounds, side by side")
    r.add_argument("rounds_dir")
    r.add_argument("--out", required=True)
    r.set_defaults(run=cmd_report)
    args = parser.parse_args()
    args.run(args)


if __name__ == "__main__":
    main()
