"""Which executor a command runs on, from its options: --serial, --workers N, --scheduler ADDRESS (with
--tls-ca-file, --tls-cert, --tls-key for a tls:// scheduler)."""
from __future__ import annotations

import argparse

from harness.distributed.executor import Executor, SerialExecutor

#: Fewer tasks than this run serially unless a cluster is asked for: starting an embedded cluster and
#: loading Mitsuba in each worker costs more than it saves on a few cases.
MIN_TASKS_FOR_CLUSTER = 8


def add_executor_options(q: argparse.ArgumentParser) -> None:
    g = q.add_argument_group("where the jobs run")
    g.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on an existing Dask cluster (tcp://HOST:PORT or tls://HOST:PORT; started with "
                        "`dask scheduler` and `dask worker ADDRESS`). A plain-TCP scheduler runs whatever its "
                        "clients send: never let it be reachable from an untrusted network")
    g.add_argument("--workers", type=int, metavar="N",
                   help="worker processes of the embedded local cluster (default: one per core)")
    g.add_argument("--serial", action="store_true",
                   help="run every job in this process, one after another (no cluster)")
    g.add_argument("--tls-ca-file", metavar="PEM", help="CA certificate a tls:// scheduler is checked against")
    g.add_argument("--tls-cert", metavar="PEM", help="this client's certificate for a tls:// scheduler")
    g.add_argument("--tls-key", metavar="PEM", help="this client's private key for a tls:// scheduler")


def open_executor(args: argparse.Namespace, tasks: int) -> Executor:
    """The executor the options ask for; without any, the embedded cluster for `tasks` of at least
    MIN_TASKS_FOR_CLUSTER and serial below (closed by the caller: it is a context manager)."""
    scheduler = getattr(args, "scheduler", None)
    tls = [getattr(args, k, None) for k in ("tls_ca_file", "tls_cert", "tls_key")]
    if getattr(args, "serial", False):
        if scheduler:
            raise ValueError("--serial and --scheduler contradict each other: choose one")
        return SerialExecutor()
    if any(tls) and not (scheduler or "").startswith("tls://"):
        raise ValueError("--tls-ca-file, --tls-cert and --tls-key apply to a tls:// --scheduler only")
    if scheduler:
        if not scheduler.startswith(("tcp://", "tls://")):
            raise ValueError(f"--scheduler {scheduler!r}: expected tcp://HOST:PORT or tls://HOST:PORT")
        security = None
        if scheduler.startswith("tls://"):
            if not all(tls):
                raise ValueError("a tls:// scheduler needs --tls-ca-file, --tls-cert and --tls-key")
            from distributed.security import Security
            security = Security(tls_ca_file=tls[0], tls_client_cert=tls[1], tls_client_key=tls[2],
                                require_encryption=True)
        from harness.distributed.dask_executor import DaskExecutor
        return DaskExecutor(scheduler, security=security)
    workers = getattr(args, "workers", None)
    if workers is not None and workers < 1:
        raise ValueError(f"--workers {workers}: expected at least 1")
    if workers is None and tasks < MIN_TASKS_FOR_CLUSTER:
        return SerialExecutor()
    from harness.distributed.dask_executor import DaskExecutor
    return DaskExecutor(workers=workers)
