"""Video files: frame count and size read back, finalization on interrupt, PNGs."""

import imageio.v3 as iio
import numpy as np
import pytest

from etswarm.errors import EtswarmError
from etswarm.viewer.render import render
from etswarm.viewer.sample import sample_scene
from etswarm.viewer.video import VideoWriter, record_video, save_png
from etswarm.viewer.view import ViewState


def frames(n: int, h: int = 120, w: int = 160) -> list[np.ndarray]:
    out = []
    for k in range(n):
        f = np.zeros((h, w, 3), np.uint8)
        f[:, : (k + 1) * w // n] = (200, 40 + 10 * k, 30)
        out.append(f)
    return out


@pytest.mark.parametrize("suffix", [".mp4", ".gif"])
def test_video_has_the_frames_written_at_their_size(tmp_path, suffix) -> None:
    path = tmp_path / f"out{suffix}"
    n = record_video(iter(frames(12)), path, fps=12, progress=False)
    assert n == 12
    back = iio.imread(path, index=None)
    assert back.shape[:3] == (12, 120, 160)


def test_rendered_frames_make_a_video_with_a_progress_bar(tmp_path) -> None:
    scene = sample_scene()
    view = ViewState.fitted(scene, 320, 240)

    def gen():
        for _ in range(6):
            scene.sim_time_s += 1
            scene.pos = scene.pos + np.array([1.0, 0.0])
            yield render(scene, view)

    path = tmp_path / "sub" / "clip.mp4"
    assert record_video(gen(), path, fps=6, progress=True, total=6) == 6
    back = iio.imread(path, index=None)
    assert back.shape == (6, 240, 320, 3)
    # the colours survive the encoding (white background in the corner)
    assert back[0, 120, 310].min() > 230


def test_interrupted_writing_keeps_what_was_written(tmp_path) -> None:
    for suffix in (".mp4", ".gif"):
        path = tmp_path / f"cut{suffix}"
        with pytest.raises(KeyboardInterrupt), VideoWriter(path, fps=10) as writer:
            for k, f in enumerate(frames(8)):
                if k == 5:
                    raise KeyboardInterrupt
                writer.write(f)
        assert writer.closed
        assert iio.imread(path, index=None).shape[0] == 5


def test_bad_formats_and_mismatched_frames_are_errors(tmp_path) -> None:
    with pytest.raises(EtswarmError, match="avi"):
        VideoWriter(tmp_path / "x.avi")
    with pytest.raises(EtswarmError, match="fps"):
        VideoWriter(tmp_path / "x.mp4", fps=0)
    with VideoWriter(tmp_path / "x.gif") as writer:
        writer.write(frames(1)[0])
        with pytest.raises(ValueError, match="differs"):
            writer.write(np.zeros((10, 10, 3), np.uint8))


def test_odd_sizes_are_padded_for_h264(tmp_path) -> None:
    path = tmp_path / "odd.mp4"
    record_video(iter(frames(3, 101, 151)), path, fps=5, progress=False)
    assert iio.imread(path, index=None).shape == (3, 102, 152, 3)


def test_save_png_round_trips(tmp_path) -> None:
    rgb = frames(1)[0]
    path = save_png(rgb, tmp_path / "a" / "snap.png")
    assert np.array_equal(iio.imread(path), rgb)
