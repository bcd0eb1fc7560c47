"""Rebuilds, with NumPy alone, the images `relume decompress` writes from the .npz that `relume
export` writes, following the archive's own description: npz_export_test.cpp runs it to check
that the archive holds (and says) everything the field is rebuilt from.

    python3 rebuild_from_npz.py FIELD.npz IMAGES.npy

writes the image of every light, float64 (lights, height * width * channels), pixel-major."""
import sys

import numpy as np


def haar_inverse(values):
    """The inverse of the orthonormal Haar transform over the last axis: the forward levels (on
    n = lights, then ceil(n / 2), ... values while n > 1) undone from the shortest."""
    values = values.copy()
    lengths = []
    n = values.shape[-1]
    while n > 1:
        lengths.append(n)
        n = (n + 1) // 2
    for n in reversed(lengths):
        pairs, averages = n // 2, (n + 1) // 2
        average, detail = values[..., :pairs], values[..., averages:averages + pairs]
        level = np.empty_like(values[..., :n])
        level[..., 0:2 * pairs:2] = (average + detail) / np.sqrt(2)
        level[..., 1:2 * pairs:2] = (average - detail) / np.sqrt(2)
        if n % 2:
            level[..., n - 1] = values[..., pairs]
        values[..., :n] = level
    return values


def field_values(archive):
    """R, float64 (height * width * channels, lights), in field units and the light basis."""
    channels, lights = int(archive["channels"]), int(archive["lights"])
    values = np.zeros((int(archive["height"]) * int(archive["width"]) * channels, lights))
    cluster = archive["cluster"]
    stored = np.einsum("st,stl->sl", archive["W"].astype(np.float64),
                       archive["F"].astype(np.float64)[cluster])
    rows = np.repeat(np.arange(cluster.size), np.diff(archive["residual_indptr"].astype(np.int64)))
    np.add.at(stored, (rows, archive["residual_indices"]), archive["residual_data"])
    values[archive["stored_function"]] = stored
    dark_pixels = archive["dark_pixels"].astype(np.int64)
    if dark_pixels.size:
        gains = archive["dark_gains"].astype(np.float64)  # (n, channels)
        values[dark_pixels[:, None] * channels + np.arange(channels)] = (
            gains[:, :, None] * archive["dark"].astype(np.float64)[None, :, :])
    if int(archive["transform"]) == 1:
        values = haar_inverse(values)
    return values


def light_images(archive):
    """Every light's image, float64 (lights, functions): R[:, i] times light i's intensity."""
    intensities = archive["intensities"].astype(np.float64)
    channels = int(archive["channels"])
    if channels == 1:
        intensities = intensities.mean(axis=1, keepdims=True)
    images = field_values(archive).T.reshape(int(archive["lights"]), -1, channels)
    return (images * intensities[:, None, :]).reshape(images.shape[0], -1)


if __name__ == "__main__":
    np.save(sys.argv[2], light_images(np.load(sys.argv[1])))
