#!/usr/bin/python3
"""Writes an 8-bit copy of a DiLiGenT field folder the way RTI tools take such data (GUIDE 3b, the
compact-container benchmark): each image read at full depth, v / (2^bits - 1) (float images, such
as `relume synth`'s EXR, as they are), divided by its row of light_intensities.txt (per channel),
times GAIN, clipped to [0, 1], rounded to 8 bits, written as PNG under the image's name with the
extension .png. filenames.txt lists those names; light_directions.txt is copied,
light_intensities.txt is left out (the images are already divided by it), mask.png is copied
unless --no-mask. The folder is written as OUTPUT_FOLDER.part and renamed when complete (an
earlier OUTPUT_FOLDER replaced), so a failed or interrupted run leaves no folder that looks
done. Uses NumPy and OpenImageIO's Python bindings only, none of relume's code.

Usage: scripts/normalize_to_8bit.py INPUT_FOLDER OUTPUT_FOLDER [--gain 5.3396] [--no-mask]
"""
import argparse
import os
import shutil
import sys

import numpy as np
import OpenImageIO as oiio


def fail(message):
    print(f"normalize_to_8bit.py: {message}", file=sys.stderr)
    sys.exit(1)


def read_image(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        fail(f"cannot read {path}: {oiio.geterror()}")
    spec = image.spec()
    if spec.format.basetype in (oiio.HALF, oiio.FLOAT, oiio.DOUBLE):
        pixels = np.asarray(image.read_image(format=oiio.FLOAT), dtype=np.float64)
        image.close()
        if not np.isfinite(pixels).all():
            fail(f"{path}: {np.count_nonzero(~np.isfinite(pixels))} values are NaN or infinite")
        return pixels
    bits = 16 if spec.format == oiio.UINT16 else 8
    pixels = image.read_image(format=oiio.UINT16 if bits == 16 else oiio.UINT8)
    image.close()
    return np.asarray(pixels, dtype=np.float64) / (2**bits - 1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--gain", type=float, default=5.3396)
    parser.add_argument("--no-mask", action="store_true")
    args = parser.parse_args()
    names_file = os.path.join(args.input, "filenames.txt")
    if not os.path.isfile(names_file):
        fail(f"{names_file} not found: expected a DiLiGenT folder")
    names = open(names_file).read().split()
    intensities = np.loadtxt(os.path.join(args.input, "light_intensities.txt"), ndmin=2)
    if intensities.shape != (len(names), 3):
        fail(f"light_intensities.txt has shape {intensities.shape}, expected ({len(names)}, 3)")
    final_output, args.output = args.output, args.output.rstrip("/") + ".part"
    shutil.rmtree(args.output, ignore_errors=True)
    os.makedirs(args.output)
    written = []
    for i, name in enumerate(names):
        values = read_image(os.path.join(args.input, name))[..., :3] / intensities[i] * args.gain
        eight_bit = np.round(np.clip(values, 0, 1) * 255).astype(np.uint8)
        png_name = os.path.splitext(name)[0] + ".png"
        out = oiio.ImageOutput.create(os.path.join(args.output, png_name))
        spec = oiio.ImageSpec(eight_bit.shape[1], eight_bit.shape[0], 3, oiio.UINT8)
        if not out.open(os.path.join(args.output, png_name), spec) or not out.write_image(eight_bit):
            fail(f"cannot write {png_name}: {out.geterror()}")
        out.close()
        written.append(png_name)
    with open(os.path.join(args.output, "filenames.txt"), "w") as listing:
        listing.write("\n".join(written) + "\n")
    shutil.copy(os.path.join(args.input, "light_directions.txt"), args.output)
    if not args.no_mask and os.path.isfile(os.path.join(args.input, "mask.png")):
        shutil.copy(os.path.join(args.input, "mask.png"), args.output)
    shutil.rmtree(final_output, ignore_errors=True)
    os.rename(args.output, final_output)
    print(f"wrote {len(names)} 8-bit images to {final_output}")


if __name__ == "__main__":
    main()
