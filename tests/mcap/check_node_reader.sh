#!/usr/bin/env bash
# check_node_reader.sh MCAP_SAMPLE_WRITER MCAP_READ_MJS — the CTest McapNode.OfficialReaderReadsTheSampleFile:
# writes the sample file with twinslam_mcap, reads it with the official reader (@mcap/core via mcap_read.mjs) and
# compares the per-topic counts, the schema names and the message count; the file must span several chunks.
# Fails (exit 1) when node or tests/node/node_modules is missing: scripts/setup.sh installs them (npm ci).
set -euo pipefail
writer=$1
script=$2
node_bin=${NODE:-node}
if ! command -v "$node_bin" >/dev/null; then
  echo "check_node_reader: '$node_bin' not found: Node.js is needed to run the official MCAP reader" >&2
  exit 1
fi
if [[ ! -d "$(dirname "$script")/node_modules/@mcap/core" ]]; then
  echo "check_node_reader: $(dirname "$script")/node_modules/@mcap/core missing: run scripts/setup.sh (npm ci)" >&2
  exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
expected=$("$writer" "$tmp/sample.mcap")
actual=$("$node_bin" "$script" "$tmp/sample.mcap")
echo "written: $expected"
echo "read:    $actual"
"$node_bin" -e '
  const [w, r] = process.argv.slice(1).map((s) => JSON.parse(s));
  const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
  const sorted = (o) => Object.fromEntries(Object.entries(o).sort());
  const problems = [];
  if (!same(sorted(w.channels), sorted(r.channels))) problems.push("per-topic counts differ");
  if (!same([...w.schemas].sort(), [...r.schemas].sort())) problems.push("schema names differ");
  if (w.messages !== r.messages) problems.push("message counts differ");
  if (!(r.chunks > 1)) problems.push(`only ${r.chunks} chunk(s)`);
  if (problems.length) { console.error(`check_node_reader: ${problems.join(", ")}`); process.exit(1); }
  console.log(`check_node_reader: ok: ${r.messages} messages, ${r.chunks} chunks`);
' "$expected" "$actual"
