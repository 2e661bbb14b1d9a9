#!/usr/bin/env python3
"""Turns pathlab_bench's JSON output (--benchmark_format=json) into the Markdown tables of
docs/benchmarks.md: integrator throughput, the Embree ceiling and the fraction of it the
integrators reach, thread scaling, and the SmallVCM comparison scenario.

Usage: bench_report.py BENCH.json
"""
import json
import sys
from collections import defaultdict

# Samples/s of the same scenario (all-diffuse Cornell box, 512², at most 10 segments, 2 threads)
# on machines of this kind, measured by the issue brief (issue 11, 2026-12-01); not measured here.
SMALLVCM_BPT = 444e3
PBRT_V4_BDPT = 102e3
# The same brief's 20 s equal-time runs: pathlab's relMSE per sample is 0.81 of SmallVCM's (19 %
# lower) on that scene. The estimator is unchanged since, so equal-time efficiency
# 1/(relMSE x time) relative to SmallVCM's BPT is (rate / SMALLVCM_BPT) / ERROR_PER_SAMPLE_RATIO.
ERROR_PER_SAMPLE_RATIO = 0.81


def load(path):
    data = json.load(open(path))
    results = {}
    for b in data["benchmarks"]:
        # With --benchmark_repetitions only the median is used; without, the single run.
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        name = b.get("run_name", b["name"]).removesuffix("/real_time").removesuffix("/manual_time")
        parts = name.split("/")
        results[tuple(parts)] = b
    return data["context"], results


def human(v):
    for scale, suffix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if v >= scale:
            return f"{v / scale:.3g}{suffix}"
    return f"{v:.3g}"


