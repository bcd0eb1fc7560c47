"""relume.Compressed: its arrays are read-only views of its own memory and hold what a direct
NumPy evaluation of R ~ W F + E needs; relighting (CPU reference and OpenCL, whole and batched,
with a residual cap, under a light moved by light_dir=) equals `relume relight` and that
evaluation; reconstruct equals `relume decompress`; export_npz writes what `relume export` does;
save and open round-trip; and bad input (exposures and light colours out of range among it) raises
relume errors."""
import json
import os

import numpy as np
import OpenImageIO as oiio
import pytest

import relume
from conftest import SMALL, cli_options, run_relume


@pytest.fixture(scope="module")
def light(field, sky_map):
    return relume.light_vector(field.directions, sky_map, rotate=30)


@pytest.fixture(scope="module")
def saved(compressed, tmp_path_factory):
    path = tmp_path_factory.mktemp("saved") / "scene.relume"
    compressed.save(path)
    return path


def numpy_relight(compressed, light, cap=None):
    """out[p] = W[s] . (F^k I[:, c]) + sum of the first `cap` residual entries E[s, e] I[e, c],
    projected onto >= 0 for a non-negative field under a non-negative light."""
    out = np.zeros(compressed.height * compressed.width * compressed.channels)
    offsets = compressed.residual_offsets
    for s, p in enumerate(compressed.stored_function):
        c = p % compressed.channels
        basis = compressed.bases[compressed.cluster[s]].astype(np.float64)
        value = compressed.weights[s].astype(np.float64) @ (basis @ light[:, c])
        end = offsets[s + 1] if cap is None else min(offsets[s + 1], offsets[s] + cap)
        entries = slice(offsets[s], end)
        value += compressed.residual_values[entries] @ light[compressed.residual_indices[entries], c]
        out[p] = value
    if compressed.non_negative and (light >= 0).all():
        out = np.maximum(out, 0)
    return out.reshape(compressed.height, compressed.width, compressed.channels)


def test_arrays_are_read_only_views_with_the_documented_shapes(compressed):
    c = compressed
    rows = c.stored_rows
    shapes = {"weights": (rows, c.terms), "bases": (c.clusters, c.terms, c.lights),
              "cluster": (rows,), "stored_function": (rows,), "residual_offsets": (rows + 1,),
              "mask": (c.height, c.width), "directions": (c.lights, 3)}
    for name, shape in shapes.items():
        view = getattr(c, name)
        assert view.shape == shape, name
        assert view.base is c, name
        assert not view.flags.writeable and not view.flags.owndata, name
        again = getattr(c, name)
        assert view.__array_interface__["data"][0] == again.__array_interface__["data"][0], name
    assert c.residual_offsets[-1] == c.residual_values.size == c.residual_indices.size
    assert c.weights.dtype == np.float32 and c.cluster.dtype == np.uint32
    with pytest.raises(ValueError):
        c.weights[0, 0] = 1


def test_cpu_reference_relight_equals_numpy_and_the_command(compressed, saved, light, tmp_path):
    relit = compressed.relight(light, reference=True)
    assert relit.shape == (compressed.height, compressed.width, compressed.channels)
    assert relit.dtype == np.float32
    np.testing.assert_allclose(relit, numpy_relight(compressed, light.astype(np.float64)),
                               rtol=1e-5, atol=1e-6)
    lights_file = tmp_path / "light.txt"
    np.savetxt(lights_file, light, fmt="%.9g")
    run_relume("relight", saved, "--lights", lights_file, "--cpu", "-o", tmp_path / "cli.exr")
    np.testing.assert_array_equal(relit, relume.read_image(tmp_path / "cli.exr"))


