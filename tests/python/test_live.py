"""tactile.live: the session `tactile live --headless` runs, from Python, with its summary."""

import os
import pathlib

import pytest

import tactile

DEMO = pathlib.Path(os.environ["TACTILE_E2E_DEMO_DIR"])


def test_a_folder_played_at_its_rate_gives_every_frame(tmp_path):
    summary = tactile.live(str(DEMO / "frames"), calib=DEMO / "calibration.json", rate_hz=20,
                           seconds=1.0, queue_frames=30, record=tmp_path / "session")
    assert summary["frames_in"] == summary["frames_processed"] + summary["frames_dropped"]
    # One second at 20 Hz: frames 0..19 handed over (the 21st is due at 1.0 s, the end).
    assert 19 <= summary["frames_in"] <= 21
    assert summary["frames_dropped"] == 0
    assert 0 < summary["latency_p50_ms"] <= summary["latency_p99_ms"] <= summary["latency_max_ms"]
    lines = (tmp_path / "session" / "latency.csv").read_text().splitlines()
    assert lines[0] == "frame,source_time_s,latency_ms,dropped"
    assert len(lines) == summary["frames_in"] + 1
    strain = tactile.read_strain_movie(tmp_path / "session" / "strain.h5")
    assert len(strain.frames) == summary["frames_processed"] - 1


def test_bad_keywords_are_the_command_lines_errors(tmp_path):
    with pytest.raises(ValueError, match="give one of calib"):
        tactile.live(str(tmp_path))
    with pytest.raises(ValueError, match="queue_frames: 0 is out of range"):
        tactile.live(str(tmp_path), px_per_mm=47, queue_frames=0)
