#!/usr/bin/env bash
# The published page's benchmark (docs/publish.md): for a synthetic 640 x 640 x 253 scene and the
# shared DiLiGenT ball, both compressed at relume's defaults, and the ball's one-basis container
# at a rate target of 0.1 B/px (its weights one JPEG 2000 codestream, which the page decodes),
# `relume publish` (with the built-in sky as a map), then the page opened in headless Chromium
# (WebGL2 on SwiftShader: the CPU) from `python3 -m http.server`: seconds and bytes to the first
# image (the whole field fitted in a 1400 x 1000 window; for the one-basis ball, the seconds of
# fetching and decoding its weight planes too), bytes for the whole field at full resolution,
# and frames/s of that view with residual caps 0, 3 and all. Also the published folder against
# the container: bytes a full view fetches / container bytes, and the same for its data files
# alone (data/field.bin, data/weights.j2k, the level-0 tiles). Needs Chromium, chromedriver and
# python3-selenium (scripts/install_deps.sh). Usage: scripts/bench_publish.sh [BUILD_DIR] [OUT_DIR]
# RELUME_DATA overrides the data folder (default ../shared/data next to the repository).
# About 7 minutes on 2 cores (the compressions take most of it, once; the folder keeps them).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-/tmp/relume-bench-publish}"
data="${RELUME_DATA:-../shared/data}"
relume="$(realpath "$build/apps/relume")"
mkdir -p "$out"
[ -f "$out/synth640/filenames.txt" ] || "$relume" -q synth -o "$out/synth640"
[ -f "$out/synth640.relume" ] || "$relume" -q compress "$out/synth640" -o "$out/synth640.relume"
[ -f "$out/ball.relume" ] ||
  "$relume" -q compress "$data/olat/diligent-ball-16bit" -o "$out/ball.relume"
[ -f "$out/ball_one_basis.relume" ] ||
  "$relume" -q compress "$data/olat/diligent-ball-16bit" --target-bytes-per-pixel 0.1 \
    -o "$out/ball_one_basis.relume"
[ -f "$out/sky.exr" ] || "$relume" -q sky -o "$out/sky.exr" --width 256

for scene in synth640 ball ball_one_basis; do
  "$relume" publish "$out/$scene.relume" --env "$out/sky.exr" -o "$out/site_$scene" -y
done

port=$((20000 + RANDOM % 20000))
/usr/bin/python3 -m http.server "$port" --bind 127.0.0.1 -d "$out" > "$out/http.log" 2>&1 &
server=$!
trap 'kill "$server"' EXIT
sleep 1

/usr/bin/python3 - "$port" "$out" <<'PYTHON'
import glob, json, os, sys, tempfile
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.support.ui import WebDriverWait

port, out = sys.argv[1], sys.argv[2]
options = webdriver.ChromeOptions()
options.binary_location = "/usr/bin/chromium"
for argument in ["--headless=new", "--no-sandbox", "--enable-unsafe-swiftshader",
                 "--window-size=1400,1000", "--disable-cache",
                 f"--user-data-dir={tempfile.mkdtemp()}"]:
    options.add_argument(argument)
print("| scene | container bytes | first image s | weights decoded s | bytes to first image "
      "| full view bytes | x container | data files x container "
      "| frames/s cap 0 / 3 / all (full view) |")
print("|---|---|---|---|---|---|---|---|---|")
for scene in ["synth640", "ball", "ball_one_basis"]:
    container = os.path.getsize(f"{out}/{scene}.relume")
    site = f"{out}/site_{scene}"
    data = sum(os.path.getsize(path) for path in
               glob.glob(f"{site}/data/*.*") + glob.glob(f"{site}/data/tiles/0/*"))
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    try:
        driver.set_script_timeout(600)
        driver.get(f"http://127.0.0.1:{port}/site_{scene}/index.html")
        WebDriverWait(driver, 120).until(
            lambda d: d.execute_script("return document.body.dataset.state") != "loading")
        state = driver.execute_script("return document.body.dataset.state")
        if state != "ready":
            sys.exit(f"{scene}: the page says {driver.find_element('id', 'status').text}")
        first = driver.execute_script("return window.relume.firstImage")
        driver.execute_async_script(
            "const done = arguments[0]; window.relume.fullResolutionPixels().then(() => done())")
        full = driver.execute_script("return window.relume.bytesOnTheWire()")
        rates = [driver.execute_script(
            "const v = window.relume.view; v.x = 0; v.y = 0; v.scale = 1;"
            f"return window.relume.framesPerSecond({cap}, 10)") for cap in (0, 3, 1 << 30)]
        planes = "-" if first["planeSeconds"] is None else f"{first['planeSeconds']:.2f}"
        print(f"| {scene} | {container} | {first['seconds']:.2f} | {planes} | {first['bytes']} "
              f"| {full} | {full / container:.3f} | {data / container:.3f} "
              f"| {' / '.join(f'{r:.1f}' for r in rates)} |")
        if scene in ("synth640", "ball_one_basis"):
            driver.set_window_size(1400, 1000)
            driver.get(f"http://127.0.0.1:{port}/site_{scene}/index.html?light=0.5,0.6,0.62")
            WebDriverWait(driver, 120).until(
                lambda d: d.execute_script("return document.body.dataset.state") == "ready")
            driver.save_screenshot(f"{out}/screenshot_{scene}.png")
    finally:
        driver.quit()
PYTHON