def test_opencl_relight_equals_the_command_and_the_reference(compressed, saved, light, tmp_path):
    relit = compressed.relight(light)
    np.testing.assert_allclose(relit, compressed.relight(light, reference=True), rtol=1e-4,
                               atol=1e-5)
    lights_file = tmp_path / "light.txt"
    np.savetxt(lights_file, light, fmt="%.9g")
    run_relume("relight", saved, "--lights", lights_file, "--residual", "2",
               "-o", tmp_path / "cli.exr")
    np.testing.assert_array_equal(compressed.relight(light, residual=2),
                                  relume.read_image(tmp_path / "cli.exr"))


def test_relight_under_a_moved_light_equals_the_command(compressed, saved, tmp_path):
    moved = dict(light_dir=(0.4, 0.5, 0.75), color=(1, 0.8, 0.6), spread=4)
    flags = ["--light-dir", "0.4,0.5,0.75", "--light-color", "1,0.8,0.6", "--spread", "4"]
    light = relume.light_vector(compressed.directions, **moved)
    for reference, device_flags in ((True, ["--cpu"]), (False, [])):
        relit = compressed.relight(**moved, reference=reference)
        np.testing.assert_array_equal(relit, compressed.relight(light, reference=reference))
        output = tmp_path / f"cli-{reference}.exr"
        run_relume("relight", saved, *flags, *device_flags, "-o", output)
        np.testing.assert_allclose(relit, oiio.ImageBuf(str(output)).get_pixels(oiio.FLOAT),
                                   rtol=1e-6, atol=1e-7)
    with pytest.raises(relume.Error, match="one of the two"):
        compressed.relight(light, light_dir=(0, 0, 1))
    with pytest.raises(relume.Error, match="one of the two"):
        compressed.relight()
    with pytest.raises(relume.Error, match="give light_dir="):
        compressed.relight(light, color=(2, 2, 2))


def test_a_residual_cap_uses_the_largest_entries_only(compressed, light):
    for cap in (0, 1, 3):
        np.testing.assert_allclose(compressed.relight(light, residual=cap, reference=True),
                                   numpy_relight(compressed, light.astype(np.float64), cap),
                                   rtol=1e-5, atol=1e-6)


def test_a_cap_of_the_longest_row_or_more_keeps_every_entry(compressed, field, light):
    longest = int(np.diff(compressed.residual_offsets).max())
    for cap in (longest, 2**31 - 1):
        for reference in (True, False):
            np.testing.assert_array_equal(
                compressed.relight(light, residual=cap, reference=reference),
                compressed.relight(light, reference=reference))
        np.testing.assert_array_equal(compressed.reconstruct(residual=cap).values,
                                      compressed.reconstruct().values)
        assert (relume.relative_error(field, compressed, residual=cap)
                == relume.relative_error(field, compressed))


def test_relight_batch_equals_one_relight_per_light(compressed, field, sky_map):
    lights = relume.light_vector(field.directions, sky_map, rotate=[0, 45, 90])
    for reference in (True, False):
        frames = compressed.relight_batch(lights, reference=reference)
        assert frames.shape == (3, compressed.height, compressed.width, compressed.channels)
        for frame, one in zip(frames, lights):
            np.testing.assert_allclose(frame, compressed.relight(one, reference=reference),
                                       rtol=1e-5, atol=1e-6)


def test_reconstruct_equals_the_command_decompress(compressed, saved, tmp_path):
    run_relume("decompress", saved, "-o", tmp_path / "back", "--residual", "2")
    ours = compressed.reconstruct(residual=2)
    assert isinstance(ours, relume.Field)
    np.testing.assert_array_equal(ours.values, relume.load(tmp_path / "back").values)
    full = compressed.reconstruct()
    assert not np.array_equal(full.values, ours.values)


