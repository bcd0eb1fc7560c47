"""`cmake --install` puts the module and its type stub into RELUME_PYTHON_INSTALL_DIR under the
prefix, and the installed module imports and works from there without the build tree."""
import os
import pathlib
import subprocess
import sys

import pytest


def test_the_installed_module_imports_and_compresses(tmp_path, scene):
    build = os.environ.get("RELUME_BUILD_DIR")
    if not build:
        pytest.fail("RELUME_BUILD_DIR is not set: run the Python tests through ctest")
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], check=True,
                   capture_output=True)
    modules = list(prefix.glob("lib/python3*/dist-packages/relume.*.so"))
    assert len(modules) == 1, sorted(map(str, prefix.rglob("*")))
    site = modules[0].parent
    assert (site / "relume.pyi").is_file()
    environment = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    environment["PYTHONPATH"] = str(site)
    check = ("import relume, sys; assert relume.__file__.startswith(sys.argv[1]), relume.__file__;"
             "c = relume.compress(relume.load(sys.argv[2]), clusters=3, terms=2, residual=2, "
             "assign='cpu', threads=2); print(c.stored_rows, relume.__version__)")
    completed = subprocess.run([sys.executable, "-c", check, str(site), str(scene)],
                               env=environment, cwd=tmp_path, capture_output=True, text=True)
    assert completed.returncode == 0, completed.stderr
    stored_rows, version = completed.stdout.split()
    assert int(stored_rows) > 0
    import relume
    assert version == relume.__version__
