"""A rigid disc sedimenting in a closed channel (Glowinski, Pan, Hesla, Joseph & Périaux 2001),
immersed in the FEM fluid: its settling velocity against the published one.

scenes/sedimenting_disc.json as it is: a disc of diameter 2.5 mm and density 1250 kg/m^3 released
from rest at (1, 4) cm in a closed 2 cm × 6 cm channel of fluid (1000 kg/m^3, 0.01 Pa s), gravity
9.81 m/s^2, midpoint rule, dt 2 ms, the first 0.6 s (the disc slows near the bottom after about
0.65 s). Its velocity is compared with Glowinski et al.'s FEM curve, digitised by a third party
(report/data/, about ±0.5 mm/s): the velocity at 0.5–0.6 s, where the reference has levelled off
at 55.7 mm/s, within 5 % on the finest fluid mesh (5 % covers the spread between published
methods for this case: 55.5–56.0 mm/s in the reference's own curve, 54.9–55.8 mm/s from the
particle Reynolds numbers 17.15–17.45 quoted for Wan & Turek 2006), and it must move toward the
reference as the fluid mesh is refined (32 × 96, 64 × 192 and 128 × 384 cells: 4, 8 and 16 fluid
cells across the disc; the error from the coarsest to the finest must fall). The disc falls on the channel's centreline by symmetry: it must neither drift nor
turn (1e-6 of its diameter, 1e-6 rad/s: round-off). The fast subset runs 32 × 96 cells to 0.3 s
and checks the velocity at 0.3 s against the reference's (54.9 mm/s) within 15 %: a coarse mesh,
where the disc is four fluid cells wide.
"""
import pathlib

import numpy as np

from report_case import Check, case_result, finish_plot, plt, read_csv, run_scene, scene_text

SCENE = "scenes/sedimenting_disc.json"
DATA = pathlib.Path(__file__).resolve().parent.parent / "data" / "glowinski2001_sedimenting_disc_velocity.csv"
DIAMETER = 0.0025


def reference_curve():
    data = np.loadtxt(DATA, delimiter=",", comments="#", skiprows=3)
    order = np.argsort(data[:, 0], kind="stable")
    return data[order, 0], -data[order, 1]  # settling speed, m/s


def run(moreau, work, out, fast):
    meshes = [(32, 96)] if fast else [(32, 96), (64, 192), (128, 384)]
    duration = 0.3 if fast else 0.6
    t_ref, v_ref = reference_curve()
    window = (0.5, 0.6)
    plateau_ref = float(np.mean(v_ref[(t_ref >= window[0] - 0.03) & (t_ref <= window[1] + 0.01)]))
    runs, wall = [], 0.0
    for nx, ny in meshes:
        overrides = [f"objects.water.mesh.cells=[{nx},{ny}]", "settings.output.every=5"]
        _, seconds = run_scene(moreau, SCENE, work / f"disc_{nx}x{ny}", overrides, duration=duration)
        wall += seconds
        probes = read_csv(work / f"disc_{nx}x{ny}" / "probes.csv")
        runs.append(((nx, ny), np.array(probes["time"]), -np.array(probes["velocity.y"]),
                     np.array(probes["centre.x"]), np.array(probes["spin.z"]), overrides))

    checks, notes = [], []
    for (nx, ny), t, v, x, spin, _ in runs:
        drift = float(np.max(np.abs(x - 0.01)))
        checks.append(Check.below(f"drift off the centreline, {nx} × {ny}", drift / DIAMETER, 1e-6, "diameters",
                                  "symmetry: round-off"))
        checks.append(Check.below(f"largest |angular velocity|, {nx} × {ny}", float(np.max(np.abs(spin))), 1e-6, "rad/s",
                                  "symmetry: round-off"))
    if fast:
        (nx, ny), t, v, *_ = runs[0]
        reference = float(np.interp(0.3, t_ref, v_ref))
        checks.append(Check(f"settling speed at 0.3 s, {nx} × {ny}", 1e3 * float(np.interp(0.3, t, v)), 1e3 * reference,
                            150 * reference, "mm/s", "15 %: the disc is four fluid cells wide"))
    else:
        plateaus = []
        for (nx, ny), t, v, *_ in runs:
            inside = (t >= window[0]) & (t <= window[1])
            plateaus.append(float(np.mean(v[inside])))
            notes.append(f"{nx} × {ny}: settling speed {1e3 * plateaus[-1]:.2f} mm/s over 0.5–0.6 s "
                         f"({100 * (plateaus[-1] / plateau_ref - 1):+.1f} %), "
                         f"{1e3 * float(np.interp(0.3, t, v)):.2f} mm/s at 0.3 s.")
        (nx, ny) = runs[-1][0]
        checks.append(Check(f"settling speed over 0.5–0.6 s, {nx} × {ny}", 1e3 * plateaus[-1], 1e3 * plateau_ref,
                            50 * plateau_ref, "mm/s", "5 %: the spread between published methods"))
        errors = [abs(p - plateau_ref) for p in plateaus]
        checks.append(Check.below(f"error at {nx} × {ny} minus at {runs[0][0][0]} × {runs[0][0][1]}",
                                  1e3 * (errors[-1] - errors[0]), 0.0, "mm/s", "falls under refinement"))
    notes.append(f"reference settling speed over 0.5–0.6 s: {1e3 * plateau_ref:.2f} mm/s.")

    figure, axis = plt.subplots(figsize=(6.4, 3.8))
    axis.plot(t_ref, 1e3 * v_ref, "k.", label="Glowinski et al. 2001 (digitised)")
    for (nx, ny), t, v, *_ in runs:
        axis.plot(t, 1e3 * v, "-", lw=1.2, label=f"moreau, {nx} × {ny} fluid cells")
    axis.set(xlabel="t (s)", ylabel="settling speed (mm/s)", title="Disc sedimenting in a closed channel")
    finish_plot(axis)
    return case_result(figure, out, "sedimenting_disc", fast, "A rigid disc sedimenting in a closed channel",
                       "Glowinski, Pan, Hesla, Joseph & Périaux (2001), J. Comput. Phys. 169, 363–426: the FEM settling "
                       "velocity, digitised by a third party from a figure that reproduces it",
                       [scene_text(SCENE, r[5], duration) for r in runs], checks, wall, notes)
