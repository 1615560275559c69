"""Tactile movies and layouts: create, write, read, zero-copy views, and bad input."""

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import tactile


def ramp_movie(frames=5):
    d = np.arange(frames * 100, dtype=np.float32).reshape(frames, 10, 10) % 40 - 20
    return tactile.Movie(d, "stress"), d


def test_create_write_read_round_trip(tmp_path):
    movie, d = ramp_movie()
    assert movie.rate_hz == 700  # the layout's own rate when none is given
    assert movie.frame_count == 5 and movie.layout.rows == 10
    movie.provenance.input = "made in a test"
    tactile.write_movie(tmp_path / "m.h5", movie)
    back = tactile.read_movie(str(tmp_path / "m.h5"))
    np.testing.assert_array_equal(back.deflection_um, d)
    assert back.deflection_um.dtype == np.float32
    assert back.provenance.input == "made in a test"
    assert back.layout.name == "stress" and back.rate_hz == 700


def test_movie_from_float64_and_custom_rate():
    d = np.zeros((3, 8, 8))
    movie = tactile.Movie(d, tactile.layout("latero"), rate_hz=500)
    assert movie.rate_hz == 500 and movie.deflection_um.shape == (3, 8, 8)


def test_deflections_are_a_view_of_the_movie(tmp_path):
    movie, _ = ramp_movie()
    a, b = movie.deflection_um, movie.deflection_um
    assert a.__array_interface__["data"][0] == b.__array_interface__["data"][0]
    assert not a.flags.owndata and a.base is movie
    a[0, 0, 0] = 7.5  # writes reach the movie itself
    tactile.write_movie(tmp_path / "m.h5", movie)
    assert tactile.read_movie(tmp_path / "m.h5").deflection_um[0, 0, 0] == 7.5


def test_view_keeps_the_movie_alive():
    movie, d = ramp_movie()
    view = movie.deflection_um
    del movie
    np.testing.assert_array_equal(view, d)


def test_one_hour_at_700_hz_is_read_without_a_copy(tmp_path):
    # A real hour at 700 Hz on a 2 x 2 array (40 MB), read in a fresh interpreter: the peak
    # resident size may grow by the movie once (plus HDF5's chunk cache), not twice.
    path = tmp_path / "hour.h5"
    frames = 3600 * 700
    layout = tactile.Layout(name="two-by-two", rows=2, cols=2, max_rate_hz=700)
    d = np.zeros((frames, 2, 2), dtype=np.float32)
    d[:, 0, 0] = np.sin(np.arange(frames) / 100.0) * 20
    tactile.write_movie(path, tactile.Movie(d, layout))
    del d
    script = textwrap.dedent(
        f"""
        import resource, numpy, tactile
        before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        m = tactile.read_movie({str(path)!r})
        a = m.deflection_um
        after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        assert a.shape == ({frames}, 2, 2) and a.base is m
        print((after - before) * 1024, a.nbytes)
        """
    )
    out = subprocess.run([sys.executable, "-c", script], check=True, capture_output=True,
                         text=True, env=os.environ).stdout.split()
    grew, nbytes = int(out[0]), int(out[1])
    assert nbytes == frames * 4 * 4
    assert grew < 1.5 * nbytes, f"reading grew the peak RSS by {grew} bytes for {nbytes}"


def test_wrong_dtype_is_a_type_error():
    with pytest.raises(TypeError, match="deflection_um: dtype int32 is not a floating-point"):
        tactile.Movie(np.zeros((2, 10, 10), dtype=np.int32), "stress")


def test_wrong_shape_is_a_value_error():
    with pytest.raises(ValueError, match=r"shape \(2, 8, 8\) does not fit the layout stress"):
        tactile.Movie(np.zeros((2, 8, 8), dtype=np.float32), "stress")
    with pytest.raises(ValueError, match=r"expected \(frames, 10, 10\)"):
        tactile.Movie(np.zeros(100, dtype=np.float32), "stress")


def test_non_finite_deflections_are_refused():
    d = np.zeros((2, 10, 10), dtype=np.float32)
    d[1, 2, 3] = np.nan
    with pytest.raises(ValueError):
        tactile.Movie(d, "stress")


def test_missing_file_is_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such file"):
        tactile.read_movie(tmp_path / "absent.h5")


def test_damaged_file_carries_the_programs_message(tmp_path, cli):
    bad = tmp_path / "bad.h5"
    bad.write_bytes(b"not an HDF5 file at all" * 10)
    with pytest.raises(tactile.FormatError) as error:
        tactile.read_movie(bad)
    assert isinstance(error.value, OSError)
    run = subprocess.run([cli, "info", str(bad)], capture_output=True, text=True)
    assert run.returncode == 1
    assert str(error.value) in run.stderr


def test_unwritable_output_is_an_os_error(tmp_path):
    movie, _ = ramp_movie()
    with pytest.raises(OSError, match="cannot write"):
        tactile.write_movie(tmp_path / "no-such-folder" / "m.h5", movie)


def test_csv_export(tmp_path):
    movie, d = ramp_movie(2)
    tactile.export_csv(tmp_path / "m.csv", movie)
    rows = (tmp_path / "m.csv").read_text().splitlines()
    assert rows[0].startswith("frame,t_s,r0c0_um,r0c1_um")
    assert len(rows) == 3 and float(rows[2].split(",")[3]) == d[1, 0, 1]


def test_layouts(tmp_path):
    latero = tactile.layout("latero")
    assert (latero.rows, latero.cols, latero.max_rate_hz, latero.axis) == (8, 8, 750, "x")
    custom = tactile.Layout(name="strip", rows=1, cols=6, pitch_x_mm=2, pitch_y_mm=2,
                            axis="y", max_rate_hz=1000)
    path = tmp_path / "strip.json"
    path.write_text(custom.to_json())
    back = tactile.layout(str(path))
    assert (back.name, back.cols, back.pitch_x_mm, back.axis) == ("strip", 6, 2.0, "y")
    assert tactile.layout_from_json(custom.to_json()).max_rate_hz == 1000


def test_bad_layouts():
    with pytest.raises(ValueError, match="unknown layout|known"):
        tactile.layout("stres")
    with pytest.raises(ValueError, match="'rows' = 0"):
        tactile.Layout(name="empty", rows=0, cols=3)
    with pytest.raises(ValueError, match="unknown axis 'z' \\(known: x, y\\)"):
        tactile.Layout(name="z", rows=2, cols=2, axis="z")
    with pytest.raises(FileNotFoundError):
        tactile.layout("/no/such/layout.json")
    with pytest.raises(tactile.FormatError, match="layout JSON"):
        tactile.layout_from_json("{")
