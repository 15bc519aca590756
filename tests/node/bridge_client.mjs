// node tests/node/bridge_client.mjs URL SECONDS — a test of node's test runner (node:test): a Foxglove WebSocket client (@foxglove/ws-protocol over `ws`, as
// Foxglove connects) against twinslam-bridge: retries until the bridge listens, subscribes to every advertised
// channel (also those advertised later) and decodes every message with the schema its channel advertised: CDR with
// the OMG IDL (@foxglove/omgidl-*), JSON of Foxglove's well-known schemas validated against Foxglove's own JSON
// Schemas (@foxglove/schemas, with ajv), other JSON against the schema advertised. Ends when the bridge closes the
// connection (the run ended) or after SECONDS; prints one JSON object {server, channels, counts, vehicles, schemas:
// {topic: schemaName}, samples: {topic: first message, JSON channels}}; the test fails (exit 1) with a one-line error
// if a message does not decode or validate, or nothing was advertised.
import test from "node:test";
import wsProtocol from "@foxglove/ws-protocol";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import { WebSocket } from "ws";
import { jsonDecoder, summary } from "./foxglove_json.mjs";

const { FoxgloveClient } = wsProtocol;

// The first failure ends the session (the socket is closed) and fails the test; handlers report through guard().
let failure = null;
let ws = null;
function fail(message) {
  throw new Error(`bridge_client: ${message}`);
}
function guard(handler) {
  return (...args) => {
    try {
      handler(...args);
    } catch (e) {
      failure ??= e;
      ws?.close();
    }
  };
}

const [url, secondsText] = process.argv.slice(2);
const deadline = Date.now() + Number(secondsText) * 1000;

const result = { server: null, channels: 0, counts: {}, vehicles: [], schemas: {}, samples: {} };
const vehicles = new Set();

// The client's handlers are attached before the socket opens: the bridge sends serverInfo and advertise at once.
function attach(client) {
  const bySubscription = new Map();
  client.on("serverInfo", (info) => { result.server = info.name; });
  client.on("advertise", guard((channels) => {
    for (const c of channels) {
      let decode;
      if (c.encoding === "cdr" && c.schemaEncoding === "omgidl") {
        const reader = new MessageReader(c.schemaName, parseIDL(c.schema));
        decode = (bytes) => reader.readMessage(bytes);
      } else if (c.encoding === "json" && c.schemaEncoding === "jsonschema") {
        decode = jsonDecoder(c.topic, c.schemaName, c.schema, fail);
      } else {
        fail(`${c.topic}: ${c.encoding} / ${c.schemaEncoding}`);
      }
      bySubscription.set(client.subscribe(c.id), { topic: c.topic, type: c.schemaName, decode, json: c.encoding === "json" });
      result.schemas[c.topic] = c.schemaName;
      result.channels++;
    }
  }));
  client.on("message", guard(({ subscriptionId, data }) => {
    const s = bySubscription.get(subscriptionId) ?? fail(`message for unknown subscription ${subscriptionId}`);
    let decoded;
    try {
      decoded = s.decode(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    } catch (e) {
      fail(`${s.topic}: a message does not decode as ${s.type}: ${e.message}`);
    }
    if (typeof decoded.vehicle_id === "string" && decoded.vehicle_id !== "") vehicles.add(decoded.vehicle_id);
    result.counts[s.topic] = (result.counts[s.topic] ?? 0) + 1;
    if (s.json && !(s.topic in result.samples)) result.samples[s.topic] = summary(decoded);
  }));
  client.on("status", guard((s) => { if (s.level >= 2) fail(`server status: ${s.message}`); }));
}

function connect() {
  return new Promise((resolve) => {
    const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
    ws.once("error", () => resolve(null));  // not listening yet
    ws.once("open", () => resolve(ws));
    attach(new FoxgloveClient({ ws }));
  });
}

test("every advertised channel of the bridge decodes with its schema", async () => {
  if (!url || !secondsText) fail("usage: node bridge_client.mjs URL SECONDS");
  while (!(ws = await connect())) {
    if (Date.now() > deadline) fail(`${url}: no bridge listening`);
    await new Promise((r) => setTimeout(r, 200));
  }
  await new Promise((resolve) => {
    ws.once("close", resolve);
    setTimeout(resolve, Math.max(0, deadline - Date.now())).unref();
  });
  if (failure) throw failure;
  if (result.channels === 0) fail(`${url}: no channel advertised`);
  result.vehicles = [...vehicles].sort();
  console.log(JSON.stringify(result));
  ws.terminate();
});
