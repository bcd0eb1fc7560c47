#!/usr/bin/env python3
"""The `relume view` page in a real browser: headless Chromium driven by Selenium loads the page
served for a small synthetic container, waits for the first frame, drags on the hemisphere widget
(a directional light) and, with an environment map, on the image (turning the map), and checks
that the frame on screen changed and that its pixels, read back through a canvas, equal
`relume relight` with the settings the page shows (its window.relumeViewer.shownQuery); so does
the PNG the page's save link names.

Exits 77 (ctest's SKIP_RETURN_CODE) only when Chromium, chromedriver or python3-selenium is
missing, saying which; scripts/install_deps.sh installs them.

Usage: view_browser_test.py --relume PATH/TO/relume
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.parse
import urllib.request

SKIP = 77


def missing_browser():
    """Why the browser test cannot run here, or None."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "python3-selenium is not installed"
    if not (shutil.which("chromium") or os.path.exists("/usr/bin/chromium")):
        return "chromium is not installed"
    if not (shutil.which("chromedriver") or os.path.exists("/usr/bin/chromedriver")):
        return "chromedriver (Debian chromium-driver) is not installed"
    return None


def run(command):
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise AssertionError(f"{' '.join(command)} failed ({result.returncode}):\n"
                             f"{result.stdout}{result.stderr}")


class ViewServer:
    """`relume view` on a free port; the port read from the address it prints."""

    def __init__(self, relume, arguments, log_path):
        self.log_path = log_path
        self.log = open(log_path, "w")
        self.process = subprocess.Popen([relume, "-q", "view", *arguments, "--port", "0"],
                                        stdout=self.log, stderr=subprocess.STDOUT)
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            match = re.search(r"relume view: (http://127\.0\.0\.1:\d+/)", self.output())
            if match:
                self.url = match.group(1)
                return
            if self.process.poll() is not None:
                break
            time.sleep(0.05)
        raise AssertionError("relume view printed no address:\n" + self.output())

    def output(self):
        with open(self.log_path) as log:
            return log.read()

    def stop(self):
        self.process.terminate()
        code = self.process.wait(timeout=30)
        self.log.close()
        if code != 128 + 15:
            raise AssertionError(f"relume view exited {code} on SIGTERM:\n{self.output()}")


def read_png(path):
    import OpenImageIO as oiio
    image = oiio.ImageInput.open(path)
    if image is None:
        raise AssertionError(f"cannot read {path}: {oiio.geterror()}")
    pixels = image.read_image(oiio.UINT8)
    image.close()
    return pixels


def start_browser(profile):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    for argument in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=1200,900", "--force-color-profile=srgb",
                     f"--user-data-dir={profile}"]:
        options.add_argument(argument)
    service = Service(executable_path=shutil.which("chromedriver") or "/usr/bin/chromedriver")
    return webdriver.Chrome(service=service, options=options)


SETTLED = """
const v = window.relumeViewer;
return v.framesShown > arguments[0] && !v.inFlight && !v.pending &&
       v.shownQuery === v.frameQuery(v.state);
"""

SHOWN_PIXELS = """
const image = document.getElementById('frame');
const canvas = document.createElement('canvas');
canvas.width = image.naturalWidth;
canvas.height = image.naturalHeight;
const g = canvas.getContext('2d');
g.drawImage(image, 0, 0);
return [canvas.width, canvas.height,
        Array.from(g.getImageData(0, 0, canvas.width, canvas.height).data)];
"""


def wait_settled(driver, frames_before):
    from selenium.webdriver.support.ui import WebDriverWait
    WebDriverWait(driver, 60, poll_frequency=0.05).until(
        lambda d: d.execute_script(SETTLED, frames_before))
    return driver.execute_script("return window.relumeViewer.shownQuery")


def shown_pixels(driver):
    import numpy
    width, height, rgba = driver.execute_script(SHOWN_PIXELS)
    return numpy.array(rgba, dtype=numpy.uint8).reshape(height, width, 4)[:, :, :3]


