"""ParaView opens every kind of .pvd the engine writes, and sees what the files hold.

Scenes that between them write every frame type (cloth, rigid-body and collider surfaces; soft-body
tetrahedra; fluid, grain and continuum particles; rod polylines; FEM hexahedra and director rigid
bodies; a 2D flow's quadrilaterals) run for two steps. ParaView's pvpython then opens each .pvd
with ParaView's own reader (paraview_read_pvd.py), and for every time step and part what ParaView
reports must match the files: the time steps of the .pvd, the dataset type, the point and cell
counts and the point-array names each frame's header declares. The falling crate's points must
average to its centre in rigid_poses.csv at every frame (a box's corners average to its centre;
1e-9 m).
"""
import csv
import json
import os
import pathlib
import re
import subprocess
import xml.etree.ElementTree as ElementTree

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
MOREAU = os.environ.get("MOREAU_BINARY", str(ROOT / "build" / "moreau"))
PVPYTHON = os.environ.get("PVPYTHON", "pvpython")

# (scene file, simulated time): two steps of each (a steady flow solves once).
SCENES = [
    ("viewer/test/falling_crate_and_flag.json", 0.4),   # cloth, rigid box and plane: triangle .vtu
    ("scenes/showcase.json", 0.02),                     # soft body: tetrahedra .vtu; a sphere collider
    ("scenes/dam_break.json", 0.008),                   # fluid particles: .vtp vertices
    ("scenes/rod_plectoneme.json", 0.004),              # Cosserat rod: .vtp polyline
    ("scenes/granular_column.json", 0.01),              # grains: .vtp vertices with angular velocity
    ("scenes/sand_column_xpbi.json", 0.01),             # XPBI continuum particles
    ("scenes/fem_beam.json", 0.02),                     # FEM solid: hexahedra .vtu with cell stresses
    ("scenes/fem_dzhanibekov.json", 0.02),              # FEM director rigid body
    ("scenes/cylinder_re20.json", None),                # steady 2D flow: quadrilaterals .vtu
]


def header(frame_file):
    """What a VTK frame's XML header declares: dataset type, points, cells and point arrays."""
    text = frame_file.read_bytes().split(b"<AppendedData")[0].decode() + "</VTKFile>"
    root = ElementTree.fromstring(text)
    piece = root.find(".//Piece")
    cells = int(piece.get("NumberOfCells", 0)) + sum(
        int(piece.get(k, 0)) for k in ("NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys"))
    point_data = piece.find("PointData")
    return {
        "type": {"UnstructuredGrid": "vtkUnstructuredGrid", "PolyData": "vtkPolyData"}[root.get("type")],
        "points": int(piece.get("NumberOfPoints")),
        "cells": cells,
        "point_arrays": sorted(a.get("Name") for a in point_data) if point_data is not None else [],
    }


def collection(pvd):
    """The .pvd's time steps, each with its files in part order."""
    steps = {}
    for d in ElementTree.parse(pvd).getroot().iter("DataSet"):
        steps.setdefault(float(d.get("timestep")), []).append((int(d.get("part")), pvd.parent / d.get("file")))
    return [(t, [f for _, f in sorted(files)]) for t, files in sorted(steps.items())]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """Runs every scene, then reads all their collections in one pvpython."""
    base = tmp_path_factory.mktemp("paraview")
    pvds = []
    for scene, duration in SCENES:
        out = base / pathlib.Path(scene).stem
        command = [MOREAU, "run", str(ROOT / scene), "--out", str(out), "--quiet", "--threads", "1"]
        if duration is not None:
            command += ["--duration", repr(duration)]
        subprocess.run(command, check=True, timeout=300)
        pvds += sorted(out.glob("*.pvd"))
    report_file = base / "report.json"
    paraview = subprocess.run([PVPYTHON, str(ROOT / "tests" / "external" / "paraview_read_pvd.py"), str(report_file)]
                              + [str(p) for p in pvds], capture_output=True, text=True, timeout=600)
    assert paraview.returncode == 0, paraview.stdout[-3000:] + paraview.stderr[-3000:]
    return pvds, json.loads(report_file.read_text())


def test_every_scene_wrote_a_collection(runs):
    pvds, _ = runs
    assert len(pvds) == len(SCENES)


@pytest.mark.parametrize("index", range(len(SCENES)), ids=[pathlib.Path(s).stem for s, _ in SCENES])
def test_paraview_sees_what_the_files_hold(runs, index):
    pvds, report = runs
    pvd = pvds[index]
    seen = report[str(pvd)]
    expected = collection(pvd)
    assert [s["time"] for s in seen] == pytest.approx([t for t, _ in expected], abs=1e-12)
    for step, (time, files) in zip(seen, expected):
        assert len(step["parts"]) == len(files), f"t = {time}: {len(files)} parts in the .pvd"
        for part, frame_file in zip(step["parts"], files):
            declared = header(frame_file)
            assert part is not None and part["points"] > 0, f"{frame_file.name}: ParaView reads no points"
            assert {k: part[k] for k in declared} == declared, frame_file.name


def test_the_crate_is_where_rigid_poses_puts_it(runs):
    pvds, report = runs
    pvd = next(p for p in pvds if p.stem == "crate_and_flag")
    with open(pvd.parent / "rigid_poses.csv") as f:
        rows = [r for r in csv.DictReader(f) if r["body"] == "crate"]
    steps = report[str(pvd)]
    crate = [i for i, f in enumerate(collection(pvd)[0][1]) if re.match(r"crate_\d+", f.name)][0]
    assert len(rows) == len(steps)
    for row, step in zip(rows, steps):
        centre = [float(row[k]) for k in ("x", "y", "z")]
        assert step["parts"][crate]["mean"] == pytest.approx(centre, abs=1e-9), f"t = {step['time']}"
