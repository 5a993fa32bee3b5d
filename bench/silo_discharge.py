#!/usr/bin/env python3
"""Granular flow from a flat-bottomed silo: Beverloo's law and the angle of repose of the pile.

1. Discharge: a 10 x 10 cm silo filled to 15 cm with 20,736 grains (r = 2 mm, 2600 kg/m^3,
   mu = 0.5, the engine's rolling resistance unless --rolling-resistance) drains through a square
   orifice of side D = 20, 24, 28 and 32 mm (5 to 8 grain diameters) for 1.2 s. The flow rate W is the least-squares slope of the discharged mass (the
   scene's `discharged` probe, `mass_flow` "beyond" the orifice plane) over [0.3, 1.2] s. Beverloo
   et al. (1961): W = C rho_b sqrt(g) (D - k d)^(5/2) for a 3D silo, so W^(2/5) is linear in D; the
   script fits k and C, and the plain power law W ~ D^n (n above 5/2 where k d matters).
2. Pile: a silo of the same section filled to 10 cm drains through D = 24 mm onto the ground 15 cm
   below for 5 s, for mu = 0.3, 0.5 and 0.8 (or --friction; walls, floor, ground and grains alike); the
   `pile_angle` probe (`angle_of_repose` about the orifice's axis, of the grains below the silo's
   floor moving slower than 5 cm/s: the pile without the stream that feeds it) at the end.
Both run 1 XPBD iteration per substep unless --iterations.

Usage: bench/silo_discharge.py [--moreau build/moreau] [--out DIR] [--threads N] [--only discharge|pile]
                               [--friction MU ...] [--rolling-resistance MU_R] [--iterations N]
"""
import argparse
import csv
import json
import math
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RADIUS = 0.002
DENSITY = 2600


def silo(D, fill, mu, duration, W=0.1, drop=0.15, rolling=None, iterations=1):
    t, w, d, h = 0.01, W / 2, D / 2, fill + 0.05

    def box(name, lo, hi):
        c = [(a + b) / 2 for a, b in zip(lo, hi)]
        e = [(b - a) / 2 for a, b in zip(lo, hi)]
        return {"name": name, "kind": "collider", "shape": {"type": "box", "center": c, "half_extents": e}, "friction": mu}

    objects = [
        {"name": "ground", "kind": "collider", "shape": {"type": "plane", "point": [0, -drop, 0]}, "friction": mu},
        box("floor_left", [-w, -t, -w], [-d, 0, w]), box("floor_right", [d, -t, -w], [w, 0, w]),
        box("floor_front", [-d, -t, -w], [d, 0, -d]), box("floor_back", [-d, -t, d], [d, 0, w]),
        box("wall_left", [-w - t, -t, -w - t], [-w, h, w + t]), box("wall_right", [w, -t, -w - t], [w + t, h, w + t]),
        box("wall_front", [-w, -t, -w - t], [w, h, -w]), box("wall_back", [-w, -t, w], [w, h, w + t]),
        {"name": "sand", "kind": "granular", "blocks": [{"min": [-w, 0, -w], "max": [w, fill, w]}],
         "radius": RADIUS, "density": DENSITY, "friction": mu},
    ]
    if rolling is not None:
        objects[-1]["rolling_resistance"] = rolling
    probes = [
        {"name": "flow", "type": "mass_flow", "object": "sand", "point": [0, 0, 0], "normal": [0, -1, 0]},
        {"name": "discharged", "type": "mass_flow", "object": "sand", "point": [0, 0, 0], "normal": [0, -1, 0],
         "quantity": "beyond"},
        {"name": "pile_angle", "type": "angle_of_repose", "object": "sand", "center": [0, -drop, 0],
         "box": {"min": [-1, -drop - 0.01, -1], "max": [1, -0.02, 1]}, "resting_speed": 0.05},
    ]
    return {"name": "silo", "settings": {"dt": 0.0025, "substeps": 5, "iterations": iterations, "duration": duration,
                                         "output": {"every": 8}},
            "objects": objects, "probes": probes}


