"""Results through Python equal the command line's bit for bit."""
import csv
import filecmp
import subprocess

import numpy as np

import moreau


def run_cli(binary, scene, out, *extra):
    subprocess.run([binary, "run", str(scene), "--out", str(out), "--quiet", *extra], check=True)


def test_world_run_writes_the_same_files_as_the_command_line(root, tmp_path, moreau_binary):
    scene = root / "scenes" / "stack_knockdown.json"
    run_cli(moreau_binary, scene, tmp_path / "cli", "--duration", "0.5")
    world = moreau.World.load(str(scene))
    result = world.run(out_dir=str(tmp_path / "python"), duration=0.5)
    assert result.steps == round(0.5 / world.dt)
    for name in ["probes.csv", "rigid_poses.csv", "stack_knockdown.pvd"]:
        assert filecmp.cmp(tmp_path / "cli" / name, tmp_path / "python" / name, shallow=False), name
    frames = sorted(p.name for p in (tmp_path / "cli" / "frames").iterdir())
    assert frames == sorted(p.name for p in (tmp_path / "python" / "frames").iterdir())
    for frame in frames:
        assert filecmp.cmp(tmp_path / "cli" / "frames" / frame, tmp_path / "python" / "frames" / frame, shallow=False)


def test_stepping_from_python_gives_the_command_lines_probes_bit_for_bit(root, tmp_path, moreau_binary):
    # Every engine: a constraint scene, a FEM solid and a transient flow. probes.csv prints the
    # probes with 17 significant digits, which read back to the same doubles, and the time with 9.
    for scene_name, steps, overrides in [("hammock_pour", 12, []), ("fem_flying_l", 6, []),
                                         ("cylinder_re100", 2, [])]:
        scene = root / "scenes" / f"{scene_name}.json"
        overrides = overrides + ["settings.output.every=1"]
        world = moreau.World.load(str(scene), overrides)
        sets = [arg for o in overrides for arg in ("--set", o)]
        run_cli(moreau_binary, scene, tmp_path / scene_name, "--duration", repr(steps * world.dt), *sets)
        with open(tmp_path / scene_name / "probes.csv", newline="") as f:
            rows = list(csv.reader(f))
        assert rows[0][1:] == world.probe_names
        history = world.record(steps * world.dt)
        assert len(rows) == steps + 2 and len(history["time"]) == steps
        for step in range(steps):
            expected = np.array(rows[step + 2], dtype=float)  # row 1 is the initial state
            got = np.array([history[column][step] for column in rows[0]])
            np.testing.assert_allclose(got[0], expected[0], rtol=1e-9, err_msg=f"{scene_name}, time of step {step + 1}")
            np.testing.assert_array_equal(got[1:], expected[1:], err_msg=f"{scene_name}, step {step + 1}")
