"""A Dask cluster started by hand, as a user would: `dask scheduler` and two `dask worker` processes on
127.0.0.1, for the tests that run the harness against --scheduler."""
from __future__ import annotations

import os
import subprocess
import sys
import time
from contextlib import contextmanager
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DASK = str(Path(sys.executable).parent / "dask")


def make_certificates(folder: Path) -> tuple[Path, Path, Path]:
    """(CA, certificate, key): a throw-away CA and one certificate for 127.0.0.1 that it signed, made with
    openssl, which every party of the TLS test uses."""
    ca_key, ca, key, csr, cert = (folder / n for n in ("ca.key", "ca.pem", "node.key", "node.csr", "node.pem"))
    run = lambda *a: subprocess.run(["openssl", *map(str, a)], check=True, capture_output=True)  # noqa: E731
    run("req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", ca_key, "-out", ca, "-days", "1",
        "-subj", "/CN=mcval test CA")
    run("req", "-newkey", "rsa:2048", "-nodes", "-keyout", key, "-out", csr, "-subj", "/CN=127.0.0.1")
    ext = folder / "ext.cnf"
    ext.write_text("subjectAltName=IP:127.0.0.1\nextendedKeyUsage=serverAuth,clientAuth\n")
    run("x509", "-req", "-in", csr, "-CA", ca, "-CAkey", ca_key, "-CAcreateserial", "-out", cert, "-days", "1",
        "-extfile", ext)
    return ca, cert, key


@contextmanager
def loopback_cluster(folder: Path, workers: int = 2, env: dict[str, str] | None = None,
                     tls: tuple[Path, Path, Path] | None = None):
    """Yields the scheduler's tcp:// address (tls:// with `tls`: CA, certificate, key); stops every
    process on exit."""
    file = folder / "scheduler.json"
    environment = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    log = open(folder / "cluster.log", "w")
    secure = [] if tls is None else ["--tls-ca-file", str(tls[0]), "--tls-cert", str(tls[1]), "--tls-key", str(tls[2])]
    procs = [subprocess.Popen([DASK, "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                               "--scheduler-file", str(file), *(["--protocol", "tls"] if tls else []), *secure],
                              env=environment, stdout=log, stderr=log)]
    try:
        deadline = time.time() + 60
        while not file.exists() and time.time() < deadline:
            time.sleep(0.1)
        for _ in range(workers):
            procs.append(subprocess.Popen([DASK, "worker", "--scheduler-file", str(file), "--host", "127.0.0.1",
                                           "--nthreads", "1", "--no-dashboard", *secure], env=environment,
                                          stdout=log, stderr=log, cwd=folder))
        from distributed import Client
        from distributed.security import Security
        security = None if tls is None else Security(tls_ca_file=str(tls[0]), tls_client_cert=str(tls[1]),
                                                     tls_client_key=str(tls[2]), require_encryption=True)
        with Client(scheduler_file=str(file), timeout="60s", security=security) as client:
            client.wait_for_workers(workers, timeout=60)
            address = client.scheduler.address
        yield address
    finally:
        # The workers first, then the scheduler: a worker closing while the scheduler closes under it can hang
        # until its nanny kills it (8 s).
        for group in (procs[1:], procs[:1]):
            for p in group:
                p.terminate()
            for p in group:
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    p.kill()
        log.close()
