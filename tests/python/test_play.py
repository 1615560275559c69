"""play(): the device selection and playing of `tactile play`, a Latero included (played to the
emulated Latero of `tactile emulate --latero` on 127.0.0.1)."""

import os
import re
import signal
import socket
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
    result = tactile.play(small_movie(), headless=True, preview=tmp_path / "p.png")
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
    # command line and the module must both choose headless; the module, which has no emulator
    # window, says that instead of looking for a screen.
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    tactile.write_movie(tmp_path / "m.h5", small_movie())
    code = ("import tactile; r = tactile.play(tactile.read_movie(%r)); print(r['target'])"
            % str(tmp_path / "m.h5"))
    py = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                        check=True, cwd=tmp_path).stdout
    run = subprocess.run([cli, "play", str(tmp_path / "m.h5"), "--preview",
                          str(tmp_path / "cli.png")], env=env, capture_output=True, text=True,
                         check=True).stdout
    assert ("play: no display attached and no screen; playing headless into the emulated device"
            in run)
    assert ("play: no display attached; playing headless into the emulated device (no emulator "
            "window in this program)" in py)
    assert py.strip().endswith("headless")


def test_the_module_links_no_gui_library():
    # play() offers displays on USB but no window, so the module itself needs neither GLFW, GL
    # nor Dear ImGui. Checked on what the module asks the loader for (not on everything those
    # libraries load in turn), and on its bytes for Dear ImGui, a static library: its default
    # settings file name would be in the module, as the play messages are.
    module = tactile.__file__
    needed = subprocess.run(["readelf", "-d", module], capture_output=True, text=True,
                            check=True).stdout
    assert "(NEEDED)" in needed and "libstdc++" in needed
    assert not re.search(r"glfw|libGL\.so|libOpenGL", needed), needed
    with open(module, "rb") as f:
        data = f.read()
    assert b"no emulator window in this program" in data
    assert b"imgui.ini" not in data


def test_play_bad_arguments():
    movie = small_movie()
    with pytest.raises(TypeError, match="unexpected keyword argument 'backend'"):
        tactile.play(movie, backend="usb")
    with pytest.raises(ValueError, match="loops: 0 is out of range"):
        tactile.play(movie, headless=True, loops=0)
    with pytest.raises(ValueError, match="preview: the path is empty"):
        tactile.play(movie, headless=True, preview="")
    with pytest.raises(ValueError, match="headless: takes true or false"):
        tactile.play(movie, headless=1)
    with pytest.raises(TypeError):
        tactile.play(np.zeros((3, 10, 10)), headless=True)


