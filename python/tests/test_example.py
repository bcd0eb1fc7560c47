"""python/examples/compression_trade.py runs end to end on a small synthetic field: it writes
the plot and the numbers, and more residual entries cost bytes and buy accuracy."""
import json
import os
import subprocess
import sys

from conftest import source_dir


def test_the_example_writes_its_plot_and_numbers(scene, sky_map, tmp_path):
    script = source_dir() / "python" / "examples" / "compression_trade.py"
    completed = subprocess.run(
        [sys.executable, str(script), str(scene), "--env", str(sky_map), "--rotate", "0",
         "--clusters", "4", "--terms", "3", "--residuals", "0,6", "--assign", "cpu",
         "--out", str(tmp_path)],
        capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"}, timeout=300)
    assert completed.returncode == 0, completed.stdout + completed.stderr
    assert (tmp_path / "trade.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    points = json.loads((tmp_path / "trade.json").read_text())["points"]
    assert [p["residual"] for p in points] == [0, 6]
    assert points[1]["bytes"] > points[0]["bytes"]
    assert points[1]["error_eq16_masked"] < points[0]["error_eq16_masked"]
    assert points[1]["relit_error"] < points[0]["relit_error"]
