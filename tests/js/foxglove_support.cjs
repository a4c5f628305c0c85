// What the Foxglove live-view checks share: a client of the protocol's own package
// (@foxglove/ws-protocol's FoxgloveClient on the `ws` package: Node has no WebSocket of its own
// before 22) that keeps everything the server said, and readers made from each channel's own
// ros2msg schema (@foxglove/rosmsg, @foxglove/rosmsg2-serialization). Nothing of hubrt's.
"use strict";
const fs = require("fs");
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const WebSocket = require("ws");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader, MessageWriter } = require("@foxglove/rosmsg2-serialization");

class Failed extends Error {}
const fail = (message) => {
  throw new Failed(message);
};
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// This machine's wall clock in ns, finer than Date.now(): what a message's receive timestamp
// (hubctl's wall clock when it took the sample) is compared with.
const wallStart = BigInt(Date.now()) * 1_000_000n;
const monoStart = process.hrtime.bigint();
const wallNs = () => wallStart + (process.hrtime.bigint() - monoStart);

// Generous: hubctl and the hubs are sanitizer builds on a loaded 2-core machine.
const PATIENCE_MS = 60_000;

class Session {
  constructor(url) {
    this.ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
    this.client = new FoxgloveClient({ ws: this.ws });
    this.channels = new Map();  // advertised now, by id
    this.unadvertised = [];     // channels as they were when unadvertised
    this.statuses = [];
    this.errors = [];
    this.subscriptions = new Map();  // subscription id -> {channel, reader, messages: [{value, timestamp, arrived}]}
    this.closed = false;
    this.client.on("serverInfo", (info) => (this.serverInfo = info));
    this.client.on("advertise", (channels) => channels.forEach((c) => this.channels.set(c.id, c)));
    this.client.on("unadvertise", (ids) =>
      ids.forEach((id) => {
        this.unadvertised.push(this.channels.get(id) ?? { id });
        this.channels.delete(id);
      }));
    this.client.on("status", (status) => this.statuses.push(status));
    this.client.on("error", (error) => this.errors.push(error));
    this.client.on("close", (event) => {
      this.closed = true;
      this.closeCode = event?.code;
    });
    this.client.on("message", (m) => this.onMessage(m));
  }

  onMessage({ subscriptionId, timestamp, data }) {
    const arrived = wallNs();
    const sub = this.subscriptions.get(subscriptionId);
    if (!sub) return this.errors.push(new Error(`a message for subscription ${subscriptionId}, which is not ours`));
    if (this.keep === false) return sub.messages.push({ timestamp, arrived, bytes: data.byteLength });
    let value;
    try {
      value = sub.reader.readMessage(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    } catch (e) {
      return this.errors.push(new Error(`${sub.channel.topic}: a message does not decode as ${sub.channel.schemaName}: ${e.message}`));
    }
    return sub.messages.push({ value, timestamp, arrived });
  }

  async until(what, predicate, timeoutMs = PATIENCE_MS) {
    const deadline = Date.now() + timeoutMs;
    while (!predicate()) {
      if (this.errors.length > 0) fail(`${what}: ${this.errors[0].message}`);
      if (this.closed) fail(`${what}: the server closed the connection`);
      if (Date.now() > deadline) fail(`timed out (${timeoutMs / 1000} s) waiting for ${what}`);
      await sleep(20);
    }
  }

  channel(topic) {
    return [...this.channels.values()].find((c) => c.topic === topic);
  }

  // Subscribes to `topic`'s channel with a reader from its own schema; returns the subscription.
  subscribe(topic) {
    const channel = this.channel(topic) ?? fail(`${topic} is not advertised`);
    const id = this.client.subscribe(channel.id);
    const sub = { channel, reader: new MessageReader(definitionsOf(channel)), messages: [] };
    this.subscriptions.set(id, sub);
    return sub;
  }

  status(fragment) {
    return this.statuses.find((s) => s.message.includes(fragment));
  }

  close() {
    this.client.close();
  }
}

// Every channel hubctl advertises: CDR with its ros2msg schema, which the ecosystem's parser reads.
function definitionsOf(channel) {
  if (channel.encoding !== "cdr") fail(`${channel.topic}: encoding '${channel.encoding}', not cdr`);
  if (channel.schemaEncoding !== "ros2msg") fail(`${channel.topic}: schemaEncoding '${channel.schemaEncoding}', not ros2msg`);
  if (!/^[a-z_]+\/msg\/[A-Za-z0-9]+$/.test(channel.schemaName)) fail(`${channel.topic}: schemaName '${channel.schemaName}'`);
  try {
    const definitions = parse(channel.schema, { ros2: true });
    if (definitions.length === 0) fail(`${channel.topic}: an empty schema`);
    return definitions;
  } catch (e) {
    if (e instanceof Failed) throw e;
    return fail(`${channel.topic}: its schema does not parse as ros2msg: ${e.message}`);
  }
}

// A writer of a type from its .msg file (a command type without dependencies, as RspCommand).
function writerOf(msgFile) {
  return new MessageWriter(parse(fs.readFileSync(msgFile, "utf-8"), { ros2: true }));
}

function args(argv, defaults) {
  const out = { ...defaults };
  for (let i = 0; i < argv.length; i += 2) {
    const key = argv[i].replace(/^--/, "");
    if (!(key in defaults)) fail(`unknown option ${argv[i]}`);
    out[key] = argv[i + 1];
  }
  return out;
}

const json = (value) => JSON.stringify(value, (_, v) => (typeof v === "bigint" ? v.toString() : v));

function run(main) {
  main().then(
    () => process.exit(0),
    (e) => {
      console.error(`${e instanceof Failed ? "" : "error: "}${e.message}`);
      process.exit(1);
    },
  );
}

module.exports = { Session, Failed, fail, sleep, wallNs, definitionsOf, writerOf, args, json, run, PATIENCE_MS };
