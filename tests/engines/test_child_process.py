"""A call's children end with it: a daemon that a renderer double-forks into a session of its own is found
by the call's token and ended when the call ends, whether the call succeeded or failed."""
import sys
import time

import psutil
import pytest

from harness.engines.base import RenderFailed
from harness.engines.child_process import run_child

DAEMON = """import os, subprocess, sys
if os.fork() == 0:
    os.setsid()
    if os.fork() == 0:
        sleeper = subprocess.Popen(["sleep", "600"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        open(sys.argv[1], "w").write(f"{os.getpid()} {sleeper.pid}")
        sleeper.wait()
    os._exit(0)
os.wait()
while not os.path.exists(sys.argv[1]) or not open(sys.argv[1]).read():
    pass
sys.exit(int(sys.argv[2]))
"""


def _gone(pid: int) -> bool:
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline:
        try:
            if psutil.Process(pid).status() == psutil.STATUS_ZOMBIE:
                return True
        except psutil.NoSuchProcess:
            return True
        time.sleep(0.05)
    return False


@pytest.mark.parametrize("status", [0, 4])
def test_a_daemon_the_renderer_left_behind_ends_with_the_call(tmp_path, status):
    script, pids = tmp_path / "daemonize.py", tmp_path / "pids"
    script.write_text(DAEMON)
    call = [sys.executable, str(script), str(pids), str(status)]
    try:
        if status:
            with pytest.raises(RenderFailed, match="exited with status 4"):
                run_child(call, tmp_path, tmp_path / "log", 30)
        else:
            run_child(call, tmp_path, tmp_path / "log", 30)
        daemon, sleeper = map(int, pids.read_text().split())
        assert _gone(daemon) and _gone(sleeper)
    finally:
        for pid in map(int, pids.read_text().split() if pids.exists() else ()):
            try:
                psutil.Process(pid).kill()
            except psutil.NoSuchProcess:
                pass
