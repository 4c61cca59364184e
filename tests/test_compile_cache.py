"""numba's disk cache goes to one folder per version of etswarm's sources
(``etswarm.compile_cache``), so that no edit leaves a stale compiled caller behind."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

from etswarm.compile_cache import STALE_DAYS, source_hash


def test_the_hash_follows_every_source_file(tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "a.py").write_text("x = 1\n")
    (pkg / "sub" / "b.py").write_text("y = 2\n")
    first = source_hash(pkg)
    assert source_hash(pkg) == first
    (pkg / "sub" / "b.py").write_text("y = 3\n")  # a callee's file, not the caller's
    assert source_hash(pkg) != first
    (pkg / "sub" / "b.py").write_text("y = 2\n")
    assert source_hash(pkg) == first
    (pkg / "sub" / "c.py").write_text("")
    assert source_hash(pkg) != first


def test_a_process_compiles_into_its_version_folder_and_old_ones_go(tmp_path: Path) -> None:
    import etswarm

    base = tmp_path / "cache"
    old, recent = base / "0000000000000000", base / "1111111111111111"
    old.mkdir(parents=True)
    recent.mkdir()
    stale = time.time() - (STALE_DAYS + 1) * 86400
    os.utime(old, (stale, stale))
    env = {**os.environ, "ETSWARM_NUMBA_BASE": str(base)}
    script = ("import os, etswarm, numba.core.config as c; "
              "print(os.environ['NUMBA_CACHE_DIR']); print(c.CACHE_DIR)")
    out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                         text=True, check=True).stdout.split()
    want = str(base / source_hash(Path(etswarm.__file__).parent))
    assert out == [want, want]  # the variable children inherit, and numba's own setting
    assert not old.exists() and recent.exists()
