#!/usr/bin/python3
"""Where two renders of one frame differ most, tile by tile, and which is closer to a reference
there: for each pair of display PNGs (A, B), the m x m tile (the blur's tile grid) where a
channel of A and B differs most, that difference, each image's largest error against the
reference in that tile, and its PSNR against the reference (peak 1, MSE over R, G, B, as the
reports measure it) over that tile, over all the tiles where A and B differ, and over the frame.
Writes a picture: per pair, the tile with one tile around it (outlined, scaled up) in the
reference, A and B, labelled.

usage: tile_differences.py TILE REFERENCE.png OUT.png LABEL_A,LABEL_B NAME=A.png,B.png ...
prints a Markdown table.
"""
import sys

import numpy as np
from PIL import Image, ImageDraw, ImageFont

SCALE = 4  # the crops' pixels, scaled up


def load(path):
    return np.asarray(Image.open(path).convert("RGB")).astype(np.int16)


def psnr(a, b):
    mse = np.mean(((a - b) / 255.0) ** 2)
    return float("inf") if mse == 0 else 10.0 * np.log10(1.0 / mse)


def crop(image, x0, y0, x1, y1, tile, tx, ty):
    part = Image.fromarray(image[y0:y1, x0:x1].astype(np.uint8))
    part = part.resize((part.width * SCALE, part.height * SCALE), Image.NEAREST)
    draw = ImageDraw.Draw(part)
    left, top = (tx - x0) * SCALE, (ty - y0) * SCALE
    right = (min(tx + tile, x1) - x0) * SCALE - 1
    bottom = (min(ty + tile, y1) - y0) * SCALE - 1
    draw.rectangle([left, top, right, bottom], outline=(255, 255, 0))
    return part


def main() -> int:
    if len(sys.argv) < 6:
        print(__doc__, file=sys.stderr)
        return 2
    tile, reference_path, out_path = int(sys.argv[1]), sys.argv[2], sys.argv[3]
    label_a, label_b = sys.argv[4].split(",")
    reference = load(reference_path)
    h, w = reference.shape[:2]
    font = ImageFont.load_default()
    rows = []
    print(f"| frame | tile (x, y) | largest A-B in the tile | tile PSNR {label_a} | tile PSNR {label_b} | "
          f"largest error {label_a} | largest error {label_b} | tiles that differ | their PSNR {label_a} | "
          f"their PSNR {label_b} | frame PSNR {label_a} | frame PSNR {label_b} |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for pair in sys.argv[5:]:
        name, files = pair.split("=", 1)
        path_a, path_b = files.split(",")
        a, b = load(path_a), load(path_b)
        if a.shape != reference.shape or b.shape != reference.shape:
            print(f"{name}: the images differ in size", file=sys.stderr)
            return 1
        difference = np.abs(a - b).max(axis=2)
        best, differing = None, 0
        in_differing = np.zeros((h, w), dtype=bool)
        for ty in range(0, h, tile):
            for tx in range(0, w, tile):
                d = difference[ty:ty + tile, tx:tx + tile]
                if d.max() > 0:
                    differing += 1
                    in_differing[ty:ty + tile, tx:tx + tile] = True
                key = (int(d.max()), int(d.sum()))
                if best is None or key > best[0]:
                    best = (key, tx, ty)
        (largest, _), tx, ty = best
        sl = (slice(ty, ty + tile), slice(tx, tx + tile))
        ra, ta, tb = reference[sl], a[sl], b[sl]
        row = (name, f"{tx // tile}, {ty // tile} (pixels {tx}-{min(tx + tile, w) - 1}, "
               f"{ty}-{min(ty + tile, h) - 1})", largest, psnr(ra, ta), psnr(ra, tb), int(np.abs(ra - ta).max()),
               int(np.abs(ra - tb).max()), differing, psnr(reference[in_differing], a[in_differing]),
               psnr(reference[in_differing], b[in_differing]), psnr(reference, a), psnr(reference, b))
        print("| %s | %s | %d/255 | %.2f dB | %.2f dB | %d/255 | %d/255 | %d | %.2f dB | %.2f dB | %.2f dB | %.2f dB |"
              % row)
        x0, y0 = max(tx - tile, 0), max(ty - tile, 0)
        x1, y1 = min(tx + 2 * tile, w), min(ty + 2 * tile, h)
        rows.append((name, [crop(image, x0, y0, x1, y1, tile, tx, ty) for image in (reference, a, b)]))
    # The picture: one row per pair, the reference, A and B, each captioned.
    gap, caption = 6, 14
    width = max(sum(c.width for c in crops) + 2 * gap for _, crops in rows)
    height = sum(max(c.height for c in crops) + caption + gap for _, crops in rows)
    picture = Image.new("RGB", (width, height), (255, 255, 255))
    draw = ImageDraw.Draw(picture)
    y = 0
    for name, crops in rows:
        x = 0
        for label, c in zip(("reference", label_a, label_b), crops):
            draw.text((x + 2, y + 1), f"{name}: {label}", fill=(0, 0, 0), font=font)
            picture.paste(c, (x, y + caption))
            x += c.width + gap
        y += max(c.height for c in crops) + caption + gap
    picture.save(out_path, optimize=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
