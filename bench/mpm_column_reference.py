#!/usr/bin/env python3
"""A material point method reference for the XPBI sand column (bench/xpbi_column_collapse.py).

The same material as scenes/sand_column_xpbi.json (Drucker-Prager sand of friction angle phi,
StVK-Hencky elasticity with E = 0.1 MPa, nu = 0.3, 1600 kg/m^3, the return map of Klar et al.
2016 in the Hencky strain, cohesionless: the cone's tip in tension) discretized by a different
method: MLS-MPM (Hu et al. 2018, "A moving least squares material point method with displacement
discontinuity and two-way rigid body coupling", SIGGRAPH) with APIC transfers and quadratic
B-splines on a grid of spacing dx, 8 particles per cell. One quarter of the column is simulated
(the planes x = 0 and z = 0 are free-slip symmetry walls); the ground y = 0 has Coulomb friction
mu against the grid's velocity. If XPBI and MPM agree on the runout of the same constitutive model,
the difference from Lube et al. (2004) is the model's, not the particles'.

Per step of length dt (explicit):
  P2G:  m_i = sum_p w_ip m_p;  (m v)_i = sum_p w_ip (m_p v_p + (m_p C_p - dt V_p^0 (4/dx^2) tau_p)(x_i - x_p))
        with tau_p the Kirchhoff stress of F_p (the MLS-MPM force: -V^0 P F^T grad w = ...);
  grid: v_i = (m v)_i / m_i + dt g, the walls' conditions;
  G2P:  v_p = sum_i w_ip v_i,  C_p = (4/dx^2) sum_i w_ip v_i (x_i - x_p)^T,  x_p += dt v_p,
        F_p = Z((I + dt C_p) F_p), Z the Drucker-Prager return map.
The runout is counted as the bench's probe counts it: the horizontal distance from the axis
within which 99 % of the particles lie, each by its centre plus half its spacing.

Needs numpy (Debian's python3-numpy, which scripts/install-deps.sh installs). A 5 mm grid takes
a few minutes a column on one core; 2.5 mm about half an hour.

Usage: bench/mpm_column_reference.py [--aspect A ...] [--dx DX] [--phi DEG] [--mu MU] [--duration T]
"""
import argparse
import math
import time

import numpy as np

from xpbi_column_collapse import R_I, lube_runout

RHO, E, NU, G = 1600.0, 1e5, 0.3, -9.81
MU_LAME, LAMBDA = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
NODE_OFFSETS = [(i, j, l) for i in range(3) for j in range(3) for l in range(3)]  # a particle's 27 nodes


def drucker_prager(F, alpha):
    """Klar et al. 2016's return in the Hencky strain; returns the returned F (n x 3 x 3)."""
    U, sig, Vt = np.linalg.svd(F)
    eps = np.log(np.maximum(sig, 0.05))
    tr = eps.sum(axis=1)
    dev = eps - tr[:, None] / 3
    norm = np.linalg.norm(dev, axis=1)
    dgamma = norm + alpha * (3 * LAMBDA + 2 * MU_LAME) / (2 * MU_LAME) * tr
    out = eps.copy()
    tip = tr > 0
    out[tip] = 0
    flow = (~tip) & (dgamma > 0) & (norm > 0)
    out[flow] = eps[flow] - (dgamma[flow] / norm[flow])[:, None] * dev[flow]
    sig = np.exp(out)
    return U @ (sig[:, :, None] * Vt), U, out


def kirchhoff(U, eps):
    """tau = U diag(2 mu eps + lambda tr eps) U^T."""
    t = 2 * MU_LAME * eps + LAMBDA * eps.sum(axis=1)[:, None]
    return U @ (t[:, :, None] * np.transpose(U, (0, 2, 1)))


def runout(x, spacing, fraction=0.99):
    reach = np.hypot(x[:, 0], x[:, 2]) + spacing / 2
    return np.quantile(reach, fraction, method="lower")


