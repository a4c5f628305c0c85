"""What the process-driving test tiers share (tests/ui, tests/js): a DDS domain id of their own,
taken with the lock files of tests/support TestDomain, free loopback ports, and the programs a run
starts, each with its log file, ended by PID at the end (python3's standard library only)."""
import fcntl
import os
import signal
import socket
import subprocess
import tempfile
import time

PATIENCE_S = 30  # a loaded 2-core machine running sanitizer builds: behaviour, not timing


class Failed(Exception):
    pass


def acquire_domain():
    """A DDS domain id no other test uses: the lock files of tests/support TestDomain (ids 100..230).
    Returns (id, fd): the lock holds while fd is open."""
    first, last = 100, 230
    count = last - first + 1
    for i in range(count):
        domain = first + (os.getpid() + i) % count
        path = os.path.join(tempfile.gettempdir(), f"hubrt-test-domain-{domain}.lock")
        fd = os.open(path, os.O_RDONLY | os.O_CREAT | os.O_CLOEXEC, 0o666)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return domain, fd
        except OSError:
            os.close(fd)
    raise Failed("no free test DDS domain id")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Processes:
    """Every program this run started, ended by PID (SIGTERM, then SIGKILL) at the end."""

    def __init__(self, out_dir):
        self.out_dir = out_dir
        self.children = []

    def start(self, name, args, env=None, stdout=None):
        """Starts `args`; its stderr (and stdout unless `stdout` names a file) go to <name>.log."""
        output = open(os.path.join(self.out_dir, f"{name}.log"), "wb")
        out = open(stdout, "wb") if stdout else output
        child = subprocess.Popen(args, stdout=out, stderr=output, stdin=subprocess.DEVNULL, env=env)
        self.children.append((name, child, output))
        if stdout:
            out.close()
        return child

    def log_text(self, name):
        with open(os.path.join(self.out_dir, f"{name}.log"), "rb") as f:
            return f.read().decode("utf-8", "replace")

    def wait_for_log(self, name, needle, child):
        deadline = time.monotonic() + PATIENCE_S
        while time.monotonic() < deadline:
            text = self.log_text(name)
            if needle in text:
                return text
            if child.poll() is not None:
                break
            time.sleep(0.1)
        raise Failed(f"{name} did not say '{needle}'; its output:\n{self.log_text(name)}")

    def stop_all(self):
        for name, child, output in reversed(self.children):
            if child.poll() is None:
                child.send_signal(signal.SIGTERM)
                try:
                    child.wait(10)
                except subprocess.TimeoutExpired:
                    child.kill()
                    child.wait()
            output.close()
