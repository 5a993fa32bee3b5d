#!/usr/bin/env python3
"""How the flow of Turek & Hron's FSI1 loads its bar when the bar is bent, body-fitted and immersed.

FSI1's deflection (0.8209 mm at A) is set by a strong feedback: the bent bar tilts against the flow
and the lift falls from CFD1's 1.119 N/m to 0.764. This script takes the feedback apart. For each
tip rise D it holds the bar rigid in the shape of a cantilever under a uniform load (rising by D at
its tip) and computes the steady flow (CFD1's inflow, Re = 20) in two ways:

- body-fitted: cylinder and bent bar cut out of the fluid mesh
  (bench/scenes/meshes/turek_hron_channel_bar_cut.geo), the load on the bar from boundary_force
  probes on 14 segments of its top and bottom and on its end;
- immersed: the bent bar (bench/scenes/meshes/turek_hron_bar_bent.geo, 70B x 4B cells) immersed in
  scenes/meshes/turek_hron_channel_refined.geo and made 1000 times stiffer than FSI1's bar, so that
  the flow sees the bent shape and the bar's small extra deflection under the load is linear in it
  (the bar's force probe leaves out its clamped nodes: what the fluid exerts there counts with the
  cylinder's reaction).

Both report the deflection g(D) that load would give FSI1's bar at A: immersed, A's displacement
times 1000; body-fitted, the Euler-Bernoulli cantilever's tip deflection under the segments'
forces (and the moments of their shear about the bar's axis), with the bending stiffness EI
calibrated on the same bar mesh alone under a uniform load (a static solve). FSI1's deflection is
the fixed point g(D) = D. Measured results are in docs/validation.md.

Usage: bench/turek_hron_fsi1_bending.py --moreau build/moreau --work DIR [--level N] [--b B ...]
           [--deflections MM ...] [--skip-immersed] [--skip-body-fitted]
One body-fitted solve takes about a minute on one core (N = 8, B = 2), an immersed one 15-20 (B = 2)
to 45 minutes (B = 3).
"""
import argparse
import math
import pathlib

from cantilever_loads import cantilever_deflection, growing_run_probes, run_scene, segment_forces

ROOT = pathlib.Path(__file__).resolve().parent.parent
MESHES = ROOT / "bench" / "scenes" / "meshes"
SEGMENTS = 14
X0 = 0.2 + math.sqrt(0.05 ** 2 - 0.01 ** 2)  # where the bar meets the cylinder
LENGTH = 0.6 - X0
INFLOW = "(t < 2 ? 0.5 * (1 - cos(pi * t / 2)) : 1) * 1.5 * 0.2 * 4 * y * (0.41 - y) / 0.41^2"
BAR = {"model": "st_venant_kirchhoff", "lame_lambda": 2e6, "lame_mu": 0.5e6, "density": 1000}
STIFFER = 1000


def fluid(mesh_file, parameters, walls):
    return {"name": "fluid", "kind": "fluid", "density": 1000, "viscosity": 1.0,
            "mesh": {"type": "geo", "file": str(mesh_file), "parameters": parameters},
            "boundaries": [{"where": {"tag": walls}, "type": "no_slip"},
                           {"where": {"tag": "inlet"}, "velocity": [INFLOW, "0"]},
                           {"where": {"tag": "outlet"}, "type": "outflow"}]}


def settings(dt, tolerance, **extra):
    return {"solver": "fem", "integrator": "backward_euler", "dt": dt, "duration": 8, "gravity": [0, 0, 0],
            "newton": {"tolerance": tolerance, "max_iterations": 40}, **extra}


def bar_alone_stiffness(moreau, work, b):
    """EI of the 70B x 4B bar mesh: its tip deflection w under a uniform load q is q L^4 / (8 EI)."""
    load = 20.0 * 0.02  # 20 N/m^3 over the bar's 0.02 m: N/m
    scene = {"name": f"bar_alone_b{b}", "settings": {"solver": "fem", "integrator": "static", "dt": 1, "duration": 1,
                                                     "gravity": [0, -10, 0], "newton": {"tolerance": 1e-10}},
             "objects": [{"name": "bar", "kind": "solid", "material": dict(BAR, density=2),
                          "mesh": {"type": "geo", "file": str(MESHES / "turek_hron_bar_bent.geo"),
                                   "parameters": {"NX": 70 * b, "NY": 4 * b, "D": 0}},
                          "dirichlet": [{"where": {"boundary": "clamp"}, "value": [0, 0]}]}],
             "probes": [{"name": "A", "type": "point", "object": "bar", "nearest": [0.6, 0.2], "quantity": "displacement"}]}
    r = run_scene(moreau, scene, work / f"bar_alone_b{b}")
    w = -float(r["A.y"])  # a solid alone names a displacement probe's columns without the quantity
    return load * LENGTH ** 4 / (8 * w)


