#!/usr/bin/env python3
"""A plant of simulated stations on this host (issue 33 point 2, docs/plant.md): what one hub costs
as the plant grows, in the two ways to lay a plant out on DDS.

Each station is the paper's full station, as ./hubrt demo runs it: five hubd (Tool, RSP and Dock
ECUs, mir_com, the operator hub) on their simulation boards, hubsim with the full station's world,
and a planner (hubctl play full-use-case.yaml --rounds 0) playing the use-case round after round.
All on loopback, release build. Two designs:
  domains  one DDS domain per station (station k in domain BASE+k): what docs/plant.md recommends;
  shared   one domain for the whole plant, each station under its ROS namespace /s<k> (hub files'
           namespace:, hubsim and play --namespace). Unicast discovery on loopback admits at most
           MaxAutoParticipantIndex participants per host and domain (hubrt's loopback configuration:
           100; src/core/ddsi/src/q_init.c); this design's configuration raises it to fit the plant,
           which is what a shared domain costs: every participant sends its discovery to every index.
For each N (stations) and design: N-1 stations are started, then the last one, timed from its spawn
to its planner's first passing command step (discovery of a station that starts last); then, over a
window, the CPU and RSS of the last station's Dock ECU (and the median over every Dock ECU), the
host's load; then two probes run as one more station beside the plant (in the shared domain, or in
a domain of their own): hubrt_bench_heartbeat (a hub's heartbeat jitter at a subscriber, 100 Hz,
beside a bare writer) and hubrt_bench_echo_latency (command -> echo, beside the raw pong). Planners
that stopped (a failed step) are counted: a station that failed its use-case. With --conformance, in
the domains design, last: `hubctl conformance` of every hub of every station, the plant running.
With --tails, after the window: hubrt_bench_tails (docs/tails.md: ten interleaved rounds, medians
of the rounds' p95 and p99 ratios) as one more station beside the plant. With --realtime, every hubd
runs as the board packages' units run it, `hubd --realtime`; the planners, hubsim and the probes do not.
With --probes-realtime [PRIORITY], every probe (its hubd and its baselines, planners and subscribers
alike) runs under SCHED_FIFO 40, the hubs' own priority, or PRIORITY: on a real plant a station's hubs
and the PC that watches them are not queued behind the other stations' processes, which on one host
only a priority gives (above 40, not behind the other stations' hubs either: cores of its own).
    bench/plant.py [--build-dir build/host-release] [--stations 1,4,16,32] [--designs domains,shared]
                   [--window 20] [--out FILE] [--no-probes] [--append] [--conformance] [--tails] [--realtime]
                   [--probes-realtime [PRIORITY]]
Prints one progress line per step and a Markdown table at the end; the JSON goes to --out
(default BUILD/bench-results/plant.json).
"""
import argparse
import collections
import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time

import yaml

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE_DOMAIN = 10  # stations in 10..41 (N = 32), outside the tests' 100..230 and the demo's 42
# (name, board, hub file): the full station, as toolchain/demo starts it.
HUBS = [("tool_ecu", "host-sim", "hubs/station/hub-files/tool_ecu.yaml"),
        ("rsp_ecu", "host-sim", "hubs/rsp_ecu/rsp_ecu.yaml"),
        ("dock_ecu", "host-sim", "hubs/dock_ecu/dock_ecu.yaml"),
        ("mir_com", "host-sim-mir-com", "hubs/mir_com/mir_com.yaml"),
        ("operator_hub", "host-sim-operator-hub", "hubs/station/hub-files/operator_hub.yaml")]
PROCESSES_PER_STATION = len(HUBS) + 2  # hubsim, the planner
CONFORMANCE_TIMEOUT_S = 300  # one station's five hubs in parallel, on a host the plant keeps busy
# A round of the full use-case takes about 33 s on a quiet host (README); a plant of 32 stations
# keeps the host 80 % busy. Past ROUND_WAIT_S a planner is stopped where it is ("mid-round").
ROUND_WAIT_S = 240
PLANNER_LOOKAHEAD = 3  # about 13 s of suites each (docs/plant.md): 40 s of a round overlapped
HUBD_ARGS = []  # more arguments for every hubd: ["--realtime"] with --realtime
PROBE_PREFIX = []  # what a probe runs under: chrt SCHED_FIFO 40 with --probes-realtime (inherited by its children)


