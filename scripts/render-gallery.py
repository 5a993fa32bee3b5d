#!/usr/bin/env python3
"""Pictures of the example scenes for the README and the docs, drawn by `moreau render`.

Runs each scene of GALLERY (for its whole duration unless a shorter one is given) into
out/gallery/<scene> and draws the frame nearest the chosen time, coloured as listed, into
docs/images/<scene>.png at 800 x 450.

    scripts/render-gallery.py [--moreau build/moreau] [--only SCENE ...]
"""
import argparse
import pathlib
import subprocess
import xml.etree.ElementTree as ElementTree

ROOT = pathlib.Path(__file__).resolve().parent.parent

# (scene, simulated time to run (None: the scene's duration), time of the picture (None: the end), colour by)
GALLERY = [
    ("showcase", None, 1.2, ""),
    ("dam_break", 0.8, None, "velocity"),
    ("rigid_playground", None, 1.5, ""),
    ("rope_bridge", None, None, ""),
    ("rod_plectoneme", None, None, ""),
    ("granular_column_collapse", None, None, "velocity"),
    ("fem_flying_l", 6, None, "velocity"),
    ("cylinder_re100", None, None, "velocity"),
    ("putty_balls", 0.5, 0.4, "plastic_strain"),
    ("honey_coiling", None, None, "velocity"),
    ("candle_jar", None, None, "liquid_fraction"),
    ("viscoelastic_coiling", None, 1.6, "velocity"),
    ("oil_and_water", None, None, ""),
]


def frame_nearest(pvd, time):
    times = sorted({float(d.get("timestep")) for d in ElementTree.parse(pvd).getroot().iter("DataSet")})
    return min(range(len(times)), key=lambda i: abs(times[i] - time)) if time is not None else len(times) - 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--moreau", default=str(ROOT / "build" / "moreau"))
    parser.add_argument("--only", nargs="*")
    args = parser.parse_args()
    images = ROOT / "docs" / "images"
    images.mkdir(parents=True, exist_ok=True)
    for scene, duration, at, colour in GALLERY:
        if args.only and scene not in args.only:
            continue
        out = ROOT / "out" / "gallery" / scene
        command = [args.moreau, "run", str(ROOT / "scenes" / f"{scene}.json"), "--out", str(out), "--quiet"]
        if duration is not None:
            command += ["--duration", str(duration)]
        subprocess.run(command, check=True)
        frame = frame_nearest(next(out.glob("*.pvd")), at)
        render = [args.moreau, "render", str(out), "--frame", str(frame), "--size", "800x450", "--quiet",
                  "--out", str(images / f"{scene}.png")]
        if colour:
            render += ["--colour-by", colour]
        subprocess.run(render, check=True)
        print(f"{scene}: frame {frame} -> docs/images/{scene}.png", flush=True)


if __name__ == "__main__":
    main()
