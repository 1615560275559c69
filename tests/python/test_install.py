"""`cmake --install` puts the module where the interpreter finds it under the prefix."""

import os
import pathlib
import subprocess
import sys


def test_installed_module_imports_from_the_prefix(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", os.environ["TACTILE_BUILD_DIR"], "--prefix", str(prefix)],
                   check=True, capture_output=True)
    site = prefix / os.environ["TACTILE_PYTHON_INSTALL_DIR"]
    assert list(site.glob("tactile*.so")), f"no module in {site}"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    code = ("import tactile, numpy; m = tactile.Movie(numpy.zeros((2, 8, 8)), 'latero'); "
            "print(tactile.__file__, m.deflection_um.shape)")
    out = subprocess.run([sys.executable, "-c", code], env=env, cwd=tmp_path, check=True,
                         capture_output=True, text=True).stdout.split()
    assert pathlib.Path(out[0]).is_relative_to(site)
    assert out[1:] == ["(2,", "8,", "8)"]
