#!/usr/bin/env python3
"""Error against run time, one PNG per scene, from hmblur-bench error-vs-time's JSON.

Blur-region PSNR (higher is better) against median frame time (log axis); one curve per
series (post-process centred, adapted and adapted along curved paths over sample counts; the
paper's hybrid over sample counts, recursion limits, edge thresholds and time slices; hybrid-rays
over sample counts, shutter strata and its ray budget, drawn bold beside the reference's curve
over spp), the sharp frame as a point, the Pareto front (no other case both faster and closer)
drawn through the cases on it, and the front's point: the fastest hybrid-rays case as close as
the reference at the front's spp, joined to that reference.

Usage: bench/scripts/plot_error_vs_time.py RESULTS.json [OUT_DIR]   (default: beside the JSON)
"""
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

path = sys.argv[1]
out_dir = sys.argv[2] if len(sys.argv) > 2 else os.path.dirname(os.path.abspath(path))
with open(path) as f:
    results = json.load(f)

styles = {
    "sharp": dict(marker="s", color="black"),
    "postprocess centered": dict(marker="v", color="tab:orange"),
    "postprocess adapted": dict(marker="^", color="tab:red"),
    "postprocess curved path": dict(marker=">", color="tab:olive"),
    "hybrid": dict(marker="o", color="tab:blue"),
    "hybrid luminance stop": dict(marker="D", color="tab:cyan"),
    "hybrid edge threshold": dict(marker="P", color="tab:purple"),
    "hybrid-rays": dict(marker="o", color="navy"),
    "hybrid-rays strata": dict(marker="X", color="tab:gray"),
    "hybrid-rays ray budget": dict(marker="d", color="darkviolet", linewidth=2.5),
    "postprocess adapted time slices": dict(marker="<", color="tab:brown"),
    "hybrid time slices": dict(marker="h", color="tab:pink"),
    "reference": dict(marker="*", color="tab:green", linewidth=2.5),
}

for scene in results["scenes"]:
    cases = [c for c in scene["cases"] if c["region"]["psnr_db"] is not None]
    fig, ax = plt.subplots(figsize=(8, 5))
    for series in dict.fromkeys(c["series"] for c in cases):
        members = [c for c in cases if c["series"] == series]
        xs = [c["frame_ms"]["median"] for c in members]
        ys = [c["region"]["psnr_db"] for c in members]
        style = {"linewidth": 1, **styles.get(series, dict(marker="x", color="grey"))}
        ax.plot(xs, ys, linestyle="-" if len(members) > 1 else "none", label=series, **style)
        if series == "hybrid-rays ray budget":
            for c, x, y in zip(members, xs, ys):
                ax.annotate(f"{c['parameter']:g}/px", (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7,
                            color="darkviolet")
        if series == "reference":
            for c, x, y in zip(members, xs, ys):
                ax.annotate(f"{c['parameter']:g}", (x, y), textcoords="offset points", xytext=(4, -10), fontsize=7)
    # Pareto front: sorted by time, each case closer than every faster one.
    front, best = [], float("-inf")
    for c in sorted(cases, key=lambda c: (c["frame_ms"]["median"], -c["region"]["psnr_db"])):
        if c["region"]["psnr_db"] > best:
            front.append(c)
            best = c["region"]["psnr_db"]
    ax.step([c["frame_ms"]["median"] for c in front], [c["region"]["psnr_db"] for c in front], where="post",
            color="grey", linewidth=2.5, alpha=0.35, label="Pareto front")
    ax.scatter([c["frame_ms"]["median"] for c in front], [c["region"]["psnr_db"] for c in front], s=120,
               facecolors="none", edgecolors="grey", linewidths=1.2)
    point = scene.get("front")
    if point and point.get("label"):
        ax.plot([point["ms"], point["reference_ms"]], [point["region_psnr_db"], point["reference_region_psnr_db"]],
                color="darkviolet", linestyle=":", linewidth=1.5)
        ax.scatter([point["ms"]], [point["region_psnr_db"]], s=220, marker="o", facecolors="none",
                   edgecolors="darkviolet", linewidths=2,
                   label=f"front: {point['time_ratio']:.2f}x faster than {point['reference_spp']} spp")
    ax.set_xscale("log")
    ax.set_xlabel("median frame time (ms, device timestamps; log scale)")
    ax.set_ylabel("blur-region PSNR against the judge (dB)")
    title = f"{scene['scene']}: error against run time ({results['settings']['size']})"
    for match in scene.get("hybrid_vs_reference") or []:
        if match.get("time_ratio") is None:
            continue
        spp, method = match["matching_spp"], match["method"]
        title += (f"\nreference matches {method} at {spp} spp, {match['time_ratio']:.1f}x its time" if spp
                  else f"\nno reference tried matches {method} (largest: {match['time_ratio']:.1f}x its time)")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    target = os.path.join(out_dir, f"{os.path.basename(scene['scene']).split('.')[0]}-error-vs-time.png")
    fig.savefig(target, dpi=100)
    plt.close(fig)
    print(target)
