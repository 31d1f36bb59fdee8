#!/usr/bin/env python3
"""Mitsuba's side of scripts/bench-vs-mitsuba.sh, and its report.

  mitsuba_time_to_error.py render SCENE.xml --reference REF.exr --max-seconds S
                                  [--threads N] [--seed K]
      Loads SCENE.xml through scripts/mitsuba_reference.py's translation (the
      one the references were rendered with: Mitsuba's `path`, max_depth 8,
      rr_depth 5, independent sampler, box filter), renders once at 1 spp to
      warm up (kernel compilation; timed and reported apart, as is the scene
      load), then renders progressively: 1 spp, 1 more, 2 more, 4 more, …, each
      batch a separate mi.render with its own seed, averaged by sample count
      into the image so far, so that after each batch the image has 1, 2, 4, 8,
      … spp. The time of a point is the sum of the batches' render times so
      far (mi.render until the image is evaluated; no loading, no error
      measurement, no kernel compilation: a batch size that needs a kernel
      not yet cached has its compile time, from Dr.Jit's kernel history,
      subtracted and recorded), i.e. what a progressive render costs, as on
      raylab's side (a single render of N spp takes about as long).
      Doubling stops once the image is below every level in LEVELS, or at S
      seconds: the last batch is sized to end near S. Prints one JSON object.

  mitsuba_time_to_error.py report ROUNDS_DIR --out FILE.json
      Reads the rounds the shell script recorded (mitsuba-SCENE-K.json,
      raylab-SCENE-K.csv from `raylab chart`), computes from each curve the
      time to each level of LEVELS and the samples per pixel per second, prints
      per scene a markdown table of the medians over the rounds with the ratios
      raylab/Mitsuba (the medians', then each round's own), and writes
      everything as JSON.

Time to a level: the first point at or below it, interpolated linearly in
log(time)–log(relMSE) with the point before (as raylab chart's own
time_to_reach does); the first point's own time if the first point is already
below. A curve that never gets there within its time has "not reached"; in
the medians over rounds it counts as infinitely slow. Samples per second: the
last point's spp over its time.

relMSE is assets/reference/README.md's: the mean over pixels and channels of
(x - ref)^2 / (ref^2 + 0.01) (mitsuba_reference.rel_mse here, raylab's
diagnostics::metrics::rel_mse there).
"""

import argparse
import csv
import glob
import json
import math
import os
import re
import statistics
import sys
import tempfile
import time

# The error levels timed, relMSE.
LEVELS = (1e-2, 1e-3)