def test_export_npz_writes_what_the_command_exports(compressed, saved, tmp_path):
    run_relume("export", saved, "--to", "npz", tmp_path / "cli.npz")
    opened = relume.open(saved)
    opened.export_npz(tmp_path / "ours.npz")
    assert (tmp_path / "ours.npz").read_bytes() == (tmp_path / "cli.npz").read_bytes()
    archive = np.load(tmp_path / "ours.npz")
    for ours, theirs in (("weights", "W"), ("bases", "F"), ("cluster", "cluster"),
                         ("residual_offsets", "residual_indptr"), ("dark_pixels", "dark_pixels"),
                         ("dark", "dark"), ("intensities", "intensities"), ("mask", "mask")):
        np.testing.assert_array_equal(getattr(compressed, ours), archive[theirs], ours)
    assert str(archive["transform"]) == "0" and compressed.transform == "identity"
    assert float(archive["weight_step"]) > 0, "the default storage is quantized"
    with pytest.raises(relume.FileError, match="no-folder"):
        opened.export_npz(tmp_path / "no-folder" / "x.npz")


def test_save_and_open_round_trip(compressed, saved, tmp_path):
    opened = relume.open(saved)
    for name in ("stored_function", "cluster", "weights", "bases", "residual_offsets",
                 "residual_indices", "residual_values", "mask", "directions", "intensities"):
        np.testing.assert_array_equal(getattr(opened, name), getattr(compressed, name), name)
    assert os.path.getsize(saved) == compressed.file_size()
    assert opened.parameters["seed"] == SMALL["seed"]
    assert opened.parameters["clusters_asked"] == SMALL["clusters"]
    info = json.loads(run_relume("info", saved, "--json").stdout)
    assert info["clusters"] == compressed.clusters


def test_default_storage_is_quantized_and_saved_as_such(compressed, tmp_path):
    assert compressed.weights_precision == "quantized"
    assert compressed.residual_precision == "quantized"
    compressed.save(tmp_path / "q.relume", weights_precision="float16")
    again = relume.open(tmp_path / "q.relume")
    assert again.weights_precision == "quantized", "a quantized field keeps its integers"
    np.testing.assert_array_equal(again.weights, compressed.weights)


def test_half_precision_is_smaller_and_close(field, tmp_path):
    compressed = relume.compress(field, **SMALL, weights_precision="float32",
                                 residual_precision="float32", bases_precision="float32")
    path = tmp_path / "half.relume"
    compressed.save(path, weights_precision="float16", residual_precision="float16")
    half = relume.open(path)
    assert half.weights_precision == "float16" and half.residual_precision == "float16"
    assert os.path.getsize(path) < compressed.file_size()
    assert os.path.getsize(path) == compressed.file_size(weights_precision="float16",
                                                         residual_precision="float16")
    np.testing.assert_allclose(half.weights, compressed.weights, rtol=1e-3, atol=1e-4)
    assert not np.array_equal(half.weights, compressed.weights)


def test_relative_error_equals_the_command_report(scene, field, tmp_path):
    report = tmp_path / "report.json"
    run_relume("compress", scene, "-o", tmp_path / "cli.relume", "--report", report,
               *cli_options(SMALL))
    ours = relume.relative_error(field, relume.open(tmp_path / "cli.relume"))
    assert ours == pytest.approx(json.loads(report.read_text())["error_masked"], rel=1e-12)
    assert 0 < ours < 1


def test_bad_relight_input_raises_relume_errors(compressed, light):
    with pytest.raises(relume.Error, match=r"light must have shape \(40, 3\), got \(39, 3\)"):
        compressed.relight(light[:39])
    bad = light.copy()
    bad[3, 1] = np.inf
    with pytest.raises(relume.Error, match=r"light\[3, 1\] is inf"):
        compressed.relight(bad)
    with pytest.raises(relume.Error, match=r"light must hold real numbers"):
        compressed.relight(light.astype(np.complex64))
    with pytest.raises(relume.Error, match=r"residual must be a count of entries >= 0"):
        compressed.relight(light, residual=-1)
    with pytest.raises(relume.Error, match="not both"):
        compressed.relight(light, device="pthread", reference=True)
    with pytest.raises(relume.Error, match="no-such-device"):
        compressed.relight(light, device="no-such-device")
    with pytest.raises(relume.Error, match=r"lights must have shape \(count, 40, 3\)"):
        compressed.relight_batch(light)


