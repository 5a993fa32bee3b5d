#!/usr/bin/env python3
"""Writes suction_cup.obj: a closed surface of revolution about +y for a soft-body suction cup.

The profile (metres): a flat annular rim on y = 0 between the inner radius r_i and the outer
radius r_o, an outer dome of height h_o over the outer edge, an inner dome (the cavity's roof) of
height h_i over the inner edge, and a cylindrical stem of radius r_s and height h_s on top that a
handle can hold. The domes are quarter ellipses. Usage: make_suction_cup.py [out.obj [segments arc]]
(32 segments around the axis and 8 points along each dome by default; tetgen fills the surface
when a scene loads it as a soft-body mesh of type "obj")."""
import math
import sys

r_o, r_i = 0.025, 0.019      # rim: outer and inner radius
h_o, h_i = 0.013, 0.008      # outer and inner dome heights above the mouth
r_s, h_s = 0.006, 0.010      # stem radius and height above the outer dome's top
segments, arc = 32, 8        # around the axis; points along each dome
if len(sys.argv) > 3:
    segments, arc = int(sys.argv[2]), int(sys.argv[3])

def ellipse(r, h, stop_r):
    """Quarter ellipse (r cos t, h sin t) from the rim up to radius stop_r."""
    t_stop = math.acos(min(1.0, stop_r / r))
    return [(r * math.cos(t_stop * k / arc), h * math.sin(t_stop * k / arc)) for k in range(arc + 1)]

# The closed profile, counter-clockwise in (r, y): rim bottom outward, outer dome up to the stem,
# the stem's side and top (to the axis), then down the axis to the inner dome's apex and along the
# inner dome back to the rim. Points on the axis (r = 0) become the poles of triangle fans.
outer = ellipse(r_o, h_o, r_s)
top = outer[-1][1] + h_s
inner = list(reversed(ellipse(r_i, h_i, 0.0)))
profile = [(r_i, 0.0)] + outer + [(r_s, top), (0.0, top)] + inner
# inner starts at the apex (0, h_i) and ends at (r_i, 0), the first point: drop the repeat.
profile = profile[:-1]

vertices, faces, ring = [], [], []
for r, y in profile:
    if r < 1e-12:
        vertices.append((0.0, y, 0.0))
        ring.append([len(vertices)] * segments)
    else:
        ids = []
        for s in range(segments):
            a = 2 * math.pi * s / segments
            vertices.append((r * math.cos(a), y, r * math.sin(a)))
            ids.append(len(vertices))
        ring.append(ids)
n = len(profile)
for k in range(n):
    a, b = ring[k], ring[(k + 1) % n]
    for s in range(segments):
        s1 = (s + 1) % segments
        quad = [a[s], a[s1], b[s1], b[s]]
        tri1, tri2 = (quad[0], quad[2], quad[1]), (quad[0], quad[3], quad[2])
        for t in (tri1, tri2):
            if len(set(t)) == 3:
                faces.append(t)

out = sys.argv[1] if len(sys.argv) > 1 else "suction_cup.obj"
with open(out, "w") as f:
    f.write("# suction cup written by make_suction_cup.py\n")
    for v in vertices:
        f.write("v %.6f %.6f %.6f\n" % v)
    for t in faces:
        f.write("f %d %d %d\n" % t)
