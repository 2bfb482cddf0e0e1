"""Tasks on a Dask cluster: an embedded one on this machine's loopback, or an existing one.

Each task runs in a worker process; a render that crashes its worker (or is killed with it) fails that
task after Dask's retries on other workers, not the run. Large inputs shared by several tasks (scene
bundles) go to the cluster once, as scattered data."""
from __future__ import annotations

import os
from typing import Any, Callable

from harness.distributed.executor import Executor, Outcome, Status, Task

#: A worker that dies under a task is retried on another this many times in all, then the task fails:
#: a render that kills its worker would otherwise take down every worker in turn.
ALLOWED_FAILURES = 2


#: Thread counts a worker of the embedded cluster sets to its share of the cores: our renders' (whose bits
#: do not depend on it) and numpy's. Mitsuba keeps its own: its llvm variant's sums change in the last
#: bits with the thread count (invariance ratios by 1e-9 at 1 thread against 2), and a run must give the
#: same numbers wherever it runs.
SHARE_CORES = ("MCVAL_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


def _worker_count() -> int:
    return max(1, len(os.sched_getaffinity(0)))


class DaskExecutor(Executor):
    """`scheduler`: an address (tcp:// or tls://) of a running scheduler, or None for an embedded cluster
    of `workers` single-threaded worker processes; everything listens on 127.0.0.1 only, on ports the
    system picks (the scheduler's HTTP endpoints too: health and metrics, no dashboard without bokeh).
    `security`: a distributed.Security for tls:// (CA, certificate, key)."""

    ships_files = True

    def __init__(self, scheduler: str | None = None, workers: int | None = None, security=None) -> None:
        import dask
        from distributed import Client, LocalCluster

        dask.config.set({"distributed.scheduler.allowed-failures": ALLOWED_FAILURES - 1,
                         # The active memory manager drops the copies `share` broadcast once no queued task
                         # waits on them; a finished result lost with its worker is then recomputed without
                         # its scene bundle (an existing scheduler keeps its own configuration).
                         "distributed.scheduler.active-memory-manager.start": False})
        self._cluster = None
        if scheduler is None:
            cores = _worker_count()
            n = workers or cores
            # One task per worker at a time, and each of our renders on its share of the cores.
            self._cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1",
                                         env={k: str(max(1, cores // n)) for k in SHARE_CORES},
                                         dashboard_address="127.0.0.1:0", scheduler_port=0, silence_logs=40)
            self._client = Client(self._cluster)
            self.description = f"embedded Dask cluster ({n} workers on 127.0.0.1)"
        else:
            self._client = Client(scheduler, security=security, timeout="30s")
            self.description = f"Dask scheduler {scheduler}"
        self.slots = max(1, sum(w.get("nthreads", 1) for w in self._client.scheduler_info()["workers"].values()))

    @property
    def client(self):
        return self._client

    def share(self, value: Any) -> Any:
        """A handle to `value` on the cluster, to pass in several tasks' args: sent once to every worker,
        so that a worker dying takes no data with it that a task (or the recomputation of a result lost
        with it) still needs."""
        return self._client.scatter(value, hash=False, broadcast=True)

    def run(self, tasks: list[Task], on_status: Callable[[Status], None] | None = None) -> list[Outcome]:
        from concurrent.futures import CancelledError

        from distributed import KilledWorker, as_completed

        status = Status(len(tasks))
        futures = [self._client.submit(t.fn, *t.args, key=f"{t.key}-{i}-{id(tasks)}", pure=False, retries=0)
                   for i, t in enumerate(tasks)]
        index = {f.key: i for i, f in enumerate(futures)}
        out: list[Outcome | None] = [None] * len(tasks)
        status.running = min(self.slots, len(tasks))
        if on_status:
            on_status(status)
        for future in as_completed(futures):
            i = index[future.key]
            try:
                out[i] = Outcome(future.result())
            except KilledWorker:
                out[i] = Outcome(error=f"its worker died while running it ({ALLOWED_FAILURES} workers tried)")
                status.failed += 1
            except CancelledError as e:
                # A worker that dies can take the scheduler's record of the task with it: the future is then
                # cancelled ("reason: unknown") instead of raising KilledWorker. The case fails either way.
                out[i] = Outcome(error=f"its worker died or the cluster cancelled it ({e})")
                status.failed += 1
            status.done += 1
            # Tasks are submitted at once and the cluster runs as many as it has threads: the rest wait.
            status.running = min(self.slots, len(tasks) - status.done)
            status.last = tasks[i].key
            if on_status:
                on_status(status)
        return out  # type: ignore[return-value]

    def close(self) -> None:
        self._client.close()
        if self._cluster is not None:
            self._cluster.close()
