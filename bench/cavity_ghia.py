#!/usr/bin/env python3
"""Maximum deviation of a cavity run's centreline profiles from Ghia, Ghia & Shin (1982).

Usage: bench/cavity_ghia.py OUT_DIR RE   (RE: 100 or 1000)

Reads OUT_DIR/line_vertical_centreline.csv (u along x = 0.5) and line_horizontal_centreline.csv
(v along y = 0.5), written by the line probes of scenes/cavity_re1000.json, interpolates them
linearly to Ghia's 17 + 17 points (exact for Q1 fields when the line runs along grid lines) and
prints the largest |u - u_Ghia| and |v - v_Ghia| in units of the lid speed.
Ghia et al., J. Comput. Phys. 48 (1982) 387-411, tables I and II (129 x 129 grid).
"""
import csv
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "report"))
from ghia1982 import U, V, X, Y  # noqa: E402


def profile(path, along, component):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [float(r[along]) for r in rows], [float(r[component]) for r in rows]


def interpolate(xs, ys, x):
    for i in range(len(xs) - 1):
        if xs[i] <= x <= xs[i + 1]:
            s = (x - xs[i]) / (xs[i + 1] - xs[i])
            return ys[i] + s * (ys[i + 1] - ys[i])
    raise ValueError(f"{x} outside the sampled line")


def main():
    out, re = sys.argv[1], int(sys.argv[2])
    ys, u = profile(f"{out}/line_vertical_centreline.csv", "y", "velocity.x")
    xs, v = profile(f"{out}/line_horizontal_centreline.csv", "x", "velocity.y")
    du = max(abs(interpolate(ys, u, y) - g) for y, g in zip(Y, U[re]))
    dv = max(abs(interpolate(xs, v, x) - g) for x, g in zip(X, V[re]))
    print(f"Re {re}: max |u - Ghia| {du:.4f}, max |v - Ghia| {dv:.4f}, max {max(du, dv):.4f}")


if __name__ == "__main__":
    main()
