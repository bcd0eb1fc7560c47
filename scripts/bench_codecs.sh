#!/usr/bin/env bash
# relume against the video codecs a user already has (issue 32): the shared ball normalised to
# 8 bit without its mask (the whole frame stored, scripts/normalize_to_8bit.py), compressed by
# `relume compress --linear` (the default, whose time a rate target is held to) and with
# `--target-bytes-per-pixel B` at each rate, and by FFmpeg's libaom AV1 (yuv444p) and x265
# (yuv444p10le) over the light images as one video (scripts/codec_curve.py). Bytes per pixel
# (file bytes / (width x height)) against the 8-bit PSNR over the whole frame and inside the
# ball's mask, the same definition for all.
#   scripts/bench_codecs.sh [BUILD_DIR] [OUT_DIR]
# BENCH_RATES="0.05 0.1" picks the rates; BENCH_MODELS=one-basis passes --target-models (default:
# all, what a user gets); BENCH_CAPTURE=pot1 (bear, harvest) takes that DiLiGenT crop's 8-bit
# images as they are, its mask for the masked PSNR, and writes under OUT_DIR/pot1;
# BENCH_CAPTURE=synth renders the demo's synthetic scene (`relume synth`, 320 x 320, 253 lights)
# and normalises it to 8 bit like the ball (gain 4: 99% of its lit values below 0.8, the
# highlights clipped), under OUT_DIR/synth. The codecs' points are kept in OUT_DIR/codec_*.json
# and reused.
# Every point is also relit under two maps (relit-image error against the images relit, scripts/
# relit_error.py) and timed: load (decode into what relights) and one relit frame.
# Writes OUT_DIR/codecs.jsonl (one line per point, relume's with its seconds), OUT_DIR/codecs.md
# (the table, each codec interpolated at relume's bytes), OUT_DIR/codecs.png and OUT_DIR/light.png
# (the most grazing light as each stores it at about 0.1 B/px, brightened).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-codecs}"
data="${RELUME_DATA:-../shared/data}"
relume="$build/apps/relume"
capture="${BENCH_CAPTURE:-ball}"
rates="${BENCH_RATES:-0.05 0.1 0.2 0.5 1 2}"
models="${BENCH_MODELS:-all}"
command -v ffmpeg >/dev/null || { echo "bench_codecs.sh: ffmpeg not found (scripts/install_deps.sh)"; exit 1; }
case "$capture" in
  ball) source_dir="$data/olat/diligent-ball-16bit" ;;
  pot1 | bear | harvest)
    source_dir="$data/olat/diligent-$capture-crop8"
    out="$out/$capture" ;;
  synth)
    out="$out/synth"
    source_dir="$out/scene"
    [ -d "$source_dir" ] || {
      "$relume" -q -y synth -o "$source_dir.part" --size 320x320 --lights 253
      mv "$source_dir.part" "$source_dir"
    } ;;
  *) echo "bench_codecs.sh: BENCH_CAPTURE is ball, pot1, bear, harvest or synth, got '$capture'"; exit 2 ;;
esac
mask="$source_dir/mask.png"
mkdir -p "$out"
# The light images as a user holds them: the ball and the synthetic scene normalised to 8 bit, a
# crop's 8-bit PNGs as they are (its light intensities left out, as a video of the images cannot
# use them).
if [ "$capture" = ball ]; then
  frames="$out/ball8_nomask"
  [ -d "$frames" ] || /usr/bin/python3 scripts/normalize_to_8bit.py "$source_dir" "$frames" --no-mask
elif [ "$capture" = synth ]; then
  frames="$out/scene8"
  [ -d "$frames" ] || /usr/bin/python3 scripts/normalize_to_8bit.py "$source_dir" "$frames" --no-mask --gain 4
else
  frames="$out/frames"
  [ -d "$frames" ] || {
    mkdir -p "$frames.part"
    cp "$source_dir"/[0-9]*.png "$source_dir/filenames.txt" "$source_dir/light_directions.txt" "$frames.part"
    mv "$frames.part" "$frames"
  }
fi
points="$out/codecs.jsonl"
: > "$points"
# Two maps to relight with, as light vectors on the capture's lights (each turned to light the
# capture best): every point's relit-image error is measured under both.
vectors=""
for map in grace_latlong_256x128.hdr stpeters_cross.hdr; do
  "$relume" -q lights --dirs "$frames" --env "$data/envmaps/$map" --rotate auto -y \
    -o "$out/light_${map%%_*}.txt"
  vectors="${vectors:+$vectors,}$out/light_${map%%_*}.txt"
