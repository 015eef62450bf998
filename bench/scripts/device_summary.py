#!/usr/bin/env python3
"""One page from a device check's results (scripts/device-check.sh): device, driver and CPU,
each method's frame and its shape, the hybrid over post-process, the BVH's build and trace
rates, and the test failures. Writes summary.md into the results folder and prints the name
of the folder the results belong in (bench/results/<device>/)."""
import argparse
import json
import re
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path


def load(path):
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def slug(text):
    return re.sub(r"-+", "-", re.sub(r"[^a-z0-9]+", "-", text.lower())).strip("-")


def folder_name(device):
    name = device.get("name", "unknown device")
    profile = device.get("profile", {})
    forced = f"-{profile.get('name')}-profile" if profile.get("forced") else ""
    if device.get("driver") == "llvmpipe":  # "llvmpipe (LLVM 15.0.6, 256 bits)": the Mesa release tells more
        mesa = re.match(r"Mesa (\d+\.\d+)", device.get("driver_info", ""))
        return slug("lavapipe-mesa-" + (mesa.group(1) if mesa else "unknown") + forced)
    return slug(name + forced)


def median(summary):
    return summary.get("median") if isinstance(summary, dict) else None


def fmt(value, digits=2):
    return "-" if value is None else f"{value:.{digits}f}"


def tests_section(results):
    lines = ["## Tests", ""]
    junit = results / "tests.xml"
    if not junit.exists():
        return lines + ["Not run (`--skip-tests`, or ctest wrote no results).", ""]
    root = ElementTree.parse(junit).getroot()
    cases = root.iter("testcase")
    failed, passed, skipped = [], 0, 0
    for case in cases:
        status = case.get("status", "")
        if case.find("failure") is not None or status == "fail":
            failed.append(case.get("name"))
        elif case.find("skipped") is not None or status in ("notrun", "disabled"):
            skipped += 1
        else:
            passed += 1
    exit_code = (results / "tests.exit").read_text().strip() if (results / "tests.exit").exists() else "?"
    lines.append(f"{passed} passed, {len(failed)} failed, {skipped} skipped (ctest exit {exit_code}; "
                 "`tests.log`; the JUnit XML only in $OUT).")
    if failed:
        lines += ["", "Failed:", ""] + [f"- `{name}`" for name in failed]
    return lines + [""]


def passes_section(passes):
    lines = ["## Frames (`passes.md`)", ""]
    if not passes:
        return lines + ["The passes suite wrote no results (`passes.err`).", ""]
    lines += ["| scene | size | method | frame ms | x post-process | dispatches (indirect) | barriers | "
              "host waits | dependent chain |", "|---|---|---|---:|---:|---:|---:|---:|---:|"]
    for c in passes["cases"]:
        shape = c.get("frame", {})
        ratio = median(c.get("frame_over_postprocess"))
        lines.append(f"| {c['scene']} | {c['width']}x{c['height']} | {c['method']} | {fmt(median(c['frame_ms']))} | "
                     f"{fmt(ratio, 3)} | {shape.get('dispatches', '-')} ({shape.get('indirect_dispatches', '-')}) | "
                     f"{shape.get('barriers', '-')} | {shape.get('host_waits', '-')} | "
                     f"{shape.get('dependent_chain', '-')} |")
    paper = [c for c in passes["cases"] if c["method"] == "hybrid" and c["width"] == 1280]
    if paper:
        worst = max(paper, key=lambda c: median(c.get("frame_over_postprocess")) or 0)
        lines += ["", "The paper's hybrid (`hybrid`) over post-process's frame at 1280x720: " +
                  ", ".join(f"{c['scene']} {fmt(median(c.get('frame_over_postprocess')), 2)}x" for c in paper) +
                  f" (the most: {worst['scene']})."]
    return lines + [""]


