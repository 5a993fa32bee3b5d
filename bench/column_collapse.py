#!/usr/bin/env python3
"""Axisymmetric granular column collapse against the scaling laws of Lube et al. (2004).

Runs scenes/granular_column_collapse.json for columns of aspect ratio a = h_i / r_i near 0.5, 1,
2 and 3 (r_i = 5 cm, grains of r = 2.5 mm: r_i = 10 grain diameters). The grains start on a cubic
lattice inside a smooth tube (friction 0; 0.35 against μ = 0.7 grains, a pair taking the mean) and settle for 0.5 s (a tall lattice column sinks by about
20 % as it packs), then the tube is removed at once; h_i is the settled column's height (its
highest grain top at 0.5 s) and a is measured from it. After 2 s:
  runout   (r_inf - r_i) / r_i with r_inf the `runout` probe (the reach of 99 % of the grains;
           also 99.9 % and all of them, as the few grains that roll away from a deposit weigh on
           the largest values)
  height   H_inf / r_i with H_inf the highest grain top.
Lube et al. (2004), J. Fluid Mech. 508: (r_inf - r_i)/r_i = 1.24 a for a < 1.7 and 1.6 a^(1/2)
above, independent of the material. The constants are quoted from secondary sources (the paper's
text was not read).

Usage: bench/column_collapse.py [--moreau build/moreau] [--out DIR] [--threads N]
                                [--rolling-resistance MU_R] [--friction MU] [--iterations N]
"""
import csv
import json
import math
import os
import subprocess

from collapse_options import ROOT, collapse_options

R_I, GRAIN, SETTLE = 0.05, 0.0025, 0.5


def lube_runout(a):
    return 1.24 * a if a < 1.7 else 1.6 * math.sqrt(a)


def run(args, a):
    scene = json.load(open(os.path.join(ROOT, "scenes", "granular_column_collapse.json")))
    spacing = 2 * GRAIN * 1.02
    height = round(a * R_I / spacing) * spacing + 0.003  # whole layers of the lattice
    sand = scene["objects"][2]
    sand["cylinders"][0]["height"] = height
    sand["rolling_resistance"] = args.rolling_resistance
    sand["friction"] = args.friction
    scene["settings"]["iterations"] = args.iterations
    scene["settings"]["output"]["every"] = 40
    scene["probes"] += [{"name": "runout999", "type": "runout", "object": "sand", "center": [0, 0, 0], "fraction": 0.999},
                        {"name": "runout_all", "type": "runout", "object": "sand", "center": [0, 0, 0], "fraction": 1}]
    out = os.path.join(args.out, f"a{a}")
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "scene.json")
    json.dump(scene, open(path, "w"))
    subprocess.run([args.moreau, "run", path, "--out", out, "--quiet", "--threads", str(args.threads)], check=True)
    rows = list(csv.DictReader(open(os.path.join(out, "probes.csv"))))
    settled = min(rows, key=lambda r: abs(float(r["time"]) - SETTLE))
    last = rows[-1]
    h_i = float(settled["top"]) + GRAIN
    a_i = h_i / R_I
    spread = [(float(last[k]) - R_I) / R_I for k in ("runout", "runout999", "runout_all")]
    seconds = json.load(open(os.path.join(out, "run.json"))).get("wall_time_s", float("nan"))
    return a_i, spread, (float(last["top"]) + GRAIN) / R_I, seconds


def main():
    args = collapse_options(__doc__, "column_collapse").parse_args()
    print(f"mu = {args.friction}, mu_r = {args.rolling_resistance}, {args.iterations} iterations")
    print("a (settled) | (r_inf - r_i)/r_i: 99 %, 99.9 %, all | Lube 2004 | 99 % vs Lube | H_inf/r_i | run s")
    for a in (0.5, 1, 2, 3):
        a_i, spread, height, seconds = run(args, a)
        law = lube_runout(a_i)
        print(f"{a_i:11.3f} | {spread[0]:6.3f} {spread[1]:6.3f} {spread[2]:6.3f} | {law:9.3f} | "
              f"{100 * (spread[0] / law - 1):+11.1f} % | {height:9.3f} | {seconds:5.1f}")


if __name__ == "__main__":
    main()
