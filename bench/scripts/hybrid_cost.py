#!/usr/bin/env python3
"""Hybrid's frame time over adapted post-process's, measured in one run.

For each scene, renders adapted post-process and hybrid alternately, RUNS + 1 times each,
drops the first of each (warm-up: the device's caches and the machine's clocks), and reports
the medians of the device time of the frame and of every pass (Vulkan timestamp queries, from
each render's JSON report). The hybrid's one-time scene setup (its mesh BVHs) is reported
apart; it is not part of a frame. Beside the ratio of the frames' medians it gives the ratio of
the passes' medians summed, which a machine's noise moves less (one slow render moves a frame's
median; a pass's median needs several). Writes OUT/hybrid-cost.md and OUT/hybrid-cost.json;
with --from-json, only the .md, from OUT/hybrid-cost.json as an earlier run wrote it.

Usage: bench/scripts/hybrid_cost.py OUT [--runs N] [--width W --height H] [--scenes A,B] [--from-json]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

parser = argparse.ArgumentParser()
parser.add_argument("out")
parser.add_argument("--runs", type=int, default=5)
parser.add_argument("--width", type=int, default=1280)
parser.add_argument("--height", type=int, default=720)
parser.add_argument("--scenes", default="living-room,temple,bistro")
parser.add_argument("--hmblur", default=os.environ.get("HMBLUR", "build/hmblur"))
parser.add_argument("--from-json", action="store_true")
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)
env = dict(os.environ)
env.setdefault("XDG_RUNTIME_DIR", "/tmp")
methods = ["postprocess", "hybrid"]


def render(scene, method, report):
    subprocess.run([args.hmblur, "--quiet", "render", "--scene", scene, "--method", method,
                    "--width", str(args.width), "--height", str(args.height), "--report", report],
                   check=True, env=env, stdout=subprocess.DEVNULL)
    with open(report) as f:
        return json.load(f)


# The hybrid's scene setup: listed with the passes, not part of its frame.
SETUP_PASSES = {"hybrid-bvh-meshes", "hybrid-bvh-still-instances"}


def passes_ratio(entry):
    def frame_sum(m):
        return sum(v for k, v in entry[m]["passes_ms"].items() if k not in SETUP_PASSES)
    return frame_sum("hybrid") / frame_sum("postprocess")


def measure():
    results = {}
    system = device = None
    with tempfile.TemporaryDirectory() as tmp:
        for scene in args.scenes.split(","):
            runs = {m: [] for m in methods}
            for r in range(args.runs + 1):
                for m in methods:
                    report = render(scene, m, os.path.join(tmp, f"{scene}-{m}.json"))
                    print(f"hybrid_cost: {scene} {m} run {r}: {report['frame_ms']:.1f} ms", file=sys.stderr)
                    if r > 0:
                        runs[m].append(report)
                    system, device = report["system"], report["device"]
            entry = {}
            for m in methods:
                passes = {}
                for report in runs[m]:
                    for p in report["passes"]:
                        if p.get("ms") is not None:
                            passes.setdefault(p["name"], []).append(p["ms"])
                entry[m] = {"frame_ms": statistics.median(r["frame_ms"] for r in runs[m]),
                            "passes_ms": {k: statistics.median(v) for k, v in passes.items()}}
            hybrid_settings = runs["hybrid"][-1]["settings"]
            entry["hybrid"]["mask_pixels"] = hybrid_settings.get("mask_pixels")
            entry["hybrid"]["reveal_rays"] = hybrid_settings.get("reveal_rays")
            entry["hybrid"]["scene_setup_ms"] = hybrid_settings.get("scene_setup_ms")
            entry["ratio"] = entry["hybrid"]["frame_ms"] / entry["postprocess"]["frame_ms"]
            results[scene] = entry

    summary = {"width": args.width, "height": args.height, "runs": args.runs, "device": device["name"],
               "driver": device.get("driver_info"), "cpu": system["cpu"], "hardware_threads": system["hardware_threads"],
               "LP_NUM_THREADS": system["LP_NUM_THREADS"], "revision": system.get("git_revision"),
               "command": "bench/scripts/hybrid_cost.py " + " ".join(sys.argv[1:]), "scenes": results}
    return summary


if args.from_json:
    with open(os.path.join(args.out, "hybrid-cost.json")) as f:
        summary = json.load(f)
    results = summary["scenes"]
else:
    summary = measure()
    results = summary["scenes"]
    with open(os.path.join(args.out, "hybrid-cost.json"), "w") as f:
        json.dump(summary, f, indent=2)

with open(os.path.join(args.out, "hybrid-cost.md"), "w") as md:
    md.write(f"Device {summary['device']} ({summary['driver']}), CPU {summary['cpu']}, "
             f"{summary['hardware_threads']} hardware threads, LP_NUM_THREADS {summary['LP_NUM_THREADS']}, "
             f"revision {summary['revision']}; {summary['width']}x{summary['height']}, median of {summary['runs']} runs "
             f"after one warm-up run per method. Command: `{summary['command']}`\n\n")
    md.write("| scene | post-process ms | hybrid ms | hybrid / post-process | summed passes, hybrid / post-process | "
             "mask pixels | reveal rays | hybrid scene setup ms |\n")
    md.write("|---|---:|---:|---:|---:|---:|---:|---:|\n")
    for scene, e in results.items():
        md.write(f"| {scene} | {e['postprocess']['frame_ms']:.1f} | {e['hybrid']['frame_ms']:.1f} | {e['ratio']:.3f} | "
                 f"{passes_ratio(e):.3f} | {e['hybrid']['mask_pixels']} | {e['hybrid']['reveal_rays']} | "
                 f"{e['hybrid']['scene_setup_ms']:.1f} |\n")
    md.write("\nSummed passes: each pass's median over the runs, summed over the frame's passes (the scene "
             "setup left out); the noise of a machine moves it less than the frames' medians.\n")
    md.write("\nWhere the time goes (median device ms per pass; passes of both methods side by side):\n\n")
    scenes = list(results)
    md.write("| pass | " + " | ".join(f"{s} post-process | {s} hybrid" for s in scenes) + " |\n")
    md.write("|---|" + "---:|" * (2 * len(scenes)) + "\n")
    names = []
    for s in scenes:
        for m in methods:
            for n in results[s][m]["passes_ms"]:
                if n not in names:
                    names.append(n)
    for n in names:
        cells = []
        for s in scenes:
            for m in methods:
                v = results[s][m]["passes_ms"].get(n)
                cells.append("" if v is None else f"{v:.2f}")
        md.write(f"| {n} | " + " | ".join(cells) + " |\n")
print(open(os.path.join(args.out, "hybrid-cost.md")).read())
