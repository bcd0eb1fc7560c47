#!/usr/bin/python3
"""Independent check of the error that `relume compress` reports (paper Eq. 16).

Reads an original DiLiGenT-layout field folder (images listed in filenames.txt or numbered
1.png, 2.png, ...; optional light_intensities.txt and mask.png) and a folder written by
`relume decompress`, with NumPy and OpenImageIO's Python bindings only (none of relume's code),
and prints Eq. 16 over the functions inside the original mask:

    err = (1/n) sum_p ( sum_i (R[p,i] - R~[p,i])^2 / sum_i R[p,i]^2 )

where p runs over every pixel and colour channel inside the mask whose energy sum_i R[p,i]^2 is
not zero (zero-energy functions are left out and counted, as relume does). Integer images are
linear values scaled to [0, 1] by their type's maximum, then divided per channel by their row of
light_intensities.txt.

Usage: scripts/check_error.py ORIGINAL_FOLDER DECOMPRESSED_FOLDER
"""
import os
import sys

import numpy as np
import OpenImageIO as oiio


def read_image(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"check_error: cannot read {path}: {oiio.geterror()}")
    pixels = image.read_image(format=oiio.FLOAT)  # integer formats come back scaled to [0, 1]
    image.close()
    if pixels is None:
        sys.exit(f"check_error: cannot decode {path}")
    return np.asarray(pixels, dtype=np.float64)


IMAGE_EXTENSIONS = {".png", ".exr", ".hdr", ".tif", ".tiff", ".jpg", ".jpeg", ".pfm"}


def image_names(folder):
    """The images in light order: filenames.txt, else the numbered images by number, as relume."""
    listing = os.path.join(folder, "filenames.txt")
    if os.path.exists(listing):
        with open(listing) as names:
            return [line.strip() for line in names if line.strip()]
    numbered = [name for name in os.listdir(folder)
                if os.path.splitext(name)[0].isdigit()
                and os.path.splitext(name)[1].lower() in IMAGE_EXTENSIONS]
    if not numbered:
        sys.exit(f"check_error: {folder} has no filenames.txt and no numbered images")
    return sorted(numbered, key=lambda name: (int(os.path.splitext(name)[0]), name))


def load_field(folder):
    """The field as (pixels, channels, lights) in float64."""
    names = image_names(folder)
    stack = np.stack([read_image(os.path.join(folder, name)) for name in names], axis=-1)
    intensities_file = os.path.join(folder, "light_intensities.txt")
    if os.path.exists(intensities_file):
        intensities = np.loadtxt(intensities_file, ndmin=2)  # lights x RGB
        stack = stack / intensities.T[np.newaxis, np.newaxis, : stack.shape[2], :]
    height, width, channels, lights = stack.shape
    return stack.reshape(height * width, channels, lights)


def load_mask(folder, pixels):
    path = os.path.join(folder, "mask.png")
    if not os.path.exists(path):
        return np.ones(pixels, dtype=bool)
    mask = read_image(path)
    return mask.reshape(pixels, -1).max(axis=1) > 0


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    original_folder, decompressed_folder = sys.argv[1:]
    original = load_field(original_folder)
    decompressed = load_field(decompressed_folder)
    if original.shape != decompressed.shape:
        sys.exit(f"check_error: shapes differ: {original.shape} vs {decompressed.shape}")
    inside = load_mask(original_folder, original.shape[0])
    R = original[inside].reshape(-1, original.shape[2])
    approximation = decompressed[inside].reshape(-1, original.shape[2])
    energy = (R**2).sum(axis=1)
    stored = energy > 0
    per_function = ((R - approximation) ** 2).sum(axis=1)[stored] / energy[stored]
    print(f"functions inside the mask: {R.shape[0]}, zero-energy skipped: {int((~stored).sum())}")
    print(f"error_masked (Eq. 16): {per_function.mean():.8g}")


if __name__ == "__main__":
    try:
        main()
    except (OSError, ValueError) as error:  # a missing listing, a malformed intensities file
        sys.exit(f"check_error: {error}")
