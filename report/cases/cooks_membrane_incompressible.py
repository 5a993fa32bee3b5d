"""Cook's membrane, nearly incompressible: the mean-dilatation element against volumetric locking.

The membrane of cooks_membrane.py (plane strain, n × n Gmsh transfinite quads, clamped at x = 0)
with Neo-Hookean E = 240.565, nu = 0.4999 (mu = 80.19, lambda = 4.0e5) and a vertical shear of
resultant F = 100 on the edge x = 48, applied in 10 load steps; the vertical displacement of the
corner (48, 60). The displacement element locks (its corner moves less than 60 % of the limit on
a 64 × 64 mesh); the mean-dilatation element ("formulation": "mean_dilatation") converges:
- under refinement n = 8 … 128 (the fast subset: 8, 16, 32) its value rises and the successive
  differences shrink; the limit is extrapolated from the last three values (Richardson, with the
  observed order) and n = 32 must be within 1 % of it;
- at nu = 0.499 it agrees with an independent Q4 F-bar implementation, the regression values of
  OpenGeoSys's Cook's membrane test (ufz/ogs, Tests/Data/LargeDeformation/CooksMembrane, whose
  energy is K/2 (J − 1)² + G/2 (J^(−2/3) tr C − 3): the same near J = 1): within 0.5 % at n = 30
  (F-bar and mean dilatation are different elements, and agree more closely as the mesh is refined).
"""
import json
import math

from .cooks_membrane import mesh, scene
from report_case import CaseResult, Check, plt, read_csv, run_scene, save_figure

E, F, STEPS = 240.565, 100.0, 10
OGS_FBAR_NU_0499 = {4: 6.141, 10: 6.746, 15: 6.824, 20: 6.859, 25: 6.873, 30: 6.891}


def corner(moreau, work, n, nu, formulation):
    msh = work / f"cook_{n}.msh"
    if not msh.exists():
        mesh(msh, n)
    name = f"cook_{n}_{nu}_{formulation}"
    path = work / f"{name}.json"
    path.write_text(json.dumps(scene(msh, E, nu, F, STEPS, formulation, tolerance=1e-10)))
    _, seconds = run_scene(moreau, path, work / name)
    return read_csv(work / name / "probes.csv")["corner.y"][-1], seconds


def run(moreau, work, out, fast):
    sizes = [8, 16, 32] if fast else [8, 16, 32, 64, 128]
    wall = 0.0
    mean, locked = [], []
    for n in sizes:
        value, seconds = corner(moreau, work, n, 0.4999, "mean_dilatation")
        mean.append(value)
        wall += seconds
        if n <= 64:
            value, seconds = corner(moreau, work, n, 0.4999, "displacement")
            locked.append(value)
            wall += seconds
    ogs_sizes = [10, 20, 30]
    ogs = []
    for n in ogs_sizes:
        value, seconds = corner(moreau, work, n, 0.499, "mean_dilatation")
        ogs.append(value)
        wall += seconds

    checks = []
    for (n0, v0), (n1, v1) in zip(zip(sizes, mean), zip(sizes[1:], mean[1:])):
        checks.append(Check.below(f"u(n = {n0}) − u(n = {n1}), nu = 0.4999", v0 - v1, 0.0, "", "rises towards the limit"))
    d1, d2 = mean[-2] - mean[-3], mean[-1] - mean[-2]
    checks.append(Check.below("difference ratio of the last three meshes", d2 / d1, 0.6, "",
                              "differences shrink (observed order > 0.7)"))
    notes = []
    if not fast:
        ratio = d1 / d2
        limit = mean[-1] + d2 / (ratio - 1)
        order = math.log2(ratio)
        checks.append(Check("u at n = 32, nu = 0.4999", mean[2], limit, 0.01 * limit, "",
                            f"1 % of the limit {limit:.4f} extrapolated from n = 32, 64, 128"))
        notes.append(f"Mean dilatation, nu = 0.4999: u = {', '.join(f'{v:.4f}' for v in mean)} at n = "
                     f"{', '.join(map(str, sizes))}; extrapolated limit {limit:.4f} (observed order {order:.2f}). The "
                     f"displacement element: {', '.join(f'{v:.4f}' for v in locked)} at n = "
                     f"{', '.join(map(str, sizes[:len(locked)]))}.")
    checks.append(Check("u at n = 30, nu = 0.499", ogs[-1], OGS_FBAR_NU_0499[30], 0.005 * OGS_FBAR_NU_0499[30], "",
                        "0.5 %: F-bar and mean dilatation are different elements"))
    notes.append(f"nu = 0.499: u = {', '.join(f'{v:.4f}' for v in ogs)} at n = {', '.join(map(str, ogs_sizes))}; "
                 f"OpenGeoSys's Q4 F-bar: {', '.join(str(OGS_FBAR_NU_0499[n]) for n in ogs_sizes)}.")

    figure, axes = plt.subplots(figsize=(6.5, 4))
    axes.plot(sizes, mean, "o-", label="mean dilatation, ν = 0.4999")
    axes.plot(sizes[:len(locked)], locked, "s-", label="displacement element, ν = 0.4999")
    axes.plot(ogs_sizes, ogs, "^-", label="mean dilatation, ν = 0.499")
    axes.plot(list(OGS_FBAR_NU_0499), list(OGS_FBAR_NU_0499.values()), "x:", color="grey",
              label="OpenGeoSys Q4 F-bar, ν = 0.499")
    axes.set(xscale="log", xlabel="cells per side n", ylabel="corner displacement",
             title="Cook's membrane, nearly incompressible, F = 100")
    axes.grid(alpha=0.3)
    axes.legend(fontsize=8)
    plot = save_figure(figure, out, "cooks_membrane_incompressible_fast.png" if fast else
                       "cooks_membrane_incompressible.png")
    return CaseResult(
        title="Cook's membrane, nearly incompressible: mean dilatation" + (" (fast subset)" if fast else ""),
        reference="convergence under refinement; OpenGeoSys's Q4 F-bar regression values (ufz/ogs, "
                  "Tests/Data/LargeDeformation/CooksMembrane) at ν = 0.499",
        scene="the membrane written by report/cases/cooks_membrane_incompressible.py (Gmsh transfinite quads)",
        checks=checks, plots=[plot], wall_s=wall, notes=notes)
