"""relume.light_vector and relume.sky: equal to `relume lights` and `relume sky`, a map given as
an array equals the same map read from its file, a sequence of angles equals one call per angle,
and bad maps, layouts and angles raise relume errors."""
import numpy as np
import pytest

import relume
from conftest import run_relume


def test_equals_the_command(scene, field, sky_map, tmp_path):
    run_relume("lights", "--dirs", scene / "light_directions.txt", "--env", sky_map,
               "--rotate", "30", "-o", tmp_path / "lights.txt")
    ours = relume.light_vector(field.directions, sky_map, rotate=30)
    assert ours.shape == (40, 3) and ours.dtype == np.float32
    np.testing.assert_array_equal(ours, np.loadtxt(tmp_path / "lights.txt", dtype=np.float32))
    assert ours.sum() > 0


def test_an_array_map_equals_its_file_and_angles_stack(field, sky_map):
    from_file = relume.light_vector(field.directions, sky_map, rotate=45)
    radiance = relume.read_image(sky_map)
    np.testing.assert_array_equal(relume.light_vector(field.directions, radiance, rotate=45),
                                  from_file)
    np.testing.assert_array_equal(
        relume.light_vector(field.directions, radiance, rotate=45, layout="latlong"), from_file)
    angles = [0, 45, 90.5]
    stacked = relume.light_vector(field.directions, sky_map, rotate=angles)
    assert stacked.shape == (3, 40, 3)
    for angle, one in zip(angles, stacked):
        np.testing.assert_array_equal(one, relume.light_vector(field.directions, sky_map,
                                                               rotate=angle))


def test_sky_equals_the_command(sky_map):
    sky = relume.sky(width=64)
    assert sky.shape == (32, 64, 3) and sky.dtype == np.float32
    np.testing.assert_array_equal(sky, relume.read_image(sky_map))


def test_bad_maps_and_angles_raise_relume_errors(field, sky_map, tmp_path):
    with pytest.raises(relume.FileError, match="missing.exr"):
        relume.light_vector(field.directions, tmp_path / "missing.exr")
    radiance = relume.read_image(sky_map)
    with pytest.raises(relume.Error, match="angular"):
        relume.light_vector(field.directions, radiance, layout="angular")
    with pytest.raises(relume.Error, match="panorama"):
        relume.light_vector(field.directions, radiance, layout="panorama")
    with pytest.raises(relume.Error, match="the env array"):
        relume.light_vector(field.directions, radiance[:, :50])
    bad = radiance.copy()
    bad[3, 4, 2] = np.nan
    with pytest.raises(relume.Error, match=r"env\[3, 4, 2\] is nan"):
        relume.light_vector(field.directions, bad)
    with pytest.raises(relume.Error, match=r"rotate\[1\] is nan"):
        relume.light_vector(field.directions, sky_map, rotate=[0, float("nan")])
    with pytest.raises(relume.Error, match=r"rotate must have shape a number or a sequence"):
        relume.light_vector(field.directions, sky_map, rotate=[[0, 1]])
    with pytest.raises(relume.Error, match="sky width must be an even number"):
        relume.sky(width=33)
