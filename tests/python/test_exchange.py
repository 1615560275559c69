"""HJIF export/import and WAV export from Python: the same files as `tactile export`."""

import struct

import numpy as np
import pytest

import tactile


def sine_movie(frames=50):
    t = np.arange(frames, dtype=np.float32)[:, None, None]
    phase = np.arange(100, dtype=np.float32).reshape(1, 10, 10) / 10.0
    d = (20.0 * np.sin(2 * np.pi * t / 25.0 + phase)).astype(np.float32)
    movie = tactile.Movie(d, "stress")
    movie.provenance.input = "a sine made in a test"
    return movie, d


def test_hjif_round_trip_keeps_deflections_layout_rate_and_provenance(tmp_path):
    movie, d = sine_movie()
    summary = tactile.export_hjif(tmp_path / "m.hjif", movie)
    # One channel per contactor of the 10 x 10 array, level 1 below 128 channels, one tick
    # per sample at 700 Hz.
    assert summary["channels"] == 100 and summary["level"] == 1
    assert summary["timescale"] == 700
    back = tactile.import_hjif(tmp_path / "m.hjif")
    assert back.layout.name == "stress" and back.rate_hz == 700
    assert back.provenance.input == "a sine made in a test"
    # Within the documented quantisation (1e-6 of full scale) and well within 0.1 um.
    assert np.max(np.abs(back.deflection_um - d)) < 0.1


def test_hjif_import_with_a_layout_that_does_not_fit_is_refused(tmp_path):
    movie, _ = sine_movie()
    tactile.export_hjif(tmp_path / "m.hjif", movie)
    with pytest.raises(Exception) as e:
        tactile.import_hjif(tmp_path / "m.hjif", layout="latero")
    assert "latero" in str(e.value) or "channel" in str(e.value)


def test_hjif_bad_input(tmp_path):
    with pytest.raises(FileNotFoundError):
        tactile.import_hjif(tmp_path / "missing.hjif")
    (tmp_path / "bad.hjif").write_text('{"version": "2023"')
    with pytest.raises(tactile.FormatError) as e:
        tactile.import_hjif(tmp_path / "bad.hjif")
    assert "bad.hjif" in str(e.value)


def test_wav_holds_every_sample_as_float32(tmp_path):
    movie, d = sine_movie()
    full_scale_um = tactile.export_wav(tmp_path / "m.wav", movie)
    raw = (tmp_path / "m.wav").read_bytes()
    assert raw[:4] == b"RIFF" and raw[8:12] == b"WAVE"
    # Walk the chunks independently of the writer; the data chunk holds frames x 100 floats.
    pos, fmt, data = 12, None, None
    while pos + 8 <= len(raw):
        cid, size = raw[pos : pos + 4], struct.unpack("<I", raw[pos + 4 : pos + 8])[0]
        body = raw[pos + 8 : pos + 8 + size]
        if cid == b"fmt ":
            fmt = body
        elif cid == b"data":
            data = body
        pos += 8 + size + (size & 1)
    channels, rate = struct.unpack("<HI", fmt[2:8])
    assert channels == 100 and rate == 700
    samples = np.frombuffer(data, dtype="<f4").reshape(-1, 100)
    np.testing.assert_allclose(samples * full_scale_um, d.reshape(-1, 100), atol=1e-4)
