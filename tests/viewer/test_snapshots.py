"""Event snapshots: one PNG at the start and one per new event."""

import imageio.v3 as iio

from etswarm.viewer.sample import sample_scene
from etswarm.viewer.snapshots import EventSnapshots


def test_start_and_each_new_event_get_a_picture(tmp_path) -> None:
    snaps = EventSnapshots(tmp_path / "snaps", size=(320, 240))
    scene = sample_scene()
    first = snaps.start(scene)
    assert first.name == "00-start-3h25m07s.png"
    events = [{"t_s": 10.0, "kind": "formed"}]
    assert [p.name for p in snaps.update(scene, events)] == ["01-formed-3h25m07s.png"]
    assert snaps.update(scene, events) == []
    events.append({"t_s": 20.0, "kind": "damage split"})
    (path,) = snaps.update(scene, events)
    assert path.name.startswith("02-damage-split-")
    assert iio.imread(path).shape == (240, 320, 3)
    assert len(snaps.saved) == 3
