"""relume.light_vector and relume.sky: equal to `relume lights` and `relume sky` (for a map and
for a moved light, with the command's defaults), a map given as an array equals the same map read
from its file, a sequence of angles or of directions equals one call each, a direction outside
the lights warns, and bad maps, layouts, angles and moved lights raise relume errors."""
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


def test_a_moved_light_equals_the_command(scene, field, tmp_path):
    run_relume("lights", "--dirs", scene / "light_directions.txt", "--light-dir", "0.5,0.3,0.8",
               "--light-color", "1,0.9,0.8", "--spread", "5", "-o", tmp_path / "moved.txt")
    ours = relume.light_vector(field.directions, light_dir=(0.5, 0.3, 0.8), color=(1, 0.9, 0.8),
                               spread=5)
    assert ours.shape == (40, 3) and ours.dtype == np.float32
    np.testing.assert_array_equal(ours, np.loadtxt(tmp_path / "moved.txt", dtype=np.float32))
    # The defaults are the command's: a white point light.
    run_relume("lights", "--dirs", scene / "light_directions.txt", "--light-dir", "-1,0.2,0.4",
               "-o", tmp_path / "point.txt")
    point = relume.light_vector(field.directions, light_dir=[-1, 0.2, 0.4])
    np.testing.assert_array_equal(point, np.loadtxt(tmp_path / "point.txt", dtype=np.float32))
    assert np.count_nonzero(point[:, 0]) <= 3
    np.testing.assert_allclose(point.sum(axis=0), 1, rtol=1e-6)


def test_directions_stack_and_one_outside_the_lights_warns(field):
    directions = [[0.5, 0.3, 0.8], [0, 1, 0], [-0.2, -0.4, 0.9]]
    stacked = relume.light_vector(field.directions, light_dir=directions, spread=3)
    assert stacked.shape == (3, 40, 3)
    for direction, one in zip(directions, stacked):
        np.testing.assert_array_equal(
            one, relume.light_vector(field.directions, light_dir=direction, spread=3))
    front = field.directions[field.directions[:, 2] > 0.3]
    with pytest.warns(UserWarning, match="1 of 1 light directions lie outside"):
        behind = relume.light_vector(front, light_dir=(0, 0, -1))
    np.testing.assert_allclose(behind.sum(axis=0), 1, rtol=1e-6)


def test_bad_moved_lights_raise_relume_errors(field, sky_map):
    dirs = field.directions
    with pytest.raises(relume.Error, match="one of the two"):
        relume.light_vector(dirs, sky_map, light_dir=(0, 0, 1))
    with pytest.raises(relume.Error, match="one of the two"):
        relume.light_vector(dirs)
    with pytest.raises(relume.Error, match="give light_dir="):
        relume.light_vector(dirs, sky_map, spread=5)
    with pytest.raises(relume.Error, match="between 0 and 90"):
        relume.light_vector(dirs, light_dir=(0, 0, 1), spread=95)
    with pytest.raises(relume.Error, match="zero or not finite"):
        relume.light_vector(dirs, light_dir=(0, 0, 0))
    with pytest.raises(relume.Error, match=r"light_dir\[1\] is nan"):
        relume.light_vector(dirs, light_dir=(0, float("nan"), 1))
    with pytest.raises(relume.Error, match=r"light_dir must have shape \(3,\)"):
        relume.light_vector(dirs, light_dir=(0, 1))
    with pytest.raises(relume.Error, match="non-negative"):
        relume.light_vector(dirs, light_dir=(0, 0, 1), color=(1, -1, 1))


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