def check_page(driver, server, drag, relight_arguments, folder, relume, container):
    """Loads the page, drags with drag(driver), and checks the frame against relume relight."""
    import numpy
    driver.get(server.url + "?transfer=png")
    first_query = wait_settled(driver, 0)
    before = shown_pixels(driver)
    frames = driver.execute_script("return window.relumeViewer.framesShown")
    drag(driver)
    query = wait_settled(driver, frames)
    after = shown_pixels(driver)
    assert query != first_query, f"the drag did not change the state: {query}"
    changed = numpy.abs(after.astype(int) - before.astype(int)).max()
    assert changed > 0, "the frame on screen did not change with the drag"

    parameters = dict(urllib.parse.parse_qsl(query))
    expected_path = os.path.join(folder, "relit.png")
    run([relume, "-q", "-y", "relight", container, *relight_arguments(parameters),
         "--exposure", parameters["exposure"], "--residual", parameters["residual"],
         "-o", expected_path])
    expected = read_png(expected_path)
    assert after.shape == expected.shape, f"{after.shape} on screen, {expected.shape} relit"
    worst = numpy.abs(after.astype(int) - expected.astype(int)).max()
    assert worst == 0, f"the frame on screen differs from relume relight by up to {worst}/255"

    saved_link = driver.find_element("id", "save-png").get_attribute("href")
    saved_path = os.path.join(folder, "saved.png")
    with urllib.request.urlopen(saved_link) as answer, open(saved_path, "wb") as saved:
        saved.write(answer.read())
    assert numpy.array_equal(read_png(saved_path), expected), "the saved PNG differs"
    return query


def drag_light(driver):
    from selenium.webdriver.common.action_chains import ActionChains
    widget = driver.find_element("id", "hemisphere")
    (ActionChains(driver).move_to_element_with_offset(widget, -50, -30).click_and_hold()
     .move_by_offset(15, 5).move_by_offset(15, 5).move_by_offset(10, 0).release().perform())


def drag_map(driver):
    from selenium.webdriver.common.action_chains import ActionChains
    image = driver.find_element("id", "frame")
    (ActionChains(driver).move_to_element_with_offset(image, -60, 0).click_and_hold()
     .move_by_offset(30, 0).move_by_offset(30, 0).move_by_offset(20, 0).release().perform())


def light_arguments(parameters):
    arguments = ["--light-dir", parameters["light"], "--light-color", parameters["color"]]
    if "spread" in parameters:
        arguments += ["--spread", parameters["spread"]]
    return arguments


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--relume", required=True)
    relume = parser.parse_args().relume
    why = missing_browser()
    if why:
        print(f"SKIP: {why}; scripts/install_deps.sh installs the browser test's packages")
        return SKIP
    with tempfile.TemporaryDirectory(prefix="relume-view-browser-") as folder:
        scene = os.path.join(folder, "scene")
        container = os.path.join(folder, "scene.relume")
        sky = os.path.join(folder, "sky.exr")
        run([relume, "-q", "synth", "-o", scene, "--size", "64x48", "--lights", "40",
             "--samples", "1"])
        run([relume, "-q", "compress", scene, "-o", container, "--clusters", "4", "--terms", "2",
             "--residual", "6"])
        run([relume, "-q", "sky", "-o", sky, "--width", "128"])
        driver = start_browser(os.path.join(folder, "profile"))
        try:
            server = ViewServer(relume, [container], os.path.join(folder, "light.log"))
            try:
                query = check_page(driver, server, drag_light, light_arguments, folder, relume,
                                   container)
                print(f"directional light: the page shows {query}, equal to relume relight")
            finally:
                server.stop()

            def map_arguments(parameters):
                assert parameters["color"] == "1.0000,1.0000,1.0000", parameters
                return ["--env", sky, "--rotate", parameters["rotate"]]

            server = ViewServer(relume, [container, "--env", sky], os.path.join(folder, "map.log"))
            try:
                query = check_page(driver, server, drag_map, map_arguments, folder, relume,
                                   container)
                assert "rotate=0.00" not in query, query
                print(f"environment map: the page shows {query}, equal to relume relight")
            finally:
                server.stop()
        finally:
            driver.quit()
    return 0


if __name__ == "__main__":
    sys.exit(main())