def simulate(a, dx, phi_deg, mu, duration, report=True):
    alpha = math.sqrt(2 / 3) * 2 * math.sin(math.radians(phi_deg)) / (3 - math.sin(math.radians(phi_deg)))
    h = a * R_I
    s = dx / 2  # particle spacing: 2 per cell and axis
    g1 = np.arange(s / 2, R_I + s, s)
    gy = np.arange(s / 2, h, s)
    X, Y, Z = np.meshgrid(g1, gy, g1, indexing="ij")
    x = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    x = x[np.hypot(x[:, 0], x[:, 2]) < R_I]
    n = len(x)
    vol = s ** 3
    m = RHO * vol
    v = np.zeros_like(x)
    C = np.zeros((n, 3, 3))
    F = np.tile(np.eye(3), (n, 1, 1))
    # Grid: nodes i dx for i in [-2, nx), y from -2 cells (the ground at y = 0).
    reach = R_I * (1 + 1.4 * a + 1.2) + 4 * dx
    nx, ny = int(reach / dx) + 4, int((h + 4 * dx) / dx) + 4
    origin = np.array([-2 * dx, -2 * dx, -2 * dx])
    shape = (nx, ny, nx)
    node_x = origin[None, :] + dx * np.stack(np.unravel_index(np.arange(nx * ny * nx), shape), axis=1)
    r0 = runout(x, s)
    c = math.sqrt((LAMBDA + 2 * MU_LAME) / RHO)
    dt = 0.25 * dx / c
    steps = int(round(duration / dt))
    start = time.time()
    for k in range(steps):
        Fr, U, eps = drucker_prager(F, alpha)
        F = Fr
        tau = kirchhoff(U, eps)
        affine = m * C - (dt * vol * 4 / dx ** 2) * tau  # n x 3 x 3
        rel = (x - origin) / dx
        base = np.floor(rel - 0.5).astype(np.int64)
        fx = rel - base
        w = [0.5 * (1.5 - fx) ** 2, 0.75 - (fx - 1) ** 2, 0.5 * (fx - 0.5) ** 2]
        grid_m = np.zeros(nx * ny * nx)
        grid_p = np.zeros((nx * ny * nx, 3))
        cache = []
        for (i, j, l) in NODE_OFFSETS:
            weight = w[i][:, 0] * w[j][:, 1] * w[l][:, 2]
            idx = np.ravel_multi_index((base[:, 0] + i, base[:, 1] + j, base[:, 2] + l), shape)
            dpos = (np.array([i, j, l])[None, :] - fx) * dx
            cache.append((weight, idx, dpos))
            grid_m += np.bincount(idx, weight * m, minlength=grid_m.size)
            mom = weight[:, None] * (m * v + np.einsum("nab,nb->na", affine, dpos))
            for d in range(3):
                grid_p[:, d] += np.bincount(idx, mom[:, d], minlength=grid_m.size)
        has = grid_m > 0
        gv = np.zeros_like(grid_p)
        gv[has] = grid_p[has] / grid_m[has, None]
        gv[has, 1] += dt * G
        # Symmetry planes x = 0 and z = 0: the normal velocity, odd across them, is zero there
        # (and on the ghost nodes behind them, which the particles within 1.5 dx reach).
        gv[node_x[:, 0] < 0.5 * dx, 0] = 0
        gv[node_x[:, 2] < 0.5 * dx, 2] = 0
        # The ground: no penetration, Coulomb friction mu on what the normal stop removes. As in
        # any MPM, the nodes' friction reaches the particles within 1.5 dx of the ground.
        ground = (node_x[:, 1] < 0.5 * dx) & (gv[:, 1] < 0)
        vn = -gv[ground, 1]
        vt = gv[ground][:, [0, 2]]
        speed = np.linalg.norm(vt, axis=1)
        scale = np.where(speed > 0, np.maximum(0, 1 - mu * vn / np.maximum(speed, 1e-30)), 0)
        gv[np.flatnonzero(ground)[:, None], [0, 2]] = vt * scale[:, None]
        gv[ground, 1] = 0
        v = np.zeros_like(x)
        B = np.zeros((n, 3, 3))
        for weight, idx, dpos in cache:
            vi = gv[idx]
            v += weight[:, None] * vi
            B += weight[:, None, None] * vi[:, :, None] * dpos[:, None, :]
        C = (4 / dx ** 2) * B
        x = x + dt * v
        F = (np.eye(3)[None] + dt * C) @ F
        if report and (k % max(1, steps // 10) == 0 or k == steps - 1):
            kinetic = 0.5 * m * (v ** 2).sum() * 4
            print(f"  t = {k * dt:.3f} s: runout {(runout(x, s) - r0) / r0:.3f}, kinetic {kinetic:.2e} J, "
                  f"top {x[:, 1].max() + s / 2:.4f} m, {time.time() - start:.0f} s", flush=True)
    return (runout(x, s) - r0) / r0, (x[:, 1].max() + s / 2) / r0, n * 4


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--aspect", type=float, nargs="+", default=[0.5, 1, 2])
    p.add_argument("--dx", type=float, default=0.005)
    p.add_argument("--phi", type=float, default=35)
    p.add_argument("--mu", type=float, default=0.6)
    p.add_argument("--duration", type=float, default=0.6)
    args = p.parse_args()
    print(f"MLS-MPM, dx = {args.dx} m (particles {args.dx / 2} m apart), phi = {args.phi} deg, ground mu = {args.mu}")
    for a in args.aspect:
        spread, height, count = simulate(a, args.dx, args.phi, args.mu, args.duration)
        law = lube_runout(a)
        print(f"a = {a}: runout {spread:.3f} against Lube {law:.3f} ({100 * (spread / law - 1):+.1f} %), "
              f"H_inf/r_i {height:.3f}, {count} particles in the whole column", flush=True)


if __name__ == "__main__":
    main()