def run(args, scene, label):
    directory = os.path.join(args.out, label)
    os.makedirs(directory, exist_ok=True)
    path = os.path.join(directory, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    subprocess.run([args.moreau, "run", path, "--out", directory, "--threads", str(args.threads), "--quiet"], check=True)
    with open(os.path.join(directory, "probes.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    with open(os.path.join(directory, "run.json")) as f:
        summary = json.load(f)
    return rows, summary


def line_fit(x, y):
    n = len(x)
    sx, sy = sum(x), sum(y)
    sxx = sum(a * a for a in x)
    sxy = sum(a * b for a, b in zip(x, y))
    slope = (n * sxy - sx * sy) / (n * sxx - sx * sx)
    return slope, (sy - slope * sx) / n


def discharge(args):
    print("silo 10 x 10 cm filled to 15 cm, grains r = 2 mm, mu = 0.5; flow over [0.3, 1.2] s")
    widths, rates = [], []
    for D in (0.020, 0.024, 0.028, 0.032):
        rows, summary = run(args, silo(D, 0.15, 0.5, 1.2, iterations=args.iterations), f"discharge_{D * 1000:g}mm")
        window = [r for r in rows if r["time"] >= 0.3 - 1e-9]
        rate, _ = line_fit([r["time"] for r in window], [r["discharged"] for r in window])
        half = len(window) // 2
        first, _ = line_fit([r["time"] for r in window[:half]], [r["discharged"] for r in window[:half]])
        second, _ = line_fit([r["time"] for r in window[half:]], [r["discharged"] for r in window[half:]])
        print(f"  D = {D * 1000:4.0f} mm ({D / (2 * RADIUS):.0f} d): W = {rate:.4f} kg/s "
              f"(first half {first:.4f}, second {second:.4f}); {summary['counts']['particles']} grains, "
              f"{summary['wall_time_s']:.1f} s wall")
        widths.append(D)
        rates.append(rate)
    # Beverloo: W^(2/5) = a (D - k d), a = (C rho_b sqrt g)^(2/5).
    slope, intercept = line_fit(widths, [w ** 0.4 for w in rates])
    k = -intercept / slope / (2 * RADIUS)
    bulk = 0.6 * DENSITY
    C = slope ** 2.5 / (bulk * math.sqrt(9.81))
    worst = max(abs((slope * D + intercept) ** 2.5 / w - 1) for D, w in zip(widths, rates))
    n, _ = line_fit([math.log(D) for D in widths], [math.log(w) for w in rates])
    n15, _ = line_fit([math.log(D - 1.5 * 2 * RADIUS) for D in widths], [math.log(w) for w in rates])
    print(f"  Beverloo fit: k = {k:.2f}, C = {C:.3f} (bulk density 0.6 rho = {bulk:.0f} kg/m^3), largest deviation "
          f"of W from it {100 * worst:.1f} %; W ~ (D - 1.5 d)^{n15:.2f} (Beverloo: 5/2); plain power law W ~ D^{n:.2f}")


def pile(args):
    print(f"silo 10 x 10 cm filled to 10 cm draining through 24 mm onto the ground 15 cm below, 5 s, "
          f"{args.iterations} iteration(s) per substep")
    for mu in args.friction:
        rows, summary = run(args, silo(0.024, 0.10, mu, 5.0, rolling=args.rolling_resistance, iterations=args.iterations),
                            f"pile_mu{mu:g}")
        last = rows[-1]
        print(f"  mu = {mu}: angle of repose {last['pile_angle']:.1f} degrees, discharged {last['discharged']:.3f} kg, "
              f"{summary['wall_time_s']:.1f} s wall")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moreau", default=os.path.join(ROOT, "build", "moreau"))
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "silo_discharge"))
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--only", choices=["discharge", "pile"])
    parser.add_argument("--friction", type=float, nargs="+", default=[0.3, 0.5, 0.8], help="the piles' mu")
    parser.add_argument("--iterations", type=int, default=1, help="XPBD iterations per substep")
    parser.add_argument("--rolling-resistance", type=float, help="the grains' mu_r (default: the engine's)")
    args = parser.parse_args()
    if args.only != "pile":
        discharge(args)
    if args.only != "discharge":
        pile(args)


if __name__ == "__main__":
    main()
