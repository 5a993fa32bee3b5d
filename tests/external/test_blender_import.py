"""Blender imports moreau's OBJ and PLY frames and renders them where they are.

A scene with a cloth, a rigid box and a block of water runs with settings.output.formats
["vtk", "obj", "ply"]; Blender (headless, its own OBJ and PLY importers) imports one frame,
every vertex must arrive where the file puts it, and in a Cycles render each object's colour must
cover part of the image centred where the camera projects the object (within 2 % of the image; measured: 0.5 %).
"""
import json
import os
import pathlib
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[2]
MOREAU = os.environ.get("MOREAU_BINARY", str(ROOT / "build" / "moreau"))

SCENE = {
    "name": "blender_frames",
    "settings": {"dt": 0.01, "duration": 0.05, "output": {"formats": ["vtk", "obj", "ply"]}},
    "objects": [
        {"name": "sheet", "kind": "cloth", "mesh": {"type": "grid", "size": [0.6, 0.6], "resolution": [8, 8],
                                                    "center": [0, 0.6, 0]},
         "material": {"area_density": 0.1}},
        {"name": "crate", "kind": "rigid_body", "shape": {"type": "box", "size": [0.3, 0.3, 0.3]},
         "position": [-0.7, 0.3, 0]},
        {"name": "water", "kind": "fluid", "particle_radius": 0.02,
         "block": {"min": [0.5, 0.1, -0.1], "max": [0.7, 0.3, 0.1]}},
    ],
}


def test_blender_imports_and_renders_a_frame(tmp_path):
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps(SCENE))
    out = tmp_path / "out"
    subprocess.run([MOREAU, "run", str(scene), "--out", str(out), "--quiet"], check=True)
    frames = out / "frames"
    assert sorted(p.name for p in frames.glob("*_000005.*")) == [
        "crate_000005.obj", "crate_000005.vtu", "sheet_000005.obj", "sheet_000005.vtu",
        "water_000005.ply", "water_000005.vtp"]
    png, report = tmp_path / "frame.png", tmp_path / "report.json"
    blender = subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                              str(ROOT / "tests" / "external" / "blender_check_frames.py"), "--",
                              str(frames), "5", str(png), str(report)], capture_output=True, text=True)
    assert blender.returncode == 0, blender.stdout[-3000:] + blender.stderr[-3000:]
    result = json.loads(report.read_text())
    assert result["problems"] == []
    assert set(result["objects"]) == {"crate_000005", "sheet_000005", "water_000005"}
    assert result["objects"]["crate_000005"]["vertices"] > 0
    assert result["objects"]["water_000005"]["vertices"] == 5 * 5 * 5  # 0.2 m at 2r = 4 cm
    for name, entry in result["objects"].items():
        assert entry["rendered_share"] > 0.002, f"{name} does not show in the render"
        dx = entry["rendered_centre"][0] - entry["image_centre"][0]
        dy = entry["rendered_centre"][1] - entry["image_centre"][1]
        assert abs(dx) < 0.02 and abs(dy) < 0.02, f"{name} rendered at {entry['rendered_centre']}, " \
                                                  f"projected at {entry['image_centre']}"
