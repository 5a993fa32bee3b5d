"""Steps and runs release the GIL; Ctrl-C stops a run with a checkpoint."""
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import moreau


def test_a_run_releases_the_gil(root, tmp_path):
    # A Python thread stamps the clock while the main thread is inside one World.run call. Had
    # the run held the GIL, the thread would stall for the whole run; released, it keeps stamping
    # (the interpreter's switch interval is 5 ms; a gap of 100 ms means it was blocked).
    world = moreau.World.load(str(root / "scenes" / "hammock_pour.json"), ["settings.threads=1"])
    stamps, done = [], threading.Event()

    def stamp():
        while not done.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.001)

    ticker = threading.Thread(target=stamp)
    ticker.start()
    time.sleep(0.05)
    begin = time.perf_counter()
    world.run(out_dir=str(tmp_path / "out"), duration=0.3)
    end = time.perf_counter()
    done.set()
    ticker.join()
    inside = [t for t in stamps if begin <= t <= end]
    assert end - begin > 0.3, "the run must last long enough to tell"
    gaps = [b - a for a, b in zip([begin] + inside, inside + [end])]
    assert max(gaps) < 0.1, f"the Python thread stalled for {max(gaps):.3f} s during a {end - begin:.3f} s run"


def test_ctrl_c_stops_a_run_after_its_step_with_a_checkpoint(root, tmp_path):
    script = textwrap.dedent(f"""
        import moreau, sys
        world = moreau.World.load({str(root / 'scenes' / 'hammock_pour.json')!r})
        print("ready", flush=True)
        try:
            world.run(out_dir={str(tmp_path / 'out')!r}, duration=30)  # far longer than the 1 s before the signal
        except KeyboardInterrupt as stop:
            print("stopped:", stop, flush=True)
            sys.exit(0)
        sys.exit(1)
    """)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True,
                             env=dict(os.environ))
    assert child.stdout.readline().strip() == "ready"
    time.sleep(1.0)
    child.send_signal(signal.SIGINT)
    output, _ = child.communicate(timeout=120)
    assert child.returncode == 0, output
    assert "checkpoint" in output and (tmp_path / "out" / "checkpoint.bin").exists()
    resumed = moreau.World.load(str(root / "scenes" / "hammock_pour.json"))
    resumed.restore(str(tmp_path / "out" / "checkpoint.bin"))
    assert resumed.steps > 0