def test_exposures_and_light_colours_out_of_range_raise_relume_errors(compressed, tmp_path):
    # The background relights to 0, which 2**128 (Inf in float) once made NaN: a crash in the
    # 8-bit encoder. Such exposures, and colours that overflow relit floats, are refused.
    relit = compressed.relight(light_dir=(0, 0, 1))
    for exposure in (128, -41, float("nan"), float("inf")):
        with pytest.raises(relume.Error, match=r"stops is out of range \(from -40 to 40\)"):
            relume.write_image(tmp_path / "x.png", relit, exposure=exposure)
        assert not (tmp_path / "x.png").exists()
    relume.write_image(tmp_path / "x.png", relit, exposure=40)
    assert relume.read_image(tmp_path / "x.png").min() == 0
    with pytest.raises(relume.Error, match=r"non-negative numbers up to 1e\+06"):
        compressed.relight(light_dir=(0, 0, 1), color=(1e7, 1, 1))


# Edges (0, range limits, the largest doubles, overflow, inf and nan) and random magnitudes.
NUMBER_EDGES = (0.0, -0.0, 1.0, -1.0, 0.5, 40.0, 40.5, -41.0, 90.0, 91.0, 128.0, 1e-30, 1e-320,
                1e6, 1e7, 1e38, 1e39, 1e308, -1e308, float("inf"), float("-inf"), float("nan"))


def random_number(rng):
    if rng.random() < 0.5:
        return NUMBER_EDGES[rng.integers(len(NUMBER_EDGES))]
    return float(rng.choice((-1, 1)) * 10.0 ** rng.uniform(-12, 12))


def test_random_numbers_in_every_numeric_argument_relight_or_raise_relume_errors(compressed,
                                                                                  tmp_path):
    # Property (fixed seed): each numeric argument of relight, and write_image's exposure, given a
    # random number either gives finite pixels or raises relume.Error; none crashes.
    rng = np.random.default_rng(35)
    arguments = ("light_dir", "color", "spread", "residual", "exposure")
    for case in range(40):
        name = arguments[case % len(arguments)]
        call = {"light_dir": (0.0, 0.3, 1.0)}
        if name in ("light_dir", "color"):
            call[name] = tuple(random_number(rng) for _ in range(3))
        elif name == "spread":
            call[name] = random_number(rng)
        elif name == "residual":
            value = random_number(rng)
            call[name] = int(value) if np.isfinite(value) and abs(value) < 2**31 else -1
        try:
            relit = compressed.relight(**call, reference=case % 2 == 1)
            assert relit.shape[:2] == (compressed.height, compressed.width)
            assert np.isfinite(relit).all()
            if name == "exposure":
                relume.write_image(tmp_path / "x.png", relit, exposure=random_number(rng))
                assert relume.read_image(tmp_path / "x.png").shape[:2] == relit.shape[:2]
        except relume.Error:
            pass


def test_bad_files_raise_file_errors(saved, tmp_path):
    with pytest.raises(relume.FileError) as raised:
        relume.open(tmp_path / "missing.relume")
    assert isinstance(raised.value, OSError) and isinstance(raised.value, relume.Error)
    assert "missing.relume" in str(raised.value)
    truncated = tmp_path / "truncated.relume"
    truncated.write_bytes(saved.read_bytes()[:-100])
    with pytest.raises(relume.FileError, match="truncated.relume"):
        relume.open(truncated)
    with pytest.raises(relume.FileError, match="no-folder"):
        relume.open(tmp_path / "no-folder" / "x.relume")
    compressed = relume.open(saved)
    with pytest.raises(relume.FileError):
        compressed.save(tmp_path / "no-folder" / "x.relume")
