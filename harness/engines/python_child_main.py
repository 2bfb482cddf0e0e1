"""The child side of harness/engines/python_child.py: `python -m harness.engines.python_child_main IN OUT`
reads (function, args) frames from fd IN, calls `module:function(*args)` and writes ("ok", value) or
("error", (reason, exception)) frames to fd OUT, until IN ends."""
from __future__ import annotations

import importlib
import os
import pickle
import sys
from typing import Any

_HEADER = 8


def _read_exactly(fd: int, size: int) -> bytes | None:
    chunks, left = [], size
    while left:
        data = os.read(fd, min(left, 1 << 20))
        if not data:
            return None
        chunks.append(data)
        left -= len(data)
    return b"".join(chunks)


def _write(fd: int, obj: Any) -> None:
    data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    view = memoryview(len(data).to_bytes(_HEADER, "little") + data)
    while view:
        view = view[os.write(fd, view):]


def _function(name: str):
    module, _, attribute = name.partition(":")
    return getattr(importlib.import_module(module), attribute)


def _picklable(e: BaseException) -> BaseException | None:
    try:
        pickle.loads(pickle.dumps(e))
        return e
    except Exception:
        return None


def main(argv: list[str]) -> int:
    request, answer = int(argv[0]), int(argv[1])
    while True:
        header = _read_exactly(request, _HEADER)
        if header is None:
            return 0  # the parent closed its end: nothing more to do
        body = _read_exactly(request, int.from_bytes(header, "little"))
        if body is None:
            return 0
        name, args = pickle.loads(body)
        try:
            reply = ("ok", _function(name)(*args))
        except Exception as e:
            reply = ("error", (f"{type(e).__name__}: {e}", _picklable(e)))
        sys.stdout.flush()
        sys.stderr.flush()
        _write(answer, reply)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
