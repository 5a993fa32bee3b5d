"""The command-line options shared by the granular collapse benchmarks (column_collapse.py,
slab_collapse.py): where moreau and the output are, threads, and the grains' friction, rolling
resistance and solver iterations."""
import argparse
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def collapse_options(doc, name):
    """A parser for a collapse benchmark whose docstring is `doc`, writing under out/<name>."""
    p = argparse.ArgumentParser(description=doc.split("\n")[0])
    p.add_argument("--moreau", default=os.path.join(ROOT, "build", "moreau"))
    p.add_argument("--out", default=os.path.join(ROOT, "out", name))
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--rolling-resistance", type=float, default=0.2)
    p.add_argument("--friction", type=float, default=0.7)
    p.add_argument("--iterations", type=int, default=4)
    return p
