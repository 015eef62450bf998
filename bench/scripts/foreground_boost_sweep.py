#!/usr/bin/env python3
"""Blur-region error of the hybrid method against its foreground boost (w_f's factor where the
pixel is deeper than the sample by SOFT_Z_EXTENT; the paper: 30), next to adapted post-process
at the paper's 30 and at each boost, per scene and frame time, against a reference. Constant
boosts (--boosts, --foreground-boost) and boosts that fall with the tile's speed, k / |v_N|
(--pixels, --foreground-boost-pixels: the hybrid's default law); the table ends with each
setting's worst loss against each case's best.

The references are rendered here (--spp, pixel centres, seed 1) at each frame time, or, with
--reference-dir, read as DIR/SCENE-reference.png at the scene's own frame time. Writes
OUT/foreground-boost.md, OUT/foreground-boost.json and OUT/foreground-boost.png (gain over
adapted post-process against the boost, one line per scene and frame time).

Usage: bench/scripts/foreground_boost_sweep.py OUT [--width W --height H] [--spp N]
       [--frame-times SCENE:T1,T2;...] [--boosts 1,3,30] [--pixels 20,40,80] [--reference-dir DIR]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

parser = argparse.ArgumentParser()
parser.add_argument("out")
parser.add_argument("--width", type=int, default=320)
parser.add_argument("--height", type=int, default=180)
parser.add_argument("--spp", type=int, default=256)
parser.add_argument("--frame-times", default="living-room:0.1,0.3;temple:0.45,1.35;bistro:0.45,1.35",
                    help="SCENE:T1,T2;... ('default' for the scene's own frame time)")
parser.add_argument("--boosts", default="1,2,3,5,10,30")
parser.add_argument("--pixels", default="20,40,80", help="k of the boosts k / |v_N| ('' for none)")
parser.add_argument("--reference-dir", help="use DIR/SCENE-reference.png (the scene's own frame time)")
parser.add_argument("--hmblur", default=os.environ.get("HMBLUR", "build/hmblur"))
args = parser.parse_args()
os.makedirs(args.out, exist_ok=True)
env = dict(os.environ)
env.setdefault("XDG_RUNTIME_DIR", "/tmp")
# Every setting swept: (label, the option that sets it, its value).
settings = ([(f"x{float(b):g}", "--foreground-boost", float(b)) for b in args.boosts.split(",") if b]
            + [(f"{float(k):g}/|v_N|", "--foreground-boost-pixels", float(k)) for k in args.pixels.split(",") if k])
cases = []
for item in args.frame_times.split(";"):
    scene, times = item.split(":")
    for t in times.split(","):
        cases.append((scene, None if args.reference_dir or t == "default" else float(t)))
if args.reference_dir:
    cases = list(dict.fromkeys((scene, None) for scene, _ in cases))


def hmblur(*words):
    subprocess.run([args.hmblur, "--quiet", *words], check=True, env=env, stdout=subprocess.DEVNULL)


def render(scene, time, out, *method):
    words = ["render", "--scene", scene, "--width", str(args.width), "--height", str(args.height), "--out", out]
    if time is not None:
        words += ["--frame-time", str(time)]
    hmblur(*words, *method)


def fmt(b):
    return f"{b:g}"


results = []
with tempfile.TemporaryDirectory() as tmp:
    for scene, time in cases:
        name = os.path.splitext(os.path.basename(scene))[0]  # a scene may be a file's path
        label = f"{name} @ {'default' if time is None else fmt(time)} s"
        print(f"foreground_boost_sweep: {label}", file=sys.stderr)
        stem = os.path.join(tmp, f"{name}-{time}")
        reference = (os.path.join(args.reference_dir, f"{scene}-reference.png") if args.reference_dir
                     else stem + "-reference.png")
        if not args.reference_dir:
            render(scene, time, reference, "--method", "reference", "--spp", str(args.spp))
        render(scene, time, stem + "-sharp.png", "--method", "sharp")
        images = [stem + "-postprocess.png"]
        render(scene, time, images[0], "--method", "postprocess")
        for i, (_, option, value) in enumerate(settings):
            images.append(f"{stem}-postprocess-{i}.png")
            render(scene, time, images[-1], "--method", "postprocess", option, fmt(value))
            images.append(f"{stem}-hybrid-{i}.png")
            render(scene, time, images[-1], "--method", "hybrid", option, fmt(value))
        hmblur("compare", reference, *images, "--sharp", stem + "-sharp.png", "--json", stem + ".json")
        with open(stem + ".json") as f:
            measured = json.load(f)["images"]
        region = [m["metrics"]["region"]["psnr_db"] for m in measured]
        frame = [m["metrics"]["frame"]["psnr_db"] for m in measured]
        results.append({
            "scene": scene, "frame_time": time, "label": label,
            "adapted_postprocess": {"region_psnr_db": region[0], "frame_psnr_db": frame[0]},
            "boosts": [{"setting": label, "option": option, "value": value,
                        "postprocess": {"region_psnr_db": region[1 + 2 * i], "frame_psnr_db": frame[1 + 2 * i]},
                        "hybrid": {"region_psnr_db": region[2 + 2 * i], "frame_psnr_db": frame[2 + 2 * i]}}
                       for i, (label, option, value) in enumerate(settings)],
        })

setup = (f"{args.width}x{args.height}; references: "
         + (f"{args.reference_dir}/SCENE-reference.png" if args.reference_dir else f"{args.spp} spp, pixel centres, seed 1"))
with open(os.path.join(args.out, "foreground-boost.json"), "w") as f:
    json.dump({"setup": setup, "results": results}, f, indent=2)

lines = [f"Blur-region PSNR (dB) against the reference, {setup}. Adapted post-process at the paper's",
         "boost of 30, then post-process and hybrid at each boost, constant (xB) or falling with the tile's",
         "speed (k/|v_N|) (the hybrid's gain over adapted post-process in brackets).", "",
         "| scene @ frame time | adapted post-process | " + " | ".join(f"{s[0]}: post-process / hybrid" for s in settings) + " |",
         "|---|---:|" + "---:|" * len(settings)]
for r in results:
    base = r["adapted_postprocess"]["region_psnr_db"]
    cells = [f"{e['postprocess']['region_psnr_db']:.2f} / {e['hybrid']['region_psnr_db']:.2f} "
             f"({e['hybrid']['region_psnr_db'] - base:+.2f})" for e in r["boosts"]]
    lines.append(f"| {r['label']} | {base:.2f} | " + " | ".join(cells) + " |")
# Each setting's hybrid against the best hybrid setting of each case.
losses = [max(max(e["hybrid"]["region_psnr_db"] for e in r["boosts"]) - r["boosts"][i]["hybrid"]["region_psnr_db"]
              for r in results) for i in range(len(settings))]
lines.append("| hybrid's worst loss against each case's best | | " + " | ".join(f"{l:.2f}" for l in losses) + " |")
with open(os.path.join(args.out, "foreground-boost.md"), "w") as f:
    f.write("\n".join(lines) + "\n")

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
laws = [("--foreground-boost", "constant foreground boost B"), ("--foreground-boost-pixels", "k of the boost k / |v_N|")]
laws = [law for law in laws if any(s[1] == law[0] for s in settings)]
fig, axes = plt.subplots(1, len(laws), figsize=(7 * len(laws), 4.5), sharey=True, squeeze=False)
for ax, (option, xlabel) in zip(axes[0], laws):
    values = [s[2] for s in settings if s[1] == option]
    for r in results:
        base = r["adapted_postprocess"]["region_psnr_db"]
        ax.plot(values, [e["hybrid"]["region_psnr_db"] - base for e in r["boosts"] if e["option"] == option],
                marker="o", label=r["label"])
    ax.set_xscale("log")
    ax.set_xticks(values)
    ax.set_xticklabels([fmt(v) for v in values])
    ax.axhline(0.0, color="grey", linewidth=0.8)
    ax.set_xlabel(xlabel)
    ax.set_title(f"Hybrid against its foreground boost ({args.width}x{args.height})")
axes[0][0].set_ylabel("blur-region PSNR gain over adapted post-process (dB)")
axes[0][-1].legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(args.out, "foreground-boost.png"), dpi=100)
print("\n".join(lines))
