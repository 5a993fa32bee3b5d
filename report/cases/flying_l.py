"""Simo & Tarnow's free-flying L (1992): the energy–momentum scheme conserves energy and angular
momentum exactly.

scenes/fem_flying_l.json (a plane-strain Neo-Hookean L pushed for 0.5 s, then free for 19.5 s at
dt = 0.05 s, ten times the cells' wave-crossing time); the fast subset runs 4 s. After the push
the total energy and the angular momentum must stay at their values to 1e-10 relative: the scheme
conserves both exactly at each step's solution, and Newton stops at a residual of 1e-12.
The plot also shows the implicit midpoint rule from the same start, whose energy drifts.
"""
import numpy as np

from report_case import CaseResult, Check, plt, read_csv, run_scene, save_figure, scene_text

SCENE = "scenes/fem_flying_l.json"
PUSH_END = 0.5


def run(moreau, work, out, fast):
    duration = 4.0 if fast else None
    _, wall = run_scene(moreau, SCENE, work / "flying_l", duration=duration)
    em = read_csv(work / "flying_l" / "probes.csv")
    run_scene(moreau, SCENE, work / "flying_l_midpoint", ["settings.integrator=midpoint"], duration=duration)
    midpoint = read_csv(work / "flying_l_midpoint" / "probes.csv")

    t = np.array(em["time"])
    free = t > PUSH_END + 1e-9
    energy, momentum = np.array(em["E"])[free], np.array(em["L.z"])[free]
    energy_drift = float(np.max(np.abs(energy - energy[0])) / energy[0])
    momentum_drift = float(np.max(np.abs(momentum - momentum[0])) / abs(momentum[0]))

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 3.8))
    left.plot(em["time"], em["E"], label="energy–momentum")
    left.plot(midpoint["time"], midpoint["E"], "--", label="implicit midpoint")
    left.set(xlabel="time (s)", ylabel="total energy (J)", title="energy")
    right.plot(em["time"], em["L.z"], label="energy–momentum")
    right.plot(midpoint["time"], midpoint["L.z"], "--", label="implicit midpoint")
    right.set(xlabel="time (s)", ylabel="angular momentum (kg m²/s)", title="angular momentum")
    for axes in (left, right):
        axes.axvspan(0, PUSH_END, color="grey", alpha=0.15)
        axes.grid(alpha=0.3)
        axes.legend()
    plot = save_figure(figure, out, "flying_l.png")

    why = "exact at each step's solution; Newton's residual 1e-12"
    return CaseResult(
        title="Free-flying L: energy and angular momentum after the push",
        reference="Simo & Tarnow, ZAMP 43 (1992): conserved exactly by the energy–momentum scheme",
        scene=scene_text(SCENE, duration=duration),
        checks=[Check.below("energy drift, relative", energy_drift, 1e-10, "", why),
                Check.below("angular momentum drift, relative", momentum_drift, 1e-10, "", why)],
        plots=[plot], wall_s=wall)
