// Copyright 2026 vehicle_sim contributors
//
// Licensed under the Apache License, Version 2.0 (the "License");
// you may not use this file except in compliance with the License.
// You may obtain a copy of the License at
//
//     http://www.apache.org/licenses/LICENSE-2.0
//
// Unless required by applicable law or agreed to in writing, software
// distributed under the License is distributed on an "AS IS" BASIS,
// WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
// See the License for the specific language governing permissions and
// limitations under the License.

// An independent reader of a vehicle_sim recording (test_record_node_reader.py): @mcap/core
// reads the file's summary through its chunk index, @foxglove/rosmsg parses each channel's
// ros2msg schema and @foxglove/rosmsg2-serialization decodes the last message of each topic.
// Prints one JSON object: the header, the statistics and, per topic, its type, encodings,
// count, QoS metadata and last message decoded.
//
// Usage: node record_node_reader.cjs NODE_MODULES_DIR FILE.mcap

const fs = require('fs');
const path = require('path');

const modules = process.argv[2];
const file = process.argv[3];
const need = (name) => require(path.join(modules, name));
const { McapIndexedReader } = need('@mcap/core');
const { parse } = need('@foxglove/rosmsg');
const { MessageReader } = need('@foxglove/rosmsg2-serialization');
const fzstd = need('fzstd');

async function main() {
  const handle = await fs.promises.open(file, 'r');
  const size = (await handle.stat()).size;
  const readable = {
    size: async () => BigInt(size),
    read: async (offset, length) => {
      const buffer = new Uint8Array(Number(length));
      await handle.read(buffer, 0, Number(length), Number(offset));
      return buffer;
    },
  };
  const reader = await McapIndexedReader.Initialize({
    readable,
    decompressHandlers: { zstd: (data, decompressedSize) => fzstd.decompress(data) },
  });
  const topics = {};
  const readers = new Map();
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    const definitions = parse(new TextDecoder().decode(schema.data), { ros2: true });
    readers.set(id, new MessageReader(definitions));
    topics[channel.topic] = {
      type: schema.name,
      schema_encoding: schema.encoding,
      message_encoding: channel.messageEncoding,
      count: Number(reader.statistics.channelMessageCounts.get(id) ?? 0n),
      qos: channel.metadata.get('offered_qos_profiles') ?? null,
      last: null,
    };
  }
  const last = new Map();
  for await (const message of reader.readMessages()) {
    last.set(message.channelId, message);
  }
  for (const [id, message] of last) {
    const topic = topics[reader.channelsById.get(id).topic];
    topic.last = readers.get(id).readMessage(message.data);
    topic.log_time = Number(message.logTime);
  }
  await handle.close();
  const out = {
    profile: reader.header.profile,
    library: reader.header.library,
    message_count: Number(reader.statistics.messageCount),
    chunks: reader.chunkIndexes.length,
    compression: [...new Set(reader.chunkIndexes.map((c) => c.compression))],
    topics,
  };
  const replacer = (key, value) => {
    if (typeof value === 'bigint') return Number(value);
    if (ArrayBuffer.isView(value)) return Array.from(value);
    return value;
  };
  process.stdout.write(JSON.stringify(out, replacer) + '\n');
}

main().catch((error) => {
  process.stderr.write(`${error.stack || error}\n`);
  process.exit(1);
});
