#!/usr/bin/python3
"""Where two builds' renders of the same frames differ: for each pair of display PNGs (before,
after), a map over the dimmed "before" image (orange: a channel differs by more than 2/255, the
blur region's threshold; blue: by 1 or 2), and a Markdown table of the counts.

usage: image_changes.py OUT_DIR NAME=BEFORE.png,AFTER.png ...
writes OUT_DIR/NAME.png per pair and prints the table.
"""
import sys
from pathlib import Path

import numpy as np
from PIL import Image


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    print("| frame | pixels | differ by more than 2/255 | by 1 or 2 | largest difference |")
    print("|---|---:|---:|---:|---:|")
    for pair in sys.argv[2:]:
        name, files = pair.split("=", 1)
        before_path, after_path = files.split(",")
        before = np.asarray(Image.open(before_path).convert("RGB")).astype(np.int16)
        after = np.asarray(Image.open(after_path).convert("RGB")).astype(np.int16)
        if before.shape != after.shape:
            print(f"{name}: the images differ in size", file=sys.stderr)
            return 1
        difference = np.abs(before - after).max(axis=2)
        large, small = difference > 2, (difference > 0) & (difference <= 2)
        picture = (before.mean(axis=2, keepdims=True) / 3).repeat(3, axis=2)
        picture[small] = (0, 90, 255)
        picture[large] = (255, 160, 0)
        Image.fromarray(picture.astype(np.uint8)).save(out / f"{name}.png")
        print(f"| {name} | {difference.size} | {int(large.sum())} | {int(small.sum())} | {int(difference.max())} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
