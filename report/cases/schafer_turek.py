"""Schäfer & Turek's benchmark 2D-1: steady flow past a cylinder at Re 20.

scenes/cylinder_re20.json at refinement level N = 8 (15,360 cells; the fast subset: N = 4).
The drag and lift coefficients and the pressure difference across the cylinder against the
reference values of John & Matthies (2001), 5.5795, 0.010618 and 0.11752 Pa, which lie in the
ranges Schäfer & Turek (1996) published. Tolerances at N = 8: drag within the published range's
half width (0.01 = 0.2 %), lift within 5 % and Δp within 1.5 % (the mesh error of Q1Q1 there;
halved at N = 16); at N = 4: 0.2 %, 15 % and 3 %.
"""

from report_case import CaseResult, Check, plt, read_csv, run_scene, save_figure, scene_text

SCENE = "scenes/cylinder_re20.json"
DRAG, LIFT, DP = 5.5795, 0.010618, 0.11752


def run(moreau, work, out, fast):
    level = 4 if fast else 8
    overrides = [f"objects.0.mesh.parameters.N={level}"]
    _, wall = run_scene(moreau, SCENE, work / "cylinder", overrides)
    probes = read_csv(work / "cylinder" / "probes.csv")
    drag, lift, dp = probes["cylinder.coefficient.x"][-1], probes["cylinder.coefficient.y"][-1], probes["dp"][-1]
    lift_tolerance, dp_tolerance = (0.15, 0.03) if fast else (0.05, 0.015)

    figure, axes = plt.subplots(1, 3, figsize=(10, 3.2))
    for ax, name, value, reference, low, high in (
            (axes[0], "drag coefficient", drag, DRAG, 5.57, 5.59),
            (axes[1], "lift coefficient", lift, LIFT, 0.0104, 0.0110),
            (axes[2], "Δp (Pa)", dp, DP, 0.1172, 0.1176)):
        ax.axhspan(low, high, color="tab:green", alpha=0.25, label="Schäfer & Turek range")
        ax.axhline(reference, color="tab:green", label="John & Matthies")
        ax.plot([0], [value], "o", color="tab:blue", label=f"moreau, N = {level}")
        ax.set(title=name, xticks=[])
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    plot = save_figure(figure, out, f"schafer_turek_2d1_n{level}.png")

    return CaseResult(
        title=f"Schäfer–Turek 2D-1 (cylinder, Re 20), mesh level N = {level}",
        reference="Schäfer & Turek (1996) benchmark ranges; reference values of John & Matthies (2001)",
        scene=scene_text(SCENE, overrides),
        checks=[Check("drag coefficient", drag, DRAG, 0.01, "", "half the published range"),
                Check("lift coefficient", lift, LIFT, lift_tolerance * LIFT, "", f"{lift_tolerance:.0%}: mesh error"),
                Check("pressure difference", dp, DP, dp_tolerance * DP, "Pa", f"{dp_tolerance:.1%}: mesh error")],
        plots=[plot], wall_s=wall)