done
# A codec's point depends on the images and its setting only: each is kept and reused.
codec() {
  local name="$1" crf
  shift
  for crf in "$@"; do
    local kept="$out/codec_${name}_crf$crf.json"
    grep -qs relit_error "$kept" || {
      /usr/bin/python3 scripts/codec_curve.py "$frames" "$mask" "$name" "$crf" \
        --light-vectors "$vectors" > "$kept.part"
      mv "$kept.part" "$kept"
    }
    cat "$kept" >> "$points"
  done
}
codec av1 50 40 30 20 10 4
codec x265 38 32 26 20 14 8 4
# One relume point: NAME, then the compress options besides the input and the PSNR mask; the
# seconds of the whole command are recorded with it.
relume_point() {
  local name="$1" start milliseconds
  shift
  start=$(date +%s%N)
  "$relume" -q compress "$frames" -o "$out/relume_$name.relume" -y --linear \
    --psnr-mask "$mask" --report "$out/relume_$name.json" "$@"
  milliseconds=$(( ($(date +%s%N) - start) / 1000000 ))
  # Relit under each map, and timed: the container's load (read and decoded into the in-memory
  # form, Python's relume.open, median of 3) and one relit frame (`relume bench --container`).
  local vector errors=""
  for vector in ${vectors//,/ }; do
    "$relume" -q relight "$out/relume_$name.relume" --lights "$vector" -o "$out/relit.exr" -y
    errors="$errors $(/usr/bin/python3 scripts/relit_error.py "$frames" "$vector" "$out/relit.exr")"
  done
  local load
  load=$(PYTHONPATH="$build/python" /usr/bin/python3 -c "
import statistics, sys, time, relume
times = []
for _ in range(3):
    start = time.perf_counter(); relume.open(sys.argv[1]); times.append(time.perf_counter() - start)
print(statistics.median(times))" "$out/relume_$name.relume")
  "$relume" -q bench --container "$out/relume_$name.relume" --repeats 3 --no-reference \
    --assign-rows 0 --json "$out/relume_${name}_bench.json" > /dev/null
  /usr/bin/python3 - "$out/relume_$name.json" "$milliseconds" "$*" "$errors" "$load" \
    "$out/relume_${name}_bench.json" >> "$points" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
# The single-frame relight with the whole residual: the sweep's last relight record.
relight = [r for r in json.load(open(sys.argv[6]))["records"] if r["kernel"] == "relight"][-1]
parameters = report["parameters"]
model = "one basis" if report["sections"].get("weight_planes", 0) > 0 else "clustered"
print(json.dumps({"codec": "relume", "setting": f"{sys.argv[3] or 'default'}: {model}, "
                  f"{parameters['terms']} terms, {parameters['clusters']} clusters",
                  "bytes": report["bytes"], "bytes_per_pixel": report["bytes_per_pixel"],
                  "psnr_whole_frame": report["psnr_8bit"]["whole_frame"],
                  "psnr_mask": report["psnr_8bit"]["mask"], "seconds": float(sys.argv[2]) / 1000,
                  "relit_error": [float(e) for e in sys.argv[4].split()],
                  "load_seconds": float(sys.argv[5]), "relight_seconds": relight["seconds"]}))
PY
}
# A plain compression first: the default's point, and the time a rate target is held to (3x).
relume_point default
for rate in $rates; do
  relume_point "$rate" --target-bytes-per-pixel "$rate" --target-models "$models"
done
/usr/bin/python3 scripts/codec_table.py "$points" "$out/codecs.md" "$out/codecs.png"
# To look at, not only measure: the most grazing light in front (the longest shadows; z > 0.1, so
# that a light behind a synthetic scene is not taken) as stored by relume
# at 0.1 B/px and by AV1 and x265 at about those bytes, brightened 8 times (OUT_DIR/light.png).
if [ -s "$out/relume_0.1.relume" ]; then
  light=$(/usr/bin/python3 -c "import numpy, sys; z = numpy.loadtxt(sys.argv[1])[:, 2]; print(int(numpy.where(z > 0.1, z, numpy.inf).argmin()) + 1)" \
    "$frames/light_directions.txt")
  /usr/bin/python3 -c "import numpy, sys; v = numpy.zeros((len(numpy.loadtxt(sys.argv[3])), 3)); v[int(sys.argv[1]) - 1] = 1; numpy.savetxt(sys.argv[2], v, fmt='%g')" \
    "$light" "$out/one_light.txt" "$frames/light_directions.txt"
  "$relume" -q relight "$out/relume_0.1.relume" --lights "$out/one_light.txt" -o "$out/relume_0.1_light$light.exr" -y
  for codec in "av1 30" "x265 26"; do
    set -- $codec
    [ -s "$out/${1}_crf${2}_light$light.png" ] ||
      /usr/bin/python3 scripts/codec_curve.py "$frames" "$mask" "$1" "$2" \
        --keep-light "$light" --keep-dir "$out" > /dev/null
  done
  light_name=$(printf "%03d" "$light")
  /usr/bin/python3 scripts/codec_light_panel.py "$out/light.png" \
    "light $light as captured=$frames/$light_name.png" \
    "relume, 0.1 B/px=$out/relume_0.1_light$light.exr" \
    "AV1 crf 30, $(grep -o '"bytes_per_pixel": [0-9.]*' "$out/codec_av1_crf30.json" | cut -c20-24) B/px=$out/av1_crf30_light$light.png" \
    "x265 crf 26, $(grep -o '"bytes_per_pixel": [0-9.]*' "$out/codec_x265_crf26.json" | cut -c20-24) B/px=$out/x265_crf26_light$light.png"
fi
cat "$out/codecs.md"
