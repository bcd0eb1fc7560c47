"""relume.Field and relume.load: the arrays are read-only views of the field's memory holding
the images as relume.read_image reads them; a Field made from arrays copies them once and
round-trips through save and load; the uncompressed relighting (under a light vector or a moved
light) equals `relume relight`; bad arrays and bad folders raise relume errors naming what is
wrong."""
import numpy as np
import OpenImageIO as oiio
import pytest

import relume
from conftest import run_relume


def test_load_gives_views_of_the_images(scene, field):
    assert (field.height, field.width, field.channels, field.lights) == (24, 32, 3, 40)
    values = field.values
    assert values.shape == (24, 32, 3, 40) and values.dtype == np.float32
    assert values.base is field and not values.flags.writeable
    assert values.__array_interface__["data"][0] == field.values.__array_interface__["data"][0]
    for i in (0, 17, 39):
        image = relume.read_image(scene / field.image_names[i])
        np.testing.assert_array_equal(values[..., i], image / field.intensities[i])
    np.testing.assert_allclose(np.linalg.norm(field.directions, axis=1), 1, rtol=1e-6)
    assert field.mask.shape == (24, 32) and field.mask.dtype == np.uint8
    assert set(np.unique(field.mask)) <= {0, 1}


def test_a_field_from_arrays_copies_once_and_round_trips(field, tmp_path):
    values = np.array(field.values)
    made = relume.Field(values, field.directions * 3.0)
    np.testing.assert_array_equal(made.values, values)
    assert not np.shares_memory(made.values, values)
    np.testing.assert_allclose(made.directions, field.directions, rtol=1e-6)
    np.testing.assert_array_equal(made.mask, np.ones((24, 32), np.uint8))
    np.testing.assert_array_equal(made.intensities, np.ones((40, 3), np.float32))
    strided = relume.Field(np.asfortranarray(values), field.directions)
    np.testing.assert_array_equal(strided.values, values)

    mask = np.zeros((24, 32), bool)
    mask[4:20, 6:30] = True
    made = relume.Field(values, field.directions, mask=mask, intensities=np.full((40, 3), 2.0))
    made.save(tmp_path / "folder")
    back = relume.load(tmp_path / "folder")
    np.testing.assert_array_equal(back.values, made.values)
    np.testing.assert_array_equal(back.mask, mask.astype(np.uint8))
    np.testing.assert_array_equal(back.intensities, made.intensities)


def test_uncompressed_relight_equals_the_command(scene, field, sky_map, tmp_path):
    light = relume.light_vector(field.directions, sky_map)
    np.savetxt(tmp_path / "light.txt", light, fmt="%.9g")
    run_relume("relight", scene, "--lights", tmp_path / "light.txt", "-o", tmp_path / "cli.exr")
    relit = field.relight(light)
    np.testing.assert_array_equal(relit, relume.read_image(tmp_path / "cli.exr"))
    expected = np.einsum("ywci,ic->ywc", field.values.astype(np.float64), light)
    np.testing.assert_allclose(relit, expected, rtol=1e-5, atol=1e-7)


def test_relight_under_a_moved_light_equals_the_command(scene, field, tmp_path):
    run_relume("relight", scene, "--light-dir", "-0.3,0.6,0.7", "--spread", "8",
               "-o", tmp_path / "cli.exr")
    relit = field.relight(light_dir=(-0.3, 0.6, 0.7), spread=8) * field.mask[..., None]
    np.testing.assert_allclose(relit, oiio.ImageBuf(str(tmp_path / "cli.exr")).get_pixels(
        oiio.FLOAT), rtol=1e-6, atol=1e-7)
    light = relume.light_vector(field.directions, light_dir=(-0.3, 0.6, 0.7), spread=8)
    np.testing.assert_array_equal(field.relight(light_dir=(-0.3, 0.6, 0.7), spread=8),
                                  field.relight(light))
    with pytest.raises(relume.Error, match="one of the two"):
        field.relight(light, light_dir=(0, 0, 1))


def test_bad_arrays_are_refused_naming_the_fault(field):
    values = np.array(field.values)
    with pytest.raises(relume.Error, match=r"must hold float32 \(convert with .astype"):
        relume.Field(values.astype(np.float16), field.directions)
    with pytest.raises(relume.Error, match=r"must have shape \(height, width, channels, lights\), "
                                           r"got \(24, 32, 120\)"):
        relume.Field(values.reshape(24, 32, 120), field.directions)
    bad = values.copy()
    bad[0, 0, 0, 0] = -np.inf
    with pytest.raises(relume.Error, match=r"field values\[0, 0, 0, 0\] is -inf"):
        relume.Field(bad, field.directions)
    dirs = np.array(field.directions)
    dirs[5] = 0
    with pytest.raises(relume.Error, match=r"dirs\[5\] has zero length"):
        relume.Field(values, dirs)
    with pytest.raises(relume.Error, match=r"dirs must have shape \(lights, 3\), got \(40, 2\)"):
        relume.Field(values, dirs[:, :2])
    with pytest.raises(relume.Error, match=r"mask must hold bool or integers, got dtype float64"):
        relume.Field(values, field.directions, mask=np.ones((24, 32)))
    with pytest.raises(relume.Error, match=r"intensities must have shape \(40, 3\)"):
        relume.Field(values, field.directions, intensities=np.ones((41, 3)))
    with pytest.raises(relume.Error, match=r"dirs must hold real numbers .*, got dtype object"):
        relume.Field(values, object())


def test_bad_folders_raise_file_errors(scene, tmp_path):
    with pytest.raises(relume.FileError) as raised:
        relume.load(tmp_path / "nothing-here")
    assert isinstance(raised.value, OSError)
    assert "nothing-here" in str(raised.value)
    broken = tmp_path / "broken"
    broken.mkdir()
    for name in ("001.exr", "002.exr"):
        (broken / name).write_bytes((scene / name).read_bytes())
    (broken / "light_directions.txt").write_text("0 0 1\n0 zero 1\n")
    with pytest.raises(relume.FileError, match=r"light_directions.txt.*2"):
        relume.load(broken)
