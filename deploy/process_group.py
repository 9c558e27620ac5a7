"""Stopping a process started in a process group of its own (start_new_session=True): SIGTERM,
or for a process that stops at the end of its stdin (a command over ssh, deploy/cluster.py)
closing that stdin; then SIGKILL for the whole group if it has not ended within the grace.
Used by deploy/cluster.py and the integration tests' harness."""
import os
import signal
import subprocess


def stop(p, grace=5.0, close_stdin=False):
    """Ends p (a subprocess.Popen) and returns its exit status."""
    if p.poll() is not None:
        return p.returncode
    try:
        if close_stdin and p.stdin:
            p.stdin.close()
        else:
            os.killpg(p.pid, signal.SIGTERM)
        return p.wait(timeout=grace)
    except (ProcessLookupError, subprocess.TimeoutExpired):
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        return p.wait()
