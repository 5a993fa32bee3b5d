"""Drops a ball onto a floor, records its height every step and plots it against free fall.

    PYTHONPATH=build/python python3 python/examples/drop_and_plot.py [out.png]

The scene is built in code as a dict in the scene format. Until it touches the floor the ball
follows y(t) = y0 - g t^2 / 2; the script prints the largest difference over that stretch.
"""
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt
import numpy as np

import moreau

G, Y0, RADIUS = 9.81, 1.0, 0.1

scene = {
    "name": "drop",
    "settings": {"dt": 1 / 240, "substeps": 4, "gravity": [0, -G, 0]},
    "objects": [
        {"name": "floor", "kind": "collider", "shape": {"type": "plane"}, "restitution": 0.5},
        {"name": "ball", "kind": "rigid_body", "shape": {"type": "sphere", "radius": RADIUS},
         "density": 1000, "position": [0, Y0, 0], "restitution": 0.5},
    ],
    "probes": [{"name": "ball", "type": "position", "object": "ball"}],
}

world = moreau.World.from_dict(scene)
history = world.record(duration=1.5)  # the probes after every step, as numpy arrays
t, y = history["time"], history["ball.y"]

falling = y > RADIUS + 0.01  # before the first contact
first_contact = np.argmin(falling)
free_fall = Y0 - 0.5 * G * t**2
error = np.max(np.abs(y[:first_contact] - free_fall[:first_contact]))
print(f"free fall until t = {t[first_contact]:.3f} s: largest difference from y0 - g t^2/2 is {error:.2e} m")

plt.plot(t, y, label="moreau")
plt.plot(t[: first_contact + 1], free_fall[: first_contact + 1], "--", label="free fall, y0 - g t²/2")
plt.xlabel("time (s)")
plt.ylabel("height of the ball's centre (m)")
plt.legend()
output = sys.argv[1] if len(sys.argv) > 1 else "drop.png"
plt.savefig(output, dpi=100)
print(f"plot written to {output}")
