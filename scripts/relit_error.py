#!/usr/bin/python3
"""Relit-image error for the codec benchmark (issue 32): a field's 8-bit light images relit with
a light vector (`relume lights` rows: one r g b weight per light, '#' lines skipped) are the
reference; an image relit from a compressed form is scored by its relative squared error
sum((relit - reference)^2) / sum(reference^2) over the whole frame. The light images count as
linear, value / 255, as `relume compress --linear` reads them. scripts/codec_curve.py imports
these functions (the light images' reader among them) for the codecs' decoded images; the command
form scores relume's relit EXR.

Example:
  relume relight ball.relume --lights grace.txt -o relit.exr
  scripts/relit_error.py ball8/ grace.txt relit.exr
"""
import glob
import os
import sys

import numpy as np
import OpenImageIO as oiio


def light_vector(path):
    rows = [line.split() for line in open(path) if line.strip() and not line.startswith("#")]
    vector = np.array(rows, dtype=np.float32)
    if vector.ndim != 2 or vector.shape[1] != 3:
        sys.exit(f"relit_error.py: {path}: expected rows of r g b, got shape {vector.shape}")
    return vector  # lights x 3


def planar(images):
    """lights x H x W x 3 (0..255) -> 3 x lights x (H x W) float32, value / 255: each channel's
    images as one matrix, the layout in which a relight is one matrix-vector product."""
    lights, height, width, _ = images.shape
    return np.ascontiguousarray(
        np.moveaxis(images, 3, 0).reshape(3, lights, height * width), dtype=np.float32) / 255.0


def relight(planes, vector, height, width):
    """planes: planar()'s; the relit H x W x 3 (float32 products, one BLAS GEMV per channel)."""
    if len(vector) != planes.shape[1]:
        sys.exit(f"relit_error.py: {len(vector)} light weights for {planes.shape[1]} light images")
    return np.stack([vector[:, c] @ planes[c] for c in range(3)], axis=-1).reshape(
        height, width, 3)


def relative_error(relit, reference):
    relit, reference = relit.astype(np.float64), reference.astype(np.float64)
    return float(((relit - reference) ** 2).sum() / max((reference ** 2).sum(), 1e-30))


def read_rgb(path, pixel_format):
    """The first three channels of an image file as pixel_format (oiio.UINT8, oiio.FLOAT)."""
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"cannot read {path}: {oiio.geterror()}")
    pixels = image.read_image(pixel_format)
    image.close()
    return pixels[..., :3]


def light_images(folder):
    names = sorted(f for f in glob.glob(os.path.join(folder, "*.png"))
                   if os.path.basename(f)[0].isdigit())
    if not names:
        sys.exit(f"{folder}: no numbered PNG light images")
    return np.stack([read_rgb(name, oiio.UINT8) for name in names])  # lights x H x W x 3, uint8


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    folder, vector_path, relit_path = sys.argv[1:]
    images = light_images(folder)
    reference = relight(planar(images), light_vector(vector_path), *images.shape[1:3])
    print(relative_error(read_rgb(relit_path, oiio.FLOAT), reference))


if __name__ == "__main__":
    main()
