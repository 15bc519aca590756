// node tests/node/run_mcap.mjs RUN [FILE] — a test of node's test runner (node:test) that checks RUN/run.mcap (written by `twinslam run --mcap`; or FILE, e.g. a
// `twinslam record` of the same run) with the official MCAP
// reader (@mcap/core, indexed and streamed, CRCs validated) and decodes every message with the schema the file
// advertises (CDR: @foxglove/omgidl-parser + omgidl-serialization, as Foxglove does; JSON of Foxglove's well-known
// schemas: validated against @foxglove/schemas, foxglove_json.mjs): every channel present, message counts equal to
// the run's (run.json `messages`, which the run's reliable monitor counted), a schema for each.
// Prints one JSON object; the test fails (exit 1) with a one-line error on the first problem.
import { readFileSync } from "node:fs";
import test from "node:test";
import { join } from "node:path";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { fileReadable } from "./file_readable.mjs";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import { jsonDecoder } from "./foxglove_json.mjs";

function fail(message) {
  throw new Error(`run_mcap: ${message}`);
}

// --at-least: another recorder of the run (`twinslam record`) may see more than the run's own monitor, which ingest
// does not wait for by identity (it counts matched readers): its counts must be at least the run's.
const atLeast = process.argv.includes("--at-least");
const args = process.argv.slice(2).filter((a) => a !== "--at-least");
test("run.mcap reads back with the official MCAP readers, every message decoding with its schema", async () => {
  const run = args[0] ?? fail("usage: node run_mcap.mjs RUN [FILE] [--at-least]");
  const file = args[1] ?? join(run, "run.mcap");
  const runJson = JSON.parse(readFileSync(join(run, "run.json"), "utf8"));

  const reader = await McapIndexedReader.Initialize({ readable: fileReadable(file) });
  if (reader.chunkIndexes.length === 0) fail(`${file}: no chunk index`);
  if (!reader.statistics) fail(`${file}: no statistics record`);
  const decoders = new Map();
  const schemas = {};
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId) ?? fail(`${file}: channel ${channel.topic} has no schema`);
    const text = new TextDecoder().decode(schema.data);
    let decode;
    if (schema.encoding === "omgidl" && channel.messageEncoding === "cdr") {
      const reader = new MessageReader(schema.name, parseIDL(text));
      decode = (bytes) => reader.readMessage(bytes);
    } else if (schema.encoding === "jsonschema" && channel.messageEncoding === "json") {
      decode = jsonDecoder(channel.topic, schema.name, text, fail);
    } else {
      fail(`${file}: ${channel.topic}: schema ${schema.encoding} / messages ${channel.messageEncoding}`);
    }
    decoders.set(id, { topic: channel.topic, type: schema.name, decode });
    schemas[channel.topic] = schema.name;
  }

  const counts = {};
  const vehicles = new Set();
  let messages = 0;
  for await (const m of reader.readMessages()) {
    const d = decoders.get(m.channelId) ?? fail(`${file}: message on unknown channel ${m.channelId}`);
    let decoded;
    try {
      decoded = d.decode(m.data);
    } catch (e) {
      fail(`${file}: ${d.topic} message ${m.sequence} does not decode as ${d.type}: ${e.message}`);
    }
    if (typeof decoded !== "object" || decoded === null) fail(`${file}: ${d.topic}: decoded to ${decoded}`);
    if (typeof decoded.vehicle_id === "string" && decoded.vehicle_id !== "") vehicles.add(decoded.vehicle_id);
    counts[d.topic] = (counts[d.topic] ?? 0) + 1;
    messages++;
  }
  if (BigInt(messages) !== reader.statistics.messageCount) {
    fail(`${file}: ${messages} messages read, statistics say ${reader.statistics.messageCount}`);
  }
  for (const [topic, n] of Object.entries(runJson.messages)) {
    const got = counts[topic] ?? 0;
    if (atLeast ? got < n : got !== n) fail(`${file}: ${topic}: ${got} messages, run.json says ${n}`);
  }

  // The same file streamed front to back, CRCs checked: what a reader without the index (or a truncated file) sees.
  const stream = new McapStreamReader({ validateCrcs: true });
  stream.append(readFileSync(file));
  let streamed = 0;
  for (let record; (record = stream.nextRecord()); ) {
    if (record.type === "Message") streamed++;
  }
  if (!stream.done()) fail(`${file}: the stream reader did not reach the footer`);
  if (streamed !== messages) fail(`${file}: streamed ${streamed} messages, indexed ${messages}`);

  console.log(JSON.stringify({ file, channels: decoders.size, messages, counts, schemas, vehicles: [...vehicles].sort(),
                               chunks: reader.chunkIndexes.length }));
});
