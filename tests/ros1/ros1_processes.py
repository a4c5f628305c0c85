"""Processes of the ROS 1 tier: a ROS master on its own port, hubbridge, the rospy Dock ECU, hubd,
hubsim and hubctl, each test on loopback in its own DDS domain. Every process started here is
ended here, by its pid."""
import fcntl
import json
import os
import signal
import socket
import subprocess
import tempfile
import threading
import time
import xmlrpc.client

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))
PYTHON = "/usr/bin/python3"  # Debian's: rospy, genmsg and genpy are its packages

# tests/support/test_domain.h: one flock'ed file per DDS domain id in [100, 230], shared with the
# C++ tests so that parallel runs never share a domain.
FIRST_DOMAIN, LAST_DOMAIN = 100, 230


class Domain:
    def __init__(self):
        count = LAST_DOMAIN - FIRST_DOMAIN + 1
        start = os.getpid() % count
        for i in range(count):
            domain = FIRST_DOMAIN + (start + i) % count
            path = os.path.join(tempfile.gettempdir(), "hubrt-test-domain-%d.lock" % domain)
            fd = os.open(path, os.O_RDONLY | os.O_CREAT | os.O_CLOEXEC, 0o666)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                os.close(fd)
                continue
            self.fd, self.id = fd, domain
            return
        raise RuntimeError("no free DDS domain id in %d..%d" % (FIRST_DOMAIN, LAST_DOMAIN))

    def args(self):
        return ["--domain", str(self.id), "--loopback"]

    def release(self):
        os.close(self.fd)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Processes:
    """Starts programs with their output in files under a temporary directory; stop() ends them."""

    def __init__(self, build, name):
        self.build = build
        self.dir = tempfile.mkdtemp(prefix="hubrt-ros1-%s-" % name)
        self.children = {}
        self.domain = Domain()
        self.master_port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % self.master_port,
                        ROS_HOSTNAME="127.0.0.1", ROS_LOG_DIR=os.path.join(self.dir, "roslog"),
                        ROS_HOME=os.path.join(self.dir, "roshome"), HUBRT_CONFIG_DIR=SOURCE)
        self.env.pop("ROS_IP", None)

    def program(self, path):
        return os.path.join(self.build, path)

    def start(self, key, argv):
        out = open(os.path.join(self.dir, key + ".log"), "w")
        self.children[key] = subprocess.Popen(argv, stdout=out, stderr=subprocess.STDOUT, env=self.env,
                                              cwd=SOURCE, start_new_session=True)
        return self.children[key]

    def stop(self, key, sig=signal.SIGTERM):
        child = self.children.pop(key, None)
        if child is None or child.poll() is not None:
            return
        child.send_signal(sig)
        try:
            child.wait(10)
        except subprocess.TimeoutExpired:
            child.kill()
            child.wait()

    def log(self, key):
        try:
            with open(os.path.join(self.dir, key + ".log")) as f:
                return f.read()
        except OSError:
            return ""

    def logs(self):
        return "".join("---- %s\n%s" % (name[:-4], self.log(name[:-4]))
                       for name in sorted(os.listdir(self.dir)) if name.endswith(".log"))

    def stop_all(self):
        for key in list(self.children):
            self.stop(key)
        self.domain.release()

    # ---- the programs --------------------------------------------------------------------------
    def master(self):
        self.start("rosmaster", ["rosmaster", "--core", "-p", str(self.master_port)])
        proxy = xmlrpc.client.ServerProxy(self.env["ROS_MASTER_URI"])
        deadline = time.monotonic() + 15
        while time.monotonic() < deadline:
            try:
                proxy.getPid("/hubrt_ros1_tier")
                return
            except OSError:
                time.sleep(0.1)
        raise RuntimeError("rosmaster did not answer on port %d" % self.master_port)

    def system_state(self):
        """(publishers, subscribers) as {topic: [node, ...]} from the master (ROS Master API)."""
        proxy = xmlrpc.client.ServerProxy(self.env["ROS_MASTER_URI"])
        _, _, (pubs, subs, _) = proxy.getSystemState("/hubrt_ros1_tier")
        return dict((t, n) for t, n in pubs), dict((t, n) for t, n in subs)

    def bridge(self, key="hubbridge", file="tests/ros1/dock_bridge.yaml"):
        return self.start(key, [self.program("firmware/hubbridge/hubbridge"), file] + self.domain.args())

    def bridge_file_with(self, file="tests/ros1/dock_bridge.yaml", **keys):
        """A copy of bridge `file` with top-level `keys` set (a msg_dir it names made absolute)."""
        import yaml
        with open(os.path.join(SOURCE, file)) as f:
            root = yaml.safe_load(f)
        if "msg_dir" in root:
            root["msg_dir"] = os.path.normpath(os.path.join(SOURCE, os.path.dirname(file), root["msg_dir"]))
        root.update(keys)
        path = os.path.join(self.dir, "bridge.yaml")
        with open(path, "w") as f:
            yaml.safe_dump(root, f)
        return path

    def dock_ecu(self, key="dock_ecu", extra=()):
        return self.start(key, [PYTHON, os.path.join(HERE, "dock_ecu_ros1.py")] + list(extra))

    def hubctl(self, args, timeout):
        argv = [self.program("firmware/hubctl/hubctl")] + args + self.domain.args()
        return subprocess.run(argv, capture_output=True, text=True, env=self.env, cwd=SOURCE, timeout=timeout)

    def echo(self, topic, count=1, wait_s=10):
        """The first `count` samples of `topic` as JSON objects ([] if none came within wait_s)."""
        try:
            done = self.hubctl(["echo", topic, "--json", "-n", str(count), "--timeout", str(wait_s)], wait_s + 20)
        except subprocess.TimeoutExpired:
            return []
        return [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]

    def record(self, topic):
        """A StateRecorder of `topic` on DDS, started now (stopped by stop_all)."""
        argv = [self.program("firmware/hubctl/hubctl"), "echo", topic, "--json"] + self.domain.args()
        child = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env=self.env,
                                 cwd=SOURCE, start_new_session=True)
        self.children["record " + topic] = child
        return StateRecorder(child)

    def bridge_status(self, dds_topic, name="dock_ecu", wait_s=10):
        """hubbridge's /diagnostics status of the bridge to `dds_topic`: {level, message, values{}}."""
        deadline = time.monotonic() + wait_s
        while time.monotonic() < deadline:
            for array in self.echo("/diagnostics", count=3, wait_s=3):
                for status in array.get("status", []):
                    if status["name"] == "hubbridge %s: %s" % (name, dds_topic):
                        values = {kv["key"]: kv["value"] for kv in status["values"]}
                        return {"level": status["level"], "message": status["message"], "values": values}
        return None


class StateRecorder:
    """The samples `hubctl echo --json` prints, each with the monotonic time it arrived here."""

    def __init__(self, child):
        self.samples = []  # (arrival, JSON object)
        self.lock = threading.Lock()
        self.thread = threading.Thread(target=self._read, args=(child.stdout,), daemon=True)
        self.thread.start()

    def _read(self, stream):
        for line in stream:
            if line.startswith("{"):
                with self.lock:
                    self.samples.append((time.monotonic(), json.loads(line)))

    def since(self, t):
        with self.lock:
            return [(at, s) for at, s in self.samples if at >= t]

    def largest_gap(self, start, end):
        """The longest time in [start, end] without a sample (end - start when none came)."""
        times = [start] + [at for at, _ in self.since(start) if at <= end] + [end]
        return max(b - a for a, b in zip(times, times[1:]))


def wait_until(predicate, timeout_s, step_s=0.2):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(step_s)
    return predicate()