def bvh_section(bvh):
    lines = ["## BVH (`bvh.json`)", ""]
    if not bvh:
        return lines + ["The bvh suite wrote no results (`bvh.err`).", ""]
    lines += ["| scene | triangles | build shape | build ms | Mtris/s | dispatches (host waits) | SAH / full sweep | "
              "coherent Mrays/s | incoherent Mrays/s | hit agreement |", "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
    for c in bvh["cases"]:
        build, sah = c.get("build", {}), c.get("sah", {})
        coherent, incoherent = c.get("coherent", {}), c.get("incoherent", {})
        agreement = min(x.get("hit_agreement", 0.0) for x in (coherent, incoherent))
        shape = build.get("device_frame", {})
        lines.append(f"| {c['scene']} | {c['triangles']} | {build.get('device_build_shape', '-')} | "
                     f"{fmt(median(build.get('device_ms')))} | {fmt(build.get('device_mtris_per_s'))} | "
                     f"{shape.get('dispatches', '-')} ({shape.get('host_waits', '-')}) | "
                     f"{fmt(sah.get('device_over_full_sweep'), 3)} | {fmt(coherent.get('device_mrays_per_s'), 1)} | "
                     f"{fmt(incoherent.get('device_mrays_per_s'), 1)} | {agreement:.4f} |")
    lines += ["", "The treelet builder (the GPU profile's mesh builder) on the same triangles:", "",
              "| scene | build ms | Mtris/s | slowest stage | dispatches (host waits) | levels | SAH / full sweep | "
              "hit agreement |", "|---|---:|---:|---|---:|---:|---:|---:|"]
    for c in bvh["cases"]:
        treelets = c.get("treelet_build")
        if not treelets:
            continue
        shape = treelets.get("device_frame", {})
        agreement = min(treelets.get(rays, {}).get("hit_agreement", 0.0) for rays in ("coherent", "incoherent"))
        stages = treelets.get("stage_ms") or {}
        slowest = max(stages, key=stages.get) if stages else None
        share = f"{slowest} {100 * stages[slowest] / max(sum(stages.values()), 1e-9):.0f}%" if slowest else "-"
        lines.append(f"| {c['scene']} | {fmt(median(treelets.get('device_ms')))} | "
                     f"{fmt(treelets.get('device_mtris_per_s'))} | {share} | {shape.get('dispatches', '-')} "
                     f"({shape.get('host_waits', '-')}) | {treelets.get('device_levels', '-')} | "
                     f"{fmt(treelets.get('sah_over_full_sweep'), 3)} | {agreement:.4f} |")
    return lines + [""]


def other_section(results):
    lines = ["## Other suites", ""]
    for name, what in (("raster", "compute raster beside the graphics pipeline"), ("kernels", "single kernels")):
        files = [f"`{path.name}`" for path in sorted(results.glob(f"{name}.*"))
                 if path.suffix in (".json", ".md", ".csv") and path.stat().st_size > 0]
        ok = (results / f"{name}.json").exists()
        lines.append(f"- `{name}` ({what}): " + (", ".join(files) if ok else f"no results (`{name}.err`)"))
    return lines + [""]


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("results", type=Path)
    parser.add_argument("--seconds", type=int, default=None, help="the check's wall time")
    parser.add_argument("--command", default="scripts/device-check.sh")
    args = parser.parse_args()
    passes, bvh = load(args.results / "passes.json"), load(args.results / "bvh.json")
    anyone = passes or bvh or load(args.results / "raster.json") or load(args.results / "kernels.json")
    if not anyone:
        print("device_summary: no suite wrote results", file=sys.stderr)
        return 1
    device, system = anyone.get("device", {}), anyone.get("system", {})
    profile = device.get("profile", {})
    lines = [f"# Device check: {device.get('name', '?')}", "",
             f"- Device: {device.get('name')} ({device.get('type')}), Vulkan {device.get('api_version')}, "
             f"subgroups of {device.get('subgroup_size')}, {device.get('device_local_bytes', 0) / 2**30:.0f} GiB "
             "device-local",
             f"- Driver: {device.get('driver')} {device.get('driver_info')}",
             f"- Profile: {profile.get('name', '?')}{' (forced)' if profile.get('forced') else ''}; loop budget "
             f"{profile.get('loop_budget') or 'none'}",
             f"- CPU: {system.get('cpu')}, {system.get('hardware_threads')} threads, LP_NUM_THREADS "
             f"{system.get('LP_NUM_THREADS') or 'unset'}",
             f"- Code: {system.get('git_revision', '?')}; command `{args.command.strip()}`" +
             (f", {args.seconds} s in all" if args.seconds is not None else ""), ""]
    lines += tests_section(args.results) + passes_section(passes) + bvh_section(bvh) + other_section(args.results)
    (args.results / "summary.md").write_text("\n".join(lines))
    print(folder_name(device))
    return 0


if __name__ == "__main__":
    sys.exit(main())
