"""A Dask cluster started by hand, as a user would: `dask scheduler` and two `dask worker` processes on
127.0.0.1, for the tests that run the harness against --scheduler."""
from __future__ import annotations

import os
import subprocess
import sys
import time
from contextlib import contextmanager
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DASK = str(Path(sys.executable).parent / "dask")


@contextmanager
def loopback_cluster(folder: Path, workers: int = 2, env: dict[str, str] | None = None):
    """Yields the scheduler's tcp:// address; stops every process on exit."""
    file = folder / "scheduler.json"
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), str(ROOT / "tests")]), **(env or {})}
    log = open(folder / "cluster.log", "w")
    procs = [subprocess.Popen([DASK, "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                               "--scheduler-file", str(file)], env=environment, stdout=log, stderr=log)]
    try:
        deadline = time.time() + 60
        while not file.exists() and time.time() < deadline:
            time.sleep(0.1)
        for _ in range(workers):
            procs.append(subprocess.Popen([DASK, "worker", "--scheduler-file", str(file), "--host", "127.0.0.1",
                                           "--nthreads", "1", "--no-dashboard"], env=environment, stdout=log,
                                          stderr=log, cwd=folder))
        from distributed import Client
        with Client(scheduler_file=str(file), timeout="60s") as client:
            client.wait_for_workers(workers, timeout=60)
            address = client.scheduler.address
        yield address
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
        log.close()
