#!/usr/bin/env python3
"""Writes the rigid-body stability and benchmark scenes of docs/validation.md and
docs/performance.md (the issue's reference scenes, also run by Bullet and MuJoCo):

  chain_100_hanging.json   100 links of 0.1 kg on ball joints holding 100 kg, hanging at rest
  chain_100_released.json  the same chain released from horizontal
  pyramid_210.json         a 2D pyramid of 210 unit cubes (base 20) on the ground, friction 0.5
  boxes_1000.json          1000 cubes of 0.5 m in a 10 x 10 x 10 grid dropped on the ground

Run from anywhere: python3 bench/scenes/generate_rigid_scenes.py
"""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, scene):
    # One object, joint or probe per line.
    lines = ["{"]
    for n, (key, value) in enumerate(scene.items()):
        comma = "," if n + 1 < len(scene) else ""
        if isinstance(value, list):
            items = ",\n  ".join(json.dumps(v) for v in value)
            lines.append(f' "{key}": [\n  {items}]{comma}')
        else:
            lines.append(f' "{key}": {json.dumps(value)}{comma}')
    lines.append("}")
    with open(os.path.join(HERE, name), "w") as f:
        f.write("\n".join(lines) + "\n")


def chain(released):
    links, length = 100, 0.1
    direction = (1.0, 0.0) if released else (0.0, -1.0)

    def at(s):  # point s metres along the chain from the pivot at (0, 10, 0)
        return [round(direction[0] * s, 10), round(10 + direction[1] * s, 10), 0]

    half = [0.05, 0.01, 0.01] if released else [0.01, 0.05, 0.01]
    objects, joints = [], []
    for i in range(links):
        objects.append({"name": f"link{i}", "kind": "rigid_body", "shape": {"type": "box", "half_extents": half},
                        "position": at(length * (i + 0.5)), "mass": 0.1})
        joints.append({"name": f"j{i}", "type": "spherical", "bodies": ["world" if i == 0 else f"link{i-1}", f"link{i}"],
                       "anchor": at(length * i)})
    objects.append({"name": "weight", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]},
                    "position": at(length * links + 0.1), "mass": 100})
    joints.append({"name": f"j{links}", "type": "spherical", "bodies": [f"link{links-1}", "weight"],
                   "anchor": at(length * links)})
    what = "released from horizontal" if released else "hanging at rest"
    return {"name": "chain_100_" + ("released" if released else "hanging"),
            "description": f"100 links of 0.1 kg (0.1 m) on ball joints holding a 100 kg weight, {what}; "
                           "mass ratio 1:1000. The joints' gaps sum to the chain's stretch.",
            "settings": {"dt": 1 / 60, "substeps": 20, "duration": 5.0},
            "objects": objects, "joints": joints,
            "probes": [{"name": "weight", "type": "position", "object": "weight"},
                       {"name": "joints", "type": "joint_error", "joint": "*"}]}


def pyramid():
    base = 20
    objects = [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}, "friction": 0.5}]
    for row in range(base):
        count = base - row
        for i in range(count):
            objects.append({"name": f"box_{row}_{i}", "kind": "rigid_body",
                            "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
                            "position": [i - (count - 1) / 2, 0.5 + row, 0], "density": 1000,
                            "friction": {"static": 0.5, "dynamic": 0.5}})
    return {"name": "pyramid_210",
            "description": "A 2D pyramid of 210 unit cubes (base 20) on the ground, friction 0.5, 10 s at 60 Hz; "
                           "the largest drift of any box from its start is the stability measure.",
            "settings": {"dt": 1 / 60, "substeps": 8, "duration": 10.0, "output": {"every": 60}},
            "objects": objects,
            "probes": [{"name": "drift", "type": "max_displacement", "object": "*"},
                       {"name": "contacts", "type": "contact_count", "object": "*"}]}


def boxes():
    objects = [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}, "friction": 0.5}]
    for i in range(10):
        for j in range(10):
            for k in range(10):
                objects.append({"name": f"box_{i}_{j}_{k}", "kind": "rigid_body",
                                "shape": {"type": "box", "half_extents": [0.25, 0.25, 0.25]},
                                "position": [0.6 * i - 2.7, 0.3 + 0.6 * j, 0.6 * k - 2.7], "density": 1000})
    return {"name": "boxes_1000",
            "description": "1000 cubes of 0.5 m in a 10 x 10 x 10 grid (0.1 m apart) dropped on the ground.",
            "settings": {"dt": 1 / 60, "substeps": 8, "duration": 5.0, "output": {"every": 30}},
            "objects": objects,
            "probes": [{"name": "contacts", "type": "contact_count", "object": "*"}]}


write("chain_100_hanging.json", chain(False))
write("chain_100_released.json", chain(True))
write("pyramid_210.json", pyramid())
write("boxes_1000.json", boxes())
