"""The LCM message types, generated from proto/msg/*.lcm at run time.

Generated code is never committed (docs/design/architecture.md), and the .lcm files change (the body
message gains fields on main), so the Python bindings are made here with lcm-gen into a cache
directory keyed by the hash of the .lcm files and of lcm-gen's path: a changed definition gets
fresh bindings, an unchanged one reuses them.
"""

from __future__ import annotations

import hashlib
import importlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

# The source tree's proto/msg, found from this file: host/viewer/syncap_view/bindings.py.
DEFAULT_MSG_DIR = Path(__file__).resolve().parents[3] / "proto" / "msg"


class BindingsError(RuntimeError):
    """The message definitions or lcm-gen are missing, or lcm-gen failed."""


def msg_dir(override: str | None = None) -> Path:
    """The folder of the .lcm files: the option, else $SYNCAP_PROTO_MSG, else the tree's."""
    chosen = override or os.environ.get("SYNCAP_PROTO_MSG")
    path = Path(chosen) if chosen else DEFAULT_MSG_DIR
    if not path.is_dir() or not sorted(path.glob("*.lcm")):
        raise BindingsError(f"{path}: no *.lcm message definitions there "
                            "(set --proto-msg or $SYNCAP_PROTO_MSG to the tree's proto/msg)")
    return path


def lcm_gen() -> str:
    """lcm-gen from $SYNCAP_LCM_GEN, else PATH, else /usr/bin (Debian's liblcm-bin)."""
    chosen = os.environ.get("SYNCAP_LCM_GEN") or shutil.which("lcm-gen") or "/usr/bin/lcm-gen"
    if not Path(chosen).is_file():
        raise BindingsError("lcm-gen not found (Debian package liblcm-bin: scripts/deps.sh "
                            "installs it; or set $SYNCAP_LCM_GEN)")
    return chosen


def cache_root() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "syncap" / "lcm-python"


def _definitions_hash(files: list[Path], generator: str) -> str:
    digest = hashlib.sha256(generator.encode())
    for f in files:
        digest.update(f.name.encode() + b"\0" + f.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def generate(directory: Path) -> Path:
    """The folder holding the generated package `syncap` for the .lcm files in `directory`."""
    files = sorted(directory.glob("*.lcm"))
    generator = lcm_gen()
    target = cache_root() / _definitions_hash(files, generator)
    if (target / "syncap" / "__init__.py").is_file():
        return target
    target.parent.mkdir(parents=True, exist_ok=True)
    # Generate beside the target and rename: two viewers starting at once never see half a
    # package.
    scratch = Path(tempfile.mkdtemp(prefix="gen-", dir=target.parent))
    result = subprocess.run([generator, "--python", "--ppath", str(scratch)] + [str(f) for f in files],
                            capture_output=True, text=True)
    if result.returncode != 0:
        shutil.rmtree(scratch, ignore_errors=True)
        raise BindingsError(f"lcm-gen failed on {directory}: {result.stderr.strip()}")
    try:
        scratch.rename(target)
    except OSError:  # another process won the race: its result is the same
        shutil.rmtree(scratch, ignore_errors=True)
    return target


def load(override: str | None = None):
    """The generated module `syncap` (its attributes are the message classes)."""
    root = generate(msg_dir(override))
    loaded = sys.modules.get("syncap")
    if loaded is not None and not str(getattr(loaded, "__file__", "")).startswith(str(root)):
        # One process, one contract: a second set of definitions would shadow the first.
        raise BindingsError(f"bindings of other definitions are loaded already ({loaded.__file__})")
    if str(root) not in sys.path:
        sys.path.insert(0, str(root))
    return importlib.import_module("syncap")


def types_by_fingerprint(module) -> dict[bytes, type]:
    """Every generated type by its 8-byte fingerprint, the first bytes of each encoding: a
    message is decoded by what it is, whatever channel it came on."""
    out = {}
    for name in dir(module):
        cls = getattr(module, name)
        if isinstance(cls, type) and hasattr(cls, "_get_packed_fingerprint"):
            out[cls._get_packed_fingerprint()] = cls
    return out
