"""capture(): strain from a folder of frames, as `tactile capture` measures it."""

import struct
import subprocess

import numpy as np
import pytest

import tactile

PX_PER_MM = 62.0  # the synthetic prism camera's scale, roughly; both sides use the same


@pytest.fixture(scope="module")
def frames(tmp_path_factory, cli):
    folder = tmp_path_factory.mktemp("scene")
    subprocess.run([cli, "synth", str(folder), "--scene", "flat-slide", "--frames", "40"],
                   check=True, capture_output=True)
    return folder


@pytest.fixture(scope="module")
def cli():
    import os
    return os.environ["TACTILE_CLI"]


def image_folder(frames):
    # synth writes its frames into a sub-folder or beside its ground truth; capture wants the
    # folder of images.
    pngs = sorted(frames.rglob("*.png"))
    return pngs[len(pngs) // 2].parent


def test_capture_matches_the_command_line(frames, cli, tmp_path, capsys):
    images = image_folder(frames)
    strain = tactile.capture(images, px_per_mm=PX_PER_MM, min_track=10)
    out = capsys.readouterr().out
    assert "capture: pores:" in out and "capture: refinement against the images:" in out
    subprocess.run([cli, "capture", str(images), "--px-per-mm", str(PX_PER_MM), "--min-track",
                    "10", "--out", str(tmp_path / "cli.h5")], check=True, capture_output=True)
    expected = tactile.read_strain_movie(tmp_path / "cli.h5")
    assert strain.camera_frame_count == expected.camera_frame_count == 40
    assert len(strain.frames) == len(expected.frames) > 0
    np.testing.assert_array_equal(strain.tracks["track_id"], expected.tracks["track_id"])
    np.testing.assert_allclose(strain.tracks["x_mm"], expected.tracks["x_mm"])
    assert strain.provenance.input == str(images) and strain.provenance.method == "capture"
    # The contact map: the same as the command line's, one cell map per camera frame, each cell in
    # contact exactly when its ridge contrast reaches the threshold.
    contact, cli_contact = strain.contact, expected.contact
    rows, columns = contact["in_contact"].shape[1:]
    assert contact["in_contact"].shape == (40, rows, columns) and rows * columns > 0
    assert rows == -(-expected.calibration.image_height_px // contact["cell_px"])
    np.testing.assert_array_equal(contact["in_contact"], cli_contact["in_contact"])
    np.testing.assert_allclose(contact["ridge_contrast"], cli_contact["ridge_contrast"])
    np.testing.assert_array_equal(contact["in_contact"] == 1,
                                  contact["ridge_contrast"] >= contact["threshold"])


def test_capture_a_range(frames):
    strain = tactile.capture(image_folder(frames), px_per_mm=PX_PER_MM, start=10, frames=25,
                             min_track=10, pores="paper", refine="off")
    assert strain.camera_frame_count == 25


def test_capture_bad_input(frames, tmp_path):
    images = image_folder(frames)
    with pytest.raises(FileNotFoundError):
        tactile.capture(tmp_path / "absent", px_per_mm=PX_PER_MM)
    with pytest.raises(ValueError, match="give one of calib"):
        tactile.capture(images)
    with pytest.raises(ValueError, match="px_per_mm: 1 is out of range"):
        tactile.capture(images, px_per_mm=1)
    # Named as Python spells it, not as the command line does.
    with pytest.raises(ValueError, match="^start: 40 is out of range"):
        tactile.capture(images, px_per_mm=PX_PER_MM, start=40)
    with pytest.raises(ValueError, match="pores: unknown value 'blobs'"):
        tactile.capture(images, px_per_mm=PX_PER_MM, pores="blobs")
    with pytest.raises(FileNotFoundError):
        tactile.capture(images, calib=tmp_path / "absent.json")
    # One frame makes no frame pair: the command line's message, without its output file.
    with pytest.raises(RuntimeError) as error:
        tactile.capture(images, px_per_mm=PX_PER_MM, frames=1, pores="paper", refine="off")
    assert str(error.value) == (f"capture: {images}: no strain measured in 1 frames (tracks of at "
                                "least --min-track 30 frames over --span 1: 0 tracked points, 0 strain "
                                "frames with any edge between them)")


def write_raw_avi(path, frames, rate_hz):
    """An uncompressed AVI (BI_RGB, 24-bit, bottom-up rows) of 8-bit grey frames: lossless, and
    written here so that the test needs no video library of its own."""
    h, w = frames[0].shape
    row = (w * 3 + 3) // 4 * 4
    size = row * h

    def chunk(tag, data):
        return tag + struct.pack("<I", len(data)) + data + (b"\0" if len(data) % 2 else b"")

    def lst(kind, data):
        return chunk(b"LIST", kind + data)

    avih = struct.pack("<14I", int(1e6 / rate_hz), size * int(rate_hz), 0, 0x10, len(frames), 0,
                       1, size, w, h, 0, 0, 0, 0)
    strh = struct.pack("<4s4sIHHIIIIIIIIhhhh", b"vids", b"\0\0\0\0", 0, 0, 0, 0, 1,
                       int(rate_hz), 0, len(frames), size, 0xFFFFFFFF, 0, 0, 0, w, h)
    strf = struct.pack("<IiiHHIIiiII", 40, w, h, 1, 24, 0, size, 0, 0, 0, 0)
    header = lst(b"hdrl", chunk(b"avih", avih) + lst(b"strl", chunk(b"strh", strh) +
                                                      chunk(b"strf", strf)))
    movi, index, offset = b"", b"", 4
    for f in frames:
        bgr = np.repeat(f[::-1, :, None], 3, axis=2)
        data = b"".join(r.tobytes().ljust(row, b"\0") for r in bgr)
        index += struct.pack("<4sIII", b"00db", 0x10, offset, len(data))
        movi += chunk(b"00db", data)
        offset += 8 + len(data)
    body = b"AVI " + header + lst(b"movi", movi) + chunk(b"idx1", index)
    path.write_bytes(b"RIFF" + struct.pack("<I", len(body)) + body)


def test_capture_from_a_video_equals_the_folder(frames, tmp_path):
    images = image_folder(frames)
    import matplotlib.image
    pngs = sorted(p for p in images.iterdir() if p.suffix == ".png")
    grey = [np.round(matplotlib.image.imread(p) * 255).astype(np.uint8) for p in pngs[:30]]
    grey = [g if g.ndim == 2 else g[:, :, 0] for g in grey]
    write_raw_avi(tmp_path / "scene.avi", grey, 30)
    from_video = tactile.capture(tmp_path / "scene.avi", px_per_mm=PX_PER_MM, min_track=10,
                                 pores="paper", refine="off")
    from_folder = tactile.capture(images, px_per_mm=PX_PER_MM, frames=30, min_track=10,
                                  pores="paper", refine="off")
    assert from_video.frame_rate_hz == 30  # the container's rate
    assert from_video.camera_frame_count == 30
    np.testing.assert_allclose(from_video.tracks["x_mm"], from_folder.tracks["x_mm"])
