"""numba's disk cache goes to one folder per version of etswarm's sources
(``etswarm.compile_cache``), so that no edit leaves a stale compiled caller behind."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from pathlib import Path

from etswarm.compile_cache import STALE_DAYS, compiled_sources, source_hash


def test_the_hash_follows_every_source_file(tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "a.py").write_text("x = 1\n")
    (pkg / "sub" / "b.py").write_text("y = 2\n")

    def key() -> str:
        return source_hash(sorted(pkg.rglob("*.py")), pkg)

    first = key()
    assert key() == first
    (pkg / "sub" / "b.py").write_text("y = 3\n")  # a callee's file, not the caller's
    assert key() != first
    (pkg / "sub" / "b.py").write_text("y = 2\n")
    assert key() == first
    (pkg / "sub" / "c.py").write_text("")
    assert key() != first


def test_the_compiled_sources_are_those_numba_may_read() -> None:
    import etswarm

    root = Path(etswarm.__file__).parent
    names = {str(p.relative_to(root)) for p in compiled_sources(root)}
    assert {"sim/radio.py", "sim/fpmath.py", "algorithm/search.py", "shapes/lattice.py",
            "sim/controllers/randomwalk.py", "compile_cache.py"} <= names
    uses_numba = re.compile(r"^\s*(from numba|import numba)", re.MULTILINE)
    for path in root.rglob("*.py"):  # every module that uses numba is among them
        if uses_numba.search(path.read_text()):
            assert str(path.relative_to(root)) in names, path


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
    root = Path(etswarm.__file__).parent
    want = str(base / source_hash(compiled_sources(root), root))
    assert out == [want, want]  # the variable children inherit, and numba's own setting
    assert not old.exists() and recent.exists()
