"""etswarm.viewer: one renderer for the live window, videos, snapshots and plots.

- :mod:`~etswarm.viewer.scene`: :class:`Scene`, the drawable snapshot (arrays).
- :mod:`~etswarm.viewer.view`: :class:`ViewState` (camera, toggles) and :class:`Trails`.
- :mod:`~etswarm.viewer.render`: ``render(scene, view) -> (H, W, 3) uint8``.
- :mod:`~etswarm.viewer.video`: :class:`VideoWriter`, ``record_video``, ``save_png``.
- :mod:`~etswarm.viewer.live`: the :class:`LiveRun` protocol the window drives.
- :mod:`~etswarm.viewer.window`: ``run_viewer(live_run, ...)``, the pygame window.

Submodules are imported on demand (pygame loads only with the renderer).
"""
