#!/usr/bin/env python3
"""Bar charts of the `raster` suite, per scene and image size (medians of the paired
per-iteration ratios, whiskers = interquartile range), with the parity line and the 2x target:
compute visibility / the graphics pipeline's id draw, and the whole compute G-buffer (visibility
+ resolve) / the graphics pipeline doing the same G-buffer (the G-buffer oracle).

usage: plot_raster.py [RESULTS.json] [OUT.png]
defaults: bench/results/raster-vs-graphics.json -> the same path with .png
"""
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    results = Path(sys.argv[1] if len(sys.argv) > 1 else "bench/results/raster-vs-graphics.json")
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else results.with_suffix(".png")
    report = json.loads(results.read_text())
    cases = report["cases"]

    scenes = list(dict.fromkeys(c["scene"] for c in cases))
    sizes = list(dict.fromkeys(f'{c["width"]}x{c["height"]}' for c in cases))
    by_key = {(c["scene"], f'{c["width"]}x{c["height"]}'): c for c in cases}

    panels = [("ratio_visibility_to_graphics", "compute visibility / graphics id draw"),
              ("ratio_gbuffer_to_graphics_gbuffer", "compute G-buffer / graphics G-buffer")]
    panels = [p for p in panels if all(p[0] in c for c in cases)]
    fig, axes = plt.subplots(1, len(panels), figsize=(8 * len(panels), 4.5), squeeze=False)
    width = 0.8 / len(sizes)
    for ax, (key, label) in zip(axes[0], panels):
        for i, size in enumerate(sizes):
            xs, medians, low, high = [], [], [], []
            for s, scene in enumerate(scenes):
                case = by_key.get((scene, size))
                if case is None:
                    continue
                ratio = case[key]
                xs.append(s + (i - (len(sizes) - 1) / 2) * width)
                medians.append(ratio["median"])
                low.append(ratio["median"] - ratio["q1"])
                high.append(ratio["q3"] - ratio["median"])
            bars = ax.bar(xs, medians, width, yerr=[low, high], capsize=3, label=size)
            ax.bar_label(bars, fmt="%.1f", fontsize=8, padding=2)
        ax.axhline(1.0, color="black", linewidth=0.8)
        ax.axhline(2.0, color="tab:red", linestyle="--", linewidth=1.0, label="2x target")
        ax.set_xticks(range(len(scenes)), scenes)
        ax.set_ylabel(label + " (device time)")
        ax.legend(fontsize=8)
        ax.set_ylim(bottom=0)
    device = report["device"]["name"]
    threads = report["system"]["LP_NUM_THREADS"]
    fig.suptitle(f"Compute rasterizer and G-buffer vs the graphics pipeline, same triangles\n{device}, "
                 f"LP_NUM_THREADS={threads}", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
