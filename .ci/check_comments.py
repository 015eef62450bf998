#!/usr/bin/env python3
"""Comments in the library's code say why, not what was measured when: no commit hash and no
measured figure (milliseconds, decibels, a ratio such as 1.5x) in a comment under include/, runtime/,
kernels/, bvh/, scenes/ or examples/. Numbers live in bench/results/<decision>/, history in git.
Prints each offending line and exits 1 when there is one; run from anywhere."""
import re
import sys
from pathlib import Path

ROOTS = ("include", "runtime", "kernels", "bvh", "scenes", "examples")
SUFFIXES = {".h", ".cpp", ".comp", ".glsl"}
# A hexadecimal word of 7 to 40 digits with both a letter and a digit: a commit.
COMMIT = re.compile(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}\b")
# A time or a level: "1.4 ms", "0.45 dB", "3-6 ms".
UNIT = re.compile(r"\b\d+(\.\d+)?(\s?[-/]\s?\d+(\.\d+)?)?\s?(ms|dB|us|µs)\b(?!\w)")
# A ratio: "1.5x", "2-3x" (not a size such as "8 x 8" or "2x2", nor "x^2").
RATIO = re.compile(r"\b\d+(\.\d+)?(-\d+(\.\d+)?)?x\b(?!\s*\d)(?!\^)")


def comment_of(line):
    at = line.find("//")
    return line[at:] if at >= 0 else None


def offences(root):
    found = []
    for top in ROOTS:
        for path in sorted((root / top).rglob("*")):
            if path.suffix not in SUFFIXES or not path.is_file():
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                comment = comment_of(line)
                if comment and (COMMIT.search(comment) or UNIT.search(comment) or RATIO.search(comment)):
                    found.append(f"{path.relative_to(root)}:{number}: {comment.strip()}")
    return found


def main():
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent
    found = offences(root)
    for line in found:
        print(line)
    sys.stdout.flush()  # the lines before the verdict, on one stream or two
    if found:
        print(f"{len(found)} comments carry a commit or a measured figure: say why, and link the result "
              "folder (bench/results/<decision>/) that shows it", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
