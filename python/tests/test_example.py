"""The example script runs and its ball falls as y0 - g t^2/2 until it lands."""
import os
import re
import subprocess
import sys


def test_drop_and_plot_matches_free_fall_and_writes_its_plot(root, tmp_path):
    png = tmp_path / "drop.png"
    result = subprocess.run([sys.executable, str(root / "python" / "examples" / "drop_and_plot.py"), str(png)],
                            capture_output=True, text=True, env=dict(os.environ), check=True)
    error = float(re.search(r"largest difference from y0 - g t\^2/2 is (\S+) m", result.stdout).group(1))
    # Symplectic Euler with h = dt/4 lags the exact fall by g h t / 2 (<= 3 mm at t = 0.4 s, h = 1/960 s).
    assert error < 3e-3, result.stdout
    assert png.stat().st_size > 10_000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
