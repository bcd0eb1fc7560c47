#!/usr/bin/env bash
# Rate-distortion of relume on DiLiGenT data and a synthetic scene, set against relight-cli's
# points of issue 11's table: bytes per pixel (file bytes / pixels) against 8-bit PSNR over the
# whole frame and inside the object's mask, the stored error (Eq. 16) and the relit error, for
# fixed settings and for the rate targets. The ball is normalised to 8 bit the way RTI tools take
# it (scripts/normalize_to_8bit.py), once with its mask and once without (the whole frame stored;
# the mask only measures), and taken as DiLiGenT's 16-bit original; pot1 and harvest are
# DiLiGenT's 8-bit crops; the synthetic scene is `relume synth` at 256x256, 253 lights.
# The relit error is the relative squared error of the container relit under Grace Cathedral
# against the uncompressed field relit under the same light vector (the map turned by `--rotate
# auto` onto each scene's lights, `relume lights`), inside the mask where there is one.
#   scripts/bench_rate_distortion.sh [BUILD_DIR] [OUT_DIR]
# Writes OUT_DIR/rate_distortion.csv and OUT_DIR/rate_distortion.png, one report per point.
# RD_SCENES="name,name" runs only those scenes (names as in the table, e.g. "harvest mask").
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-rate-distortion}"
data="${RELUME_DATA:-../shared/data}"
relume="$build/apps/relume"
ball="$data/olat/diligent-ball-16bit"
pot="$data/olat/diligent-pot1-crop8"
harvest="$data/olat/diligent-harvest-crop8"
map="$data/envmaps/grace_cross.hdr"
mkdir -p "$out"
[ -d "$out/ball8" ] || /usr/bin/python3 scripts/normalize_to_8bit.py "$ball" "$out/ball8"
[ -d "$out/ball8_nomask" ] ||
  /usr/bin/python3 scripts/normalize_to_8bit.py "$ball" "$out/ball8_nomask" --no-mask
[ -f "$out/synth/filenames.txt" ] ||
  "$relume" -q synth -o "$out/synth" --size 256x256 --lights 253

# scene|input|options every point of the scene gets|options reading the field
scenes=(
  "ball8 mask|$out/ball8|--linear|--linear"
  "ball8 whole frame|$out/ball8_nomask|--linear --psnr-mask $ball/mask.png|--linear"
  "pot1 mask|$pot||"
  "ball 16-bit mask|$ball||"
  "harvest mask|$harvest||"
  "synthetic 256x256|$out/synth||"
)
settings=(
  "--clusters 256 --terms 1 --residual 0"
  "--clusters 64 --terms 4 --residual 0"
  "--clusters 64 --terms 4 --residual 5%"
  "--target-bytes-per-pixel 0.51"
  "--target-bytes-per-pixel 0.93"
)
echo "scene,setting,bytes_per_pixel,psnr_whole_frame,psnr_mask,error_masked,relit_error,seconds" \
  >"$out/rate_distortion.csv"
n=0
for scene in "${scenes[@]}"; do
  IFS='|' read -r name input common reading <<<"$scene"
  [ -z "${RD_SCENES:-}" ] || [[ ",$RD_SCENES," == *",$name,"* ]] || continue
  lights="$out/lights_${name// /_}.txt"
  reference="$out/reference_${name// /_}.exr"
  "$relume" lights -q -y --dirs "$input" --env "$map" --rotate auto -o "$lights"
  # shellcheck disable=SC2086  # the options are words
  "$relume" relight -q -y "$input" $reading --lights "$lights" -o "$reference"
  for setting in "${settings[@]}"; do
    n=$((n + 1))
    echo "bench_rate_distortion: $name: $setting" >&2
    # shellcheck disable=SC2086  # the options are words
    "$relume" compress -q -y "$input" -o "$out/point$n.relume" $common $setting \
      --report "$out/point$n.json"
    "$relume" relight -q -y "$out/point$n.relume" --lights "$lights" -o "$out/relit$n.exr"
    "$relume" compare -y "$out/relit$n.exr" "$reference" --json "$out/compare$n.json" >/dev/null
    /usr/bin/python3 - "$out/point$n.json" "$out/compare$n.json" "$name" "$setting" \
      >>"$out/rate_distortion.csv" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
relit = json.load(open(sys.argv[2]))
p = r["psnr_8bit"]
db = lambda v: "" if v is None else f"{v:.2f}"  # null: lossless
print(f'{sys.argv[3]},{sys.argv[4]},{r["bytes_per_pixel"]:.4f},{db(p["whole_frame"])},'
      f'{db(p["mask"])},{r["error_masked"]:.6f},{relit["relative_squared_error"]:.6f},'
      f'{r["seconds"]:.1f}')
EOF
  done
done
cat "$out/rate_distortion.csv"

/usr/bin/python3 - "$out" <<'EOF'
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
out = sys.argv[1]
rows = list(csv.DictReader(open(f"{out}/rate_distortion.csv")))
# relight-cli on the normalised ball, issue 11's table: (name, bytes/px, whole frame, mask)
cli = [("hsh 12", 0.51, 40.45, 29.33), ("ptm 18", 0.93, 42.42, 32.34),
       ("rbf 9", 1.71, 41.77, 31.95), ("bilinear 27", 11.40, 42.34, 32.87)]
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
for ax, key, index, title in ((axes[0], "psnr_whole_frame", 2, "whole frame"),
                              (axes[1], "psnr_mask", 3, "inside the mask")):
    for scene in dict.fromkeys(r["scene"] for r in rows):
        points = sorted((float(r["bytes_per_pixel"]), float(r[key])) for r in rows
                        if r["scene"] == scene and r[key] not in ("", "nan"))
        if scene.endswith("mask") and key == "psnr_whole_frame":
            continue  # a masked container does not store the background
        ax.plot([p[0] for p in points], [p[1] for p in points], "o-", label=f"relume, {scene}")
    ax.plot([c[1] for c in cli], [c[index] for c in cli], "s--", color="grey",
            label="relight-cli, ball (issue 11)")
    ax.set_xscale("log")
    ax.set_xlabel("bytes per pixel")
    ax.set_ylabel("8-bit PSNR (dB)")
    ax.set_title(f"PSNR {title}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(f"{out}/rate_distortion.png", dpi=120)
print(f"bench_rate_distortion: wrote {out}/rate_distortion.csv and {out}/rate_distortion.png")
EOF