def cmd_render(args):
    # Imported here so that `report` needs neither Mitsuba nor its LLVM.
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import drjit as dr
    import mitsuba as mi
    import mitsuba_reference  # sets the llvm_ad_rgb variant
    import numpy as np

    dr.set_thread_count(args.threads)
    dr.set_flag(dr.JitFlag.KernelHistory, True)
    reference = np.array(mi.Bitmap(args.reference), dtype=np.float64)[:, :, :3]

    def render(spp, seed):
        """One render: seconds, image, seconds of it spent compiling kernels."""
        dr.kernel_history()  # clears it
        start = time.perf_counter()
        image = mi.render(scene, spp=spp, seed=seed)
        dr.eval(image)
        dr.sync_thread()
        seconds = time.perf_counter() - start
        compiled = sum(k["codegen_time"] + k["backend_time"] for k in dr.kernel_history()
                       if k.get("cache_hit") == 0) / 1000  # milliseconds there
        return seconds, np.array(image, dtype=np.float64)[:, :, :3], compiled

    with tempfile.TemporaryDirectory() as workdir:
        start = time.perf_counter()
        try:
            scene = mitsuba_reference.load(args.scene, workdir)
        except mitsuba_reference.Untranslated as e:
            sys.exit(f"mitsuba_time_to_error: {e}")
        load_seconds = time.perf_counter() - start
    warm_up_seconds, image, warm_up_compiled = render(1, seed=1_000_000 + args.seed)
    if image.shape != reference.shape:
        sys.exit(f"{args.scene}: Mitsuba renders {image.shape}, the reference is {reference.shape}")

    total = np.zeros_like(reference)
    spp, spent, batch, points = 0, 0.0, 1, []
    while batch >= 1:
        seconds, image, compiled = render(batch, seed=1000 * args.seed + len(points))
        # Now and then a batch size needs a kernel not yet in the cache: its
        # compilation (synchronous, before the launch) is not counted either.
        seconds -= compiled
        total += batch * image
        spp += batch
        spent += seconds
        error = mitsuba_reference.rel_mse(total / spp, reference)
        points.append({"spp": spp, "seconds": spent, "rel_mse": error, "batch_seconds": seconds,
                       "compile_seconds": compiled})
        if error <= min(LEVELS) or spent >= args.max_seconds:
            break
        # Double the samples; if that would pass the cap, only as many as fit before it.
        batch = spp if 2 * spent <= args.max_seconds else int(spp * (args.max_seconds - spent) / spent)
        if batch < max(1, spp // 16):
            break
    print(json.dumps({
        "renderer": f"Mitsuba {mi.__version__} ({mi.variant()}), Dr.Jit {dr.__version__}",
        "scene": args.scene, "threads": dr.thread_count(), "seed": args.seed,
        "max_seconds": args.max_seconds, "load_seconds": load_seconds,
        "warm_up_seconds": warm_up_seconds, "warm_up_compile_seconds": warm_up_compiled,
        "width": int(reference.shape[1]), "height": int(reference.shape[0]),
        "points": points,
    }, indent=1))


def time_to_reach(points, level):
    """Seconds until relMSE ≤ level, log–log interpolated; None if never."""
    for k, p in enumerate(points):
        if p["rel_mse"] <= level:
            if k == 0:
                return p["seconds"]
            b = points[k - 1]
            le0, le1, lt = math.log(b["rel_mse"]), math.log(p["rel_mse"]), math.log(level)
            f = (le0 - lt) / (le0 - le1) if le0 != le1 else 1.0
            ls0, ls1 = math.log(b["seconds"]), math.log(p["seconds"])
            return math.exp(ls0 + f * (ls1 - ls0))
    return None


def raylab_points(path):
    with open(path) as f:
        return [{"spp": int(r["spp"]), "seconds": float(r["seconds"]), "rel_mse": float(r["rel_mse"])}
                for r in csv.DictReader(f)]


def summary(points):
    """The figures one round's curve gives."""
    last = points[-1]
    return {
        "time_to": {str(level): time_to_reach(points, level) for level in LEVELS},
        "spp_per_second": last["spp"] / last["seconds"],
        "last": {k: last[k] for k in ("spp", "seconds", "rel_mse")},
        "rel_mse_at_spp": {p["spp"]: p["rel_mse"] for p in points},
    }


def median(values):
    """Median where None (not reached) counts as infinitely slow; None if that is the median."""
    m = statistics.median(math.inf if v is None else v for v in values)
    return None if math.isinf(m) else m


def per_round(pairs):
    """Each round's own ratio raylab/Mitsuba (its two renders ran back to back), as text after the
    median: how far apart the rounds are says how much the median can be trusted. Empty for one
    round; a round where either side missed is shown as –."""
    pairs = list(pairs)
    if len(pairs) < 2:
        return ""
    return " (rounds: " + ", ".join(fmt(y / x) if x and y else "–" for y, x in pairs) + ")"


def exp(level):
    """1e-2, not 1e-02."""
    return f"1e{round(math.log10(level))}"


def fmt(v, unit=""):
    if v is None:
        return "–"
    return (f"{v:.3g}" if v < 100 else f"{v:.0f}") + unit


def cmd_report(args):
    found = {}
    for path in sorted(glob.glob(os.path.join(args.rounds_dir, "mitsuba-*.json"))):
        scene, r = re.fullmatch(r"mitsuba-(.+)-(\d+)\.json", os.path.basename(path)).groups()
        csv_path = os.path.join(args.rounds_dir, f"raylab-{scene}-{r}.csv")
        if not os.path.exists(csv_path):
            sys.exit(f"{csv_path} missing beside {path}")
        with open(path) as f:
            mitsuba = json.load(f)
        found.setdefault(scene, []).append((int(r), mitsuba, raylab_points(csv_path)))
    if not found:
        sys.exit(f"no mitsuba-*.json in {args.rounds_dir}")

    report = {"levels": list(LEVELS), "method": args.method, "scenes": {}}
    first = next(iter(found.values()))[0][1]
    rounds = max(len(v) for v in found.values())
    print(f"raylab ({args.method}) against {first['renderer']}, {first['threads']} threads each; "
          f"cap {fmt(first['max_seconds'])} s of render time per renderer, scene and round; "
          f"medians of {rounds} alternated round{'s' if rounds > 1 else ''}")
    for scene, runs in found.items():
        runs.sort(key=lambda run: run[0])
        m = [summary(mit["points"]) for _, mit, _ in runs]
        y = [summary(ray) for _, _, ray in runs]
        mit0 = runs[0][1]
        rows, medians = [], {}
        for level in LEVELS:
            a = median(s["time_to"][str(level)] for s in m)
            b = median(s["time_to"][str(level)] for s in y)
            reached = (sum(s["time_to"][str(level)] is not None for s in m),
                       sum(s["time_to"][str(level)] is not None for s in y))
            # A side that never got there gives a bound: it took longer than its whole curve.
            a_end = median(s["last"]["seconds"] for s in m)
            b_end = median(s["last"]["seconds"] for s in y)
            if a is not None and b is not None:
                ratio, ratio_text = b / a, fmt(b / a) + per_round(
                    (ys["time_to"][str(level)], ms["time_to"][str(level)]) for ms, ys in zip(m, y))
            elif a is not None:
                ratio, ratio_text = None, f"> {fmt(b_end / a)}"
            elif b is not None:
                # Mitsuba stops early only below the last level, so not reached means its cap.
                ratio, ratio_text = None, f"< {fmt(b / a_end)}"
            else:
                ratio, ratio_text = None, "–"

            def cell(v, end, n):
                text = fmt(v, " s") if v is not None else f"not reached in {fmt(end)} s"
                return text + (f" ({n}/{len(runs)} rounds)" if 0 < n < len(runs) else "")

            rows.append((f"time to relMSE {exp(level)}", cell(a, a_end, reached[0]), cell(b, b_end, reached[1]),
                         ratio_text))
            medians[f"seconds_to_{exp(level)}"] = {"mitsuba": a, "raylab": b, "ratio_raylab_over_mitsuba": ratio,
                                                  "rounds_reached": {"mitsuba": reached[0], "raylab": reached[1]}}
        a = median(s["spp_per_second"] for s in m)
        b = median(s["spp_per_second"] for s in y)
        rows.append(("samples per pixel per second", fmt(a), fmt(b), fmt(b / a) + per_round(
            (ys["spp_per_second"], ms["spp_per_second"]) for ms, ys in zip(m, y))))
        medians["spp_per_second"] = {"mitsuba": a, "raylab": b, "ratio_raylab_over_mitsuba": b / a}
        # Error per sample: the largest power of two of spp every curve has.
        common = set.intersection(*(set(s["rel_mse_at_spp"]) for s in m + y))
        n = max((k for k in common if k & (k - 1) == 0), default=None)
        if n is not None:
            a = median(s["rel_mse_at_spp"][n] for s in m)
            b = median(s["rel_mse_at_spp"][n] for s in y)
            rows.append((f"relMSE at {n} spp", f"{a:.2e}", f"{b:.2e}", fmt(b / a)))
            medians["rel_mse_at_equal_spp"] = {"spp": n, "mitsuba": a, "raylab": b,
                                               "ratio_raylab_over_mitsuba": b / a}
        a = [s["last"] for s in m]
        b = [s["last"] for s in y]
        rows.append(("last point: spp, relMSE",
                     f"{statistics.median(p['spp'] for p in a):.0f}, {statistics.median(p['rel_mse'] for p in a):.2e}",
                     f"{statistics.median(p['spp'] for p in b):.0f}, {statistics.median(p['rel_mse'] for p in b):.2e}",
                     ""))
        load = statistics.median(r[1]["load_seconds"] for r in runs)
        warm = statistics.median(r[1]["warm_up_seconds"] for r in runs)
        compiled = statistics.median(sum(p["compile_seconds"] for p in r[1]["points"]) for r in runs)

        print(f"\n### {scene} ({mit0['width']}×{mit0['height']})\n")
        print("| | Mitsuba | raylab | raylab/Mitsuba |")
        print("|---|---|---|---|")
        for row in rows:
            print("| " + " | ".join(row) + " |")
        print(f"\nMitsuba, not counted above: scene load {fmt(load)} s, warm-up render at 1 spp "
              f"(kernel compilation) {fmt(warm)} s"
              + (f", kernels compiled during timed renders {fmt(compiled)} s" if compiled >= 0.01 else ""))
        report["scenes"][scene] = {
            "width": mit0["width"], "height": mit0["height"], "rounds": len(runs), "medians": medians,
            "mitsuba_load_seconds": load, "mitsuba_warm_up_seconds": warm,
            "mitsuba_compile_seconds_while_timed": compiled,
            "raw": [{"round": r, "mitsuba": mit, "raylab": {"points": ray}} for r, mit, ray in runs],
        }
    print("\nTimes: above 1 is raylab slower. spp/s: below 1 is raylab slower. relMSE at equal spp: "
          "above 1 is raylab noisier per sample.")
    report.update({"mitsuba": first["renderer"], "threads": first["threads"], "max_seconds": first["max_seconds"],
                   "rounds": rounds})
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        json.dump(report, f, indent=1)
    print(f"JSON: {args.out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    r = sub.add_parser("render", help="Mitsuba's curve of relMSE against render time for one scene")
    r.add_argument("scene")
    r.add_argument("--reference", required=True)
    r.add_argument("--max-seconds", type=float, required=True)
    r.add_argument("--threads", type=int, default=os.cpu_count())
    r.add_argument("--seed", type=int, default=0)
    r.set_defaults(run=cmd_render)
    p = sub.add_parser("report", help="medians of the recorded rounds, side by side")
    p.add_argument("rounds_dir")
    p.add_argument("--out", required=True)
    p.add_argument("--method", default="path-sobol", help="raylab's chart method, for the title")
    p.set_defaults(run=cmd_report)
    args = parser.parse_args()
    args.run(args)


if __name__ == "__main__":
    main()
