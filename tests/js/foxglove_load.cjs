// Many Foxglove clients at once, one of them never reading: does it slow the others?
//
//   node foxglove_load.cjs --url WS --clients 19 --seconds 10
//
// Opens --clients clients of the protocol's own package and one more that subscribes like them and
// then stops reading (ws's pause(): its socket is not read, so the server's writes to it stall
// once the kernel's buffers are full). Every client subscribes to every channel. Prints the stalled
// client's local port ("stalled PORT", to find it in hubctl's log), then, after --seconds, one JSON
// line: per reading client the messages, the rate and the latency from hubctl's receive timestamp
// to here (p50, p99, max in ms), and this process's own load over the window (CPU seconds, its event
// loop's utilization), which tells a slow server from a starved measurer when the latency fails.
"use strict";
const { performance } = require("perf_hooks");
const { Session, fail, sleep, wallNs, args, json, run } = require("./foxglove_support.cjs");

function percentile(sorted, p) {
  if (sorted.length === 0) return NaN;
  return sorted[Math.min(sorted.length - 1, Math.floor((p / 100) * sorted.length))];
}

async function subscribedToAll(url) {
  const session = new Session(url);
  session.keep = false;  // count and time the messages, do not decode them (the check does)
  await session.until("serverInfo and the channels", () => session.serverInfo && session.channels.size > 0);
  for (const channel of session.channels.values()) session.subscribe(channel.topic);
  return session;
}

run(async () => {
  const a = args(process.argv.slice(2), { url: "", clients: "19", seconds: "10" });
  const readers = await Promise.all(Array.from({ length: Number(a.clients) }, () => subscribedToAll(a.url)));
  const stalled = await subscribedToAll(a.url);
  stalled.ws.pause();
  console.log(`stalled ${stalled.ws._socket.localPort}`);
  const from = wallNs();
  const cpuFrom = process.cpuUsage();
  const loopFrom = performance.eventLoopUtilization();
  await sleep(Number(a.seconds) * 1000);
  const seconds = Number(wallNs() - from) / 1e9;
  const cpu = process.cpuUsage(cpuFrom);
  const node = {
    cpu_s: (cpu.user + cpu.system) / 1e6,
    event_loop_utilization: performance.eventLoopUtilization(loopFrom).utilization,
  };
  const clients = readers.map((session) => {
    const messages = [...session.subscriptions.values()].flatMap((s) => s.messages).filter((m) => m.arrived >= from);
    const latencies = messages.map((m) => Number(m.arrived - m.timestamp) / 1e6).sort((x, y) => x - y);
    if (session.errors.length > 0) fail(`a reading client: ${session.errors[0].message}`);
    if (session.closed) fail("a reading client was disconnected");
    return {
      messages: messages.length,
      rate_hz: Math.round(messages.length / seconds),
      latency_ms: { p50: percentile(latencies, 50), p99: percentile(latencies, 99), max: latencies.at(-1) },
      channels: session.subscriptions.size,
    };
  });
  console.log(json({ seconds, clients, node }));
  for (const session of readers) session.close();
  stalled.ws.terminate();
});
