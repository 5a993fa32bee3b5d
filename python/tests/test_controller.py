"""A controller loop in Python steers a scene as the scene file would."""
import numpy as np

import moreau
from conftest import box_on_floor


def test_setting_a_kinematic_bodys_velocity_each_step_equals_the_prescribed_velocity():
    # The same kinematic pusher, once given its velocity in the scene and once at rest with the
    # velocity written by a controller before every step: the crate it pushes ends bit for bit
    # where the prescribed motion puts it.
    prescribed = moreau.World.from_dict(box_on_floor([0.4, 0, 0]))
    controlled = moreau.World.from_dict(box_on_floor([0, 0, 0]))
    pusher = next(o.first for o in controlled.objects() if o.name == "pusher")
    steps = round(0.5 / controlled.dt)
    for _ in range(steps):
        controlled.array("body.velocity")[pusher] = [0.4, 0, 0]
        controlled.step()
    prescribed.step(count=steps)
    for name in ("body.position", "body.orientation", "body.velocity", "body.angular_velocity"):
        np.testing.assert_array_equal(controlled.array(name), prescribed.array(name), err_msg=name)
    # The crate was pushed: it moved with the pusher (not a scene where nothing touches).
    crate = next(o.first for o in controlled.objects() if o.name == "crate")
    assert controlled.array("body.position")[crate, 0] > 0.05
