"""Bad input and numerical failure raise Python exceptions carrying the command line's message."""
import pytest

import moreau


def test_a_missing_file_is_named(tmp_path):
    missing = tmp_path / "nope.json"
    with pytest.raises(moreau.InputError, match="nope.json") as error:
        moreau.World.load(str(missing))
    assert isinstance(error.value, ValueError)


def test_a_misspelt_key_names_its_json_path_and_the_closest_allowed_key():
    scene = {"name": "typo", "objects": [
        {"name": "ball", "kind": "rigid_body", "shape": {"type": "sphere", "radius": 0.1}, "position": [0, 1, 0],
         "densty": 1000}]}
    with pytest.raises(moreau.InputError) as error:
        moreau.World.from_dict(scene)
    message = str(error.value)
    assert "(scene JSON)" in message and "objects[0]" in message and "densty" in message and "density" in message


def test_an_out_of_range_override_names_its_path():
    with pytest.raises(moreau.InputError, match="settings.dt"):
        moreau.World.from_dict({"name": "empty", "objects": []}, overrides=["settings.dt=-1"])


def test_an_unknown_solver_names_the_allowed_ones():
    with pytest.raises(moreau.InputError, match="xpbd"):
        moreau.World.from_dict({"name": "empty", "objects": []}, solver="nope")


def test_a_diverging_step_raises_numerical_error_naming_step_time_and_object():
    # A cloth pulled by 1e4 m/s^2 passes settings.max_speed = 100 m/s within the first steps.
    scene = {"name": "boom", "settings": {"dt": 0.02, "substeps": 1, "max_speed": 100, "gravity": [0, -10000, 0]},
             "objects": [{"name": "sheet", "kind": "cloth", "mesh": {"type": "grid", "size": [1, 1], "resolution": [4, 4]},
                          "material": {"area_density": 0.1, "stretch_compliance": 0}}]}
    world = moreau.World.from_dict(scene)
    with pytest.raises(moreau.NumericalError) as error:
        world.step(count=50)
    message = str(error.value)
    assert isinstance(error.value, RuntimeError)
    assert "step" in message and "t =" in message and "'sheet'" in message
