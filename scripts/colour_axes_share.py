#!/usr/bin/python3
"""How much of each term of a one-basis container's weights falls outside the first colour plane,
with the fixed transform (luma, R - G, R + G - 2B) and with the term's own principal axes (what
container version 6 stores, lib/model/weight_planes.hpp). The weights are those of `relume export
C.relume --to npz C.npz` (three channels, every pixel's channels stored). Prints one line per
term asked: the share of its energy outside the first plane and in the third, for both.

Example (docs/compression.md, "Each term's own colour transform"):
  relume export ball_0.1.relume ball.npz && scripts/colour_axes_share.py ball.npz 0,1,2,20,47
"""
import argparse
import sys

import numpy as np

FIXED = np.array([[1, 1, 1], [1, -1, 0], [1, 1, -2]], float)
FIXED /= np.linalg.norm(FIXED, axis=1, keepdims=True)

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("npz", help="relume export's archive of a three-channel container")
parser.add_argument("terms", help="comma-separated term indices, e.g. 0,1,2,20,47")
args = parser.parse_args()
archive = np.load(args.npz)
if int(archive["channels"]) != 3:
    sys.exit(f"{args.npz}: {int(archive['channels'])} channels, expected 3")
functions = archive["stored_function"]
if len(functions) % 3 or np.any(functions != np.arange(len(functions))):
    sys.exit(f"{args.npz}: expected every function stored in order (a whole-frame container)")
weights = archive["W"].astype(np.float64).reshape(len(functions) // 3, 3, -1)
print("term  fixed: outside first / in third   principal axes: outside first / in third")
for term in (int(t) for t in args.terms.split(",")):
    if not 0 <= term < weights.shape[2]:
        sys.exit(f"term {term}: the container has {weights.shape[2]} terms")
    moments = weights[:, :, term].T @ weights[:, :, term]
    energy = np.trace(moments)
    fixed = np.diag(FIXED @ moments @ FIXED.T) / energy
    principal = np.sort(np.linalg.eigvalsh(moments))[::-1] / energy
    print(f"{term:4d}  {1 - fixed[0]:8.4%} / {fixed[2]:8.4%}        "
          f"{1 - principal[0]:8.4%} / {principal[2]:8.4%}")
