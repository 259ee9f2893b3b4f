"""What a worker needs, shipped by content: the scene with every file it reads (as
`rt info --inputs` lists them, BVH caches included) in one archive, and rt itself.
Each is named by its BLAKE2 hash; a worker unpacks it once into its cache."""

import hashlib
import io
import os
import subprocess
import tarfile
import tempfile
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Bundle:
    """An archive of files below `root`, and the scene's path inside it."""

    data: bytes
    digest: str
    scene: str


def digest(data: bytes) -> str:
    return hashlib.blake2b(data, digest_size=16).hexdigest()


def scene_inputs(rt: str, scene: Path) -> list[Path]:
    """The files rendering `scene` reads; packs stale caches first (rt does)."""
    run = subprocess.run([rt, "info", "--inputs", str(scene)], capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"{scene}: rt info --inputs failed:\n{run.stderr.strip()}")
    return [Path(line) for line in run.stdout.splitlines() if line.strip()]


def bundle_scene(rt: str, scene: Path) -> Bundle:
    """The scene and its inputs in one archive, with paths relative to their common folder."""
    files = scene_inputs(rt, scene)
    scene = scene.resolve()
    root = Path(os.path.commonpath([str(f.parent) for f in files + [scene]]))
    archive = io.BytesIO()
    with tarfile.open(fileobj=archive, mode="w") as tar:
        for f in sorted(set(files + [scene])):
            info = tar.gettarinfo(str(f), arcname=str(f.relative_to(root)))
            # Only the bytes and names matter: the same files give the same archive.
            info.mtime, info.uid, info.gid, info.uname, info.gname, info.mode = 0, 0, 0, "", "", 0o644
            with open(f, "rb") as stream:
                tar.addfile(info, stream)
    data = archive.getvalue()
    return Bundle(data, digest(data), str(scene.relative_to(root)))


def cache_dir() -> Path:
    base = os.environ.get("RT_FARM_CACHE") or os.path.join(tempfile.gettempdir(), f"rt-farm-{os.getuid()}")
    path = Path(base)
    path.mkdir(parents=True, exist_ok=True)
    return path


def materialise(name: str, fetch, unpack) -> Path:
    """The cache entry `name`, made once: `unpack(fetch(), folder)` fills a private folder
    that is then renamed into place, so a reader never sees half an entry."""
    final = cache_dir() / name
    if final.exists():
        return final
    partial = Path(tempfile.mkdtemp(prefix=f".{name}.", dir=cache_dir()))
    unpack(fetch(), partial)
    try:
        os.rename(partial, final)
    except OSError:
        # Another task on this machine made it first.
        subprocess.run(["rm", "-rf", "--", str(partial)], check=False)
    return final


def unpack_archive(data: bytes, folder: Path) -> None:
    with tarfile.open(fileobj=io.BytesIO(data)) as tar:
        tar.extractall(folder, filter="data")


def unpack_executable(data: bytes, folder: Path) -> None:
    path = folder / "rt"
    path.write_bytes(data)
    path.chmod(0o755)
