"""Functions a child process runs for the tests of harness/engines/library_process.py: each answers with the
child's pid after a pause, or dies after one, so that calls from two threads overlap."""
import os
import signal
import time


def pid_after(seconds: float) -> int:
    time.sleep(seconds)
    return os.getpid()


def crash_after(seconds: float) -> None:
    time.sleep(seconds)
    os.kill(os.getpid(), signal.SIGSEGV)
