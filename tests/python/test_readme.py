"""The README's Python example and its acceptance line, run on the demo's files."""

import os
import pathlib
import re
import shutil
import subprocess
import sys

import tactile

README = pathlib.Path(os.environ["TACTILE_SOURCE_DIR"]) / "README.md"
DEMO = pathlib.Path(os.environ["TACTILE_E2E_DEMO_DIR"])


def python_section():
    text = README.read_text()
    return text[text.index("## Python"):text.index("## Where things are")]


def test_example_maps_with_two_methods_and_plots(tmp_path):
    example = re.search(r"```python\n(.*?)```", python_section(), re.S).group(1)
    assert len(example.strip().splitlines()) <= 12
    shutil.copy(DEMO / "strain.h5", tmp_path / "strain.h5")
    env = dict(os.environ, MPLBACKEND="Agg")
    subprocess.run([sys.executable, "-c", example], cwd=tmp_path, env=env, check=True)
    png = tmp_path / "methods.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10000


def test_acceptance_line_prints_the_movies_shape(tmp_path):
    line = re.search(r'/usr/bin/python3 -c "(.*?)"', python_section()).group(1)
    shutil.copy(DEMO / "movie.h5", tmp_path / "movie.h5")
    out = subprocess.run(["/usr/bin/python3", "-c", line], cwd=tmp_path, env=os.environ,
                         check=True, capture_output=True, text=True).stdout
    movie = tactile.read_movie(DEMO / "movie.h5")
    assert out.strip() == str((movie.frame_count, 10, 10))
