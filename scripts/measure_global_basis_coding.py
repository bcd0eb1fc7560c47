#!/usr/bin/python3
"""Measures one design for issue 32 before it is built: a global basis over the lights (no
clusters) whose per-pixel weight planes are coded in the camera domain by a real image coder.

Every function (pixel, channel) of a folder of 8-bit light images is projected onto the k leading
eigenvectors of the lights' second-moment matrix, stored as B-bit integers (one scale per row) and
zstd; the three channels' weights go through an orthonormal colour transform (luma, R - G,
R + G - 2B, each of unit length). Both transforms are orthonormal, so a weight error costs the same
squared error in the light images whatever plane it is in. Every one of the 3k weight planes is
one component of a single JPEG 2000 codestream (OpenJPEG's opj_compress, irreversible 9/7, no
colour transform of its own, compression ratio R), so the coder's rate allocation (PCRD) spends
the bytes over terms and colours by exactly the squared error that PSNR measures: no weighting to
choose. Decoded with opj_decompress, the light images are rebuilt. Bytes = the codestream + the
coded basis + its scales. PSNR as issue 32 defines it: on the 8-bit scale per light image, then
averaged, over the whole frame and inside a mask.

Needs numpy, OpenImageIO's Python module, `opj_compress` (Debian: libopenjp2-tools) and `zstd`.
Example (the whole-frame ball of docs/compression.md):
  scripts/normalize_to_8bit.py ../shared/data/olat/diligent-ball-16bit ball8 --no-mask
  scripts/measure_global_basis_coding.py ball8 ../shared/data/olat/diligent-ball-16bit/mask.png \
      --terms 48,96 --ratios 4000,8000
"""
import argparse
import glob
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

# Orthonormal rows: luma, red - green, red + green - 2 blue.
COLOUR = np.array([[1, 1, 1], [1, -1, 0], [1, 1, -2]], float)
COLOUR /= np.linalg.norm(COLOUR, axis=1, keepdims=True)


def read_float(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"cannot read {path}: {oiio.geterror()}")
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    return pixels


def read_lights(folder):
    names = sorted(f for f in glob.glob(os.path.join(folder, "*.png"))
                   if os.path.basename(f)[0].isdigit())
    if not names:
        sys.exit(f"{folder}: no numbered PNG light images")
    return np.stack([read_float(name)[..., :3] for name in names])  # lights x H x W x 3


def coded_basis(basis, bits, scratch):
    """The basis rows as `bits`-bit integers times one scale per row: (values, bytes coded)."""
    scales = np.abs(basis).max(axis=1, keepdims=True) / (2 ** (bits - 1) - 1)
    integers = np.round(basis / scales)
    integers.astype("<i2").tofile(f"{scratch}/basis.raw")
    subprocess.run(["zstd", "-q", "-f", "-19", f"{scratch}/basis.raw", "-o",
                    f"{scratch}/basis.zst"], check=True)
    return integers * scales, os.path.getsize(f"{scratch}/basis.zst") + 4 * len(basis)


def code_planes(planes, ratio, scratch):
    """The planes (n x H x W), each a component of one codestream, coded at `ratio`, decoded;
    (planes, bytes)."""
    count, height, width = planes.shape
    step = max(np.abs(planes).max(), 1e-30) / 32000.0
    np.round(planes / step).astype(">i2").tofile(f"{scratch}/planes.raw")
    subprocess.run(["opj_compress", "-i", f"{scratch}/planes.raw", "-o", f"{scratch}/planes.j2k",
                    "-F", f"{width},{height},{count},16,s", "-I", "-mct", "0", "-r", str(ratio),
                    "-n", "6"], check=True, capture_output=True)
    subprocess.run(["opj_decompress", "-i", f"{scratch}/planes.j2k", "-o",
                    f"{scratch}/back.raw"], check=True, capture_output=True)
    decoded = np.fromfile(f"{scratch}/back.raw", "<i2").reshape(count, height, width) * step
    return decoded, os.path.getsize(f"{scratch}/planes.j2k")


def psnr_8bit(rebuilt8, reference8, where):
    mse = ((rebuilt8 - reference8) ** 2)[:, where].reshape(len(reference8), -1).mean(axis=1)
    return float(np.mean(10 * np.log10(255.0 ** 2 / np.maximum(mse, 1e-12))))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("lights", help="folder of numbered 8-bit PNG light images")
    parser.add_argument("mask", help="PNG mask for the second PSNR")
    parser.add_argument("--terms", default="48,96", help="basis sizes k, comma-separated")
    parser.add_argument("--ratios", default="4000,8000", help="JPEG 2000 compression ratios")
    parser.add_argument("--basis-bits", type=int, default=12, help="bits per basis value")
    args = parser.parse_args()
    for tool, package in (("opj_compress", "libopenjp2-tools"), ("zstd", "zstd")):
        if shutil.which(tool) is None:
            sys.exit(f"{tool} not found: apt-get install {package}")
    images = read_lights(args.lights)
    lights, height, width, channels = images.shape
    if channels != 3:
        sys.exit(f"{args.lights}: the colour transform needs RGB images, got {channels} channels")
    mask = read_float(args.mask).reshape(height, width, -1)[..., 0] > 0.5
    functions = images.transpose(1, 2, 3, 0).reshape(-1, lights).astype(np.float64)
    eigenvalues, eigenvectors = np.linalg.eigh(functions.T @ functions)
    leading = eigenvectors[:, np.argsort(eigenvalues)[::-1]].T
    reference8 = np.clip(np.round(images * 255), 0, 255)
    frame = np.ones((height, width), bool)
    with tempfile.TemporaryDirectory() as scratch:
        for k in (int(t) for t in args.terms.split(",")):
            basis, basis_bytes = coded_basis(leading[:k], args.basis_bits, scratch)
            weights = (functions @ basis.T).reshape(height, width, channels, k)
            planes = np.einsum("ij,hwjk->ikhw", COLOUR, weights).reshape(3 * k, height, width)
            for ratio in (float(r) for r in args.ratios.split(",")):
                decoded, plane_bytes = code_planes(planes, ratio, scratch)
                rebuilt = np.einsum("ji,jkhw->hwik", COLOUR, decoded.reshape(3, k, height, width))
                rebuilt = (rebuilt.reshape(-1, k) @ basis).reshape(height, width, channels, lights)
                rebuilt8 = np.clip(np.round(rebuilt.transpose(3, 0, 1, 2) * 255), 0, 255)
                total = plane_bytes + basis_bytes
                print(f"k {k}, ratio {ratio:g}: {total} bytes ({basis_bytes} basis), "
                      f"{total / (height * width):.4f} B/px, whole frame "
                      f"{psnr_8bit(rebuilt8, reference8, frame):.2f} dB, "
                      f"mask {psnr_8bit(rebuilt8, reference8, mask):.2f} dB", flush=True)


if __name__ == "__main__":
    main()
