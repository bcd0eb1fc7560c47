#!/usr/bin/env python3
"""The interactive latency of `relume view` (docs/viewer.md): starts the viewer on a 640x640
container and "drags" as the page does, with one request in flight at a time: a sequence of light
directions (or map rotations) requested back to back over one keep-alive connection. Reports, per
case, the request-to-image latency (send to last byte received) median and 95th percentile, the
frames/s delivered, and the server's own render and encode times (its X-Relume-* headers).
With --browser it also drags in headless Chromium (the real page: fetch, decode, display) and
counts the frames the page shows per second.

The container is made once in --work (default out/bench_viewer): `relume synth` at its defaults
(640x640, 253 lights) compressed with `relume compress` at its defaults, and the built-in sky.

Usage: scripts/bench_viewer.py [--relume build/apps/relume] [--work out/bench_viewer]
                               [--frames 300] [--device D] [--browser] [--json FILE]
"""
import argparse
import http.client
import json
import math
import os
import re
import statistics
import subprocess
import sys
import time


def run(command):
    print("+", " ".join(command), flush=True)
    subprocess.run(command, check=True)


def make_container(relume, work):
    container = os.path.join(work, "scene.relume")
    sky = os.path.join(work, "sky.exr")
    if not os.path.exists(container):
        os.makedirs(work, exist_ok=True)
        scene = os.path.join(work, "scene")
        if not os.path.exists(os.path.join(scene, "light_directions.txt")):
            run([relume, "-q", "-y", "synth", "-o", scene])
        run([relume, "-q", "compress", scene, "-o", container])
    if not os.path.exists(sky):
        run([relume, "-q", "sky", "-o", sky])
    return container, sky


def start_viewer(relume, container, sky, device, log_path):
    command = [relume, "-q", "view", container, "--env", sky, "--port", "0",
               "--max-requests", "1000"]
    if device:
        command += ["--device", device]
    log = open(log_path, "w")
    process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        with open(log_path) as text:
            match = re.search(r"relume view: http://127\.0\.0\.1:(\d+)/", text.read())
        if match:
            return process, int(match.group(1))
        if process.poll() is not None:
            break
        time.sleep(0.05)
    with open(log_path) as text:
        raise SystemExit("relume view did not start:\n" + text.read())


def drag_path(frames, kind):
    """The queries of a drag: the light circling at 45 degrees elevation, or the map turning."""
    queries = []
    for i in range(frames):
        angle = 2 * math.pi * i / frames
        if kind == "map":
            queries.append(f"rotate={360.0 * i / frames:.2f}&map=0")
        else:
            x, y, z = 0.7 * math.cos(angle), 0.7 * math.sin(angle), 0.7
            queries.append(f"light={x:.4f},{y:.4f},{z:.4f}")
    return queries


def percentile(values, p):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(math.ceil(p / 100 * len(ordered))) - 1)]


def drag(port, queries, suffix):
    connection = http.client.HTTPConnection("127.0.0.1", port)
    latencies, render, encode, sizes = [], [], [], []
    for query in queries[:5]:  # warm-up: kernels built, first-touch allocations
        connection.request("GET", f"/frame?{query}{suffix}")
        connection.getresponse().read()
    started = time.perf_counter()
    for query in queries:
        sent = time.perf_counter()
        connection.request("GET", f"/frame?{query}{suffix}")
        response = connection.getresponse()
        body = response.read()
        latencies.append(1e3 * (time.perf_counter() - sent))
        if response.status != 200:
            raise SystemExit(f"/frame?{query}{suffix}: {response.status} {body[:200]!r}")
        render.append(float(response.getheader("X-Relume-Render-Ms")))
        encode.append(float(response.getheader("X-Relume-Encode-Ms")))
        sizes.append(len(body))
    elapsed = time.perf_counter() - started
    connection.close()
    return {
        "frames": len(queries),
        "latency_ms_median": statistics.median(latencies),
        "latency_ms_p95": percentile(latencies, 95),
        "frames_per_second": len(queries) / elapsed,
        "render_ms_median": statistics.median(render),
        "encode_ms_median": statistics.median(encode),
        "bytes_median": statistics.median(sizes),
    }


