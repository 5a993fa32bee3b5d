"""World through Python: loading, stepping, state arrays as views, probes, checkpoints."""
import numpy as np
import pytest

import moreau


def test_state_arrays_are_views_that_follow_the_steps(root):
    world = moreau.World.load(str(root / "scenes" / "tablecloth.json"))
    assert world.engine == "xpbd" and world.steps == 0 and world.time == 0
    position = world.array("particle.position")
    start = position.copy()
    assert position.shape[1] == 3 and position.shape[0] == sum(
        o.count for o in world.objects() if o.kind == "cloth")
    world.step(count=5)
    assert world.steps == 5 and world.time == pytest.approx(5 * world.dt, rel=1e-12)
    # The view taken before the steps sees the new state: it is the engine's storage, not a copy.
    assert not np.array_equal(position, start)
    assert np.shares_memory(position, world.array("particle.position"))
    assert world.array_units()["particle.position"] == "m"


def test_writing_velocities_steers_the_next_step():
    # Without gravity, a velocity written between steps moves a free body and a cloth at rest by
    # exactly v dt in the next step (a uniform translation violates no constraint), to round-off.
    scene = {"name": "drift", "settings": {"dt": 0.01, "gravity": [0, 0, 0]},
             "objects": [{"name": "ball", "kind": "rigid_body", "shape": {"type": "sphere", "radius": 0.1},
                          "position": [0, 1, 0]},
                         {"name": "sheet", "kind": "cloth", "mesh": {"type": "grid", "size": [1, 1], "resolution": [4, 4]},
                          "material": {"area_density": 0.1}}]}
    world = moreau.World.from_dict(scene)
    v = np.array([1.0, -2.0, 0.5])
    world.array("body.velocity")[:] = v
    world.array("particle.velocity")[:] = v
    body, cloth = world.array("body.position").copy(), world.array("particle.position").copy()
    world.step()
    np.testing.assert_allclose(world.array("body.position") - body, np.tile(v * world.dt, (1, 1)), rtol=0, atol=1e-12)
    np.testing.assert_allclose(world.array("particle.position") - cloth, np.tile(v * world.dt, (len(cloth), 1)),
                               rtol=0, atol=1e-12)


def test_read_only_arrays_refuse_writes(root):
    world = moreau.World.load(str(root / "scenes" / "dam_break.json"), ["settings.threads=1"])
    world.array("fluid.velocity")[0, 0] = 0.0  # writable
    with pytest.raises(ValueError):
        world.array("fluid.position")[0, 0] = 1.0
    with pytest.raises(ValueError):
        world.array("fluid.enthalpy")[0] = 1.0
    with pytest.raises(moreau.InputError, match="fluid.position"):
        world.array("no.such.array")


def test_record_returns_the_probes_after_every_step(root):
    world = moreau.World.load(str(root / "scenes" / "tablecloth.json"))
    history = world.record(0.1)
    steps = round(0.1 / world.dt)
    assert list(history) == ["time"] + world.probe_names
    assert all(len(column) == steps for column in history.values())
    np.testing.assert_allclose(np.diff(history["time"]), world.dt, rtol=1e-9)
    last = world.probes()
    assert all(history[name][-1] == value for name, value in last.items())


def test_checkpoint_restores_the_state_bit_for_bit_into_the_same_views(root, tmp_path):
    world = moreau.World.load(str(root / "scenes" / "rigid_playground.json"))
    world.step(count=10)
    pose = world.array("body.position")
    saved = pose.copy()
    world.save_checkpoint(str(tmp_path / "state.bin"))
    world.step(count=10)
    assert not np.array_equal(pose, saved)
    world.restore(str(tmp_path / "state.bin"))
    assert world.steps == 10
    np.testing.assert_array_equal(pose, saved)  # the old view sees the restored state


def test_help_documents_units():
    assert "m/s" in moreau.World.array.__doc__
    assert "InputError" in moreau.__doc__
    assert moreau.__version__ == moreau.version()
