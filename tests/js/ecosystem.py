#!/usr/bin/env python3
"""The ecosystem tier (./hubrt ecosystem-test; tests/js/README.md): every MCAP file hubctl record and
hubd's black box write, judged by the ecosystem's own JavaScript readers (check_mcap.cjs).

In a DDS domain of its own on loopback: the Dock and RSP ECUs' hubd on the simulation board, a
planner commanding the dock (hubctl send at 10 Hz), and
  - hubctl record of the station's traffic while hubctl echo --json prints a dock State topic, the
    RSP's State, the dock's command and /diagnostics: the file, finished by SIGINT, is read with
    @mcap/core's indexed and streamed readers, every message decoded from its own schema, each
    echoed sample found in it field by field; hubctl echo --from the file prints what it printed live;
  - lz4 chunks; --max-duration 1 (each part complete on its own); a recorder killed with SIGKILL
    (read up to its last whole chunk, the indexed reader refusing it) and hubctl record --recover
    (whole again, with as many messages as the whole chunks held);
  - the black box of the Dock ECU asked for with hubctl blackbox, judged the same way.
Then hubctl foxglove, driven by the Foxglove WebSocket protocol's own client (foxglove_live.py).
Exit status 0 passed, 1 failed. python3's standard library only; node runs the judge.
"""
import argparse
import glob
import json
import os
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from tier import PATIENCE_S, Failed, Processes, acquire_domain  # noqa: E402
import foxglove_live  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def log(message):
    print(f"ecosystem-test: {message}", flush=True)


class Tier:
    def __init__(self, args):
        self.source = os.path.abspath(args.source_dir)
        self.build = os.path.abspath(args.build_dir)
        self.out = os.path.abspath(args.out_dir)
        self.node_modules = os.path.join(self.build, "ecosystem", "node_modules")
        self.hubd = os.path.join(self.build, "firmware/hubd/hubd")
        self.hubctl_path = os.path.join(self.build, "firmware/hubctl/hubctl")
        for program in (self.hubd, self.hubctl_path):
            if not os.access(program, os.X_OK):
                raise Failed(f"{program} is missing: build hubd and hubctl first")
        if not os.path.isdir(os.path.join(self.node_modules, "@mcap", "core")):
            raise Failed(f"no {self.node_modules}: run toolchain/install-js-deps --build-dir {args.build_dir}")
        self.domain, self._lock = acquire_domain()
        self.env = dict(os.environ)
        self.env.pop("CYCLONEDDS_URI", None)
        self.env["HUBRT_CONFIG_DIR"] = self.source
        self.env["ROS_DOMAIN_ID"] = str(self.domain)
        self.procs = Processes(self.out)

    def path(self, name):
        return os.path.join(self.out, name)

    def hubctl(self, name, args, stdout=None):
        """hubctl in the tier's domain on loopback, its output in <name>.log (stdout to `stdout`)."""
        return self.procs.start(name, [self.hubctl_path, *args, "--loopback"], env=self.env, stdout=stdout)

    def finish(self, name, child, timeout=PATIENCE_S * 4):
        try:
            code = child.wait(timeout)
        except subprocess.TimeoutExpired as e:
            raise Failed(f"{name} did not end within {timeout} s:\n{self.procs.log_text(name)}") from e
        if code != 0:
            raise Failed(f"{name} exited {code}:\n{self.procs.log_text(name)}")

    def judge(self, file, *extra):
        """check_mcap.cjs on `file`: its report, or Failed with what the judge said."""
        env = dict(self.env, NODE_PATH=self.node_modules)
        result = subprocess.run(["node", os.path.join(HERE, "check_mcap.cjs"), file, *extra], env=env,
                                capture_output=True, text=True, timeout=PATIENCE_S * 4, check=False)
        if result.returncode != 0:
            raise Failed(f"the judge refused {file}:\n{result.stderr}{result.stdout}")
        report = json.loads(result.stdout.strip().splitlines()[-1])
        log(f"judged {os.path.basename(file)}: {report['messages']} messages, topics {report['topics']}"
            + (f", echo matched {report['echo_matched']}" if report.get("echo_matched") else ""))
        return report

    def record(self, name, *args):
        child = self.hubctl(name, ["record", "-o", self.path(f"{name}.mcap"), "--quiet", *args])
        self.procs.wait_for_log(name, "recording into", child)
        return child

    def wait_for_file(self, pattern):
        deadline = time.monotonic() + PATIENCE_S
        while time.monotonic() < deadline:
            found = sorted(glob.glob(self.path(pattern)))
            if found:
                return found
            time.sleep(0.1)
        raise Failed(f"no {pattern} in {self.out}")


