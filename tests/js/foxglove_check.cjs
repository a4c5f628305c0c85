// hubctl foxglove judged by the Foxglove WebSocket protocol's own client (foxglove_support.cjs).
//
//   node foxglove_check.cjs check --url WS --topic T --echo FILE --count N --rsp-state T --rsp-command T --msg FILE
//     serverInfo without clientPublish; every advertised channel cdr + a ros2msg schema that parses;
//     subscribes to T (prints "subscribed"), decodes each message from the advertised schema and
//     finds every sample `hubctl echo --json` printed into FILE (N lines), in order, field by field;
//     receive timestamps near this machine's clock and in order; a publish on the RSP's command
//     topic is refused with a status and the RSP's State shows no command; a client that sends more
//     than 64 KiB at once is closed (1009) and the others go on.
//   node foxglove_check.cjs publish --url WS --rsp-state T --rsp-command T --msg FILE
//     (--allow-publish) serverInfo with clientPublish and cdr; a command published on the command
//     topic takes effect (the RSP's State echoes it, fresh); a State topic and bad bytes refused.
//   node foxglove_check.cjs lifecycle --url WS --topics T1,T2 --layout FILE
//     prints "ready"; T1 and T2 are advertised when their hub starts (prints "advertised" once a
//     message of T1 decoded, and checks every layout path of an advertised topic against its
//     schema); both are unadvertised when the hub stops (prints "unadvertised").
// The last line printed is a JSON report; exit status 0 or 1.
"use strict";
const fs = require("fs");
const { Session, fail, sleep, wallNs, definitionsOf, writerOf, args, json, run } = require("./foxglove_support.cjs");
const { compareTyped } = require("./compare_typed.cjs");
const { layoutPaths, resolvePath } = require("./foxglove_layout_paths.cjs");

const LOCK = { target_type: "tool_changer", target_name: "rsp", action: "lock", gripper: "" };

async function connected(url, publishing) {
  const session = new Session(url);
  await session.until("serverInfo", () => session.serverInfo);
  const { capabilities, supportedEncodings } = session.serverInfo;
  if (capabilities.includes("clientPublish") !== publishing)
    fail(`serverInfo capabilities ${JSON.stringify(capabilities)}: clientPublish expected ${publishing ? "" : "absent"}`);
  if (publishing && JSON.stringify(supportedEncodings) !== '["cdr"]')
    fail(`supportedEncodings ${JSON.stringify(supportedEncodings)}, not ["cdr"]`);
  if (!publishing && supportedEncodings !== undefined) fail("supportedEncodings without client publishing");
  return session;
}

function checkChannels(session) {
  const topics = new Set();
  for (const channel of session.channels.values()) {
    definitionsOf(channel);
    if (topics.has(channel.topic)) fail(`${channel.topic} advertised twice`);
    topics.add(channel.topic);
  }
  return [...topics].sort();
}

// Each echoed sample among the decoded messages, in order (as check_mcap.cjs's checkEcho).
function matchEcho(sub, lines) {
  const definitions = definitionsOf(sub.channel);
  let from = 0;
  for (const [n, line] of lines.entries()) {
    const echoed = JSON.parse(line);
    let best;
    let found = -1;
    for (let i = from; i < sub.messages.length && found < 0; i++) {
      const problems = compareTyped(sub.messages[i].value, echoed, definitions);
      if (problems.length === 0) found = i;
      else if (!best || problems.length < best.length) best = problems;
    }
    if (found < 0)
      fail(`${sub.channel.topic}: echoed sample ${n + 1} of ${lines.length} was not received (in order); nearest differs: ` +
           (best ?? ["no messages left"]).slice(0, 5).join("; "));
    from = found + 1;
  }
}

// Receive timestamps: hubctl's wall clock when it took the sample, this machine's too.
function checkTimestamps(sub) {
  let last = 0n;
  for (const m of sub.messages) {
    const skew = Number(m.arrived - m.timestamp) / 1e6;
    if (skew < -1000 || skew > 10_000) fail(`${sub.channel.topic}: receive timestamp ${m.timestamp} is ${skew} ms from arrival`);
    if (m.timestamp < last) fail(`${sub.channel.topic}: receive timestamps go back`);
    last = m.timestamp;
  }
}

