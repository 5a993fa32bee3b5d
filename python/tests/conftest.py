"""Shared fixtures: the repository root, the command-line binary, small scenes."""
import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def moreau_binary():
    binary = os.environ.get("MOREAU_BINARY", str(ROOT / "build" / "moreau"))
    assert pathlib.Path(binary).exists(), f"the moreau binary is missing: {binary} (build it, or set MOREAU_BINARY)"
    return binary


def box_on_floor(pusher_velocity):
    """A kinematic box pushing a dynamic box along a floor with friction."""
    return {
        "name": "push",
        "settings": {"dt": 0.01, "duration": 0.5, "substeps": 10},
        "objects": [
            {"name": "floor", "kind": "collider", "shape": {"type": "plane"}, "friction": 0.5},
            {"name": "pusher", "kind": "rigid_body", "kinematic": True, "shape": {"type": "box", "size": [0.2, 0.2, 0.2]},
             "position": [-0.3, 0.1, 0], "velocity": pusher_velocity},
            {"name": "crate", "kind": "rigid_body", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]},
             "density": 500, "position": [0, 0.1, 0], "friction": 0.5},
        ],
        "probes": [{"name": "crate", "type": "position", "object": "crate"}],
    }
