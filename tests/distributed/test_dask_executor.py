"""Jobs on Dask: the same answer as in this process, a render killed on a worker fails its case only,
a worker dying under a task fails that task only, and the embedded cluster listens on loopback only."""
from __future__ import annotations

import json
import os
import time
from types import SimpleNamespace

import psutil
import pytest

from tests.helpers.dask_cluster import loopback_cluster, make_certificates
from tests.helpers.render_wrappers import write_wrapper
from harness.cli import main
from harness.distributed.cluster import open_executor
from harness.distributed.executor import SerialExecutor, Task

pytestmark = [pytest.mark.dask, pytest.mark.slow]  # Dask clusters on loopback: seconds each to start


#: results.json keys that differ between any two runs: times, speeds, names, where and how it ran.
VOLATILE = ("seconds", "run", "throughput", "image seconds", "ran on", "invocation", "phase_seconds", "wall_seconds",
            "phases before the images")


def _stripped(value, rounded: bool = False):
    """results.json without what differs between any two runs: times and speeds, run names, where it ran and
    the options it was run with (--out, --scheduler). Mitsuba's own
    renders (its invariance cells) are rounded to 6 digits: its llvm variant's sums change in the last bits
    from one run to the next (two serial runs: ratios by 1e-9), wherever it runs."""
    if isinstance(value, dict):
        rounded = rounded or value.get("engine", "").startswith("mitsuba")
        return {k: _stripped(v, rounded) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [_stripped(v, rounded) for v in value]
    if rounded and isinstance(value, float):
        return float(f"{value:.6g}")
    return value


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    with loopback_cluster(tmp_path_factory.mktemp("cluster")) as address:
        yield address


def test_validate_on_a_scheduler_gives_the_local_answer(cluster, tmp_path):
    # The warps run in this process either way (one warp keeps their section in the comparison).
    # A closed-form plane, a stored reference (the bundle must carry it) and the sphere.
    args = ["validate", "--only", "plane_point:simple", "cornell:normals", "sphere_floor_unit:simple",
            "--warps-only", "tent", "--invariance-only", "plane_point:simple", "scale", "--seed", "3",
            "--no-bsdfs"]
    assert main(args + ["--scheduler", cluster, "--out", str(tmp_path / "cluster")]) == 0
    assert main(args + ["--serial", "--out", str(tmp_path / "local")]) == 0
    far, near = (json.loads((tmp_path / d / "latest" / "results.json").read_text()) for d in ("cluster", "local"))
    assert len(near["images"]) == 3 and all(e["pass"] for e in near["images"])
    assert {e["reference"] for e in near["images"]} == {"stored reference"}  # the bundle carried them
    assert _stripped(far) == _stripped(near)


def test_bench_runs_each_case_on_one_worker(cluster, tmp_path):
    args = ["bench", "--only", "plane_point:simple", "cornell:ao", "--engines", "mcval", "--max-spp", "2",
            "--runs", "1", "--same-sampler", "--seed-runs", "0", "--throughput-runs", "0"]
    assert main(args + ["--scheduler", cluster, "--out", str(tmp_path / "r")]) == 0
    speed = json.loads((tmp_path / "r" / "latest" / "results.json").read_text())["speed"]
    assert sorted((c["scene"], [len(k["steps"]) for k in c["curves"]]) for c in speed) == \
        [("cornell", [2]), ("plane_point", [2])]
    assert main(args + ["--workers", "2", "--out", str(tmp_path / "w")]) == 2  # timings would fight: refused


def test_calibrate_on_a_scheduler_gives_the_local_rates(cluster, tmp_path):
    """Warps (one task each, with Mitsuba's) and image null comparisons on the cluster: the figures of a
    serial run, times aside."""
    args = ["calibrate", "--only", "tent", "uniform_disk", "--seeds", "2", "--samples",
            "20000", "--comparisons", "1"]
    assert main(args + ["--scheduler", cluster, "--out", str(tmp_path / "cluster")]) == 0
    assert main(args + ["--serial", "--out", str(tmp_path / "local")]) == 0
    far, near = (json.loads((tmp_path / d / "calibration-latest" / "calibration.json").read_text())
                 for d in ("cluster", "local"))
    assert [w["warp"] for w in near["warps"]["warps"]] == ["tent"] * 3 + ["uniform_disk"] * 3  # chi2, by name, Mitsuba
    assert far["warps"]["warps"] == near["warps"]["warps"] and far["warps"]["pooled"] == near["warps"]["pooled"]
    assert far["images"]["blocks"] == near["images"]["blocks"] and near["images"]["comparisons"] == 3
    assert far["meta"]["warps ran on"].startswith("Dask scheduler") and near["meta"]["warps ran on"] == "serial"


@pytest.fixture(scope="module")
def tls_cluster(tmp_path_factory):
    """A TLS cluster of one worker whose renders of `ao` are killed mid-run (the others run the real renderer):
    (address, the TLS options a client gives)."""
    folder = tmp_path_factory.mktemp("tls")
    tls = make_certificates(folder)
    env = {"MCVAL_RENDER": str(write_wrapper(folder, "kill", "ao")), "MCVAL_RENDER_TIMEOUT": "60"}
    with loopback_cluster(folder, workers=1, env=env, tls=tls) as address:
        yield address, ["--tls-ca-file", str(tls[0]), "--tls-cert", str(tls[1]), "--tls-key", str(tls[2])]


def test_a_tls_scheduler_runs_the_cases_and_refuses_plain_tcp(tls_cluster, tmp_path):
    address, files = tls_cluster
    assert address.startswith("tls://127.0.0.1:")
    out = tmp_path / "r"
    assert main(["images", "--only", "plane_point:simple", "--scheduler", address, *files, "--out", str(out)]) == 0
    assert json.loads((out / "latest" / "results.json").read_text())["images"][0]["pass"]
    plain = address.replace("tls://", "tcp://")
    assert main(["images", "--only", "plane_point:simple", "--scheduler", plain, "--out", str(out)]) == 2


def test_a_render_killed_on_a_worker_fails_its_case_only(tls_cluster, tmp_path, capsys):
    # One worker runs both cases: the render killed under it is a failed case, not a dead worker.
    address, files = tls_cluster
    code = main(["images", "--only", "plane_point:ao", "plane_point:normals", "--scheduler", address, *files,
                 "--out", str(tmp_path / "r")])
    assert code == 1
    entries = {e["integrator"]: e for e in json.loads((tmp_path / "r" / "latest" / "results.json").read_text())["images"]}
    assert entries.keys() == {"ao", "normals"}
    assert entries["ao"]["pass"] is False and "killed by signal SIGKILL" in entries["ao"]["error"]
    assert entries["normals"]["pass"]
    assert "plane_point:ao" in capsys.readouterr().out


@pytest.fixture(scope="module")
def embedded():
    """The embedded cluster, three workers: the tests that need nothing of a worker but that it runs, then (last
    in this file, as it kills two of them) the one whose task kills its workers."""
    from harness.distributed.dask_executor import DaskExecutor

    with DaskExecutor(workers=3) as executor:
        yield executor


def test_shared_data_stays_on_every_worker_once_no_task_waits_on_it(embedded):
    handle = embedded.share(b"scene files")
    time.sleep(5)  # past two rounds of the active memory manager (every 2 s), which would drop the copies
    assert len(embedded.client.who_has(handle)[handle.key]) == 3


def test_the_embedded_cluster_listens_on_loopback_only(embedded):
    pids = [os.getpid(), *embedded.client.run(os.getpid).values()]
    nannies = [psutil.Process(p).parent().pid for p in pids[1:]]
    listening = [c for pid in {*pids, *nannies} for c in psutil.Process(pid).net_connections("inet")
                 if c.status == psutil.CONN_LISTEN]
    assert len(listening) >= 3  # the scheduler and each worker
    assert {c.laddr.ip for c in listening} == {"127.0.0.1"}, listening
    assert 8787 not in {c.laddr.port for c in listening}  # no fixed port, none a dashboard would take


def _args(**kw):
    return SimpleNamespace(**{"scheduler": None, "workers": None, "serial": False, "tls_ca_file": None,
                              "tls_cert": None, "tls_key": None, **kw})


@pytest.mark.parametrize("kw, message", [
    ({"serial": True, "scheduler": "tcp://127.0.0.1:1"}, "contradict"),
    ({"scheduler": "127.0.0.1:8786"}, "expected tcp://HOST:PORT"),
    ({"scheduler": "tcp://127.0.0.1:1", "tls_ca_file": "ca.pem"}, "tls:// --scheduler only"),
    ({"scheduler": "tls://127.0.0.1:1", "tls_ca_file": "ca.pem"}, "needs --tls-ca-file, --tls-cert and --tls-key"),
    ({"workers": 0}, "at least 1"),
])
def test_executor_options_that_contradict_are_refused(kw, message):
    with pytest.raises(ValueError, match=message):
        open_executor(_args(**kw))


def test_without_workers_or_a_scheduler_jobs_stay_in_this_process():
    assert isinstance(open_executor(_args()), SerialExecutor)
    assert isinstance(open_executor(_args(serial=True)), SerialExecutor)


def _boom(x):
    raise RuntimeError(f"bad input {x}")


def test_tasks_come_back_in_order_and_a_raising_task_stops_the_run():
    seen = []
    out = SerialExecutor().run([Task("a", abs, (-2,)), Task("b", abs, (3,))], seen.append)
    assert [o.value for o in out] == [2, 3] and all(o.ok for o in out)
    assert (seen[-1].done, seen[-1].failed, seen[-1].total, seen[-1].last) == (2, 0, 2, "b")
    # A job catches what it expects (a failed render); anything else is a bug, raised wherever it ran.
    with pytest.raises(RuntimeError, match="bad input 7"):
        SerialExecutor().run([Task("a", abs, (1,)), Task("b", _boom, (7,))])


def test_a_task_raising_on_a_worker_raises_here(embedded):
    with pytest.raises(RuntimeError, match="bad input 5"):
        embedded.run([Task("b", _boom, (5,))])


def test_a_worker_dying_under_a_task_fails_that_case_only(embedded):
    from tests.helpers.dask_engines import DiesOn
    from harness.engines.mitsuba import MitsubaEngine
    from harness.images.run import run_images
    from harness.images.suite import ImageCase

    cases = [ImageCase("plane_point", "normals"), ImageCase("plane_point", "simple")]
    # Three workers: the failing case kills two (ALLOWED_FAILURES), and the third keeps the scattered scene files
    # from which the cluster recomputes a finished case whose result died with a worker. Last in the file: the
    # cluster it leaves has lost two workers.
    results, _ = run_images(cases, DiesOn("simple"), MitsubaEngine(), executor=embedded)
    normals, simple = results
    assert normals.passed and normals.error is None
    assert not simple.passed and simple.error.startswith("task failed: its worker died")
