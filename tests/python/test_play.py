"""play(): the device selection and playing of `tactile play`."""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import tactile


def small_movie():
    t = np.arange(140) / 700.0
    d = np.zeros((140, 10, 10), dtype=np.float32)
    d[:, :, :] = (20 * np.sin(2 * np.pi * 5 * t))[:, None, None]
    return tactile.Movie(d, "stress")


def test_headless_plays_every_frame_and_ends_at_rest(tmp_path, capsys):
    result = tactile.play(small_movie(), backend="headless", preview=tmp_path / "p.png")
    out = capsys.readouterr().out
    assert result["target"] == "headless" and not result["stopped"]
    # The movie plus the start and stop ramps, all played by the emulated firmware.
    assert result["frames_played"] >= 140 and result["underruns"] == 0
    assert result["rate_hz"] == 700
    assert result["final_max_um"] == 0
    assert (tmp_path / "p.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "play: headless (emulated device)" in out and "preview of what" in out


def test_auto_without_display_or_screen_goes_headless_like_the_command_line(tmp_path, cli):
    # No display is attached to this machine, and without DISPLAY there is no screen: the
    # command line and the module must both choose headless and say so in the same words.
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    tactile.write_movie(tmp_path / "m.h5", small_movie())
    code = ("import tactile; r = tactile.play(tactile.read_movie(%r)); print(r['target'])"
            % str(tmp_path / "m.h5"))
    py = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                        check=True, cwd=tmp_path).stdout
    run = subprocess.run([cli, "play", str(tmp_path / "m.h5"), "--preview",
                          str(tmp_path / "cli.png")], env=env, capture_output=True, text=True,
                         check=True).stdout
    decision = "play: no display attached and no screen; playing headless into the emulated device"
    assert decision in py and decision in run
    assert py.strip().endswith("headless")


def test_play_bad_arguments():
    movie = small_movie()
    with pytest.raises(ValueError, match="backend: 'usb' is not auto or headless"):
        tactile.play(movie, backend="usb")
    with pytest.raises(ValueError, match="loops: 0 is out of range"):
        tactile.play(movie, backend="headless", loops=0)
    with pytest.raises(TypeError):
        tactile.play(np.zeros((3, 10, 10)), backend="headless")


def test_ctrl_c_stops_between_frames_ramps_to_rest_and_raises(tmp_path):
    # Long enough (1000 loops of 2 s) that only the signal can end it in time.
    script = (
        "import sys, numpy as np, tactile\n"
        "d = np.zeros((1400, 10, 10), dtype=np.float32)\n"
        "d[:] = (20 * np.sin(np.arange(1400) / 20.0))[:, None, None]\n"
        "movie = tactile.Movie(d, 'stress')\n"
        "print('ready', flush=True)\n"
        "tactile.play(movie, backend='headless', loops=1000, preview=%r)\n"
        % str(tmp_path / "p.png"))
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, env=os.environ)
    try:
        assert child.stdout.readline().strip() == "ready"
        time.sleep(0.5)
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=60)
    finally:
        child.kill()
    assert child.returncode != 0 and "KeyboardInterrupt" in err
    assert "stopped by a stop request, every contactor ramped to rest" in out
    assert "outputs ended at most 0 um from rest" in out
    assert "no preview written" in out and not (tmp_path / "p.png").exists()