# Drags the page's light for `seconds`: every 5 ms a new direction along a circle is set and asked
# for, as pointer moves do; the page's coalescing sends what it can.
BROWSER_DRAG = """
const done = arguments[arguments.length - 1];
const v = window.relumeViewer;
const seconds = arguments[0];
v.state.mode = 'light';
const start = performance.now();
const shownBefore = v.framesShown;
const timer = setInterval(() => {
  const t = (performance.now() - start) / 1000;
  const angle = 2 * Math.PI * t / seconds;
  v.state.light = [0.7 * Math.cos(angle), 0.7 * Math.sin(angle), 0.7];
  v.requestFrame();
  if (t >= seconds) {
    clearInterval(timer);
    done({frames: v.framesShown - shownBefore, seconds: (performance.now() - start) / 1000});
  }
}, 5);
"""


def browser_drag(port, transfer, seconds, profile):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.support.ui import WebDriverWait
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for argument in ["--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,1000",
                     f"--user-data-dir={profile}"]:
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    try:
        driver.set_script_timeout(seconds + 60)
        driver.get(f"http://127.0.0.1:{port}/?transfer={transfer}")
        WebDriverWait(driver, 60).until(
            lambda d: d.execute_script("return window.relumeViewer.framesShown > 0"))
        result = driver.execute_async_script(BROWSER_DRAG, seconds)
    finally:
        driver.quit()
    return {"frames": result["frames"], "seconds": result["seconds"],
            "frames_per_second": result["frames"] / result["seconds"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--relume", default="build/apps/relume")
    parser.add_argument("--work", default="out/bench_viewer")
    parser.add_argument("--frames", type=int, default=300)
    parser.add_argument("--device", default="")
    parser.add_argument("--browser", action="store_true")
    parser.add_argument("--json", default="")
    args = parser.parse_args()
    container, sky = make_container(args.relume, args.work)
    process, port = start_viewer(args.relume, container, sky, args.device,
                                 os.path.join(args.work, "view.log"))
    try:
        connection = http.client.HTTPConnection("127.0.0.1", port)
        connection.request("GET", "/info")
        info = json.loads(connection.getresponse().read())
        connection.close()
        print(f"{info['width']}x{info['height']}, {info['lights']} lights, {info['clusters']} "
              f"clusters x {info['terms']} terms, residual up to {info['residual_entries_max']} "
              f"entries; device {info['device']}; load {os.getloadavg()[0]:.1f}")
        cases = [
            ("light, JPEG", "light", "&format=jpeg"),
            ("light, PNG", "light", "&format=png"),
            ("map rotation, JPEG", "map", "&format=jpeg"),
            ("light, JPEG, residual 3 (+ its error)", "light", "&format=jpeg&residual=3"),
        ]
        results = {"info": {k: info[k] for k in ("width", "height", "lights", "clusters", "terms",
                                                 "residual_entries_max", "device")},
                   "load_before": os.getloadavg()[0], "cases": {}}
        print("| case | latency median (ms) | latency p95 (ms) | frames/s | render median (ms) "
              "| encode median (ms) | bytes |")
        print("|---|---|---|---|---|---|---|")
        for name, kind, suffix in cases:
            result = drag(port, drag_path(args.frames, kind), suffix)
            results["cases"][name] = result
            print(f"| {name} | {result['latency_ms_median']:.1f} | {result['latency_ms_p95']:.1f} "
                  f"| {result['frames_per_second']:.1f} | {result['render_ms_median']:.1f} "
                  f"| {result['encode_ms_median']:.1f} | {result['bytes_median']:.0f} |",
                  flush=True)
        if args.browser:
            for transfer in ("jpeg", "png"):
                result = browser_drag(port, transfer, 10, os.path.join(args.work, "profile"))
                results["cases"][f"browser, {transfer}"] = result
                print(f"page (headless Chromium), {transfer}: {result['frames']} frames shown in "
                      f"{result['seconds']:.1f} s = {result['frames_per_second']:.1f} frames/s",
                      flush=True)
        results["load_after"] = os.getloadavg()[0]
        print(f"load after: {results['load_after']:.1f}")
        if args.json:
            with open(args.json, "w") as out:
                json.dump(results, out, indent=2)
    finally:
        process.terminate()
        process.wait(timeout=30)
    return 0


if __name__ == "__main__":
    sys.exit(main())
