// The IReadable of @mcap/core's McapIndexedReader over a file: random access by (offset, length) as Foxglove reads a
// local file. Loops because readSync may return less than asked.
import { openSync, readSync, fstatSync } from "node:fs";

export function fileReadable(path) {
  const fd = openSync(path, "r");
  const size = BigInt(fstatSync(fd).size);
  return {
    size: async () => size,
    read: async (offset, length) => {
      const buf = new Uint8Array(Number(length));
      for (let done = 0; done < buf.length; ) {
        const n = readSync(fd, buf, done, buf.length - done, Number(offset) + done);
        if (n === 0) throw new Error(`${path}: short read at ${offset}`);
        done += n;
      }
      return buf;
    },
  };
}