def test_ctrl_c_stops_between_frames_ramps_to_rest_and_raises(tmp_path):
    # Long enough (1000 loops of 2 s) that only the signal can end it in time.
    script = (
        "import sys, numpy as np, tactile\n"
        "d = np.zeros((1400, 10, 10), dtype=np.float32)\n"
        "d[:] = (20 * np.sin(np.arange(1400) / 20.0))[:, None, None]\n"
        "movie = tactile.Movie(d, 'stress')\n"
        "print('ready', flush=True)\n"
        "tactile.play(movie, headless=True, loops=1000, preview=%r)\n"
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


def latero_movie(frames, amplitude_um=40.0):
    t = np.arange(frames) / 750.0
    k = np.arange(64).reshape(8, 8) / 64.0
    d = amplitude_um * np.sin(2 * np.pi * (3 * t[:, None, None] + k[None, :, :]))
    return tactile.Movie(d.astype(np.float32), "latero")


class EmulatedLatero:
    """`tactile emulate --latero` on a free loopback port, stopped with SIGINT (its ordinary
    end), after which its counters and where it left the blades are read from what it printed."""

    def __init__(self, cli):
        self.process = subprocess.Popen([cli, "emulate", "--latero", "--port", "0", "--seconds",
                                         "60"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        text=True)
        first = self.process.stdout.readline()
        found = re.search(r"answering on (127\.0\.0\.1:\d+) \(UDP\)", first)
        assert found, first
        self.address = found.group(1)

    def stop(self):
        self.process.send_signal(signal.SIGINT)
        out, _ = self.process.communicate(timeout=10)
        assert self.process.returncode == 0, out
        return out

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


def counters(emulator_output):
    datagrams = re.search(r"datagrams\s+(\d+) received: (\d+) FULL \(frames played\), (\d+) IO, "
                          r"(\d+) RAW, (\d+) malformed", emulator_output)
    replies = re.search(r"replies\s+(\d+) sent, (\d+) left out", emulator_output)
    blades = re.search(r"blades\s+left at raw (\d+)\.\.(\d+)", emulator_output)
    assert datagrams and replies and blades, emulator_output
    return {"full": int(datagrams.group(2)), "io": int(datagrams.group(3)),
            "malformed": int(datagrams.group(5)), "replies_sent": int(replies.group(1)),
            "blades": (int(blades.group(1)), int(blades.group(2)))}


def test_latero_backend_plays_to_the_emulated_latero_and_ends_at_rest(cli, capsys):
    with EmulatedLatero(cli) as latero:
        result = tactile.play(latero_movie(150), latero=latero.address)
        got = counters(latero.stop())
    out = capsys.readouterr().out
    assert result["target"] == "latero" and result["address"] == latero.address
    assert not result["stopped"]
    # Every movie frame was sent, with the start and stop ramps around them.
    assert result["movie_frames"] == 150 and result["ramp_frames"] > 0
    assert result["frames_sent"] == 150 + result["ramp_frames"]
    assert result["rate_hz"] == 750 and result["achieved_rate_hz"] > 0
    # What the sender counted is what the device received: every request a FULL request (the
    # frames and the stop ramp), one IO request (the probe), nothing malformed, and every reply
    # the device sent came back (the probe's among them).
    assert got["full"] == result["requests_sent"] and got["full"] > result["frames_sent"]
    assert got["io"] == 1 and got["malformed"] == 0
    assert got["replies_sent"] == result["replies_received"] + 1
    # The movie moved the blades (40 um of 100 um full scale: raw 75 +- 30); the stop ramp brought
    # every one back to OpenLatero's centre, raw 75.
    assert got["blades"] == (75, 75)
    assert "play: streaming to the Latero at " + latero.address in out
    assert "raw 75 at rest, +75 per 100 um, at most 150" in out


def test_latero_blade_mapping_is_the_users_to_set(cli, capsys):
    with EmulatedLatero(cli) as latero:
        result = tactile.play(latero_movie(75), latero=latero.address,
                              blade_centre_raw=128, blade_max_raw=255)
        got = counters(latero.stop())
    assert result["target"] == "latero"
    assert got["blades"] == (128, 128)
    assert "raw 128 at rest" in capsys.readouterr().out


def test_latero_bad_arguments(cli):
    movie = latero_movie(10)
    with pytest.raises(ValueError, match="latero: is empty"):
        tactile.play(movie, latero="")
    with pytest.raises(ValueError, match="headless: not with latero"):
        tactile.play(movie, headless=True, latero="127.0.0.1")
    with pytest.raises(ValueError, match="blade mapping is only for a Latero: give latero"):
        tactile.play(movie, headless=True, blade_centre_raw=100)
    with pytest.raises(ValueError, match="blade_raw_per_unit: 0 is out of range"):
        tactile.play(movie, latero="127.0.0.1:9", blade_raw_per_unit=0)
    for address, why in [("127.0.0.1:0", "outside 1..65535"), ("127.0.0.1:port", "not a number"),
                         (":8900", "no host"), ("[::1", "without ']'")]:
        with pytest.raises(ValueError, match=re.escape(why)):
            tactile.play(movie, latero=address)
    # The movie and the blade mapping are checked before anything is sent: no device needed.
    with pytest.raises(ValueError, match="centre_raw 200 is outside \\[0, max_raw 150\\]"):
        tactile.play(movie, latero="127.0.0.1:9", blade_centre_raw=200)
    with pytest.raises(ValueError) as e:
        tactile.play(small_movie(), latero="127.0.0.1:9")
    assert "'stress'" in str(e.value) and "'latero'" in str(e.value)
    assert "--layout latero" in str(e.value)


def test_latero_nothing_answering_is_a_device_error_naming_the_address():
    # A port with nobody on it (bound here, never answered): the probe gets no reply.
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        address = "127.0.0.1:%d" % s.getsockname()[1]
        with pytest.raises(tactile.DeviceError, match=re.escape(address)):
            tactile.play(latero_movie(10), latero=address)


def test_ctrl_c_on_the_latero_stops_and_ramps_every_blade_to_rest(cli):
    with EmulatedLatero(cli) as latero:
        # Ten seconds: only the signal can end it in time.
        script = (
            "import sys, numpy as np, tactile\n"
            "t = np.arange(7500) / 750.0\n"
            "d = np.zeros((7500, 8, 8), dtype=np.float32)\n"
            "d[:] = (40 * np.sin(2 * np.pi * 3 * t))[:, None, None]\n"
            "movie = tactile.Movie(d, 'latero')\n"
            "print('ready', flush=True)\n"
            "tactile.play(movie, latero=%r)\n" % latero.address)
        child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, text=True, env=os.environ)
        try:
            assert child.stdout.readline().strip() == "ready"
            time.sleep(1.0)
            signalled = time.monotonic()
            child.send_signal(signal.SIGINT)
            out, err = child.communicate(timeout=30)
            stop_s = time.monotonic() - signalled
        finally:
            child.kill()
        got = counters(latero.stop())
    assert child.returncode != 0 and "KeyboardInterrupt" in err
    assert "stopped     by a stop request before the end" in out
    # Within the 20 ms stop ramp and the wait for its replies, with room for a busy machine.
    assert stop_s < 5
    sent = re.search(r"frames\s+(\d+) sent \((\d+) movie", out)
    requests = re.search(r"replies\s+(\d+) requests", out)
    assert sent and requests, out
    assert int(sent.group(2)) == 7500 and 0 < int(sent.group(1)) < 7500  # movie, sent
    # The device received every request the player counted, the stop ramp included, and the
    # blades are where its last request left them: at centre.
    assert got["full"] == int(requests.group(1))
    assert got["blades"] == (75, 75)