async function check(a) {
  const session = await connected(a.url, false);
  await session.until(`${a.topic} advertised`, () => session.channel(a.topic) && session.channel(a["rsp-state"]));
  const topics = checkChannels(session);
  const sub = session.subscribe(a.topic);
  const rsp = session.subscribe(a["rsp-state"]);
  await session.until(`a message of ${a.topic}`, () => sub.messages.length > 0);
  console.log("subscribed");
  const lines = () => (fs.existsSync(a.echo) ? fs.readFileSync(a.echo, "utf-8").split("\n").filter((l) => l.trim()) : []);
  await session.until(`${a.count} lines of hubctl echo in ${a.echo}`, () => lines().length >= Number(a.count));
  await sleep(500);  // what hubctl echo printed last is on its way here too
  matchEcho(sub, lines());
  checkTimestamps(sub);

  // Publishing is off: refused, and the RSP never sees a command.
  const before = rsp.messages.length;
  const channel = session.client.advertise({ topic: a["rsp-command"], encoding: "cdr", schemaName: "hub_msgs/msg/RspCommand" });
  const writer = writerOf(a.msg);
  for (let i = 0; i < 5; i++) {
    session.client.sendMessage(channel, writer.writeMessage(LOCK));
    await sleep(100);
  }
  await session.until("the refusals", () => session.status("publishing is off") && session.status("message not written"));
  await sleep(1500);
  const after = rsp.messages.slice(before);
  if (after.length < 5) fail(`${after.length} RSP States in 2 s after the refused publish`);
  const commanded = after.find((m) => m.value.echo.action !== "" || m.value.fresh_msg);
  if (commanded) fail(`the RSP took a command although publishing is off: ${json(commanded.value.echo)}`);
  // A client message over the server's 64 KiB: the connection is closed (RFC 6455 1009), the others go on.
  const big = new Session(a.url);
  await big.until("serverInfo", () => big.serverInfo);
  big.ws.send("x".repeat(70 * 1024));
  const deadline = Date.now() + 30_000;
  while (!big.closed && Date.now() < deadline) await sleep(20);
  if (big.closeCode !== 1009) fail(`a 70 KiB message: close code ${big.closeCode}, not 1009 (message too big)`);
  const still = sub.messages.length;
  await session.until("messages after the big one", () => sub.messages.length > still);
  console.log(json({ topics, matched: lines().length, received: sub.messages.length, too_big_closed: big.closeCode,
                     refused: session.statuses.map((s) => s.message) }));
  session.close();
}

async function publish(a) {
  const session = await connected(a.url, true);
  await session.until(`${a["rsp-state"]} advertised`, () => session.channel(a["rsp-state"]));
  const rsp = session.subscribe(a["rsp-state"]);
  const writer = writerOf(a.msg);
  const channel = session.client.advertise({ topic: a["rsp-command"], encoding: "cdr", schemaName: "hub_msgs/msg/RspCommand" });
  const start = wallNs();
  const inForce = () => rsp.messages.some((m) => m.arrived > start && m.value.echo.action === "lock" && m.value.fresh_msg);
  const timer = setInterval(() => session.client.sendMessage(channel, writer.writeMessage(LOCK)), 100);
  try {
    await session.until("the RSP's State echoing the published lock, fresh", inForce);
  } finally {
    clearInterval(timer);
  }
  const tookMs = Number(wallNs() - start) / 1e6;
  session.client.advertise({ topic: a["rsp-state"], encoding: "cdr", schemaName: "hub_msgs/msg/RspCommand" });
  await session.until("the State topic refused", () => session.status("is not a command topic"));
  session.client.sendMessage(channel, new Uint8Array([0, 1, 0, 0, 200, 0, 0, 0, 1]));
  await session.until("bad bytes refused", () => session.status("does not deserialize"));
  const bad = session.statuses.find((s) => !/not a command topic|does not deserialize/.test(s.message));
  if (bad) fail(`an unexpected status: ${bad.message}`);
  console.log(json({ in_force_after_ms: Math.round(tookMs), refused: session.statuses.map((s) => s.message) }));
  session.close();
}

function checkLayout(session, file) {
  const layout = JSON.parse(fs.readFileSync(file, "utf-8"));
  const checked = [];
  const absent = new Set();
  for (const path of layoutPaths(layout)) {
    const channel = session.channel(path.topic);
    if (!channel) {
      absent.add(path.topic);
      continue;
    }
    const problem = resolvePath(definitionsOf(channel), path.fields);
    if (problem) fail(`${file}: ${path.text}: ${problem} in ${channel.schemaName}`);
    checked.push(path.text);
  }
  return { checked: checked.length, topics_not_running: [...absent].sort() };
}

async function lifecycle(a) {
  const [first, ...others] = a.topics.split(",");
  const session = await connected(a.url, false);
  await sleep(500);
  for (const topic of [first, ...others]) if (session.channel(topic)) fail(`${topic} is advertised before its hub started`);
  console.log("ready");
  await session.until(`${a.topics} advertised`, () => [first, ...others].every((t) => session.channel(t)));
  const ids = [first, ...others].map((t) => session.channel(t).id);
  const sub = session.subscribe(first);
  await session.until(`a message of ${first}`, () => sub.messages.length > 0);
  const layout = checkLayout(session, a.layout);
  console.log("advertised");
  await session.until(`${a.topics} unadvertised`, () => ids.every((id) => session.unadvertised.some((c) => c.id === id)));
  const count = sub.messages.length;
  await sleep(500);
  if (sub.messages.length !== count) fail(`${first}: messages after its unadvertise`);
  console.log("unadvertised");
  console.log(json({ advertised: a.topics, ids, messages: count, layout }));
  session.close();
}

run(async () => {
  const [mode, ...rest] = process.argv.slice(2);
  const a = args(rest, { url: "", topic: "", echo: "", count: "0", "rsp-state": "", "rsp-command": "", msg: "", topics: "", layout: "" });
  if (mode === "check") return check(a);
  if (mode === "publish") return publish(a);
  if (mode === "lifecycle") return lifecycle(a);
  return fail(`mode '${mode}': check, publish or lifecycle`);
});
