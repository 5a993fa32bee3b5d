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
import sys

Y = [1.0000, 0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5000,
     0.4531, 0.2813, 0.1719, 0.1016, 0.0703, 0.0625, 0.0547, 0.0000]
X = [1.0000, 0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5000,
     0.2344, 0.2266, 0.1563, 0.0938, 0.0781, 0.0703, 0.0625, 0.0000]
U = {100: [1.00000, 0.84123, 0.78871, 0.73722, 0.68717, 0.23151, 0.00332, -0.13641, -0.20581,
           -0.21090, -0.15662, -0.10150, -0.06434, -0.04775, -0.04192, -0.03717, 0.00000],
     1000: [1.00000, 0.65928, 0.57492, 0.51117, 0.46604, 0.33304, 0.18719, 0.05702, -0.06080,
            -0.10648, -0.27805, -0.38289, -0.29730, -0.22220, -0.20196, -0.18109, 0.00000]}
V = {100: [0.00000, -0.05906, -0.07391, -0.08864, -0.10313, -0.16914, -0.22445, -0.24533, 0.05454,
           0.17527, 0.17507, 0.16077, 0.12317, 0.10890, 0.10091, 0.09233, 0.00000],
     1000: [0.00000, -0.21388, -0.27669, -0.33714, -0.39188, -0.51550, -0.42665, -0.31966, 0.02526,
            0.32235, 0.33075, 0.37095, 0.32627, 0.30353, 0.29012, 0.27485, 0.00000]}


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