def main():
    context, r = load(sys.argv[1])
    threads = sorted({int(k[-1].split(":")[1]) for k in r if k[-1].startswith("threads:")})
    n = threads[-1]
    scenes = sorted({k[1] for k in r if k[0] in ("Render", "Ceiling")})
    integrators = ["bpt", "pt", "lt"]
    load_avg = context.get("load_avg")
    print(f"Load average (1, 5, 15 min) when the run began: {', '.join(f'{x:.2f}' for x in load_avg) if load_avg else 'unknown'}; "
          f"{context.get('num_cpus')} CPUs at {context.get('mhz_per_cpu')} MHz; {context.get('date')}.\n")

    def get(*key):
        return r.get(tuple(key))

    def per_cpu(b, field):
        # At 1 thread all the work runs on the benchmark's own thread, so its CPU time is the
        # time the work actually had: the rate per CPU-second is robust to other processes taking
        # the CPU (load average above the core count), unlike the wall-clock rate.
        return b[field] * b["real_time"] / b["cpu_time"]

    print("### Integrator throughput, 1 thread, per CPU-second (load-corrected; 128², max length 10)\n")
    print("| scene | " + " | ".join(f"{i} samples/s | {i} rays/s" for i in integrators) + " | rays/sample bpt · pt · lt |")
    print("|---|" + "---:|" * (2 * len(integrators) + 1))
    for s in scenes:
        cells, per_sample = [], []
        for i in integrators:
            b = get("Render", s, i, "threads:1")
            cells += [human(per_cpu(b, "samples_per_s")), human(per_cpu(b, "rays_per_s"))] if b else ["–"] * 2
            per_sample.append(f"{b['rays_per_sample']:.1f}" if b else "–")
        print(f"| {s} | " + " | ".join(cells) + " | " + " · ".join(per_sample) + " |")
    print()

    print(f"### Integrator throughput, {n} threads, wall clock (128², max length 10)\n")
    print("| scene | " + " | ".join(f"{i} samples/s | {i} rays/s" for i in integrators) + " |")
    print("|---|" + "---:|" * (2 * len(integrators)))
    for s in scenes:
        cells = []
        for i in integrators:
            b = get("Render", s, i, f"threads:{n}")
            cells += [human(b["samples_per_s"]), human(b["rays_per_s"])] if b else ["–"] * 2
        print(f"| {s} | " + " | ".join(cells) + " |")

    print(f"\n### The ceiling: raw Embree incoherent single rays (rays/s)\n")
    print(f"| scene | triangles | hit fraction | rtcIntersect1 1 thr per CPU-s | rtcOccluded1 1 thr per CPU-s "
          f"| rtcIntersect1 {n} thr wall | rtcOccluded1 {n} thr wall |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for s in scenes:
        b0 = get("Ceiling", s, "intersect", "threads:1") or get("Ceiling", s, "occluded", "threads:1")
        if not b0:
            continue
        cells = [f"{b0['triangles']:.0f}", f"{b0['hit_fraction']:.2f}"]
        for kind in ("intersect", "occluded"):
            b = get("Ceiling", s, kind, "threads:1")
            cells.append(human(per_cpu(b, "rays_per_s")) if b else "–")
        for kind in ("intersect", "occluded"):
            b = get("Ceiling", s, kind, f"threads:{n}")
            cells.append(human(b["rays_per_s"]) if b else "–")
        print(f"| {s} | " + " | ".join(cells) + " |")

    print(f"\n### Fraction of the ray-tracing ceiling the integrators reach\n")
    print("Integrator rays/s ÷ the ceiling for the integrator's own mix of rays, "
          "1 / (closest-hit share / rtcIntersect1 rate + shadow share / rtcOccluded1 rate), both measured in this run: "
          "at 1 thread per CPU-second (load-corrected) and at all threads by the wall clock. "
          "The rest of the time goes to shading, sampling, MIS and the film.\n")
    print("| scene | " + " | ".join(f"{i} 1 thr | {i} {n} thr" for i in integrators) + " |")
    print("|---|" + "---:|" * (2 * len(integrators)))
    for s in scenes:
        cells = []
        for i in integrators:
            for t in (1, n):
                ci, co = get("Ceiling", s, "intersect", f"threads:{t}"), get("Ceiling", s, "occluded", f"threads:{t}")
                b = get("Render", s, i, f"threads:{t}")
                if not (b and ci and co):
                    cells.append("–")
                    continue
                rate = (lambda x, f: per_cpu(x, f)) if t == 1 else (lambda x, f: x[f])
                share = b["shadow_ray_share"]
                ceiling = 1.0 / ((1 - share) / rate(ci, "rays_per_s") + share / rate(co, "rays_per_s"))
                cells.append(f"{100 * rate(b, 'rays_per_s') / ceiling:.0f} %")
        print(f"| {s} | " + " | ".join(cells) + " |")

    if n > 1:
        print(f"\n### Thread scaling, 1 → {n} threads (rate at {n} ÷ rate at 1)\n")
        print(f"When the host is busy these {n} vCPUs deliver about one core of throughput (two threads of pure "
              "arithmetic then take about 1.8× as long as one, ../shared/TOOLCHAIN.md) and ≈1.1× is what to expect; "
              "on a quiet host they give close to 2×. Read this table with the load average above.\n")
        print("| scene | " + " | ".join(integrators) + " | rtcIntersect1 | rtcOccluded1 |")
        print("|---|" + "---:|" * (len(integrators) + 2))
        for s in scenes:
            cells = []
            for key, field in [(("Render", s, i), "samples_per_s") for i in integrators] + [
                    (("Ceiling", s, k), "rays_per_s") for k in ("intersect", "occluded")]:
                a, b = get(*key, "threads:1"), get(*key, f"threads:{n}")
                cells.append(f"{b[field] / a[field]:.2f}×" if a and b else "–")
            print(f"| {s} | " + " | ".join(cells) + " |")

    print("\n### SmallVCM's scenario: all-diffuse Cornell box, 512², at most 10 segments, bpt\n")
    print("| renderer | camera samples/s |")
    print("|---|---:|")
    b = get("SmallVCM", "cornell-box", "bpt", "512", "threads:1")
    if b:
        print(f"| pathlab bpt, 1 thread, per CPU-second (measured) | {human(per_cpu(b, 'samples_per_s'))} |")
    for t in threads:
        b = get("SmallVCM", "cornell-box", "bpt", "512", f"threads:{t}")
        if b:
            print(f"| pathlab bpt, {t} thread{'s' if t > 1 else ''}, wall clock (measured) | {human(b['samples_per_s'])} |")
    for t in threads:
        b = get("SmallVCMGeneralPath", "cornell-box", "bpt", "512", f"threads:{t}")
        if b:
            print(f"| pathlab bpt without its image-only path, {t} thread{'s' if t > 1 else ''}, wall clock (measured) "
                  f"| {human(b['samples_per_s'])} |")
    print(f"| SmallVCM bpt (quoted) | {human(SMALLVCM_BPT)} |")
    print(f"| pbrt-v4 bdpt (quoted) | {human(PBRT_V4_BDPT)} |")
    b = get("SmallVCM", "cornell-box", "bpt", "512", f"threads:{n}")
    if b:
        rate = b["samples_per_s"]
        print(f"\nAt {n} threads: {rate / SMALLVCM_BPT:.2f}× SmallVCM's and {rate / PBRT_V4_BDPT:.1f}× pbrt-v4's camera "
              f"samples/s; with pathlab's error per sample ({ERROR_PER_SAMPLE_RATIO} of SmallVCM's) an equal-time "
              f"efficiency of {rate / SMALLVCM_BPT / ERROR_PER_SAMPLE_RATIO:.2f}× SmallVCM's BPT (target 1.5×).")

    own = [(t, get("OwnRays", "cornell-box", "bpt", "512", f"threads:{t}")) for t in threads]
    if any(b for _, b in own):
        print("\n### The BPT's share of the ceiling for its own rays (SmallVCM's scenario)\n")
        print("One pass's rays recorded as they reach Embree and traced again by raw Embree beside each render "
              "pass (tests/bench/own_rays_bench.cpp); share = BPT rays/s ÷ the replay's rays/s (target ≥ 50 %).\n")
        print("| threads | BPT camera samples/s | BPT rays/s | the same rays, raw Embree | share |")
        print("|---:|---:|---:|---:|---:|")
        for t, b in own:
            if b:
                print(f"| {t} | {human(b['samples_per_s'])} | {human(b['bpt_rays_per_s'])} | "
                      f"{human(b['ceiling_rays_per_s'])} | {100 * b['share']:.1f} % |")

    toggles = sorted(k for k in r if k[0] == "ToggleLatency")
    if toggles:
        print("\n### Toggle latency: settings change to the first image of the new generation (640×480, bpt, all threads)\n")
        print("| change | mean | worst of the iterations |")
        print("|---|---:|---:|")
        for k in toggles:
            b = r[k]
            unit = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
            print(f"| {k[3]} | {b['real_time'] * unit:.1f} ms | {b['worst_ms']:.1f} ms |")


if __name__ == "__main__":
    main()
