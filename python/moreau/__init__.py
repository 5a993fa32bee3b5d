"""moreau: a multiphysics simulation engine, driven from Python.

    import moreau
    world = moreau.World.load("scenes/tablecloth.json")
    for _ in range(60):
        world.step()                                  # one step of settings.dt, GIL released
        v = world.array("particle.velocity")          # (n, 3) numpy view of the state, m/s
        v *= 0.999                                    # steers the next step
    history = world.record(0.5)                       # probes after every step, as arrays
    world.run(out_dir="out/tablecloth")               # frames, probes.csv and run.json, as `moreau run`

A scene is a file (World.load) or a dict in the scene format (World.from_dict): the same keys,
defaults, SI units and checks as docs/scene-format.md. Bad input raises InputError (a ValueError)
naming the file or '(scene JSON)', the JSON path and what is allowed; a diverging step raises
NumericalError (a RuntimeError) naming the step, the time and the object.
"""
import csv as _csv
import json as _json
import os as _os

import numpy as _np

from ._moreau import (InputError, NumericalError, RunResult, World, WorldObject, set_memory_limit,
                      version)

__version__ = version()
__all__ = ["World", "WorldObject", "RunResult", "InputError", "NumericalError", "read_probes",
           "set_memory_limit", "version"]


def _from_dict(scene, overrides=(), solver=None):
    """Builds a World from a scene as a dict (the scene format's JSON as Python objects).

    overrides are 'json.path=value' assignments, as the command line's --set; solver sets
    settings.solver. Relative mesh paths are resolved against the working directory. Raises
    InputError naming '(scene JSON)', the JSON path and what is allowed."""
    return World.from_json(_json.dumps(scene), list(overrides), solver)


World.from_dict = staticmethod(_from_dict)


def read_probes(out_dir):
    """The probes.csv of an output directory as numpy arrays by column name ('time' first, s).

    Raises FileNotFoundError naming the file if the directory holds no probes.csv."""
    path = _os.path.join(_os.fspath(out_dir), "probes.csv")
    with open(path, newline="") as f:
        rows = list(_csv.reader(f))
    header, values = rows[0], _np.array(rows[1:], dtype=float).reshape(-1, len(rows[0]))
    return {name: values[:, i].copy() for i, name in enumerate(header)}
