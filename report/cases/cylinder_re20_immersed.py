"""Schäfer & Turek's benchmark 2D-1 (steady flow past a cylinder at Re 20) with the cylinder
immersed: a driven rigid body held still in a channel mesh that does not fit it.

scenes/cylinder_re20_immersed.json: the channel meshed by scenes/meshes/immersed_cylinder_channel.geo
with N cells per cylinder diameter (square cells around the cylinder and its near wake), the
cylinder an O-grid disc (scenes/meshes/disc.geo) at least as fine, backward Euler steps of 0.5 s
to t = 10 s (the drag has settled to 1e-5). The fluid's force on the body is the sum of the
coupling's forces at its nodes (docs/fem-scenes.md, "Rigid bodies in a fluid").

Reference: the drag coefficient 5.5795 (John & Matthies 2001, inside Schäfer & Turek's range
5.57–5.59). The immersed boundary is diffuse over about a fluid cell, so the body acts slightly
larger than it is and the drag converges from above at about first order in h. The checks: the
error falls at each refinement, and on the finest mesh (N = 48) the drag lies within 5 %, the
tolerance set for immersed drag. The lift coefficient (0.0106, 0.2 % of the drag: the cylinder
sits 5 mm below the channel's axis) is below what a diffuse boundary resolves on these meshes; it
is reported, not checked. The fast subset runs N = 16 to t = 5 s and checks the drag within 10 %
(the diffuse boundary's error at 16 cells per diameter, +6.5 % when measured).
"""
import math

from report_case import Check, case_result, finish_plot, plt, read_csv, run_scene, scene_text

SCENE = "scenes/cylinder_re20_immersed.json"
DRAG, LIFT = 5.5795, 0.010618


def run(moreau, work, out, fast):
    levels = [16] if fast else [16, 32, 48]
    duration = 5 if fast else None
    results, wall, scenes = [], 0.0, []
    for n in levels:
        overrides = [f"objects.fluid.mesh.parameters.N={n}", f"objects.cylinder.mesh.parameters.n={n}",
                     f"objects.cylinder.mesh.parameters.layers={n // 2}"]
        _, seconds = run_scene(moreau, SCENE, work / f"cylinder_n{n}", overrides, duration=duration)
        wall += seconds
        probes = read_csv(work / f"cylinder_n{n}" / "probes.csv")
        results.append((n, probes["cylinder.coefficient.x"][-1], probes["cylinder.coefficient.y"][-1], seconds))
        scenes.append(scene_text(SCENE, overrides, duration))

    notes = [f"N = {n}: drag {drag:.4f} ({100 * (drag / DRAG - 1):+.2f} %), lift {lift:.5f}, {seconds:.0f} s"
             for n, drag, lift, seconds in results]
    if fast:
        n, drag, _, _ = results[0]
        checks = [Check(f"drag coefficient, N = {n}", drag, DRAG, 0.10 * DRAG, "",
                        "10 %: the diffuse boundary's error at 16 cells per diameter")]
    else:
        errors = [abs(drag - DRAG) for _, drag, _, _ in results]
        for (n1, d1, *_), (n2, d2, *_) in zip(results, results[1:]):
            notes.append(f"N = {n1} to {n2}: the error falls as h^{math.log(abs(d1 - DRAG) / abs(d2 - DRAG)) / math.log(n2 / n1):.2f}")
        n, drag, _, _ = results[-1]
        checks = [Check.below(f"error at N = {results[1][0]} minus at N = {results[0][0]}", errors[1] - errors[0], 0.0, "",
                              "falls under refinement"),
                  Check.below(f"error at N = {results[2][0]} minus at N = {results[1][0]}", errors[2] - errors[1], 0.0, "",
                              "falls under refinement"),
                  Check(f"drag coefficient, N = {n}", drag, DRAG, 0.05 * DRAG, "",
                        "5 %: the diffuse boundary's first-order error, the tolerance set for immersed drag")]

    figure, axis = plt.subplots(figsize=(6.0, 3.6))
    axis.axhspan(5.57, 5.59, color="tab:green", alpha=0.25, label="Schäfer & Turek range")
    axis.axhline(DRAG, color="tab:green", label="John & Matthies")
    axis.plot([1 / n for n, *_ in results], [d for _, d, *_ in results], "o-", label="moreau, immersed cylinder")
    axis.set(xlabel="h / D", ylabel="drag coefficient", title="Immersed cylinder, Re 20", xlim=(0, None))
    finish_plot(axis)
    return case_result(figure, out, "cylinder_re20_immersed", fast,
                       "Schäfer–Turek 2D-1 with the cylinder immersed (a driven rigid body held still)",
                       "Schäfer & Turek (1996) benchmark range; reference drag of John & Matthies (2001)", scenes, checks,
                       wall, notes)
