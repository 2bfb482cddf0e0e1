"""Which executor a command runs on, from its options: --serial, --workers N, --scheduler ADDRESS (with
--tls-ca-file, --tls-cert, --tls-key for a tls:// scheduler)."""
from __future__ import annotations

import argparse

from harness.distributed.executor import Executor, SerialExecutor

# Without --workers or --scheduler, jobs run serially. On a 2-core machine two embedded workers make
# `validate` slower (docs/performance.md, "Where validate's time goes"): each render already uses every
# core, and a cluster adds its start-up, per-worker caches and data transfer. A cluster is for more
# machines (or more cores than one render keeps busy).


def add_executor_options(q: argparse.ArgumentParser) -> None:
    g = q.add_argument_group("where the jobs run")
    g.add_argument("--scheduler", metavar="ADDRESS",
                   help="run on an existing Dask cluster (tcp://HOST:PORT or tls://HOST:PORT; started with "
                        "`dask scheduler` and `dask worker ADDRESS`). A plain-TCP scheduler runs whatever its "
                        "clients send: never let it be reachable from an untrusted network")
    g.add_argument("--workers", type=int, metavar="N",
                   help="run on an embedded Dask cluster of N worker processes on this machine (127.0.0.1 only), "
                        "our renders on their share of the cores")
    g.add_argument("--serial", action="store_true",
                   help="run every job in this process, one after another (the default without --workers or "
                        "--scheduler)")
    g.add_argument("--tls-ca-file", metavar="PEM", help="CA certificate a tls:// scheduler is checked against")
    g.add_argument("--tls-cert", metavar="PEM", help="this client's certificate for a tls:// scheduler")
    g.add_argument("--tls-key", metavar="PEM", help="this client's private key for a tls:// scheduler")


def open_executor(args: argparse.Namespace) -> Executor:
    """The executor the options ask for, serial without any (a context manager: the caller closes it)."""
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
    if workers is None:
        return SerialExecutor()
    from harness.distributed.dask_executor import DaskExecutor
    return DaskExecutor(workers=workers)
