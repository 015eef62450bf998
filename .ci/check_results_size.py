#!/usr/bin/env python3
"""bench/results holds the current run of every suite and the comparisons behind design choices,
not every probe: it stays within 10 MiB on disk (files counted in 4 KiB blocks, as `du` counts
them). Git keeps whatever leaves. Prints the largest files and exits 1 when over; run from anywhere."""
import subprocess
import sys
from pathlib import Path

LIMIT = 10 * 1024 * 1024
BLOCK = 4096


def results_files(root):
    """The files git tracks under bench/results (a build's scratch output does not count), or
    every file there when the tree is not a git checkout."""
    folder = root / "bench" / "results"
    try:
        listed = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "bench/results"],
                                capture_output=True, check=True).stdout.split(b"\0")
        return [root / name.decode() for name in listed if name]
    except (OSError, subprocess.CalledProcessError):
        return [path for path in folder.rglob("*") if path.is_file()]


def main():
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent
    sizes = [(path.stat().st_size, path) for path in results_files(root) if path.is_file()]
    used = sum(-(-size // BLOCK) * BLOCK for size, _ in sizes)
    print(f"bench/results: {len(sizes)} files, {used / 2**20:.1f} MiB on disk (limit {LIMIT / 2**20:.0f} MiB)")
    if used <= LIMIT:
        return 0
    print("over the limit; the largest files:")
    for size, path in sorted(sizes, reverse=True)[:10]:
        print(f"  {size / 2**20:6.2f} MiB  {path.relative_to(root)}")
    return 1


if __name__ == "__main__":
    sys.exit(main())
