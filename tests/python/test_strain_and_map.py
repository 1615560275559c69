"""Strain movies as arrays, and map() with the rules of `tactile map`."""

import subprocess

import numpy as np
import pytest

import tactile
from conftest import stretched_grid


def test_strain_movie_round_trip_and_views(tmp_path, strain):
    assert strain.camera_frame_count == 12 and len(strain.frames) == 11
    tactile.write_strain_movie(tmp_path / "s.h5", strain)
    back = tactile.read_strain_movie(tmp_path / "s.h5")
    assert back.frame_rate_hz == 60 and back.provenance.input == "stretched grid"
    np.testing.assert_allclose(back.tracks["x_mm"], strain.tracks["x_mm"])
    f = back.frames[3]
    assert (f.frame_from, f.frame_to) == (3, 4)
    horizontal = np.abs(f.edges["track_a"] - f.edges["track_b"]) == 1
    np.testing.assert_allclose(f.edges["rel_change"][horizontal], 0.01, atol=1e-12)
    vertical = np.abs(f.edges["track_a"] - f.edges["track_b"]) == 14
    np.testing.assert_allclose(f.edges["rel_change"][vertical], 0.0, atol=1e-12)
    assert f.triangles.shape == (2 * 13 * 13, 3)
    tracks = back.tracks
    assert tracks.base is back and not tracks.flags.owndata
    assert tracks.__array_interface__["data"][0] == back.tracks.__array_interface__["data"][0]
    assert f.points_from.__array_interface__["data"][0] == \
        back.frames[3].points_from.__array_interface__["data"][0]
    # A movie made in Python has no contact map, and none is written for it.
    assert strain.contact is None and back.contact is None


def test_strain_frame_bad_input():
    p = np.zeros(3, dtype=tactile.POINT_DTYPE)
    e = np.zeros(0, dtype=tactile.EDGE_DTYPE)
    ok = dict(frame_from=0, frame_to=1, t_s=0.1, points_from=p, points_to=p, edges=e,
              triangles=np.array([[0, 1, 2]]))
    tactile.StrainFrame(**ok)
    with pytest.raises(TypeError, match="points_from: dtype float64 has no field 'track_id'"):
        tactile.StrainFrame(**{**ok, "points_from": np.zeros(3)})
    with pytest.raises(ValueError, match="points_to: 2 points but points_from has 3"):
        tactile.StrainFrame(**{**ok, "points_to": p[:2]})
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        tactile.StrainFrame(**{**ok, "triangles": np.array([0, 1, 2])})
    with pytest.raises(ValueError, match="point index 3 is out of range: must be 0 to 2"):
        tactile.StrainFrame(**{**ok, "triangles": np.array([[0, 1, 3]])})
    with pytest.raises(TypeError, match="triangles: dtype float64 is not an integer"):
        tactile.StrainFrame(**{**ok, "triangles": np.array([[0.0, 1.0, 2.0]])})
    with pytest.raises(ValueError, match="frame_rate_hz: 0 is out of range"):
        tactile.StrainMovie(frame_rate_hz=0, tracks=p, frames=[])


def test_read_strain_movie_missing_and_wrong_kind(tmp_path):
    with pytest.raises(FileNotFoundError):
        tactile.read_strain_movie(tmp_path / "absent.h5")
    tactile.write_movie(tmp_path / "m.h5", tactile.Movie(np.zeros((1, 10, 10)), "stress"))
    with pytest.raises(tactile.FormatError, match="tactile-strain-movie"):
        tactile.read_strain_movie(tmp_path / "m.h5")


def test_integrated_imposes_the_known_strain(strain):
    # Uniform e_xx = 0.01 and 1 mm pitch: neighbouring contactors along x differ by
    # 1000 um/strain * 0.01 * 1 mm = 10 um (methods.hpp), in every row.
    movie = tactile.map(strain, "stress", method="integrated")
    assert movie.rate_hz == 700 and movie.provenance.method == "integrated"
    middle = movie.deflection_um[movie.frame_count // 2]
    np.testing.assert_allclose(np.diff(middle, axis=1), 10.0, atol=0.05)
    proportional = tactile.map(strain, "stress", method="proportional", gain=2000)
    np.testing.assert_allclose(proportional.deflection_um[proportional.frame_count // 2],
                               20.0, atol=0.05)


def test_map_matches_the_command_line(tmp_path, strain, cli):
    tactile.write_strain_movie(tmp_path / "s.h5", strain)
    subprocess.run([cli, "map", str(tmp_path / "s.h5"), "--out", str(tmp_path / "cli.h5"),
                    "--layout", "latero", "--method", "proportional", "--normalise", "peak"],
                   check=True, capture_output=True)
    cli_movie = tactile.read_movie(tmp_path / "cli.h5")
    py_movie = tactile.map(strain, "latero", method="proportional", normalise="peak")
    assert py_movie.rate_hz == cli_movie.rate_hz == 750  # the layout's own rate
    np.testing.assert_array_equal(py_movie.deflection_um, cli_movie.deflection_um)


def test_map_refuses_what_the_command_line_refuses(tmp_path, strain, cli):
    tactile.write_strain_movie(tmp_path / "s.h5", strain)
    run = subprocess.run([cli, "map", str(tmp_path / "s.h5"), "--out", str(tmp_path / "m.h5"),
                          "--layout", "latero", "--rate-hz", "800"], capture_output=True,
                         text=True)
    assert run.returncode == 2  # a parameter the layout cannot play is wrong usage
    with pytest.raises(ValueError) as error:
        tactile.map(strain, "latero", rate_hz=800)
    assert str(error.value) in run.stderr
    with pytest.raises(ValueError, match="integrated"):
        tactile.map(strain, method="sideways")
    with pytest.raises(ValueError, match="peak_fraction"):
        tactile.map(strain, normalise="peak", peak_fraction=1.5)
    with pytest.raises(ValueError, match="no strain frames"):
        tactile.map(tactile.StrainMovie(frame_rate_hz=60, tracks=strain.tracks, frames=[]))
    with pytest.raises(TypeError):
        tactile.map(np.zeros(3))
    with pytest.raises(ValueError, match="reference_frame: frame 5000 is not in the strain movie"):
        tactile.map(strain, strain_mode="accumulated", reference_frame=5000)


def test_accumulated_strain():
    movie = tactile.map(stretched_grid(frames=8), "stress2", strain_mode="accumulated")
    assert movie.layout.name == "stress2" and movie.frame_count > 0
