"""tactile.synth writes the sequences `tactile synth` writes, by the same run."""

import json
import os
import pathlib
import subprocess

import pytest

import tactile

PRINT = pathlib.Path(os.environ["TACTILE_TEST_DATA_DIR"]) / "polyu-hrf-pores" / "image_12.jpg"


def frames_in(folder):
    return sorted(p.name for p in folder.glob("frame_*.png"))


def test_a_scene_is_the_command_lines_byte_for_byte(cli, tmp_path):
    got = tactile.synth(tmp_path / "py", frames=3, scene="hole", seed=7)
    assert got["frames"] == 3 and frames_in(tmp_path / "py") == [
        "frame_000.png", "frame_001.png", "frame_002.png"]
    assert got["landmark_positions"] > 0
    subprocess.run([cli, "synth", str(tmp_path / "cli"), "--frames", "3", "--scene", "hole",
                    "--seed", "7"], check=True, capture_output=True)
    for name in frames_in(tmp_path / "cli") + ["landmarks.csv"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    scene = json.loads((tmp_path / "py" / "scene.json").read_text())
    assert scene["spec"]["scene"] == "hole" and scene["spec"]["seed"] == 7


def test_a_print_with_a_speed_and_its_marks(tmp_path):
    got = tactile.synth(tmp_path / "warp", from_print=PRINT, px_per_mm=47, frames=4,
                        warp="full-slip", travel_speed=25, rate_hz=120)
    assert got["frames"] == 4 and len(frames_in(tmp_path / "warp")) == 4
    # pores_12.txt beside image_12.jpg is found, as the command line finds it.
    assert got["marked_pores"] > 100
    assert "25 mm/s" in got["summary"] and "120 Hz" in got["summary"]


def test_a_seed_beyond_the_signed_range_is_taken_whole(tmp_path):
    tactile.synth(tmp_path / "s", frames=2, seed=2**64 - 1)
    scene = json.loads((tmp_path / "s" / "scene.json").read_text())
    assert str(scene["spec"]["seed"]) == str(2**64 - 1)
    with pytest.raises(ValueError, match="18446744073709551616 is not a whole number"):
        tactile.synth(tmp_path / "t", frames=2, seed=2**64)


def test_stale_frames_are_refused_before_any_work(tmp_path):
    tactile.synth(tmp_path / "s", frames=3)
    with pytest.raises(Exception, match="already holds 1 image file"):
        tactile.synth(tmp_path / "s", frames=2)
