// node tests/node/mcap_read.mjs FILE — reads FILE with the official MCAP reader (@mcap/core), as Foxglove does:
// McapIndexedReader (summary, Chunk Index and Message Index records; summary and chunk CRCs checked) over every
// message, then McapStreamReader (validateCrcs) over the whole file; both must agree with each other and with the
// Statistics record, and the Data End CRC must match the data section (node:zlib crc32; the readers don't check it).
// Prints {"channels": {topic: count}, "schemas": [names], "messages": N, "chunks": N}; exits 1 with a one-line
// error on the first problem.
import { readFileSync } from "node:fs";
import { crc32 } from "node:zlib";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { fileReadable } from "./file_readable.mjs";

function fail(message) {
  console.error(`mcap_read: ${message}`);
  process.exit(1);
}

async function readIndexed(file) {
  const reader = await McapIndexedReader.Initialize({ readable: fileReadable(file) });
  if (reader.chunkIndexes.length === 0) fail(`${file}: no Chunk Index records`);
  if (!reader.statistics) fail(`${file}: no Statistics record`);
  for (const opcode of [0x03, 0x04, 0x0b, 0x08]) {
    if (!reader.summaryOffsetsByOpcode.has(opcode)) fail(`${file}: no Summary Offset for opcode ${opcode}`);
  }
  const channels = {};
  let messages = 0;
  let last = 0n;
  for await (const m of reader.readMessages({ validateCrcs: true })) {
    const topic = reader.channelsById.get(m.channelId)?.topic ?? fail(`${file}: message on unknown channel`);
    if (m.logTime < last) fail(`${file}: indexed messages out of log-time order`);
    last = m.logTime;
    channels[topic] = (channels[topic] ?? 0) + 1;
    messages += 1;
  }
  return { reader, channels, messages };
}

function readStreamed(file, bytes) {
  const reader = new McapStreamReader({ validateCrcs: true });
  reader.append(bytes);
  const topics = new Map();
  const channels = {};
  let messages = 0;
  for (let record; (record = reader.nextRecord()); ) {
    if (record.type === "Channel") topics.set(record.id, record.topic);
    if (record.type === "Message") {
      const topic = topics.get(record.channelId);
      channels[topic] = (channels[topic] ?? 0) + 1;
      messages += 1;
    }
  }
  if (!reader.done()) fail(`${file}: the stream reader did not reach the footer`);
  return { channels, messages };
}

function sameCounts(a, b) {
  const keys = Object.keys(a).sort();
  return JSON.stringify(keys) === JSON.stringify(Object.keys(b).sort()) && keys.every((k) => a[k] === b[k]);
}

function checkStatistics(file, reader, indexed) {
  const stats = reader.statistics;
  if (stats.messageCount !== BigInt(indexed.messages)) fail(`${file}: Statistics.message_count ${stats.messageCount}`);
  if (stats.chunkCount !== reader.chunkIndexes.length) fail(`${file}: Statistics.chunk_count ${stats.chunkCount}`);
  for (const [id, count] of stats.channelMessageCounts) {
    const topic = reader.channelsById.get(id)?.topic;
    if (BigInt(indexed.channels[topic] ?? 0) !== count) fail(`${file}: Statistics count of ${topic}: ${count}`);
  }
}

async function main() {
  const file = process.argv[2] ?? fail("usage: node mcap_read.mjs FILE");
  const bytes = readFileSync(file);
  const indexed = await readIndexed(file);
  const { reader } = indexed;
  checkStatistics(file, reader, indexed);
  const crc = crc32(bytes.subarray(0, Number(reader.dataEndOffset)));
  if (reader.dataSectionCrc === undefined) fail(`${file}: Data End has no CRC`);
  if (crc !== reader.dataSectionCrc) {
    fail(`${file}: Data End CRC ${reader.dataSectionCrc}, data section ${crc}`);
  }
  const streamed = readStreamed(file, bytes);
  if (streamed.messages !== indexed.messages || !sameCounts(streamed.channels, indexed.channels)) {
    fail(`${file}: streamed ${JSON.stringify(streamed.channels)} but indexed ${JSON.stringify(indexed.channels)}`);
  }
  const schemas = [...reader.schemasById.values()].map((s) => s.name);
  const chunks = reader.chunkIndexes.length;
  console.log(JSON.stringify({ channels: indexed.channels, schemas, messages: indexed.messages, chunks }));
}

main().catch((error) => fail(String(error?.message ?? error).split("\n")[0]));
