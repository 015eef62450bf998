#!/usr/bin/env python3
"""Stacked bars of a `passes` run: per scene, each method's frame at one image size, split into
its passes (median device ms; passes under 3% of the scene's largest frame grouped as "other").
The hybrid's one-time scene setup (its mesh trees) is left out, as the frame leaves it out.

usage: plot_frame_passes.py PASSES.json OUT.png [WIDTHxHEIGHT]   (default size 1280x720)
"""
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

SETUP_PASSES = {"hybrid-bvh-meshes", "hybrid-bvh-still-instances"}  # scene setup, not part of a frame


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    report = json.loads(Path(sys.argv[1]).read_text())
    out = Path(sys.argv[2])
    size = sys.argv[3] if len(sys.argv) > 3 else "1280x720"
    cases = [c for c in report["cases"] if f'{c["width"]}x{c["height"]}' == size]
    if not cases:
        print(f"plot_frame_passes.py: no case at {size}", file=sys.stderr)
        return 1
    scenes = list(dict.fromkeys(c["scene"] for c in cases))
    methods = list(dict.fromkeys(c["method"] for c in cases))

    def passes(case):
        return {p["name"]: p["ms"]["median"] for p in case["passes"] if p["name"] not in SETUP_PASSES}

    # A pass is drawn on its own where it takes 3% of its scene's largest frame; the 12 largest such.
    largest = {scene: max(sum(passes(c).values()) for c in cases if c["scene"] == scene) for scene in scenes}
    shown = sorted({name for c in cases for name, ms in passes(c).items() if ms >= 0.03 * largest[c["scene"]]},
                   key=lambda n: -max(passes(c).get(n, 0.0) / largest[c["scene"]] for c in cases))[:12]
    colours = plt.get_cmap("tab20").colors

    fig, axes = plt.subplots(1, len(scenes), figsize=(4.6 * len(scenes), 5.4), sharey=True, squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        by_method = {c["method"]: c for c in cases if c["scene"] == scene}
        for x, method in enumerate(methods):
            if method not in by_method:
                continue
            times = passes(by_method[method])
            bottom = 0.0
            for k, name in enumerate(shown + ["other"]):
                ms = times.get(name, 0.0) if name != "other" else sum(
                    v for n, v in times.items() if n not in shown)
                colour = colours[k % len(colours)] if name != "other" else (0.75, 0.75, 0.75)
                ax.bar(x, ms, bottom=bottom, color=colour, label=name if (scene == scenes[0] and x == 0) or
                       name not in ax.get_legend_handles_labels()[1] else None)
                bottom += ms
            frame = by_method[method]["frame_ms"]["median"]
            ax.text(x, bottom, f"{frame:.2f}", ha="center", va="bottom", fontsize=8)
        ax.set_xticks(range(len(methods)), methods, rotation=30, ha="right", fontsize=8)
        ax.set_title(f"{scene}, {size}")
    axes[0][0].set_ylabel("median device ms (frame printed on top)")
    handles, labels = [], []
    for ax in axes[0]:
        for h, label in zip(*ax.get_legend_handles_labels()):
            if label not in labels:
                handles.append(h)
                labels.append(label)
    fig.legend(handles, labels, loc="lower center", ncol=6, fontsize=8, frameon=False)
    device = report.get("device", {})
    fig.suptitle(f'Frame by pass: {device.get("name", "?")} ({device.get("driver_info", "?")}), '
                 f'revision {report.get("system", {}).get("git_revision", "?")}')
    fig.tight_layout(rect=(0, 0.16, 1, 0.95))
    fig.savefig(out, dpi=110)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
