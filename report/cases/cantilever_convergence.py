"""A slender plane-strain cantilever against beam theory, under mesh refinement.

L = 1 m, h = 0.05 m (L/h = 20), E = 1 MPa, ν = 0.3, clamped at x = 0, a shear traction on the
free end giving the Euler–Bernoulli tip deflection δ = P L³/(3 E′ I) = 1e-4 L (E′ = E/(1 − ν²),
I = h³/12; small enough that geometric nonlinearity changes it by ~1e-8). Bilinear quads lock in
bending (parasitic shear, too stiff by ~(1 − ν)/2 (a/b)² for cells of length a and height b), so
the mesh is refined along the beam with 8 cells through the height: the error must fall with
every refinement and be within 2 % at 320 cells along (the fast subset: 80 and 160 cells, within
2 % at 160). Timoshenko's shear term P L/(κ G h), κ = 5/6, adds 0.2 % to the reference.
"""
import json


from report_case import CaseResult, Check, plt, read_csv, run_scene, save_figure

L, H, E, NU = 1.0, 0.05, 1e6, 0.3
E_PLANE = E / (1 - NU * NU)
INERTIA = H ** 3 / 12
DEFLECTION = 1e-4 * L
LOAD = 3 * E_PLANE * INERTIA * DEFLECTION / L ** 3  # N per metre of thickness
TIMOSHENKO = DEFLECTION + LOAD * L / (5 / 6 * E / (2 * (1 + NU)) * H)


def scene(cells_along):
    return {
        "name": f"cantilever_{cells_along}",
        "settings": {"solver": "fem", "integrator": "static", "dt": 1, "duration": 1, "gravity": [0, 0, 0],
                     "newton": {"tolerance": 1e-12}},
        "objects": [{"name": "beam", "kind": "solid",
                     "mesh": {"type": "rectangle", "min": [0, 0], "max": [L, H], "cells": [cells_along, 8],
                              "element": "quad4"},
                     "material": {"model": "neo_hookean", "youngs_modulus": E, "poisson_ratio": NU, "density": 1000},
                     "loads": [{"type": "traction", "where": {"boundary": "right"}, "value": [0, LOAD / H]}],
                     "dirichlet": [{"where": {"boundary": "left"}, "value": [0, 0]}]}],
        "probes": [{"name": "tip", "type": "point", "object": "beam", "nearest": [L, H / 2],
                    "quantity": "displacement"}],
    }


def run(moreau, work, out, fast):
    meshes = [80, 160] if fast else [80, 160, 320, 640]
    checked = meshes[-1] if fast else 320
    errors, wall = [], 0.0
    for n in meshes:
        path = work / f"cantilever_{n}.json"
        path.write_text(json.dumps(scene(n)))
        _, seconds = run_scene(moreau, path, work / f"cantilever_{n}")
        wall += seconds
        tip = read_csv(work / f"cantilever_{n}" / "probes.csv")["tip.y"][-1]
        errors.append(tip / DEFLECTION - 1)

    figure, axes = plt.subplots(figsize=(6.5, 4))
    axes.loglog(meshes, [abs(e) for e in errors], "o-", label="moreau, quad4, 8 cells through the height")
    axes.axhline(abs(TIMOSHENKO / DEFLECTION - 1), color="grey", ls=":", label="Timoshenko's shear correction")
    axes.axhline(0.02, color="tab:red", ls="--", label="2 % criterion")
    axes.set(xlabel="cells along the beam", ylabel="|δ / δ_EB − 1|", title="cantilever tip deflection")
    axes.grid(alpha=0.3, which="both")
    axes.legend(fontsize=8)
    plot = save_figure(figure, out, "cantilever_convergence.png")

    checks = [Check.below(f"|δ/δ_EB − 1|, {checked} cells along", abs(errors[meshes.index(checked)]), 0.02, "",
                          "bilinear locking on this mesh")]
    for (n0, e0), (n1, e1) in zip(zip(meshes, errors), zip(meshes[1:], errors[1:])):
        checks.append(Check.below(f"error ratio, {n1} against {n0} cells", abs(e1) / abs(e0), 1.0, "",
                                  "refinement reduces the error"))
    return CaseResult(
        title="Slender cantilever: tip deflection under refinement",
        reference="Euler–Bernoulli δ = P L³/(3 E′ I) (plane strain); Timoshenko's shear term shown",
        scene="a 1 × 0.05 m quad4 cantilever written by report/cases/cantilever_convergence.py",
        checks=checks, plots=[plot], wall_s=wall)
