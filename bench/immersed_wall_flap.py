#!/usr/bin/env python3
"""How an immersed flap clamped on a no-slip wall takes a channel flow's load, against body-fitted.

A flap 0.01 m wide and 0.05 m tall (St. Venant-Kirchhoff, shear modulus 0.5 MPa, nu = 0.4, as Turek &
Hron's bar) stands on the bottom wall of a channel 0.4 x 0.1 m at x = 0.1 m, in a steady Poiseuille
inflow of mean speed 0.1 m/s (1000 kg/m^3, 1 Pa s: Re = 10, ramped up over 5 s; backward Euler to
t = 20 s). Its tip moves by under a millimetre, so the flow hardly feels the deflection and the
load is that of the straight flap.

- body-fitted: the flap cut out of the fluid mesh (bench/scenes/meshes/wall_flap_channel_cut.geo),
  the forces on 10 segments of each face and on its top from boundary_force probes;
- immersed: the fluid on a structured mesh of square cells 0.1/NY m, the flap a solid of sx x sy
  cells clamped on the wall, its cells RATIO times the fluid's.

It reports the immersed tip deflection against g, the deflection the body-fitted load gives the same
flap mesh (an Euler-Bernoulli cantilever, its EI calibrated on that flap mesh alone under a uniform
load), and how the drag splits between flap and walls. Measured results are in docs/validation.md.

With --base B the immersed flap stands on a clamp B metres above the wall instead (clamped in the
flow; its load is then not the body-fitted one, and g is not reported).

Usage: bench/immersed_wall_flap.py --work DIR [--moreau build/moreau] [--ny NY ...] [--ratio R ...]
           [--reference-h H] [--dt DT] [--base B]
One immersed run takes 1-4 minutes on one core, up to 15 where Newton needs many iterations
(docs/validation.md).
"""
import argparse
import pathlib

from cantilever_loads import cantilever_deflection, growing_run_probes, run_scene, segment_forces

ROOT = pathlib.Path(__file__).resolve().parent.parent
SEGMENTS = 10
HEIGHT, WIDTH, X0 = 0.05, 0.01, 0.1
INFLOW = "(t < 5 ? t / 5 : 1) * 1.5 * 0.1 * 4 * y * (0.1 - y) / 0.01"
FLAP = {"model": "st_venant_kirchhoff", "lame_lambda": 2e6, "lame_mu": 5e5, "density": 1000}


def settings(dt, **extra):
    return {"solver": "fem", "integrator": "backward_euler", "dt": dt, "duration": 20, "gravity": [0, 0, 0],
            "newton": {"tolerance": 1e-10, "max_iterations": 40}, **extra}


def flap_mesh(sx, sy, base=0.0):
    return {"type": "rectangle", "min": [X0, base], "max": [X0 + WIDTH, base + HEIGHT], "cells": [sx, sy]}


def body_fitted(moreau, work, h):
    """The load on the flap: per face, the x and y forces on each segment; and the top's x force."""
    up = [f"up_{k}" for k in range(1, SEGMENTS + 1)]
    down = [f"down_{k}" for k in range(1, SEGMENTS + 1)]
    probes = [{"name": "walls", "type": "boundary_force", "where": {"tag": "walls"}},
              {"name": "flap", "type": "boundary_force", "where": {"tag": ["flap_top"] + up + down}}]
    probes += growing_run_probes({"up": up, "down": down})
    fluid = {"name": "fluid", "kind": "fluid", "density": 1000, "viscosity": 1.0,
             "mesh": {"type": "geo", "file": str(ROOT / "bench" / "scenes" / "meshes" / "wall_flap_channel_cut.geo"),
                      "parameters": {"h": h, "K": SEGMENTS}},
             "boundaries": [{"where": {"tag": ["walls", "flap_top"] + up + down}, "type": "no_slip"},
                            {"where": {"tag": "inlet"}, "velocity": [INFLOW, "0"]},
                            {"where": {"tag": "outlet"}, "type": "outflow"}]}
    r = run_scene(moreau, {"name": f"body_fitted_h{h}", "settings": settings(0.5, output={"every": 40, "formats": []}),
                           "objects": [fluid], "probes": probes}, work / f"body_fitted_h{h}")
    force = lambda name, c: float(r[f"{name}.force.{c}"])  # noqa: E731
    segments = [(side, k) + segment_forces(r, side, k) for k in range(1, SEGMENTS + 1) for side in ("up", "down")]
    top_x = force("flap", "x") - sum(s[2] for s in segments)
    return {"flap_drag": force("flap", "x"), "walls_drag": force("walls", "x"), "segments": segments, "top_x": top_x}


