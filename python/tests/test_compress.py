"""relume.compress against `relume compress` on the same field with the same seed (both the C++
and the OpenCL assignment, the Haar basis, an exact LP refit), on a field given as a
relume.Field or as arrays, its progress callback, the GIL released while it runs, and the
errors its options raise."""
import json
import os
import pathlib
import threading
import time

import numpy as np
import pytest

import relume
from conftest import SMALL, cli_options, run_relume, source_dir


def assert_same_compression(ours, theirs):
    for name in ("width", "height", "channels", "lights", "terms", "clusters", "transform"):
        assert getattr(ours, name) == getattr(theirs, name), name
    for name in ("stored_function", "cluster", "weights", "bases", "residual_offsets",
                 "residual_indices", "residual_values", "mask", "directions"):
        np.testing.assert_array_equal(getattr(ours, name), getattr(theirs, name), err_msg=name)


@pytest.mark.parametrize("extra", [
    {},
    {"assign": "opencl"},
    {"transform": "haar", "residual": "10%"},
    {"solver": "lp-dual", "iterations": 2},
    {"multires": 1, "refine": 1},
], ids=["cpu", "opencl", "haar", "lp-dual", "multires"])
def test_equals_the_command_with_the_same_seed(scene, field, tmp_path, extra):
    options = {**SMALL, **extra}
    output = tmp_path / "cli.relume"
    run_relume("compress", scene, "-o", output, *cli_options(options))
    ours = relume.compress(field, **options)
    assert_same_compression(ours, relume.open(output))
    assert ours.residual_values.size > 0


def test_an_array_field_compresses_as_the_same_field_loaded(field, compressed):
    from_arrays = relume.compress(field.values, field.directions, mask=field.mask,
                                  intensities=field.intensities, **SMALL)
    assert_same_compression(from_arrays, compressed)


def test_residual_count_and_budget_text_agree(field):
    by_count = relume.compress(field, **{**SMALL, "residual": 4})
    by_text = relume.compress(field, **{**SMALL, "residual": "4"})
    by_percent = relume.compress(field, **{**SMALL, "residual": "10%"})  # 10% of 40 lights
    assert_same_compression(by_count, by_text)
    assert_same_compression(by_count, by_percent)
    lengths = np.diff(by_count.residual_offsets)
    assert lengths.max() == 4


def test_progress_is_told_phases_from_zero_to_one(field):
    heard = []
    relume.compress(field, **SMALL, progress=lambda phase, fraction: heard.append((phase, fraction)))
    phases = {phase for phase, _ in heard}
    assert "compress: iterations" in phases
    assert any(phase.endswith("assigning") for phase in phases)
    iterations = [fraction for phase, fraction in heard if phase == "compress: iterations"]
    assert iterations[0] == 0.0 and iterations[-1] == 1.0
    assert all(0.0 <= fraction <= 1.0 for _, fraction in heard)


def test_the_gil_is_released_while_compressing(field):
    """Another Python thread keeps running in the middle of a compress."""
    span = {}
    ticks = []

    def work():
        span["start"] = time.perf_counter()
        relume.compress(field, **{**SMALL, "iterations": 8, "residual": "50%"})
        span["end"] = time.perf_counter()

    worker = threading.Thread(target=work)
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    duration = span["end"] - span["start"]
    assert duration > 0.05, "the compress is too short to tell"
    middle = [t for t in ticks
              if span["start"] + 0.3 * duration < t < span["start"] + 0.7 * duration]
    assert len(middle) > 100, f"{len(middle)} ticks in the middle of a {duration:.3f} s compress"


@pytest.mark.parametrize("options, message", [
    ({"transform": "wavelet"}, "transform must be 'identity' or 'haar', got 'wavelet'"),
    ({"assign": "gpu"}, "assign must be 'opencl' or 'cpu', got 'gpu'"),
    ({"residual": "5 %"}, "residual budget '5 %' is invalid"),
    ({"residual": 0.5}, "residual must be a count of entries per function (an int)"),
    ({"residual": -1}, "residual must be a count of entries per function >= 0, got -1"),
    ({"terms": 17}, "terms per cluster must be in [1, 16], got 17"),
    ({"clusters": 0}, "clusters must be >= 1, got 0"),
    ({"solver": "simplex"}, "unknown L1 solver 'simplex'"),
    ({"weights_precision": "float8"}, 'unknown precision "float8"'),
    ({"target_error": -0.1}, "--target-error must be a finite number > 0"),
    ({"target_psnr": 40, "target_bytes": 1000}, "--target-bytes and --target-psnr are two targets"),
    ({"clusterz": 4}, "unknown compress option 'clusterz'"),
    ({"threshold": float("nan")}, "residual threshold must be a finite value (negative: the noise floor)"),
    ({"progress": 3}, "progress must be a callable"),
])
def test_bad_options_raise_relume_errors(field, options, message):
    with pytest.raises(relume.Error) as raised:
        relume.compress(field, **{**SMALL, **options})
    assert message in str(raised.value)
    assert isinstance(raised.value, ValueError)


