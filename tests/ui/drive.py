#!/usr/bin/env python3
"""The operator screen in a real browser (./hubrt ui-test; docs/operator-screen.md).

hubd runs the operator hub on its test board (fake backend, simulated RFID reader) in a DDS
domain of its own on loopback, a planner (hubctl send) keeps `verify` in force and publishes an
instruction, and `hubctl serve` serves the screen on a free loopback port. Headless Chromium,
driven through chromedriver's W3C WebDriver HTTP API, loads the page and checks: the instruction
and the station overview arrive over server-sent events; "done" without a verified operator shows
the server's refusal; a simulated badge makes Anna Svensson appear; "done" is accepted and the
operator panel's State, read by the planner side with `hubctl echo`, has confirm_seq grown by one.
A screenshot of the page is kept under the output directory.

python3's standard library only (urllib, json): no pip. Exit status 0 passed, 1 failed.
"""
import argparse
import base64
import json
import os
import shutil
import subprocess
import sys
import time
import urllib.error
import urllib.request

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from tier import PATIENCE_S, Failed, Processes, acquire_domain, free_port  # noqa: E402

ELEMENT = "element-6066-11e4-a52e-4f735466cecf"  # W3C WebDriver's element reference key


def log(message):
    print(f"ui-test: {message}", flush=True)


class WebDriver:
    """The few W3C WebDriver commands this test needs (https://www.w3.org/TR/webdriver2/)."""

    def __init__(self, port):
        self.base = f"http://127.0.0.1:{port}"
        self.session = None

    def call(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(self.base + path, data=data, method=method,
                                         headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=60) as response:
                return json.loads(response.read() or b"{}").get("value")
        except urllib.error.HTTPError as e:
            raise Failed(f"WebDriver {method} {path}: {e.code} {e.read()[:500]!r}") from e

    def wait_ready(self):
        deadline = time.monotonic() + PATIENCE_S
        while time.monotonic() < deadline:
            try:
                if self.call("GET", "/status").get("ready"):
                    return
            except (OSError, Failed):
                pass
            time.sleep(0.2)
        raise Failed("chromedriver did not become ready")

    def open_session(self, chromium, profile_dir):
        args = ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                f"--user-data-dir={profile_dir}", "--window-size=1100,1000", "--no-first-run",
                "--no-default-browser-check", "--disable-extensions", "--disable-background-networking",
                "--disable-sync", "--disable-component-update", "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"]
        caps = {"capabilities": {"alwaysMatch": {"browserName": "chrome", "goog:chromeOptions": {
            "binary": chromium, "args": args}}}}
        self.session = self.call("POST", "/session", caps)["sessionId"]

    def s(self, path):
        return f"/session/{self.session}{path}"

    def go(self, url):
        self.call("POST", self.s("/url"), {"url": url})

    def find(self, css):
        return self.call("POST", self.s("/element"), {"using": "css selector", "value": css})[ELEMENT]

    def text(self, css):
        return self.call("GET", self.s(f"/element/{self.find(css)}/text"))

    def click(self, css):
        self.call("POST", self.s(f"/element/{self.find(css)}/click"), {})

    def wait_text(self, css, predicate, what):
        deadline = time.monotonic() + PATIENCE_S
        last = None
        while time.monotonic() < deadline:
            try:
                last = self.text(css)
                if predicate(last):
                    return last
            except Failed:
                pass
            time.sleep(0.2)
        raise Failed(f"{what}: '{css}' shows {last!r}")

    def screenshot(self, path):
        with open(path, "wb") as f:
            f.write(base64.b64decode(self.call("GET", self.s("/screenshot"))))

    def close(self):
        if self.session:
            try:
                self.call("DELETE", self.s(""))
            except (OSError, Failed):
                pass


def confirm_seq(hubctl, dds_args):
    """The operator panel's confirm_seq as the planner sees it: `hubctl echo --json --count 1`."""
    out = subprocess.run([hubctl, "echo", "/operator_hub/panel/state", "--json", "--count", "1", *dds_args],
                         capture_output=True, timeout=PATIENCE_S, check=True)
    return json.loads(out.stdout.decode().splitlines()[-1])["confirm_seq"]