def station(tier):
    for hub in ("dock_ecu", "rsp_ecu"):
        child = tier.procs.start(hub, [tier.hubd, "--board", "host-sim", "--hub", hub, "--loopback"], env=tier.env)
        tier.procs.wait_for_log(hub, "running", child)
    tier.hubctl("planner", ["send", "/dock/command", "target_type=dock", "target_name=dock", "action=monitor",
                            "--rate", "10", "--quiet", "--timeout", "30"])


def record_beside_echo(tier):
    recorder = tier.record("station")
    echoes = {"/dock_ecu/dock/state": 40, "/rsp_ecu/rsp/state": 40, "/dock/command": 20, "/diagnostics": 3}
    children = {}
    for n, (topic, count) in enumerate(echoes.items()):
        out = tier.path(f"echo_{n}.jsonl")
        children[topic] = (f"echo_{n}", out, tier.hubctl(f"echo_{n}", ["echo", topic, "--json", "-n", str(count),
                                                                        "--timeout", "60"], stdout=out))
    for topic, (name, _, child) in children.items():
        tier.finish(name, child)
    recorder.send_signal(signal.SIGINT)
    tier.finish("station", recorder)
    file = tier.path("station.mcap")
    judge_args = []
    for topic, (_, out, _) in children.items():
        judge_args += ["--echo", f"{topic}={out}"]
    report = tier.judge(file, *judge_args)
    for topic, count in echoes.items():
        if report["echo_matched"].get(topic) != count:
            raise Failed(f"{topic}: {report['echo_matched'].get(topic)} echoed samples matched, {count} printed")
    # hubctl echo --from the file prints what hubctl echo printed live, in the same order.
    replayed = tier.path("echo_from_file.jsonl")
    tier.finish("echo_from", tier.hubctl("echo_from", ["echo", "/dock_ecu/dock/state", "--json", "--from", file],
                                         stdout=replayed))
    with open(tier.path("echo_0.jsonl"), encoding="utf-8") as f:
        live = f.read().splitlines()
    with open(replayed, encoding="utf-8") as f:
        from_file = f.read().splitlines()
    joined = "\n".join(from_file)
    if "\n".join(live) not in joined:
        raise Failed("hubctl echo --from the recording does not print the lines hubctl echo printed live")
    log(f"echo --from the file: {len(from_file)} States, the {len(live)} echoed live among them in order")


def compressions_and_splits(tier):
    lz4 = tier.record("lz4", "--compression", "lz4", "--chunk-seconds", "0.3")
    split = tier.record("split", "--max-duration", "1")
    tier.wait_for_file("split_2.mcap")
    time.sleep(1.0)
    lz4.send_signal(signal.SIGTERM)
    split.send_signal(signal.SIGTERM)
    tier.finish("lz4", lz4)
    tier.finish("split", split)
    report = tier.judge(tier.path("lz4.mcap"))
    if report["chunks"] < 2:
        raise Failed(f"lz4.mcap: {report['chunks']} chunk(s); the test needs several")
    parts = sorted(glob.glob(tier.path("split_*.mcap")))
    for part in parts:
        tier.judge(part)
    log(f"--max-duration 1: {len(parts)} parts, each complete")


def killed_and_recovered(tier):
    killed = tier.record("killed", "--chunk-seconds", "0.3")
    time.sleep(3.0)
    killed.send_signal(signal.SIGKILL)
    killed.wait(PATIENCE_S)
    file = tier.path("killed.mcap")
    cut = tier.judge(file, "--cut")
    if cut["messages"] == 0:
        raise Failed("the killed recorder's file holds no whole chunk")
    recovered = tier.path("recovered.mcap")
    tier.finish("recover", tier.hubctl("recover", ["record", "--recover", file, "-o", recovered]))
    tier.judge(recovered, "--messages", str(cut["messages"]))
    log(f"killed recorder: {cut['messages']} messages in whole chunks, all of them in the recovered file")


def run(args):
    tier = Tier(args)
    try:
        station(tier)
        record_beside_echo(tier)
        compressions_and_splits(tier)
        killed_and_recovered(tier)
        foxglove_live.run(tier)
    finally:
        tier.procs.stop_all()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source-dir", default=".")
    parser.add_argument("--build-dir", default="build/host-asan")
    parser.add_argument("--out-dir", default="build/host-asan/ecosystem-test")
    args = parser.parse_args()
    started = time.monotonic()
    try:
        run(args)
    except (Failed, subprocess.SubprocessError) as e:
        print(f"ecosystem-test: FAILED: {e}\n(logs in {args.out_dir})", file=sys.stderr)
        return 1
    log(f"passed in {time.monotonic() - started:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
