"""tactile.live: the session `tactile live --headless` runs, from Python, with its summary."""

import os
import pathlib

import numpy as np
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
    # The demo's skin stays in view (no slide), so the contact rule leaves nothing out, and every
    # edge measured is in the recording.
    assert summary["median_points"] > 0
    assert summary["strain_edges_near_gaps"] == 0
    assert sum(len(f.edges) for f in strain.frames) == summary["strain_edges"] > 0
    # Where the skin touched, judged frame by frame as the frames came: a threshold per camera
    # frame, every frame seen (none dropped), each cell in contact exactly when its contrast
    # reaches its own frame's threshold.
    contact, frames = strain.contact, strain.camera_frame_count
    assert contact["threshold"].shape == (frames,) and contact["seen"].shape == (frames,)
    assert contact["seen"].all()
    judged = contact["ridge_contrast"] >= contact["threshold"][:, None, None]
    np.testing.assert_array_equal(contact["in_contact"], judged)


def test_bad_keywords_are_the_command_lines_errors(tmp_path):
    with pytest.raises(ValueError, match="give one of calib"):
        tactile.live(str(tmp_path))
    with pytest.raises(ValueError, match="queue_frames: 0 is out of range"):
        tactile.live(str(tmp_path), px_per_mm=47, queue_frames=0)


def test_a_session_on_the_emulated_latero_leaves_every_blade_at_rest(cli):
    from test_play import EmulatedLatero, counters

    with EmulatedLatero(cli) as latero:
        summary = tactile.live(str(DEMO / "frames"), calib=DEMO / "calibration.json", rate_hz=20,
                               seconds=1.0, layout="latero", latero=latero.address,
                               blade_centre_raw=128, blade_max_raw=255)
        got = counters(latero.stop())
    assert summary["target"] == "latero"
    assert summary["frames_processed"] > 0 and summary["device_frames_sent"] > 0
    # Every frame the session sent, and its stop ramp, reached the Latero as a FULL request,
    # none malformed; the blades ended at the centre the blade mapping names.
    assert got["full"] >= summary["device_frames_sent"] and got["malformed"] == 0
    assert got["blades"] == (128, 128)


def test_the_output_keywords_are_plays(tmp_path):
    assert tactile.live(str(DEMO / "frames"), calib=DEMO / "calibration.json", rate_hz=20,
                        seconds=0.3, headless=True)["target"] == "headless"
    with pytest.raises(ValueError, match="headless: not with latero"):
        tactile.live(str(tmp_path), px_per_mm=47, headless=True, latero="127.0.0.1:9")
    with pytest.raises(ValueError, match="the blade mapping is only for a Latero"):
        tactile.live(str(tmp_path), px_per_mm=47, blade_max_raw=200)
    # A Latero plays the latero layout only: refused before anything is sent.
    with pytest.raises(ValueError, match="layout: a Latero plays the latero layout"):
        tactile.live(str(DEMO / "frames"), calib=DEMO / "calibration.json", seconds=0.3,
                     latero="127.0.0.1:9")
