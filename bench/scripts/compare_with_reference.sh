#!/usr/bin/env bash
# Renders a scene with a set of methods, measures each against a reference image, and writes
# per scene: the images, FLIP error maps, a comparison strip, the JSON reports and a Markdown
# table. The strip (images on top, FLIP error maps below, the reference at the right) is
# written at half size. Usage:
#   bench/scripts/compare_with_reference.sh SCENE REFERENCE.exr REFERENCE.png OUT_DIR [WIDTH HEIGHT [SET]]
# SET: postprocess (the sharp frame and every post-process filter, the default) or hybrid
# (the sharp frame, adapted post-process at the paper's foreground boost and at the hybrid's,
# hybrid with each composite, at the paper's boost and at the constant 3 it had before its
# boost fell with the speed).
set -euo pipefail
scene=$1 reference=$2 reference_png=$3 out=$4 width=${5:-1280} height=${6:-720} set=${7:-postprocess}
hmblur=${HMBLUR:-build/hmblur}
mkdir -p "$out"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
case "$set" in
  postprocess)
    declare -a names=(sharp postprocess-adapted postprocess-centered postprocess-jimenez)
    declare -a args=("--method sharp" "--method postprocess --range adapted" "--method postprocess --range centered"
                     "--method postprocess --filter jimenez") ;;
  hybrid)
    declare -a names=(sharp postprocess-adapted postprocess-boost80px hybrid hybrid-weights hybrid-boost30 hybrid-boost3)
    declare -a args=("--method sharp" "--method postprocess --range adapted"
                     "--method postprocess --range adapted --foreground-boost-pixels 80" "--method hybrid"
                     "--method hybrid --composite weights" "--method hybrid --foreground-boost 30"
                     "--method hybrid --foreground-boost 3") ;;
  *) echo "unknown set '$set' (postprocess|hybrid)" >&2; exit 2 ;;
esac
for i in "${!names[@]}"; do
  "$hmblur" --quiet render --scene "$scene" ${args[$i]} --width "$width" --height "$height" \
    --out "$out/$scene-${names[$i]}.png" --reference "$reference" --error-image "$out/$scene-${names[$i]}-error.png" \
    --report "$out/$scene-${names[$i]}.json"
done
cp "$reference_png" "$out/$scene-reference.png"
/usr/bin/python3 - "$scene" "$reference" "$out" "${names[@]}" <<'PY'
import json, os, sys
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
scene, reference, out, names = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
rows = []
for name in names:
    path = f"{out}/{scene}-{name}.json"
    report = json.load(open(path))
    # The reports are committed: name the reference by its file name, not where it lay.
    if isinstance(report.get("metrics"), dict) and report["metrics"].get("reference"):
        report["metrics"]["reference"] = os.path.basename(report["metrics"]["reference"])
    if report.get("reference"):
        report["reference"] = os.path.basename(report["reference"])
    json.dump(report, open(path, "w"), indent=2)
    m = report["metrics"]
    rows.append((name, report["frame_ms"], m["frame"], m["region"], m["region_pixels"]))
# Strip: the images on top, their FLIP error maps below, the reference at the right.
images = [plt.imread(f"{out}/{scene}-{n}.png")[:, :, :3] for n in names]
errors = [plt.imread(f"{out}/{scene}-{n}-error.png")[:, :, :3] for n in names]
ref_png = f"{out}/{scene}-reference.png"
top = np.concatenate(images + [plt.imread(ref_png)[:, :, :3]], axis=1)
bottom = np.concatenate(errors + [np.zeros_like(images[0])], axis=1)
strip = np.concatenate([top, bottom], axis=0)
h, w = strip.shape[0] // 2 * 2, strip.shape[1] // 2 * 2
half = strip[:h, :w].reshape(h // 2, 2, w // 2, 2, 3).mean(axis=(1, 3))
plt.imsave(f"{out}/{scene}-strip.png", np.clip(half, 0, 1))
def f(v, fmt):
    return "n/a" if v is None else fmt % v
with open(f"{out}/{scene}.md", "w") as md:
    md.write(f"| {scene} | frame ms | PSNR dB | SSIM | FLIP | blur-region PSNR dB | SSIM | FLIP |\n|---|---:|---:|---:|---:|---:|---:|---:|\n")
    for name, ms, frame, region, pixels in rows:
        region = region or {}
        md.write(f"| {name} | {f(ms, '%.1f')} | {f(frame['psnr_db'], '%.2f')} | {f(frame['ssim'], '%.4f')} | "
                 f"{f(frame['flip'], '%.4f')} | {f(region.get('psnr_db'), '%.2f')} | {f(region.get('ssim'), '%.4f')} | "
                 f"{f(region.get('flip'), '%.4f')} |\n")
    md.write(f"\nBlur region: {rows[0][4]} pixels. Strip: {scene}-strip.png (top: {', '.join(names)}, reference; "
             "bottom: FLIP error maps).\n")
print(open(f"{out}/{scene}.md").read())
PY