def test_field_arrays_are_refused_clearly(field):
    values = np.array(field.values)
    with pytest.raises(relume.Error, match=r"dirs= is needed when the field is given as an array"):
        relume.compress(values)
    with pytest.raises(relume.Error, match=r"field values must hold float32 \(convert with"):
        relume.compress(values.astype(np.float64), field.directions)
    with pytest.raises(relume.Error, match=r"must have shape \(height, width, channels, lights\)"):
        relume.compress(values[..., 0], field.directions)
    bad = values.copy()
    bad[2, 5, 1, 7] = np.nan
    with pytest.raises(relume.Error, match=r"field values\[2, 5, 1, 7\] is nan"):
        relume.compress(bad, field.directions)
    with pytest.raises(relume.Error, match=r"dirs has 39 rows but the field has 40 lights"):
        relume.compress(values, field.directions[:39])
    with pytest.raises(relume.Error, match=r"mask must have shape \(24, 32\)"):
        relume.compress(values, field.directions, mask=np.ones((32, 24), bool))
    with pytest.raises(relume.Error, match="a relume.Field has its own"):
        relume.compress(field, field.directions)


def test_target_error_equals_the_command_and_reaches_its_target(scene, field, tmp_path):
    options = {"target_error": 0.01, "seed": 3, "threads": 2, "assign": "cpu"}
    run_relume("compress", scene, "-o", tmp_path / "cli.relume", *cli_options(options))
    ours = relume.compress(field, **options)
    assert_same_compression(ours, relume.open(tmp_path / "cli.relume"))
    assert relume.relative_error(field, ours) <= 0.01 * (1 + 1e-6)


def file_bytes(path):
    with open(path, "rb") as stream:
        return stream.read()


def shared_capture(name):
    data = pathlib.Path(os.environ.get("RELUME_DATA", source_dir().parent / "shared" / "data"))
    path = data / "olat" / name
    if not path.exists():
        pytest.skip(f"shared data not found at {data} (set RELUME_DATA to the folder that holds olat/)")
    return path


@pytest.mark.parametrize("capture", ["diligent-bear-crop8", "rti-loewenkopf/dirs.lp"])
def test_compress_file_and_load_write_the_commands_container(capture, tmp_path):
    """The same bytes from the command, from compress_file, and from load + compress + save (an
    .lp capture of 8-bit JPEGs is decoded as sRGB by all three)."""
    source = shared_capture(capture)
    options = {**SMALL, "iterations": 2}
    run_relume("compress", source, "-o", tmp_path / "cli.relume", *cli_options(options))
    report = relume.compress_file(source, tmp_path / "file.relume", report=tmp_path / "r.json",
                                  **options)
    relume.compress(relume.load(source), **options).save(tmp_path / "memory.relume")
    command = file_bytes(tmp_path / "cli.relume")
    assert file_bytes(tmp_path / "file.relume") == command
    assert file_bytes(tmp_path / "memory.relume") == command
    assert report["bytes"] == len(command)
    assert json.loads((tmp_path / "r.json").read_text())["bytes"] == len(command)


def test_rate_target_memory_limit_and_report_from_python(field, tmp_path):
    target = 30  # bytes per pixel of the 32 x 24 frame
    ours = relume.compress(field, threads=2, assign="cpu", seed=3,
                           target_bytes_per_pixel=target, memory_limit="2G",
                           report=tmp_path / "report.json")
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["bytes"] == ours.file_size() <= target * 32 * 24
    assert report["software"].startswith("relume")
    assert report["rate_target"]["met"]
    assert ours.file_size() > 0.9 * target * 32 * 24
