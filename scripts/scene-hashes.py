#!/usr/bin/env python3
"""Hashes of what every example and benchmark scene computes over a short run.

A redesign that changes no algorithm must leave every hash unchanged (the engine is bit-for-bit
deterministic for any thread count). For each scene in scenes/ and bench/scenes/ this runs

    moreau run SCENE --duration D --threads N --quiet --set settings.output.every=100000

(frames at the start and after the last step only), with D = 20 time steps for XPBD scenes and 5
for FEM time steppers (a static or steady scene runs whole), and prints one line per scene: the
SHA-256 of its probes.csv, rigid_poses.csv and frame files, in name order, then the run's status.

The FEM scenes' sparse factorizations call BLAS, and OpenBLAS picks its kernels for the CPU it
runs on: an AVX-512 kernel sums in another order than an AVX2 one, so the last bits of a FEM
result differ between CPUs (not between thread counts). The runs here pin OpenBLAS's AVX2 kernels
(OPENBLAS_CORETYPE=Haswell, which every x86-64 CPU since 2013 runs), so one baseline holds on
every such machine.

    scripts/scene-hashes.py [--moreau build/moreau] [--threads N] [--only SCENE ...] > hashes.txt
    diff bench/baseline/scene_hashes.txt hashes.txt
"""
import argparse
import hashlib
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent


def short_duration(scene):
    settings = scene.get("settings", {})
    dt = settings.get("dt", 1 / 60)
    if settings.get("solver", "xpbd") == "fem":
        if settings.get("integrator") in ("static", "steady"):
            return None  # the whole (short) load-step sequence or steady solve
        return 5 * dt
    return 20 * dt


def output_hash(out):
    digest = hashlib.sha256()
    files = [out / "probes.csv", out / "rigid_poses.csv"] + sorted((out / "frames").glob("*"))
    for f in files:
        if f.is_file():
            digest.update(f.name.encode())
            digest.update(f.read_bytes())
    return digest.hexdigest()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--moreau", default=str(ROOT / "build" / "moreau"))
    parser.add_argument("--threads", default="1", help="worker threads (the hashes must not depend on it)")
    parser.add_argument("--only", nargs="*", help="scene names (file stems) to hash; default: all")
    args = parser.parse_args()
    scenes = sorted((ROOT / "scenes").glob("*.json")) + sorted((ROOT / "bench" / "scenes").glob("*.json"))
    if args.only:
        scenes = [s for s in scenes if s.stem in args.only]
    failures = 0
    env = dict(os.environ, OPENBLAS_CORETYPE="Haswell")
    with tempfile.TemporaryDirectory() as tmp:
        for path in scenes:
            scene = json.loads(path.read_text())
            out = pathlib.Path(tmp) / path.stem
            command = [args.moreau, "run", str(path), "--out", str(out), "--threads", args.threads, "--quiet",
                       "--set", "settings.output.every=100000"]
            duration = short_duration(scene)
            if duration is not None:
                command += ["--duration", repr(duration)]
            result = subprocess.run(command, capture_output=True, text=True, env=env)
            status = json.loads((out / "run.json").read_text())["status"] if (out / "run.json").exists() else "none"
            if result.returncode != 0:
                failures += 1
                status += f" exit {result.returncode}"
            print(f"{path.relative_to(ROOT)} {output_hash(out)} {status}", flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
