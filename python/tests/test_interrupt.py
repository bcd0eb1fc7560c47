"""Ctrl-C and exceptions during relume.compress and relume.factor: a SIGINT that arrives while
the library works raises KeyboardInterrupt soon after (well before the work would have ended),
an exception raised by the progress callback comes out of compress as it was raised, and in
both cases the next call runs to the end (the interruption request was cleared). The SIGINT
runs in a child process, so that the test runner's own handling of Ctrl-C is not involved."""
import os
import subprocess
import sys

import numpy as np
import pytest

import relume
from conftest import synth_scene

# Compresses (or factors) once uninterrupted, then again with a SIGINT sent by another thread:
# with a progress callback as soon as the first report arrives (Python's handler then runs in
# the callback), without one a tenth of the first run's time after the start (the binding's
# signal check raises it); prints both times.
CHILD = r"""
import os, signal, sys, threading, time
import numpy as np
import relume

what, path, assign, callback = sys.argv[1:5]
if what == "compress":
    field = relume.load(path)
    options = dict(clusters=12, terms=3, residual=8, seed=3, threads=2, assign=assign,
                   iterations=12)
    run = lambda **extra: relume.compress(field, **options, **extra)
else:
    matrix = np.random.default_rng(1).standard_normal((480, 24))  # ~1 s: well above the
    # tens of milliseconds a signal takes to arrive from the other thread
    run = lambda **extra: relume.factor(matrix, 4, solver="lp", max_iterations=30,
                                        tolerance=0, threads=2, **extra)

start = time.perf_counter()
run()
whole = time.perf_counter() - start

started = threading.Event()
def send_sigint():
    if callback == "callback":
        started.wait()
    else:
        time.sleep(0.1 * whole)
    os.kill(os.getpid(), signal.SIGINT)
threading.Thread(target=send_sigint, daemon=True).start()
start = time.perf_counter()
try:
    if callback == "callback":
        run(progress=lambda phase, fraction: started.set())
    else:
        run()
    print("not interrupted")
except KeyboardInterrupt:
    print(f"interrupted {time.perf_counter() - start:.4f} of {whole:.4f}")
run()
print("ran again")
"""


@pytest.fixture(scope="module")
def larger_scene(tmp_path_factory):
    return synth_scene(tmp_path_factory.mktemp("larger") / "scene", "96x72", 60)


def run_child(*arguments):
    completed = subprocess.run([sys.executable, "-c", CHILD, *map(str, arguments)],
                               capture_output=True, text=True, timeout=300)
    assert completed.returncode == 0, completed.stdout + completed.stderr
    return completed.stdout.split("\n")


@pytest.mark.parametrize("what, assign, callback", [
    ("compress", "cpu", "callback"), ("compress", "cpu", "none"), ("compress", "opencl", "none"),
    ("factor", "-", "none")])
def test_sigint_raises_keyboard_interrupt_soon_and_the_next_call_runs(larger_scene, what, assign,
                                                                      callback):
    lines = run_child(what, larger_scene, assign, callback)
    assert lines[0].startswith("interrupted"), lines
    interrupted, whole = float(lines[0].split()[1]), float(lines[0].split()[3])
    assert interrupted < 0.5 * whole, f"stopped after {interrupted} s of a {whole} s run"
    assert lines[1] == "ran again"


def test_an_exception_from_progress_comes_out_of_compress(field):
    class Stop(Exception):
        pass

    def progress(phase, fraction):
        if phase.endswith("assigning"):
            raise Stop(phase)

    with pytest.raises(Stop, match="assigning"):
        relume.compress(field, clusters=5, terms=3, residual=4, assign="cpu", progress=progress)
    compressed = relume.compress(field, clusters=5, terms=3, residual=4, assign="cpu")
    assert compressed.clusters >= 1


def test_keyboard_interrupt_from_progress_stops_factor():
    matrix = np.random.default_rng(2).standard_normal((50, 8))

    def progress(phase, fraction):
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        relume.factor(matrix, 1, progress=progress)
    W, F, E = relume.factor(matrix, 1)
    assert W.shape == (matrix.shape[0], 1)
