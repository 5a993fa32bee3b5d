"""Shared by the bench scripts that take a flow's load on a cantilever apart (turek_hron_fsi1_bending.py,
immersed_wall_flap.py): running a scene, the forces on a face's segments from boundary_force probes,
and the tip deflection those forces give an Euler-Bernoulli cantilever."""
import csv
import json
import subprocess


def run_scene(moreau, scene, out):
    """Writes `scene` next to its output directory `out`, runs it on one core and returns the last probes row."""
    out.parent.mkdir(parents=True, exist_ok=True)
    path = out.with_suffix(".json")
    path.write_text(json.dumps(scene, indent=1))
    subprocess.run([moreau, "run", str(path), "--out", str(out), "--threads", "1", "--quiet"], check=True)
    with open(out / "probes.csv") as f:
        return list(csv.DictReader(f))[-1]


def growing_run_probes(faces):
    """boundary_force probes over growing runs of each face's segments, from the clamp: a probe counts each
    node once and neighbouring segments share one, so a segment's force is the difference of two runs (the
    node between segments k and k + 1 counts in k). `faces` maps a face's name to its segments' tags."""
    return [{"name": f"{face}_upto_{k}", "type": "boundary_force", "where": {"tag": tags[:k]}}
            for face, tags in faces.items() for k in range(1, len(tags) + 1)]


def segment_forces(row, face, k):
    """The (x, y) force on segment k (from 1) of `face`, from the probes of growing_run_probes."""
    def run_force(j, c):
        return float(row[f"{face}_upto_{j}.force.{c}"]) if j > 0 else 0.0
    return tuple(run_force(k, c) - run_force(k - 1, c) for c in ("x", "y"))


def cantilever_deflection(length, ei, loads, end_force=0.0):
    """The tip deflection of a cantilever of `length` and bending stiffness `ei` under `loads`, each
    (a, c, f_transverse, f_axial): a force at distance a from the clamp on a face at c from the axis
    (measured along the deflection). A transverse force P deflects the tip by P a^2 (3L - a) / (6 EI);
    an axial force f on the face at c is a moment -c f, which deflects it by -c f a (2L - a) / (2 EI).
    `end_force`: a transverse force at the tip, P L^3 / (3 EI)."""
    g = end_force * length ** 3 / (3 * ei)
    for a, c, transverse, axial in loads:
        g += transverse * a * a * (3 * length - a) / (6 * ei) - c * axial * a * (2 * length - a) / (2 * ei)
    return g
