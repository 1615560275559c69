"""tactile.experiment runs an experiment file as `tactile experiment` does, by the same run."""

import csv
import json
import subprocess

import pytest

import tactile

TINY = {"name": "tiny", "seed": 1,
        "sources": [{"name": "gt", "ground_truth": {"scene": "bump", "frames": 8},
                     "grid_spacing_mm": 0.6}],
        "layouts": ["stress"], "methods": ["integrated", "proportional"],
        "parameters": {"rate_hz": 100}}


def test_the_runs_and_their_figures_are_the_command_lines(cli, tmp_path):
    exp = tmp_path / "tiny.json"
    exp.write_text(json.dumps(TINY))
    got = tactile.experiment(exp, out=tmp_path / "py", threads=2, quiet=True)
    assert len(got["runs"]) == 2 and all(r["frames"] > 0 for r in got["runs"])
    subprocess.run([cli, "experiment", str(exp), "--out", str(tmp_path / "cli"), "--quiet"],
                   check=True, capture_output=True)
    # The figures are computed from the same movies: metrics.csv of both runs agree.
    with open(tmp_path / "cli" / "metrics.csv") as f:
        rows = {r["run"]: r for r in csv.DictReader(line for line in f if not line.startswith("#"))}
    assert set(rows) == {r["id"] for r in got["runs"]}
    for r in got["runs"]:
        assert float(rows[r["id"]]["strain_correlation"]) == pytest.approx(
            r["strain_correlation"], abs=1e-6)
    assert (tmp_path / "py" / "metrics.csv").read_text() != ""


def test_an_output_over_the_file_is_refused_before_any_work(tmp_path):
    # The folder's experiment.json would be the experiment file itself.
    exp = tmp_path / "experiment.json"
    exp.write_text(json.dumps(TINY))
    with pytest.raises(Exception, match=r"out .*its experiment.json.* would write over the input "
                                        r"file"):
        tactile.experiment(exp, out=tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["experiment.json"]


def test_a_missing_file_and_a_bad_value(tmp_path):
    with pytest.raises(FileNotFoundError):
        tactile.experiment(tmp_path / "absent.json")
    with pytest.raises(ValueError, match="threads: 300 is out of range: must be from 0 to 256"):
        tactile.experiment(tmp_path / "absent.json", threads=300)
