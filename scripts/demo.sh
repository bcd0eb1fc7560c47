#!/usr/bin/env bash
# The main job on a built-in default: installs dependencies, builds, renders a synthetic OLAT set
# (`relume synth`), compresses it, and relights it under the built-in sky rotating through a full
# turn. Everything goes to out/demo/ (overwritten on each run):
#   scene/            the OLAT set (253 EXR images + light files)
#   scene.relume      the compressed field, report.json its compression report
#   reference.exr/png the uncompressed field relit (ground truth), relit.exr/png the compressed one,
#   relit_error.json  how far relit.exr is from reference.exr (relume compare)
#   frames/NNNN.png   36 frames of the rotating sequence, sequence.json their timings and errors
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh relume  # the main job runs only the command

relume="build/apps/relume -y"  # -y: a rerun replaces the previous outputs
out=out/demo
mkdir -p "$out"
$relume synth -o "$out/scene" --size 320x320 --lights 253
$relume sky -o "$out/sky.exr"
# Light weighting 0.5: the sky's sun is behind the scene; docs/relit_quality.md, Remedy 3.
$relume compress "$out/scene" -o "$out/scene.relume" --clusters 64 --terms 8 --residual 7 \
  --light-weighting 0.5 --report "$out/report.json"
$relume info "$out/scene.relume"
for image in reference.exr reference.png; do
  $relume relight "$out/scene" --env "$out/sky.exr" -o "$out/$image" --exposure -1
done
for image in relit.exr relit.png; do
  $relume relight "$out/scene.relume" --env "$out/sky.exr" -o "$out/$image" --exposure -1
done
$relume compare "$out/relit.exr" "$out/reference.exr" --json "$out/relit_error.json"
$relume relight-sequence "$out/scene.relume" --env "$out/sky.exr" --frames 36 --rotate-step 10 \
  --exposure -1 --compare -o "$out/frames/%04d.png" --report "$out/sequence.json"
echo "demo: images in $out (reference.png, relit.png, frames/)"
