"""Cook's membrane in its linear limit against published fine-mesh solutions, under refinement.

The trapezoid (0, 0), (48, 44), (48, 60), (0, 44) in n × n bilinear quads (a Gmsh transfinite
mesh, written by this case), clamped at x = 0, with a uniform vertical shear traction of
resultant F on the edge x = 48. Plane strain, Neo-Hookean, ν = 1/3, F/E = 1e-6 (geometric
nonlinearity changes the result by ~1e-6). The vertical displacement of the corner (48, 60) in
units of F/E is published as 22.59 (CalculiX), 22.54 (Code_Aster) and 22.60 (Elmer) on very fine
quadratic meshes (CoFEA's results, quoted in the solids4foam Cook's membrane tutorial). Bilinear
quads approach it from below (shear locking of the distorted cells): the value must rise with
each refinement and be within 1 % of 22.59 at n = 64 (the fast subset: n = 8 and 16, within 5 %
at 16).
"""
import json
import subprocess


from report_case import CaseResult, Check, plt, read_csv, run_scene, save_figure

PUBLISHED = {"CalculiX": 22.59, "Code_Aster": 22.54, "Elmer": 22.60}
REFERENCE = PUBLISHED["CalculiX"]
E, NU, F = 1e6, 1 / 3, 1.0


def mesh(path, n):
    """Writes the n × n transfinite quad mesh of the membrane (Gmsh MSH 4.1) to `path`."""
    geo = path.with_suffix(".geo")
    geo.write_text(f"""Point(1) = {{0, 0, 0}}; Point(2) = {{48, 44, 0}}; Point(3) = {{48, 60, 0}}; Point(4) = {{0, 44, 0}};
Line(1) = {{1, 2}}; Line(2) = {{2, 3}}; Line(3) = {{3, 4}}; Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}}; Plane Surface(1) = {{1}};
Transfinite Curve{{1, 2, 3, 4}} = {n + 1}; Transfinite Surface{{1}}; Recombine Surface{{1}};
Physical Curve("left") = {{4}}; Physical Curve("right") = {{2}}; Physical Surface("plate") = {{1}};
""")
    subprocess.run(["gmsh", "-2", str(geo), "-format", "msh41", "-o", str(path), "-v", "0"], check=True)


def scene(mesh_file, youngs_modulus=E, poisson_ratio=NU, force=F, load_steps=1, formulation="displacement",
          tolerance=1e-12):
    """The membrane under a vertical shear of resultant `force` on its right edge, applied in
    `load_steps` equal static steps."""
    traction = force / 16 if load_steps == 1 else f"{force / 16} * t"
    return {
        "name": "cooks_membrane",
        "settings": {"solver": "fem", "integrator": "static", "dt": 1 / load_steps, "duration": 1,
                     "gravity": [0, 0, 0], "newton": {"tolerance": tolerance}},
        "objects": [{"name": "plate", "kind": "solid", "mesh": {"type": "msh", "file": str(mesh_file)},
                     "formulation": formulation,
                     "material": {"model": "neo_hookean", "youngs_modulus": youngs_modulus,
                                  "poisson_ratio": poisson_ratio, "density": 1},
                     "loads": [{"type": "traction", "where": {"boundary": "right"}, "value": [0, traction]}],
                     "dirichlet": [{"where": {"boundary": "left"}, "value": [0, 0]}]}],
        "probes": [{"name": "corner", "type": "point", "object": "plate", "nearest": [48, 60],
                    "quantity": "displacement"}],
    }


def run(moreau, work, out, fast):
    sizes = [8, 16] if fast else [8, 16, 32, 64]
    values, wall = [], 0.0
    for n in sizes:
        msh = work / f"cook_{n}.msh"
        mesh(msh, n)
        path = work / f"cook_{n}.json"
        path.write_text(json.dumps(scene(msh)))
        _, seconds = run_scene(moreau, path, work / f"cook_{n}")
        wall += seconds
        values.append(read_csv(work / f"cook_{n}" / "probes.csv")["corner.y"][-1] * E / F)

    figure, axes = plt.subplots(figsize=(6.5, 4))
    axes.plot(sizes, values, "o-", label="moreau, quad4")
    for (name, value), style in zip(PUBLISHED.items(), (":", "--", "-.")):
        axes.axhline(value, color="grey", ls=style, lw=1, label=f"{name} (fine quadratic mesh)")
    axes.set(xscale="log", xlabel="cells per side n", ylabel="corner displacement u E / F",
             title="Cook's membrane, linear limit")
    axes.set_xticks(sizes, [str(n) for n in sizes])
    axes.grid(alpha=0.3)
    axes.legend(fontsize=8)
    plot = save_figure(figure, out, "cooks_membrane.png")

    tolerance = 0.05 if fast else 0.01
    checks = [Check(f"u E / F at n = {sizes[-1]}", values[-1], REFERENCE, tolerance * REFERENCE, "",
                    f"{tolerance:.0%}: bilinear locking at this n")]
    for (n0, v0), (n1, v1) in zip(zip(sizes, values), zip(sizes[1:], values[1:])):
        checks.append(Check.below(f"u(n = {n0}) − u(n = {n1})", v0 - v1, 0.0, "", "rises towards the limit"))
    return CaseResult(
        title="Cook's membrane (linear limit) under refinement",
        reference="CalculiX 22.59, Code_Aster 22.54, Elmer 22.60 (CoFEA, quoted in the solids4foam tutorial)",
        scene="the n × n membrane written by report/cases/cooks_membrane.py (Gmsh transfinite quads)",
        checks=checks, plots=[plot], wall_s=wall)
