"""The lid-driven cavity against Ghia, Ghia & Shin (1982): the centreline velocity profiles.

The report runs scenes/cavity_re1000.json as it is (Re 1000 on 128 x 128 Q1Q1 cells, Newton
with continuation 100 -> 400 -> 1000); the fast subset runs the same scene at Re 100 on 64 x 64.
The largest deviation from Ghia's 17 + 17 points, in units of the lid speed, must stay within
0.015 at Re 1000 (FEniCS's P1/P1 reaches 0.0105 on its mesh) and 0.02 at Re 100 on 64 x 64 (the
mesh error there, halving with each refinement).
"""
import numpy as np

from ghia1982 import U, V, X, Y
from report_case import CaseResult, Check, plt, read_csv, run_scene, save_figure, scene_text

SCENE = "scenes/cavity_re1000.json"


def run(moreau, work, out, fast):
    re = 100 if fast else 1000
    overrides = ["objects.0.viscosity=0.01", "objects.0.mesh.cells=[64,64]",
                 "objects.0.continuation.viscosity=[0.04]"] if fast else []
    _, wall = run_scene(moreau, SCENE, work / "cavity", overrides)
    vertical = read_csv(work / "cavity" / "line_vertical_centreline.csv")
    horizontal = read_csv(work / "cavity" / "line_horizontal_centreline.csv")
    # Linear interpolation to Ghia's points is exact for Q1 fields along grid lines.
    u = np.interp(Y, vertical["y"], vertical["velocity.x"])
    v = np.interp(X, horizontal["x"], horizontal["velocity.y"])
    du = np.abs(u - U[re])
    dv = np.abs(v - V[re])
    tolerance = 0.02 if fast else 0.015
    why = ("mesh error on 64 x 64" if fast else "FEniCS P1/P1 reaches 0.0105") + "; in units of the lid speed"

    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
    left.plot(vertical["velocity.x"], vertical["y"], label="moreau")
    left.plot(U[re], Y, "o", mfc="none", label="Ghia et al. (1982)")
    left.set(xlabel="u / U (x = 0.5)", ylabel="y / L", title=f"u on the vertical centreline, Re {re}")
    right.plot(horizontal["x"], horizontal["velocity.y"], label="moreau")
    right.plot(X, V[re], "o", mfc="none", label="Ghia et al. (1982)")
    right.set(xlabel="x / L", ylabel="v / U (y = 0.5)", title=f"v on the horizontal centreline, Re {re}")
    for axes in (left, right):
        axes.grid(alpha=0.3)
        axes.legend()
    plot = save_figure(figure, out, f"ghia_re{re}.png")

    return CaseResult(
        title=f"Lid-driven cavity, Re {re}: centreline velocities",
        reference="Ghia, Ghia & Shin, J. Comput. Phys. 48 (1982), tables I and II (129 x 129 grid)",
        scene=scene_text(SCENE, overrides),
        checks=[Check.below("largest |u − u_Ghia| / U", float(du.max()), tolerance, "", why),
                Check.below("largest |v − v_Ghia| / U", float(dv.max()), tolerance, "", why)],
        plots=[plot], wall_s=wall)