def progress(line):
    print(f"plant: {time.strftime('%H:%M:%S')} {line}", file=sys.stderr, flush=True)


def cyclone_xml(participants):
    """hubrt's loopback configuration (dds::loopback_config_xml), with room for `participants`."""
    index = max(100, participants + 16)
    return ("<CycloneDDS><Domain id=\"any\"><General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
            "<AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex>"
            f"<MaxAutoParticipantIndex>{index}</MaxAutoParticipantIndex>"
            "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery></Domain></CycloneDDS>")


def hub_file(source, namespace, folder, name):
    """The hub file, under `namespace` (its subscriptions to other hubs' States too)."""
    path = os.path.join(REPO, source)
    if not namespace:
        return path
    with open(path) as f:
        root = yaml.safe_load(f)
    root["namespace"] = namespace
    for sub in (root.get("subscriptions") or {}).values():
        sub["topic"] = namespace + sub["topic"]
    for node in (root.get("nodes") or {}).values():
        allow = node.get("allow_list")
        if allow and not os.path.isabs(allow):
            node["allow_list"] = os.path.join(os.path.dirname(path), allow)
    out = os.path.join(folder, f"{name}.yaml")
    with open(out, "w") as f:
        yaml.safe_dump(root, f, sort_keys=False)
    return out


class Station:
    """One station's seven processes; the planner's output lines are read with their arrival times."""

    def __init__(self, build, k, design, xml, scratch):
        self.k = k
        self.domain = BASE_DOMAIN if design == "shared" else BASE_DOMAIN + k
        self.namespace = f"/s{k}" if design == "shared" else ""
        self.env = dict(os.environ, ROS_DOMAIN_ID=str(self.domain), CYCLONEDDS_URI=xml, HUBRT_CONFIG_DIR=REPO,
                        HUBRT_BLACKBOX_DIR=os.path.join(scratch, "blackbox"))
        self.folder = os.path.join(scratch, f"s{k}")
        os.makedirs(self.folder, exist_ok=True)
        self.processes = {}
        self.first_pass = None
        self.spawned = time.monotonic()
        ns = ["--namespace", self.namespace] if self.namespace else []
        for name, board, source in HUBS:
            self._start(name, [f"{build}/firmware/hubd/hubd", "--board", board, "--log-level", "warn",
                               "--hub", hub_file(source, self.namespace, self.folder, name)] + HUBD_ARGS)
        self._start("hubsim", [f"{build}/firmware/sim/station/hubsim", "--log-level", "warn", "--station",
                               os.path.join(REPO, "hubs/station/full-station.yaml")] + ns)
        play = [f"{build}/firmware/hubctl/hubctl", "play", os.path.join(REPO, "hubs/station/scenarios/full-use-case.yaml"),
                "--rounds", "0", "--timeout", "60"] + ns
        self.planner = subprocess.Popen(play, env=self.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        text=True, start_new_session=True)
        self.processes["planner"] = self.planner
        # Not --quiet: the step and round lines say where the planner is (its first passing
        # command step; the start of a round, where conform() stops it). The last lines are kept.
        self.planner_lines = collections.deque(maxlen=40)
        self.stop_at_round_start = threading.Event()
        self._planner_reader = threading.Thread(target=self._read_planner, daemon=True)
        self._planner_reader.start()

    def _start(self, name, argv):
        log = open(os.path.join(self.folder, f"{name}.log"), "w")
        self.processes[name] = subprocess.Popen(argv, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                                                start_new_session=True)

    def _read_planner(self):
        for line in self.planner.stdout:
            self.planner_lines.append(line)
            # A round ends where it starts: the MiR home, no mission queued. Stopped as the next
            # round begins, before its first move, the planner leaves the platform standing still.
            if line.startswith("play: round") and self.stop_at_round_start.is_set() and self.planner.poll() is None:
                self.planner.send_signal(signal.SIGINT)
            if self.first_pass is None and "PASS" in line and " command " in line:
                self.first_pass = time.monotonic()

    def stop_planner_between_rounds(self, timeout_s):
        """Waits (at most timeout_s) for the planner, armed with stop_at_round_start, to stop at the
        start of a round; past that, stops it where it is. Says which."""
        self.stop_at_round_start.set()
        if self.planner.poll() is not None:
            self._planner_reader.join(timeout=5)  # its last lines, read to the end of its output
            if not self.planner_lines_say_interrupted():
                return "had stopped"  # a failed step: its lines say which
        try:
            self.planner.wait(timeout=timeout_s)
            return "between rounds"
        except subprocess.TimeoutExpired:
            self.planner.send_signal(signal.SIGINT)
        try:
            self.planner.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.planner.kill()
            self.planner.wait()
        return "mid-round"

    def planner_lines_say_interrupted(self):
        return any(line.startswith("play: interrupted") for line in self.planner_lines)

    def failed(self):
        """The planner stopped by itself: a step failed (its output says which)."""
        return self.planner.poll() is not None

    def signal_stop(self):
        for p in self.processes.values():
            if p.poll() is None:
                p.send_signal(signal.SIGINT if p is self.planner else signal.SIGTERM)

    def reap(self, deadline):
        """Waits for every process until `deadline` (monotonic), then kills what still runs: on a
        saturated host (the shared design at N = 32) a hub's orderly stop can take tens of seconds."""
        for p in self.processes.values():
            try:
                p.wait(timeout=max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def stop_all(stations):
    for s in stations:
        s.signal_stop()
    deadline = time.monotonic() + 30
    for s in stations:
        s.reap(deadline)


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def rss_mb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


def host_times():
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:]]
    idle = v[3] + v[4]
    return sum(v), idle, v[7] if len(v) > 7 else 0