def body_fitted(moreau, work, level, b, d_mm, ei):
    top = [f"top_{k}" for k in range(1, SEGMENTS + 1)]
    bottom = [f"bottom_{k}" for k in range(1, SEGMENTS + 1)]
    walls = ["walls", "cylinder", "end"] + top + bottom
    probes = [{"name": "cylinder", "type": "boundary_force", "where": {"tag": "cylinder"}},
              {"name": "obstacle", "type": "boundary_force", "where": {"tag": ["cylinder", "end"] + top + bottom}},
              {"name": "bar", "type": "boundary_force", "where": {"tag": ["end"] + top + bottom}}]
    probes += growing_run_probes({"top": top, "bottom": bottom})
    scene = {"name": "cfd1_body_fitted", "settings": settings(0.5, 1e-10, output={"every": 16, "formats": []}),
             "objects": [fluid(MESHES / "turek_hron_channel_bar_cut.geo",
                               {"N": level, "B": b, "K": SEGMENTS, "D": d_mm * 1e-3}, walls)],
             "probes": probes}
    r = run_scene(moreau, scene, work / f"body_fitted_n{level}_b{b}_d{d_mm}")
    force = lambda name, c: float(r[f"{name}.force.{c}"])  # noqa: E731
    end_y = force("bar", "y") - force(f"top_upto_{SEGMENTS}", "y") - force(f"bottom_upto_{SEGMENTS}", "y")
    # Each segment's force at its middle, a from the clamp, on its face 0.01 m below or above the axis.
    loads = []
    for k in range(1, SEGMENTS + 1):
        for side, y in (("bottom", -0.01), ("top", 0.01)):
            fx, fy = segment_forces(r, side, k)
            loads.append((LENGTH * (k - 0.5) / SEGMENTS, y, fy, fx))
    deflection = cantilever_deflection(LENGTH, ei, loads, end_y)
    # The bar's share: the obstacle's less the cylinder's (the two corners where they meet count
    # with the cylinder).
    return {"drag": force("obstacle", "x"), "lift": force("obstacle", "y"),
            "bar_drag": force("obstacle", "x") - force("cylinder", "x"),
            "bar_lift": force("obstacle", "y") - force("cylinder", "y"), "g_mm": deflection * 1e3}


def immersed(moreau, work, level, b, d_mm, bar_b=None):
    bar_b = bar_b or b
    scene = {"name": "cfd1_immersed_bent", "settings": settings(0.1, 1e-8, output={"every": 80, "formats": []}),
             "objects": [fluid(ROOT / "scenes" / "meshes" / "turek_hron_channel_refined.geo", {"N": level, "B": b},
                               ["walls", "cylinder"]),
                         {"name": "bar", "kind": "solid",
                          "material": dict(BAR, lame_lambda=STIFFER * BAR["lame_lambda"], lame_mu=STIFFER * BAR["lame_mu"]),
                          "mesh": {"type": "geo", "file": str(MESHES / "turek_hron_bar_bent.geo"),
                                   "parameters": {"NX": 70 * bar_b, "NY": 4 * bar_b, "D": d_mm * 1e-3}},
                          "dirichlet": [{"where": {"boundary": "clamp"}, "value": [0, 0]}]}],
             "probes": [{"name": "A", "type": "point", "object": "bar", "nearest": [0.6, 0.2], "quantity": "displacement"},
                        {"name": "cylinder", "type": "boundary_force", "where": {"tag": "cylinder"}},
                        {"name": "bar", "type": "force", "object": "bar"}]}
    bar = "" if bar_b == b else f"_bar{bar_b}"
    r = run_scene(moreau, scene, work / f"immersed_n{level}_b{b}{bar}_d{d_mm}")
    return {"drag": float(r["cylinder.force.x"]) + float(r["bar.x"]), "lift": float(r["cylinder.force.y"]) + float(r["bar.y"]),
            "bar_drag": float(r["bar.x"]), "bar_lift": float(r["bar.y"]), "g_mm": STIFFER * float(r["A.displacement.y"]) * 1e3}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moreau", default=str(ROOT / "build" / "moreau"))
    parser.add_argument("--work", required=True, type=pathlib.Path)
    parser.add_argument("--level", type=int, default=8, help="N: the channel's cells are 0.05/N m")
    parser.add_argument("--b", type=int, nargs="+", default=[2], help="B: the bar zone's cells are 0.05/(N B) m")
    parser.add_argument("--bar-b", type=int, help="the immersed bar's cells 70 b x 4 b (default: B's)")
    parser.add_argument("--deflections", type=float, nargs="+", default=[0, 0.82], help="tip rises D in mm")
    parser.add_argument("--skip-immersed", action="store_true")
    parser.add_argument("--skip-body-fitted", action="store_true")
    args = parser.parse_args()
    for b in args.b:
        ei = None if args.skip_body_fitted else bar_alone_stiffness(args.moreau, args.work, b)
        if ei:
            print(f"B = {b}: the {70 * b} x {4 * b} bar alone, EI = {ei:.4f} N m^2/m")
        for d in args.deflections:
            kinds = [("body-fitted", lambda: body_fitted(args.moreau, args.work, args.level, b, d, ei), args.skip_body_fitted),
                     ("immersed", lambda: immersed(args.moreau, args.work, args.level, b, d, args.bar_b), args.skip_immersed)]
            for kind, compute, skip in kinds:
                if skip:
                    continue
                r = compute()
                print(f"  D = {d} mm, {kind}: drag {r['drag']:.4f} N/m (bar {r['bar_drag']:.4f}), lift {r['lift']:.4f} "
                      f"(bar {r['bar_lift']:.4f}), FSI1's bar under this load: {r['g_mm']:.4f} mm at A", flush=True)


if __name__ == "__main__":
    main()
