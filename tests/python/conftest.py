"""Shared fixtures of the Python module's tests: the paths CTest passes, and a strain movie made
from arrays whose strain is known exactly (a grid of points stretched uniformly along x)."""

import os
import pathlib

import numpy as np
import pytest

import tactile


@pytest.fixture
def cli():
    """The `tactile` program of the same build."""
    return os.environ["TACTILE_CLI"]


@pytest.fixture
def data_dir():
    return pathlib.Path(os.environ["TACTILE_TEST_DATA_DIR"])


def stretched_grid(strain_per_frame=0.01, frames=12, points=14, rate_hz=60.0):
    """Points 1 mm apart on a points x points grid; between consecutive camera frames every
    length along x grows by strain_per_frame (so each strain frame's e_xx is exactly that)."""
    ys, xs = np.mgrid[0:points, 0:points].astype(float)
    ids = np.arange(points * points, dtype=np.int32)
    centre = (points - 1) / 2

    def positions(f):
        return centre + (xs.ravel() - centre) * (1 + strain_per_frame) ** f, ys.ravel()

    def point_array(f):
        p = np.zeros(ids.size, dtype=tactile.POINT_DTYPE)
        x, y = positions(f)
        p["track_id"], p["frame"], p["type"] = ids, f, 0
        p["x_mm"], p["y_mm"], p["x_px"], p["y_px"] = x, y, 10 * x, 10 * y
        return p

    triangles = []
    for r in range(points - 1):
        for c in range(points - 1):
            a, b = r * points + c, r * points + c + 1
            d, e = a + points, b + points
            triangles += [(a, b, d), (b, e, d)]
    triangles = np.array(triangles, dtype=np.int32)
    pairs = sorted({tuple(sorted((t[i], t[(i + 1) % 3]))) for t in triangles for i in range(3)})
    strain_frames = []
    for f in range(frames - 1):
        p0, p1 = point_array(f), point_array(f + 1)
        edges = np.zeros(len(pairs), dtype=tactile.EDGE_DTYPE)
        for k, (a, b) in enumerate(pairs):
            l0 = np.hypot(p0["x_mm"][a] - p0["x_mm"][b], p0["y_mm"][a] - p0["y_mm"][b])
            l1 = np.hypot(p1["x_mm"][a] - p1["x_mm"][b], p1["y_mm"][a] - p1["y_mm"][b])
            edges[k] = (a, b, l0, l1, (l1 - l0) / l0)
        strain_frames.append(tactile.StrainFrame(frame_from=f, frame_to=f + 1, t_s=(f + 1) / rate_hz,
                                                 points_from=p0, points_to=p1, edges=edges,
                                                 triangles=triangles))
    tracks = np.concatenate([point_array(f) for f in range(frames)])
    tracks = tracks[np.lexsort((tracks["frame"], tracks["track_id"]))]
    return tactile.StrainMovie(frame_rate_hz=rate_hz, tracks=tracks, frames=strain_frames,
                               field_width_mm=points - 1.0, field_height_mm=points - 1.0,
                               calibration=tactile.Calibration.uniform(10.0, 140, 140),
                               source="stretched grid")


@pytest.fixture
def strain():
    return stretched_grid()
