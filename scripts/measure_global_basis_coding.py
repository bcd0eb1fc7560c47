#!/usr/bin/python3
"""Measures one design for issue 32 before it is built: a global basis over the lights (no
clusters) whose per-pixel weight planes are coded in the camera domain by a real image coder.

Every function (pixel, channel) of a folder of 8-bit light images is projected onto the k leading
eigenvectors of the lights' second-moment matrix; the three channels' weights go through a colour
transform (mean, R - G, G - B); each component's k weight planes are tiled into one mosaic and
coded with JPEG 2000 (OpenJPEG's opj_compress, irreversible 9/7, compression ratio R for the
mean and 3R for the differences), decoded with opj_decompress, and the light images rebuilt.
Bytes = the three codestreams + the basis as 16-bit values. PSNR as issue 32 defines it: on the
8-bit scale per light image, then averaged, over the whole frame and inside a mask.

Needs numpy, OpenImageIO's Python module and `opj_compress` (Debian: libopenjp2-tools).
Example (the whole-frame ball of docs/compression.md):
  scripts/normalize_to_8bit.py ../shared/data/olat/diligent-ball-16bit ball8 --no-mask
  scripts/measure_global_basis_coding.py ball8 ../shared/data/olat/diligent-ball-16bit/mask.png \
      --terms 24,48 --ratios 300,1000
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

COLOUR = np.array([[1 / 3, 1 / 3, 1 / 3], [1, -1, 0], [0, 1, -1]])


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


def write_pgm16(path, values):
    height, width = values.shape
    with open(path, "wb") as out:
        out.write(b"P5\n%d %d\n65535\n" % (width, height))
        out.write(values.astype(">u2").tobytes())


def read_pgm16(path):
    data = open(path, "rb").read()
    fields, position = [], 0
    while len(fields) < 4:  # magic, width, height, maximum; comment lines skipped
        end = data.index(b"\n", position)
        line, position = data[position:end], end + 1
        if not line.startswith(b"#"):
            fields += line.split()
    width, height = int(fields[1]), int(fields[2])
    return np.frombuffer(data[position:position + 2 * width * height], ">u2").reshape(height, width)


def code_planes(planes, ratio, scratch):
    """The planes (k x H x W) tiled into one mosaic, coded at `ratio`, decoded; (planes, bytes)."""
    k, height, width = planes.shape
    columns = int(np.ceil(np.sqrt(k)))
    rows = int(np.ceil(k / columns))
    mosaic = np.zeros((rows * height, columns * width))
    tiles = [(j // columns * height, j % columns * width) for j in range(k)]
    for plane, (y, x) in zip(planes, tiles):
        mosaic[y:y + height, x:x + width] = plane
    scale = max(np.abs(mosaic).max(), 1e-30) / 32000.0
    write_pgm16(f"{scratch}/plane.pgm", np.round(mosaic / scale + 32768))
    subprocess.run(["opj_compress", "-i", f"{scratch}/plane.pgm", "-o", f"{scratch}/plane.j2k",
                    "-I", "-r", str(ratio), "-n", "6"], check=True, capture_output=True)
    subprocess.run(["opj_decompress", "-i", f"{scratch}/plane.j2k", "-o", f"{scratch}/back.pgm"],
                   check=True, capture_output=True)
    decoded = (read_pgm16(f"{scratch}/back.pgm").astype(np.float64) - 32768) * scale
    return (np.stack([decoded[y:y + height, x:x + width] for y, x in tiles]),
            os.path.getsize(f"{scratch}/plane.j2k"))


def psnr_8bit(rebuilt8, reference8, where):
    mse = ((rebuilt8 - reference8) ** 2)[:, where].reshape(len(reference8), -1).mean(axis=1)
    return float(np.mean(10 * np.log10(255.0 ** 2 / np.maximum(mse, 1e-12))))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("lights", help="folder of numbered 8-bit PNG light images")
    parser.add_argument("mask", help="PNG mask for the second PSNR")
    parser.add_argument("--terms", default="24,48", help="basis sizes k, comma-separated")
    parser.add_argument("--ratios", default="300,1000", help="JPEG 2000 ratios of the mean")
    args = parser.parse_args()
    if shutil.which("opj_compress") is None:
        sys.exit("opj_compress not found: apt-get install libopenjp2-tools")
    images = read_lights(args.lights)
    lights, height, width, channels = images.shape
    mask = read_float(args.mask).reshape(height, width, -1)[..., 0] > 0.5
    functions = images.transpose(1, 2, 3, 0).reshape(-1, lights).astype(np.float64)
    eigenvalues, eigenvectors = np.linalg.eigh(functions.T @ functions)
    basis = eigenvectors[:, np.argsort(eigenvalues)[::-1]].T
    reference8 = np.clip(np.round(images * 255), 0, 255)
    frame = np.ones((height, width), bool)
    with tempfile.TemporaryDirectory() as scratch:
        for k in (int(t) for t in args.terms.split(",")):
            weights = (functions @ basis[:k].T).reshape(height, width, channels, k)
            components = np.einsum("ij,hwjk->hwik", COLOUR, weights)
            for ratio in (float(r) for r in args.ratios.split(",")):
                decoded = np.empty_like(components)
                total = k * lights * 2  # the basis as 16-bit values
                for c in range(3):
                    planes, size = code_planes(components[:, :, c, :].transpose(2, 0, 1),
                                               ratio * (1 if c == 0 else 3), scratch)
                    decoded[:, :, c, :] = planes.transpose(1, 2, 0)
                    total += size
                rebuilt = np.einsum("ij,hwjk->hwik", np.linalg.inv(COLOUR), decoded)
                rebuilt = (rebuilt.reshape(-1, k) @ basis[:k]).reshape(height, width, channels,
                                                                       lights)
                rebuilt8 = np.clip(np.round(rebuilt.transpose(3, 0, 1, 2) * 255), 0, 255)
                print(f"k {k}, ratio {ratio:g}: {total} bytes, {total / (height * width):.4f} "
                      f"B/px, whole frame {psnr_8bit(rebuilt8, reference8, frame):.2f} dB, "
                      f"mask {psnr_8bit(rebuilt8, reference8, mask):.2f} dB", flush=True)


if __name__ == "__main__":
    main()
