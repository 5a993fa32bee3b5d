#!/usr/bin/env python3
"""The 30k dam break under PBF (xpbd) and constraint fluids (nmd) at growing time steps.

Each run simulates the first 0.3 s of bench/scenes/dam_break_30k.json on one thread (the surge is
then 1.4 m into the tank, before it reaches the far wall) and reports where the surge front (the
scene's `front` probe, the largest x of any particle) stands against a reference run at a quarter
of the stock step, and the wall time per simulated second (run.json). The largest step each
formulation can take with a front error below one particle diameter (2r = 31 mm) is what
docs/performance.md compares.

Usage: bench/dam_break_front.py [--moreau build/moreau] [--out DIR]
Run it on an otherwise idle machine: it times the runs.
"""
import argparse
import csv
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "bench", "scenes", "dam_break_30k.json")
DURATION = 0.3
DIAMETER = 2 * 0.015625

# (label, solver, dt in s, overrides)
REFERENCE = ("xpbd reference", "xpbd", 0.00025, ["settings.iterations=3"])
CANDIDATES = [
    ("xpbd", "xpbd", 0.001, ["settings.iterations=3"]),
    ("xpbd", "xpbd", 0.002, ["settings.iterations=3"]),
    ("xpbd", "xpbd", 0.004, ["settings.iterations=3"]),
    ("nmd", "nmd", 0.002, ["settings.nmd.iterations=50"]),
    ("nmd", "nmd", 0.004, ["settings.nmd.iterations=50"]),
    ("nmd", "nmd", 0.008, ["settings.nmd.iterations=50"]),
]


def run(moreau, out, label, solver, dt, overrides):
    directory = os.path.join(out, f"{solver}_{dt * 1000:g}ms")
    command = [moreau, "run", SCENE, "--out", directory, "--threads", "1", "--quiet",
               "--duration", str(DURATION), "--set", f'settings.solver="{solver}"', "--set", f"settings.dt={dt}",
               "--set", "settings.output.formats=[]"]
    for value in overrides:
        command += ["--set", value]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        return {"label": label, "dt": dt, "failed": result.stdout + result.stderr}
    with open(os.path.join(directory, "probes.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(directory, "run.json")) as f:
        report = json.load(f)
    return {"label": label, "dt": dt, "time": float(rows[-1]["time"]), "front": float(rows[-1]["front"]),
            "wall": report["wall_time_s"], "steps": report["steps"]}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--moreau", default=os.path.join(ROOT, "build", "moreau"))
    parser.add_argument("--out", default="/tmp/dam_break_front")
    args = parser.parse_args()
    reference = run(args.moreau, args.out, *REFERENCE)
    if "failed" in reference:
        sys.exit(f"the reference run failed:\n{reference['failed']}")
    print(f"reference ({REFERENCE[1]}, dt = {REFERENCE[2] * 1000:g} ms): front at x = {reference['front']:.4f} m "
          f"at t = {reference['time']:.3f} s")
    print("| solver | dt (ms) | front (m) | error (mm) | ms per step | s per simulated s |")
    print("|---|---:|---:|---:|---:|---:|")
    for candidate in CANDIDATES:
        r = run(args.moreau, args.out, *candidate)
        if "failed" in r:
            print(f"| {r['label']} | {r['dt'] * 1000:g} | failed | | | |")
            continue
        error = abs(r["front"] - reference["front"])
        print(f"| {r['label']} | {r['dt'] * 1000:g} | {r['front']:.4f} | {error * 1000:.1f}"
              f"{' ✓' if error < DIAMETER else ''} | {r['wall'] / r['steps'] * 1000:.1f} | {r['wall'] / r['time']:.1f} |",
              flush=True)


if __name__ == "__main__":
    main()
