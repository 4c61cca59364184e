"""Where numba keeps etswarm's compiled functions: one folder per version of the sources.

numba's disk cache (``@njit(cache=True)``) checks the file of the function it loads, not
the files of the functions that one calls. Session 53 found ``sim.motion.move_phase``
loaded from a cache written when ``sim.fpmath`` still drew normals by the polar method:
``motion.py`` had not changed since, so numba took the old machine code, and the same seed
gave another run than in a fresh checkout. So etswarm points numba's cache at
``BASE/<hash>``, where the hash covers every ``.py`` file of the packages with compiled
code (:data:`COMPILED_PACKAGES`) and the numba, numpy and Python versions: an edit there
or an upgrade compiles everything afresh, once.

BASE is ``$NUMBA_CACHE_DIR`` when the user set it, else ``~/.cache/etswarm/numba`` (a
temporary folder when that cannot be written). The versioned folder is passed on to
child processes in ``NUMBA_CACHE_DIR``, and BASE in ``ETSWARM_NUMBA_BASE``, so that a
child running other sources (another checkout) keys its own folder. Folders of other
versions not used for :data:`STALE_DAYS` days are removed.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import sys
import tempfile
import time
from importlib import metadata
from pathlib import Path

#: Days after which the cache folder of another version of the sources is removed.
STALE_DAYS = 14

#: The subpackages with compiled code (``@njit``) or the constants it reads; the others
#: (the CLI, viewer, experiments, measures, damage) run as plain Python, so editing them
#: keeps the compiled functions.
COMPILED_PACKAGES = ("sim", "algorithm", "shapes")

#: Environment variable that carries BASE to child processes.
BASE_VARIABLE = "ETSWARM_NUMBA_BASE"


def compiled_sources(package_dir: Path) -> list[Path]:
    """The ``.py`` files whose code or constants numba may compile: the package's own
    top-level modules and every module of :data:`COMPILED_PACKAGES`, in path order."""
    files = list(package_dir.glob("*.py"))
    for name in COMPILED_PACKAGES:
        files.extend((package_dir / name).rglob("*.py"))
    return sorted(files)


def source_hash(files: list[Path], root: Path) -> str:
    """SHA-256 (first 16 hex digits) of ``files`` (their paths from ``root`` and their
    bytes, in the order given) and of the numba, numpy and Python versions."""
    digest = hashlib.sha256()
    for name in ("numba", "numpy"):
        try:
            digest.update(f"{name} {metadata.version(name)}\n".encode())
        except metadata.PackageNotFoundError:
            digest.update(f"{name} none\n".encode())
    digest.update(sys.version.encode())
    for path in files:
        digest.update(str(path.relative_to(root)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _writable(folder: Path) -> bool:
    try:
        folder.mkdir(parents=True, exist_ok=True)
        probe = folder / f".probe-{os.getpid()}"
        probe.write_bytes(b"")
        probe.unlink()
    except OSError:
        return False
    return True


def _remove_stale(base: Path, keep: Path) -> None:
    """Delete the version folders in ``base`` other than ``keep`` whose last change is
    more than STALE_DAYS days old (errors ignored: another process may hold one)."""
    cutoff = time.time() - STALE_DAYS * 86400
    try:
        folders = [p for p in base.iterdir() if p.is_dir() and p != keep]
    except OSError:
        return
    for folder in folders:
        try:
            if folder.stat().st_mtime < cutoff:
                shutil.rmtree(folder, ignore_errors=True)
        except OSError:
            continue


def use_versioned_cache() -> Path:
    """Point numba's cache at this version's folder (see the module doc); return it.

    Must run before any etswarm module that defines cached functions is imported."""
    package_dir = Path(__file__).resolve().parent
    base_text = os.environ.get(BASE_VARIABLE) or os.environ.get("NUMBA_CACHE_DIR")
    if base_text:
        base = Path(base_text)
    else:
        try:
            base = Path.home() / ".cache" / "etswarm" / "numba"
        except RuntimeError:  # no home folder to be found
            base = Path(tempfile.gettempdir()) / "etswarm-numba"
    if not _writable(base):
        base = Path(tempfile.gettempdir()) / f"etswarm-numba-{getattr(os, 'getuid', lambda: 0)()}"
    folder = base / source_hash(compiled_sources(package_dir), package_dir)
    if not _writable(folder):
        folder = Path(tempfile.mkdtemp(prefix="etswarm-numba-"))
    else:
        os.utime(folder)  # in use: not stale for the others
        _remove_stale(base, folder)
    os.environ[BASE_VARIABLE] = str(base)
    os.environ["NUMBA_CACHE_DIR"] = str(folder)
    if "numba" in sys.modules:
        # numba read its settings when it was imported: have it read them again
        from numba.core import config

        config.reload_config()
    return folder
