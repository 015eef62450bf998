#!/usr/bin/env python3
"""Frame times of two builds side by side, from `hmblur-bench passes` reports.

Each build ran the suite one or more times, alternated with the other on one machine; the
table lists each case's median device frame time from every run, and compares the faster run
of each build (after / before), with the peak device memory of each. Below the table: the
median ratio per method.

    bench/scripts/compare_runs.py --before before-1.json before-2.json \\
                                  --after after-1.json after-2.json > table.md
"""
import argparse
import json
import statistics


def cases(path):
    with open(path) as f:
        report = json.load(f)
    out = {}
    for c in report["cases"]:
        key = (c["scene"], f'{c["width"]}x{c["height"]}', c["method"])
        out[key] = (c["frame_ms"]["median"], c["device_memory"]["peak_bytes"] / 2**20)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--before", nargs="+", required=True, help="reports of the first build's runs")
    parser.add_argument("--after", nargs="+", required=True, help="reports of the second build's runs")
    args = parser.parse_args()
    before = [cases(p) for p in args.before]
    after = [cases(p) for p in args.after]
    keys = [k for k in before[0] if all(k in run for run in before + after)]
    print("| scene | size | method | before ms (runs) | after ms (runs) | after / before | peak MiB before | after |")
    print("|---|---|---|---:|---:|---:|---:|---:|")
    ratios = {}
    for key in keys:
        b = [run[key][0] for run in before]
        a = [run[key][0] for run in after]
        ratio = min(a) / min(b)
        ratios.setdefault(key[2], []).append(ratio)
        print(f"| {key[0]} | {key[1]} | {key[2]} | {', '.join(f'{x:.1f}' for x in b)} | "
              f"{', '.join(f'{x:.1f}' for x in a)} | {ratio:.3f} | {before[0][key][1]:.1f} | {after[0][key][1]:.1f} |")
    print()
    for method, values in ratios.items():
        print(f"- {method}: median after / before {statistics.median(values):.3f} "
              f"({min(values):.3f} to {max(values):.3f}, {len(values)} cases)")


if __name__ == "__main__":
    main()
