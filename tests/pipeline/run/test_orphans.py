"""An interrupted run ends its whole process tree (:func:`orphans.stop_process_tree`), checked on
real processes: a root, a child in a session of its own (as jupyter_client starts a kernel) and
that child's own child (as a Dask worker or a cell's subprocess), one of them deaf to SIGTERM."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from sss_locus.pipeline.run import orphans

psutil = pytest.importorskip("psutil")

#: A root that starts a kernel-like child in a new session, which starts a worker that ignores
#: SIGTERM; each writes its pid into the file named by argv[1] and then sleeps.
TREE = """\
import os, signal, subprocess, sys, time
pids, level = sys.argv[1], int(sys.argv[2])
if level == 2:
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
if level < 2:
    subprocess.Popen([sys.executable, "-c", sys.argv[3], pids, str(level + 1), sys.argv[3]],
                     start_new_session=level == 0)
with open(pids, "a") as fh:
    fh.write(f"{os.getpid()}\\n")
time.sleep(600)
"""


def _ended(pid: int) -> bool:
    try:
        return psutil.Process(pid).status() == psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return True


def test_the_whole_tree_ends_before_it_returns_even_what_ignores_sigterm(tmp_path):
    pids = tmp_path / "pids.txt"
    root = subprocess.Popen([sys.executable, "-c", TREE, str(pids), "0", TREE])
    try:
        end = time.monotonic() + 60
        while (not pids.exists() or len(pids.read_text().split()) < 3) and time.monotonic() < end:
            time.sleep(0.05)
        tree = [int(p) for p in pids.read_text().split()]
        assert len(tree) == 3 and root.pid in tree
        kernel = next(p for p in tree if p != root.pid and os.getsid(p) == p)  # its own session
        assert os.getpgid(kernel) != os.getpgid(root.pid)  # a signal to the root's group misses it
        start = time.monotonic()
        signalled = orphans.stop_process_tree(root.pid, grace_s=0.5)
        took = time.monotonic() - start
        ended = {pid: _ended(pid) for pid in tree}
    finally:
        for pid in (int(p) for p in pids.read_text().split()) if pids.exists() else ():
            if not _ended(pid):
                os.kill(pid, signal.SIGKILL)
        root.kill()
        root.wait()
    assert ended == {pid: True for pid in tree}
    assert sorted(signalled) == sorted(tree) and signalled[0] == root.pid
    assert took >= 0.5  # the worker deaf to SIGTERM waited out the grace, then got SIGKILL


def test_a_pid_that_is_gone_is_a_tree_of_nothing():
    done = subprocess.Popen([sys.executable, "-c", "pass"])
    done.wait()
    assert orphans.stop_process_tree(done.pid, grace_s=0.1) == []
