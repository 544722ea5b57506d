"""Writing a file atomically: what every product and kept file is written through, so that an
interrupted write leaves no file that looks complete. A module of the standard library alone, so
that the plotting jobs take it without the NetCDF stack."""

import contextlib
import os
import tempfile
from pathlib import Path


@contextlib.contextmanager
def atomic_output(path):
    """Yield a temporary path beside ``path``; when the block succeeds it becomes ``path`` (readable
    by all, mode 0644), on any failure it is removed, so an interrupted write leaves no file that
    looks complete."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
