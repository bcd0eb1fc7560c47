"""Shared fixtures of the relume Python tests (run by ctest, which sets PYTHONPATH to the built
module and RELUME_BINARY to the built command): a small synthetic scene written by
`relume synth`, a small sky map written by `relume sky`, and running the command."""
import os
import pathlib
import subprocess

import pytest

import relume


def relume_binary():
    binary = os.environ.get("RELUME_BINARY")
    if not binary:
        pytest.fail("RELUME_BINARY is not set: run the Python tests through ctest")
    return binary


def run_relume(*arguments):
    """Runs the relume command; fails the test with its output when it fails."""
    completed = subprocess.run([relume_binary(), "-q", *map(str, arguments)],
                               capture_output=True, text=True)
    if completed.returncode != 0:
        pytest.fail(f"relume {' '.join(map(str, arguments))} failed ({completed.returncode}):\n"
                    f"{completed.stdout}{completed.stderr}")
    return completed


def synth_scene(folder, size, lights):
    """A field folder rendered by `relume synth` (lights over the whole sphere)."""
    run_relume("synth", "-o", folder, "--size", size, "--lights", lights, "--samples", "1",
               "--threads", "2")
    return folder


@pytest.fixture(scope="session")
def scene(tmp_path_factory):
    """32x24 pixels, 40 lights."""
    return synth_scene(tmp_path_factory.mktemp("scene") / "scene", "32x24", 40)


@pytest.fixture(scope="session")
def field(scene):
    return relume.load(scene)


@pytest.fixture(scope="session")
def sky_map(tmp_path_factory):
    """The built-in sky as a 64x32 lat-long EXR, written by `relume sky`."""
    path = tmp_path_factory.mktemp("sky") / "sky.exr"
    run_relume("sky", "-o", path, "--width", "64")
    return path


# Small settings that every compress test shares (the C++ assignment path unless a test says).
SMALL = dict(clusters=5, terms=3, residual=4, seed=3, threads=2, assign="cpu")


def cli_options(options):
    """The `relume compress` options for the keyword arguments in SMALL."""
    flags = []
    for key, value in options.items():
        flags += ["--" + key.replace("_", "-"), str(value)]
    return flags


@pytest.fixture(scope="session")
def compressed(field):
    return relume.compress(field, **SMALL)


def source_dir():
    return pathlib.Path(os.environ.get("RELUME_SOURCE_DIR",
                                       pathlib.Path(__file__).resolve().parents[2]))