def run(args):
    source = os.path.abspath(args.source_dir)
    build = os.path.abspath(args.build_dir)
    out_dir = os.path.abspath(args.out_dir)
    os.makedirs(out_dir, exist_ok=True)
    hubd = os.path.join(build, "firmware/hubd/hubd")
    hubctl = os.path.join(build, "firmware/hubctl/hubctl")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    chromedriver = shutil.which("chromedriver")
    for program, what in ((hubd, "hubd"), (hubctl, "hubctl"), (chromium, "chromium"), (chromedriver, "chromedriver")):
        if not program or not os.access(program, os.X_OK):
            raise Failed(f"{what} not found ({program}): build it / toolchain/install-deps --ui")

    domain, _lock = acquire_domain()
    dds_args = ["--domain", str(domain), "--loopback"]
    env = dict(os.environ)
    env.pop("CYCLONEDDS_URI", None)
    env["HUBRT_CONFIG_DIR"] = source
    operator_dir = os.path.join(source, "hubs/operator_hub")
    with open(os.path.join(operator_dir, "operator_hub.yaml"), encoding="utf-8") as f:
        hub_text = f.read().replace("allow_list: operators.list",
                                    "allow_list: " + os.path.join(operator_dir, "test/operators.list"))
    hub_file = os.path.join(out_dir, "operator_hub.yaml")
    with open(hub_file, "w", encoding="utf-8") as f:
        f.write(hub_text)

    procs = Processes(out_dir)
    driver = None
    try:
        hub = procs.start("hubd", [hubd, "--board", os.path.join(operator_dir, "../../boards/host-sim-operator-hub.yaml"),
                                   "--hub", hub_file, *dds_args], env)
        procs.wait_for_log("hubd", "running hub", hub)
        procs.start("planner", [hubctl, "send", "/operator_panel/command", "target_type=operator_panel",
                                "target_name=panel", "action=verify", "--rate", "20", "--quiet", *dds_args], env)
        procs.start("instruction", [hubctl, "send", "/operator/instruction", "--type",
                                    "hub_msgs/msg/OperatorInstruction", "step=ladder_frame",
                                    "text=Place the ladder frame <on the jig> & confirm", "seq=1", "--rate", "2",
                                    "--quiet", *dds_args], env)
        serve = procs.start("serve", [hubctl, "serve", "--listen", "127.0.0.1:0", *dds_args], env)
        line = procs.wait_for_log("serve", "serving http://", serve)
        url = line[line.index("serving http://") + len("serving "):].split()[0]
        log(f"screen at {url}, DDS domain {domain}")

        driver_port = free_port()
        procs.start("chromedriver", [chromedriver, f"--port={driver_port}", "--allowed-ips=127.0.0.1"])
        driver = WebDriver(driver_port)
        driver.wait_ready()
        driver.open_session(chromium, os.path.join(out_dir, "chromium-profile"))
        started = time.monotonic()
        driver.go(url)
        driver.wait_text("#link", lambda t: t == "live", "the event stream")
        driver.wait_text("#instruction", lambda t: t == "Place the ladder frame <on the jig> & confirm",
                         "the planner's instruction (escaped markup shown as text)")
        driver.wait_text("#station-rows", lambda t: "/operator_hub/panel/state" in t, "the station overview")
        driver.wait_text("#who", lambda t: t == "nobody verified", "no operator yet")
        log("page loaded, instruction and station overview live")

        before = confirm_seq(hubctl, dds_args)
        driver.click("#done")
        driver.wait_text("#confirm-message", lambda t: "no operator is verified" in t, "the refusal (409)")
        log("done without an operator: refused on the page")

        subprocess.run([hubctl, "send", "/sim/badge", "hub=operator_hub", "reader=operator_rfid",
                        "text=0004123456", "--once", "--wait", "1", "--quiet", *dds_args],
                       check=True, timeout=PATIENCE_S, env=env)
        driver.wait_text("#who", lambda t: t == "Anna Svensson", "the badge's operator over server-sent events")
        log("badge shown: Anna Svensson appears")

        time.sleep(1.1)  # the refused press started no interval, but keep clear of the rate limit
        driver.click("#done")
        driver.wait_text("#confirm-message", lambda t: t == "done: sent", "the accepted press")
        deadline = time.monotonic() + PATIENCE_S
        after = before
        while time.monotonic() < deadline and after != before + 1:
            after = confirm_seq(hubctl, dds_args)
        if after != before + 1:
            raise Failed(f"the planner saw confirm_seq {after}, wanted {before + 1}")
        log(f"done pressed: the planner sees confirm_seq {before} -> {after}")
        driver.screenshot(os.path.join(out_dir, "operator-screen.png"))
        log(f"screenshot: {os.path.join(out_dir, 'operator-screen.png')} "
            f"(browser part {time.monotonic() - started:.1f} s)")
    finally:
        if driver:
            driver.close()
        procs.stop_all()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source-dir", default=".")
    parser.add_argument("--build-dir", default="build/host-asan")
    parser.add_argument("--out-dir", default="build/host-asan/ui-test")
    args = parser.parse_args()
    started = time.monotonic()
    try:
        run(args)
    except (Failed, subprocess.SubprocessError) as e:
        print(f"ui-test: FAILED: {e}\n(logs in {args.out_dir})", file=sys.stderr)
        return 1
    log(f"passed in {time.monotonic() - started:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
