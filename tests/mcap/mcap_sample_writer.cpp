// mcap_sample_writer FILE: writes a small MCAP file with twinslam_mcap for the official reader's test
// (check_node_reader.sh): 2 schemas (omgidl with CDR messages, jsonschema with JSON messages), 3 channels,
// 1000 messages in chunks of 4 KiB. Messages are valid for their schemas so Foxglove can decode them too.
// Prints {"channels": {topic: count}, "schemas": [names], "messages": N} on stdout.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "twinslam/mcap/writer.hpp"

namespace {

// CDR of `struct A { long x; }`: the little-endian encapsulation header (CDR_LE = 0x0001), then the int32.
std::vector<std::uint8_t> cdr_a(std::int32_t x) {
  std::vector<std::uint8_t> b{0x00, 0x01, 0x00, 0x00};
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(static_cast<std::uint32_t>(x) >> (8 * i)));
  return b;
}

std::vector<std::uint8_t> json_status(std::uint32_t i) {
  const std::string s = "{\"ok\":" + std::string(i % 2 == 0 ? "true" : "false") + ",\"n\":" + std::to_string(i) + "}";
  return {s.begin(), s.end()};
}

void print_counts(const std::map<std::string, int>& counts, int total) {
  std::printf("{\"channels\": {");
  const char* sep = "";
  for (const auto& [topic, n] : counts) {
    std::printf("%s\"%s\": %d", sep, topic.c_str(), n);
    sep = ", ";
  }
  std::printf("}, \"schemas\": [\"m::A\", \"Status\"], \"messages\": %d}\n", total);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mcap_sample_writer FILE.mcap\n");
    return 2;
  }
  try {
    twinslam::mcap::WriterOptions options;
    options.chunk_size = 4096;  // several chunks for 1000 small messages
    twinslam::mcap::Writer w(argv[1], options);
    const auto idl = w.add_schema("m::A", "omgidl", "module m { struct A { long x; }; };");
    const auto json = w.add_schema(
        "Status", "jsonschema", R"({"type":"object","properties":{"ok":{"type":"boolean"},"n":{"type":"integer"}}})");
    const std::uint16_t channels[3] = {w.add_channel(idl, "/a", "cdr"), w.add_channel(idl, "/c", "cdr"),
                                       w.add_channel(json, "/status", "json", {{"source", "mcap_sample_writer"}})};
    const char* topics[3] = {"/a", "/c", "/status"};
    std::map<std::string, int> counts;
    for (std::uint32_t i = 0; i < 1000; ++i) {
      const int k = i % 4 < 2 ? 0 : (i % 4 == 2 ? 1 : 2);  // /a 500, /c 250, /status 250
      const auto data = k == 2 ? json_status(i) : cdr_a(static_cast<std::int32_t>(i));
      const std::uint64_t t = 1'700'000'000'000'000'000ull + i * 10'000'000ull;  // 100 Hz
      w.write(channels[k], i, t, t, data.data(), data.size());
      ++counts[topics[k]];
    }
    w.close();
    print_counts(counts, 1000);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mcap_sample_writer: %s\n", e.what());
    return 1;
  }
  return 0;
}
