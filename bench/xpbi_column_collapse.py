#!/usr/bin/env python3
"""Axisymmetric collapse of a Drucker-Prager continuum column under XPBI, against Lube et al. (2004).

Runs scenes/sand_column_xpbi.json (R_i = 4 cm, phi = 35 degrees, rough ground) with the column's
height set to a * R_i for each aspect ratio a and the particle spacing r given, and measures after
the run's duration:
  runout  (r_inf - r_i) / r_i with r_i and r_inf the `runout` probe (the reach of 99 % of the
          particles, each counted by its outer edge) at the start and at the end
  height  H_inf / r_i, the highest particle's top
  slope   the `angle_of_repose` probe: the flank's mean slope between 20 % and 80 % of the height
Lube et al. (2004), J. Fluid Mech. 508: (r_inf - r_i)/r_i = 1.24 a for a < 1.7 and 1.6 a^(1/2)
above, independent of the material (the constants are quoted from secondary sources).

Extra `--set key=value` pairs go to every run (e.g. --set settings.xpbi.xsph=0).

Usage: bench/xpbi_column_collapse.py [--moreau build/moreau] [--out DIR] [--threads N]
           [--spacing R] [--aspect A ...] [--duration T] [--friction-angle DEG] [--set k=v ...]
"""
import argparse
import csv
import json
import os
import subprocess

from collapse_options import ROOT
from column_collapse import lube_runout

R_I = 0.04  # the scene's column radius, m


def run(args, a):
    scene = json.load(open(os.path.join(ROOT, "scenes", "sand_column_xpbi.json")))
    sand = next(o for o in scene["objects"] if o["name"] == "sand")
    sand["cylinders"][0]["height"] = a * R_I
    sand["spacing"] = args.spacing
    sand["plasticity"]["friction_angle_deg"] = args.friction_angle
    scene["settings"]["duration"] = args.duration
    scene["settings"]["output"]["every"] = 20
    scene["probes"] = [p for p in scene["probes"] if p["name"] in ("slope", "runout", "height", "kinetic")]
    tag = f"a{a}_r{args.spacing}_phi{args.friction_angle}" + "".join("_" + s.replace("/", "_") for s in args.set)
    out = os.path.join(args.out, tag)
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "scene.json")
    json.dump(scene, open(path, "w"))
    command = [args.moreau, "run", path, "--out", out, "--quiet", "--threads", str(args.threads)]
    for s in args.set:
        command += ["--set", s]
    subprocess.run(command, check=True)
    rows = list(csv.DictReader(open(os.path.join(out, "probes.csv"))))
    first, last = rows[0], rows[-1]
    r_i = float(first["runout"])
    spread = (float(last["runout"]) - r_i) / r_i
    seconds = json.load(open(os.path.join(out, "run.json"))).get("wall_time_s", float("nan"))
    return spread, float(last["slope"]), (float(last["height"]) + args.spacing / 2) / r_i, float(last["kinetic"]), seconds


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--moreau", default=os.path.join(ROOT, "build", "moreau"))
    p.add_argument("--out", default=os.path.join(ROOT, "out", "xpbi_column_collapse"))
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--spacing", type=float, default=0.005)
    p.add_argument("--aspect", type=float, nargs="+", default=[0.5, 1, 2])
    p.add_argument("--duration", type=float, default=0.6)
    p.add_argument("--friction-angle", type=float, default=35)
    p.add_argument("--set", action="append", default=[])
    args = p.parse_args()
    print(f"r = {args.spacing} m, phi = {args.friction_angle} deg, {args.duration} s {' '.join(args.set)}")
    print("a    | (r_inf - r_i)/r_i | Lube 2004 | error    | slope deg | H_inf/r_i | kinetic J | run s")
    for a in args.aspect:
        spread, slope, height, kinetic, seconds = run(args, a)
        law = lube_runout(a)
        print(f"{a:4.2f} | {spread:17.3f} | {law:9.3f} | {100 * (spread / law - 1):+7.1f} % | {slope:9.1f} | "
              f"{height:9.3f} | {kinetic:9.2e} | {seconds:5.1f}", flush=True)


if __name__ == "__main__":
    main()
