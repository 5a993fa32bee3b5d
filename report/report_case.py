"""What a validation case of the report returns, and the helpers cases share: running a scene
through the command line and reading its CSV output."""
import csv
import dataclasses
import json
import pathlib
import subprocess
import time

import matplotlib

matplotlib.use("Agg")  # pictures to files; no display
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent


@dataclasses.dataclass
class Check:
    """One quantity against its reference: passed when |value - reference| <= tolerance, or, for
    a bound (Check.below), when value <= reference."""
    quantity: str
    value: float
    reference: float
    tolerance: float
    unit: str = ""
    why: str = ""  # what the tolerance allows for
    is_bound: bool = False

    @staticmethod
    def below(quantity, value, bound, unit="", why=""):
        return Check(quantity, value, bound, 0.0, unit, why, is_bound=True)

    @property
    def error(self):
        return max(0.0, self.value - self.reference) if self.is_bound else abs(self.value - self.reference)

    @property
    def passed(self):
        return self.error <= self.tolerance


@dataclasses.dataclass
class CaseResult:
    title: str
    reference: str          # the published or analytic reference, with its source
    scene: str              # what ran (scene file and overrides)
    checks: list
    plots: list             # PNG files, relative to the report's directory
    wall_s: float = 0.0
    notes: list = dataclasses.field(default_factory=list)  # measured figures that are not checks
    provenance: str = ""    # which commit, when and where computed it (make_report sets it)

    @property
    def passed(self):
        return all(c.passed for c in self.checks)


def run_scene(moreau, scene, out, overrides=(), duration=None, threads=1):
    """Runs `scene` (relative to the repository) into `out`; returns its run.json and wall time."""
    command = [moreau, "run", str(ROOT / scene), "--out", str(out), "--quiet", "--threads", str(threads)]
    for o in overrides:
        command += ["--set", o]
    if duration is not None:
        command += ["--duration", repr(duration)]
    start = time.perf_counter()
    subprocess.run(command, check=True)
    return json.loads((pathlib.Path(out) / "run.json").read_text()), time.perf_counter() - start


def read_csv(path):
    """A CSV file with a header row as {column: [floats]}."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]} if rows else {}


def scene_text(scene, overrides=(), duration=None):
    text = scene + "".join(f" --set {o}" for o in overrides)
    return text + (f" --duration {duration:g}" if duration is not None else "")


def save_figure(figure, out, name):
    """Writes `figure` as out/name (PNG) and returns `name`, as CaseResult.plots lists it."""
    figure.tight_layout()
    figure.savefig(pathlib.Path(out) / name, dpi=110)
    plt.close(figure)
    return name


def finish_plot(axis, legend_size=8):
    """The cases' common axis finish: a light grid and a small legend."""
    axis.grid(alpha=0.3)
    axis.legend(fontsize=legend_size)


def case_result(figure, out, stem, fast, title, reference, scenes, checks, wall, notes):
    """Writes `figure` as <stem>.png (<stem>_fast.png for the fast subset) and returns the case's
    result, its title marked as the fast subset when it is one."""
    plot = save_figure(figure, out, f"{stem}_fast.png" if fast else f"{stem}.png")
    return CaseResult(title=title + (" (fast subset)" if fast else ""), reference=reference, scene="; ".join(scenes),
                      checks=checks, plots=[plot], wall_s=wall, notes=notes)