def flap_alone_stiffness(moreau, work, sx, sy):
    """EI of the sx x sy flap mesh: its tip deflection w under a uniform load q is q L^4 / (8 EI)."""
    load = 20.0 * WIDTH  # 20 N/m^3 over the flap's width: N/m
    scene = {"name": f"flap_alone_{sx}x{sy}",
             "settings": {"solver": "fem", "integrator": "static", "dt": 1, "duration": 1, "gravity": [10, 0, 0],
                          "newton": {"tolerance": 1e-12}},
             "objects": [{"name": "flap", "kind": "solid", "material": dict(FLAP, density=2), "mesh": flap_mesh(sx, sy),
                          "dirichlet": [{"where": {"boundary": "bottom"}, "value": [0, 0]}]}],
             "probes": [{"name": "tip", "type": "point", "object": "flap", "nearest": [X0 + WIDTH / 2, HEIGHT],
                         "quantity": "displacement"}]}
    # A solid alone names a displacement probe's columns without the quantity.
    w = float(run_scene(moreau, scene, work / scene["name"])["tip.x"])
    return load * HEIGHT ** 4 / (8 * w)


def beam_deflection(load, ei):
    """The flap's tip deflection under the body-fitted forces: each segment's at its middle, on its face
    half the flap's width upstream or downstream of the axis, and the top's."""
    loads = [(HEIGHT * (k - 0.5) / SEGMENTS, -WIDTH / 2 if side == "up" else WIDTH / 2, fx, fy)
             for side, k, fx, fy in load["segments"]]
    return cantilever_deflection(HEIGHT, ei, loads, load["top_x"])


def immersed(moreau, work, ny, sx, sy, dt, base):
    fluid = {"name": "fluid", "kind": "fluid", "density": 1000, "viscosity": 1.0,
             "mesh": {"type": "rectangle", "min": [0, 0], "max": [0.4, 0.1], "cells": [4 * ny, ny]},
             "boundaries": [{"where": {"side": ["top", "bottom"]}, "type": "no_slip"},
                            {"where": {"side": "left"}, "velocity": [INFLOW, "0"]},
                            {"where": {"side": "right"}, "type": "outflow"}]}
    flap = {"name": "flap", "kind": "solid", "material": FLAP, "mesh": flap_mesh(sx, sy, base),
            "dirichlet": [{"where": {"boundary": "bottom"}, "value": [0, 0]}]}
    name = f"immersed_ny{ny}_flap{sx}x{sy}" + (f"_base{base}" if base else "")
    scene = {"name": name, "settings": settings(dt, output={"every": round(4 / dt), "formats": []}),
             "objects": [fluid, flap],
             "probes": [{"name": "tip", "type": "point", "object": "flap", "nearest": [X0 + WIDTH / 2, base + HEIGHT],
                         "quantity": "displacement"},
                        {"name": "walls", "type": "boundary_force", "where": {"side": ["top", "bottom"]}},
                        {"name": "flap", "type": "force", "object": "flap"}]}
    r = run_scene(moreau, scene, work / name)
    return {"tip": float(r["tip.displacement.x"]), "flap_drag": float(r["flap.x"]), "walls_drag": float(r["walls.force.x"])}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moreau", default=str(ROOT / "build" / "moreau"))
    parser.add_argument("--work", required=True, type=pathlib.Path)
    parser.add_argument("--ny", type=int, nargs="+", default=[20], help="the fluid's cells across the channel")
    parser.add_argument("--ratio", type=float, nargs="+", default=[1.0], help="the flap's cell size over the fluid's")
    parser.add_argument("--reference-h", type=float, default=0.00125, help="the body-fitted mesh's cell size, m")
    parser.add_argument("--dt", type=float, default=0.1, help="the immersed runs' step, s")
    parser.add_argument("--base", type=float, default=0.0, help="the immersed flap's clamp above the wall, m")
    args = parser.parse_args()
    if not args.base:
        load = body_fitted(args.moreau, args.work, args.reference_h)
        print(f"body-fitted (h = {args.reference_h} m): flap drag {load['flap_drag']:.4f} N/m, walls {load['walls_drag']:.4f}")
    for ny in args.ny:
        for ratio in args.ratio:
            size = ratio * 0.1 / ny
            sx, sy = max(1, round(WIDTH / size)), max(1, round(HEIGHT / size))
            r = immersed(args.moreau, args.work, ny, sx, sy, args.dt, args.base)
            against = ""
            if not args.base:
                g = beam_deflection(load, flap_alone_stiffness(args.moreau, args.work, sx, sy))
                against = f" against g = {g * 1e3:.4f} mm ({100 * (r['tip'] / g - 1):+.1f} %)"
            print(f"  NY = {ny}, flap {sx} x {sy} (cells {ratio} of the fluid's): tip {r['tip'] * 1e3:.4f} mm{against}; "
                  f"drag: flap {r['flap_drag']:.4f}, walls {r['walls_drag']:.4f} N/m", flush=True)


if __name__ == "__main__":
    main()