PROBE_TIMEOUT_S = 150  # on a host the plant saturates a probe may not finish: recorded as such
TAILS_TIMEOUT_S = 1200  # hubrt_bench_tails: about 7 minutes on a quiet host


def probe(build, program, args, design, domain, xml, scratch, timeout_s=None):
    """A bench program as one more station: in the plant's shared domain, or a private one. None when
    it did not finish within timeout_s (PROBE_TIMEOUT_S by default) or failed."""
    timeout_s = timeout_s or PROBE_TIMEOUT_S
    env = dict(os.environ, HUBRT_CONFIG_DIR=REPO, HUBRT_BLACKBOX_DIR=os.path.join(scratch, "blackbox"))
    if design == "shared":
        env.update(HUBRT_BENCH_DOMAIN=str(domain), HUBRT_BENCH_CYCLONEDDS_URI=xml)
    out = os.path.join(scratch, f"{program}.json")
    # A session of its own: stopped at the timeout with the hubd and raw peer it started.
    bench = subprocess.Popen(PROBE_PREFIX + [f"{build}/bench/{program}", "--out", out] + args, env=env,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        status = bench.wait(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        os.killpg(bench.pid, signal.SIGTERM)
        try:
            bench.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(bench.pid, signal.SIGKILL)
            bench.wait()
        progress(f"{program}: not done in {timeout_s} s; stopped")
        return None
    if status != 0:
        progress(f"{program}: exit status {status}")
        return None
    with open(out) as f:
        return json.load(f)


def conform(build, stations):
    """`hubctl conformance` of every hub of every station, the plant still running: each station's
    planner is stopped first (the suite commands the hubs itself, and two planners commanding one
    hub measure neither), between two rounds of its use-case: the suite's probes are for a platform
    standing still (hubs/mir_com/conformance.yaml), and a planner stopped mid-mission leaves one in
    the MiR's queue for the suite's `continue` to resume. The next PLANNER_LOOKAHEAD stations' planners
    are told to stop at their next round too, so that waiting for a round overlaps the suites before.
    Its hubs and hubsim keep running (the station's domain and Cyclone configuration come with its
    environment), the other stations keep playing until their turn. One station after the other,
    its five hubs in parallel (--parallel)."""
    names = [name for name, _, _ in HUBS]
    passed, failures, stops, stopped_alone, t0 = 0, [], collections.Counter(), [], time.monotonic()
    for i, s in enumerate(stations):
        for ahead in stations[i:i + 1 + PLANNER_LOOKAHEAD]:
            ahead.stop_at_round_start.set()
        progress(f"conformance: station {s.k + 1} of {len(stations)} (domain {s.domain}): its planner stops "
                 "at the start of a round")
        stop = s.stop_planner_between_rounds(ROUND_WAIT_S)
        stops[stop] += 1
        if stop != "between rounds":
            progress(f"conformance: station {s.k + 1}'s planner {stop}")
        if stop == "had stopped":  # a failed step, maybe mid-mission: the suite's results say more
            stopped_alone.append({"station": s.k, "last_lines": "".join(list(s.planner_lines)[-3:])})
        argv = [f"{build}/firmware/hubctl/hubctl", "conformance", "--parallel", "--domain", str(s.domain)] + [
                arg for name in names for arg in ("--hub", name)]
        try:
            run = subprocess.run(argv, env=s.env, capture_output=True, text=True, timeout=CONFORMANCE_TIMEOUT_S)
            ok, said = run.returncode == 0, run.stdout + run.stderr
        except subprocess.TimeoutExpired:
            ok, said = False, f"did not finish in {CONFORMANCE_TIMEOUT_S} s"
        if ok:
            passed += 1
        else:
            # The checks that failed, each under the topic it was measured on, and the whole report.
            failing, topic = [], ""
            for line in said.splitlines():
                if line.startswith("/") or line.startswith("rt/"):
                    topic = line.strip()
                elif "FAIL" in line:
                    failing.append(f"{topic}: {line.strip()}")
            failures.append({"station": s.k, "domain": s.domain, "failing": failing, "output": said})
    return {"stations": len(stations), "hubs": len(stations) * len(names), "stations_passed": passed,
            "failures": failures, "planners_stopped": dict(stops),
            "planners_that_had_stopped": stopped_alone, "seconds": round(time.monotonic() - t0, 1)}


def run_plant(build, n, design, window, probes, conformance, tails=False):
    xml = cyclone_xml(n * PROCESSES_PER_STATION + 8 if design == "shared" else 0)
    result = {"stations": n, "design": design, "processes": n * PROCESSES_PER_STATION,
              "hubd_args": " ".join(HUBD_ARGS), "probes_under": " ".join(PROBE_PREFIX)}
    with tempfile.TemporaryDirectory(prefix="hubrt-plant-") as scratch:
        stations = []
        try:
            start = time.monotonic()
            for k in range(n - 1):
                stations.append(Station(build, k, design, xml, scratch))
                time.sleep(0.2)  # a plant is not switched on in one instant
            settle = 3 + 0.3 * n
            result["start_others_s"] = time.monotonic() - start
            progress(f"N={n} {design}: {n - 1} stations started in {result['start_others_s']:.1f} s; "
                     f"settling {settle:.0f} s, then the last one")
            time.sleep(settle)
            last = Station(build, n - 1, design, xml, scratch)
            stations.append(last)
            deadline = time.monotonic() + 120
            while last.first_pass is None and time.monotonic() < deadline and not last.failed():
                time.sleep(0.05)
            result["discovery_last_s"] = (last.first_pass - last.spawned) if last.first_pass else None
            progress(f"N={n} {design}: the last station's first command step passed "
                     f"{result['discovery_last_s']} s after its spawn; measuring {window} s")
            docks = [s.processes["dock_ecu"].pid for s in stations]
            cpu0 = {pid: cpu_seconds(pid) for pid in docks}
            host0 = host_times()
            t0 = time.monotonic()
            time.sleep(window)
            span = time.monotonic() - t0
            host1 = host_times()
            cpu = {pid: 100 * (cpu_seconds(pid) - cpu0[pid]) / span for pid in docks}
            total = host1[0] - host0[0]
            result.update({
                "window_s": round(span, 1),
                "dock_last": {"cpu_pct": cpu[docks[-1]], "rss_mb": rss_mb(docks[-1])},
                "dock_median": {"cpu_pct": statistics.median(cpu.values()),
                                "rss_mb": statistics.median(rss_mb(p) for p in docks)},
                "host": {"busy_pct": 100 * (1 - (host1[1] - host0[1]) / total),
                         "steal_pct": 100 * (host1[2] - host0[2]) / total, "loadavg_1m": os.getloadavg()[0]},
            })
            result["probed"] = probes
            if probes:
                progress(f"N={n} {design}: heartbeat probe")
                hb = probe(build, "hubrt_bench_heartbeat", ["--rates", "100", "--seconds", "10", "--cpu-turns", "2",
                                                            "--cpu-turn-seconds", "1",
                                                            "--periods", os.path.join(scratch, "periods.csv")],
                           design, BASE_DOMAIN, xml, scratch)
                if hb:
                    hb = hb["rates"][0]
                    result["heartbeat"] = {"hub_p99_ms": hb["hub"]["arrival_jitter_ms"]["p99"],
                                           "raw_p99_ms": hb["raw"]["arrival_jitter_ms"]["p99"],
                                           "ratio_p99": hb["ratio_arrival_p99"], "hub_rss_mb": hb["hub"]["rss_mb"],
                                           "hub_cpu_pct": hb["hub"]["cpu_pct"], "hub_states": hb["hub"]["states"],
                                           "raw_states": hb["raw"]["states"]}
                progress(f"N={n} {design}: echo probe")
                echo = probe(build, "hubrt_bench_echo_latency", ["--sparse", "150", "--back-to-back", "600",
                                                                 "--rounds", "3"],
                             design, BASE_DOMAIN, xml, scratch)
                if echo:
                    result["echo"] = {regime: {"hub_p99_ms": echo[regime]["hub_ms"]["p99"],
                                               "raw_p99_ms": echo[regime]["raw_ms"]["p99"],
                                               "ratio_p99": echo[regime]["ratio_p99"]}
                                      for regime in ("sparse", "back_to_back")}
            if tails:
                progress(f"N={n} {design}: tails probe (hubrt_bench_tails, 10 rounds)")
                t = probe(build, "hubrt_bench_tails", [], design, BASE_DOMAIN, xml, scratch, TAILS_TIMEOUT_S)
                if t:
                    result["tails"] = {name: {k: v[k] for k in ("median_p95", "spread_p95", "median_p99", "spread_p99",
                                                                "judged_rounds")}
                                       for name, v in t["verdicts"].items()}
                    result["tails_per_round"] = t["per_round"]
            failed = [s for s in stations if s.failed()]
            result["stations_failed"] = len(failed)
            if failed:
                result["first_failure"] = "".join(list(failed[0].planner_lines)[-6:])
            if conformance and design == "domains":
                result["conformance"] = conform(build, stations)
        finally:
            stop_all(stations)
    return result


def fmt(value, spec=".2f"):
    return "-" if value is None else format(value, spec)


def table(results):
    rows = ["| design | N | processes | last station found its hubs | Dock ECU CPU (last / median) | "
            "Dock ECU RSS (last / median) | host busy, load | heartbeat p99 hub / raw writer | "
            "echo p99 sparse hub / raw pong | stations failed | stations whose hubs all pass conformance |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        hb, echo = r.get("heartbeat"), r.get("echo", {}).get("sparse")
        missing = "not run" if not r.get("probed") else f"did not finish ({PROBE_TIMEOUT_S} s bound)"
        hb_missing = missing
        if hb and (hb["hub_p99_ms"] == 0 or hb["raw_p99_ms"] == 0):
            hb, hb_missing = None, "no periods: the States did not arrive"  # a saturated host
        rows.append(
            f"| {r['design']}{' (hubd ' + r['hubd_args'] + ')' if r.get('hubd_args') else ''}"
            f"{' (probes under ' + r['probes_under'] + ')' if r.get('probes_under') else ''} | {r['stations']} | "
            f"{r['processes']} | {fmt(r.get('discovery_last_s'))} s | "
            f"{fmt(r['dock_last']['cpu_pct'])} / {fmt(r['dock_median']['cpu_pct'])} % | "
            f"{fmt(r['dock_last']['rss_mb'], '.1f')} / {fmt(r['dock_median']['rss_mb'], '.1f')} MB | "
            f"{fmt(r['host']['busy_pct'], '.0f')} %, {fmt(r['host']['loadavg_1m'], '.1f')} | "
            + (f"{fmt(hb['hub_p99_ms'], '.3f')} / {fmt(hb['raw_p99_ms'], '.3f')} ms ({fmt(hb['ratio_p99'])}x) | "
               if hb else f"{hb_missing} | ")
            + (f"{fmt(echo['hub_p99_ms'], '.3f')} / {fmt(echo['raw_p99_ms'], '.3f')} ms ({fmt(echo['ratio_p99'])}x) | "
               if echo else f"{missing} | ")
            + f"{r['stations_failed']} | "
            + (f"{r['conformance']['stations_passed']} of {r['conformance']['stations']} "
               f"({r['conformance']['seconds']:.0f} s) |" if r.get("conformance") else "not run |"))
    return "\n".join(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default=os.path.join(REPO, "build", "host-release"))
    parser.add_argument("--stations", default="1,4,16,32")
    parser.add_argument("--designs", default="domains,shared")
    parser.add_argument("--window", type=float, default=20.0)
    parser.add_argument("--out")
    parser.add_argument("--no-probes", action="store_true")
    parser.add_argument("--tails", action="store_true",
                        help="after the window: hubrt_bench_tails as one more station beside the plant (docs/tails.md)")
    parser.add_argument("--conformance", action="store_true",
                        help="after each domains-design plant's window: hubctl conformance of every hub of every station")
    parser.add_argument("--realtime", action="store_true",
                        help="every hubd with --realtime, as the board packages' units run it (docs/deploy.md): "
                             "SCHED_FIFO 40, memory locked; needs root or CAP_SYS_NICE and CAP_IPC_LOCK")
    parser.add_argument("--probes-realtime", type=int, nargs="?", const=40, metavar="PRIORITY",
                        help="every probe and its children under SCHED_FIFO (chrt), by default at 40, the hubs' own "
                             "priority; above it (41) as if the probe's station had cores of its own; needs root or "
                             "CAP_SYS_NICE")
    parser.add_argument("--append", action="store_true",
                        help="keep the results already in --out and run only the N and designs not there yet")
    args = parser.parse_args()
    build = os.path.abspath(args.build_dir)
    HUBD_ARGS.extend(["--realtime"] if args.realtime else [])
    if args.probes_realtime is not None and not 1 <= args.probes_realtime <= 99:
        parser.error(f"--probes-realtime: {args.probes_realtime} is not a SCHED_FIFO priority (1-99)")
    PROBE_PREFIX.extend(["chrt", "--fifo", str(args.probes_realtime)] if args.probes_realtime else [])
    if PROBE_PREFIX and subprocess.run(PROBE_PREFIX + ["true"], capture_output=True).returncode != 0:
        parser.error(f"--probes-realtime: {' '.join(PROBE_PREFIX)} is refused here (needs root or CAP_SYS_NICE, "
                     "and a priority of 1-99)")
    # Only the programs this run starts: --no-probes needs no bench program, and any build with
    # hubd, hubctl and hubsim runs the plant (a sanitizer build for a check of the bench itself).
    tools = ["firmware/hubd/hubd", "firmware/hubctl/hubctl", "firmware/sim/station/hubsim"]
    tools += [] if args.no_probes else ["bench/hubrt_bench_heartbeat", "bench/hubrt_bench_echo_latency"]
    tools += ["bench/hubrt_bench_tails"] if args.tails else []
    for tool in tools:
        if not os.access(os.path.join(build, tool), os.X_OK):
            parser.error(f"{build}/{tool} is missing: cmake --build {args.build_dir} --target hubd hubctl hubsim "
                         "bench-programs")
    counts = [int(x) for x in args.stations.split(",")]
    designs = args.designs.split(",")
    for d in designs:
        if d not in ("domains", "shared"):
            parser.error(f"--designs: '{d}' is neither domains nor shared")
    out = args.out or os.path.join(build, "bench-results", "plant.json")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    results = []
    if args.append and os.path.exists(out):
        with open(out) as f:
            results = json.load(f)["results"]
    for n in counts:
        for design in designs:
            if any(r["stations"] == n and r["design"] == design for r in results):
                continue
            results.append(run_plant(build, n, design, args.window, not args.no_probes, args.conformance, args.tails))
            with open(out, "w") as f:
                json.dump({"host_cpus": os.cpu_count(), "results": results}, f, indent=1)
    print(table(results))
    progress(f"results in {out}")


if __name__ == "__main__":
    main()
