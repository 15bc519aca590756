#pragma once
// Private: a pre-flight check of a Draco bitstream's element counts, before Draco sizes its buffers from them.
#include <cstddef>
#include <cstdint>
#include <string>

namespace twinslam::twin::detail {

// Draco allocates its point, face and vertex tables from the counts at the head of a bitstream before it reads one
// element: a corrupt count makes it allocate gigabytes (fuzzing found 3 GB from 187 bytes for a point cloud,
// 5.6 GB from 187 bytes for an edgebreaker mesh, 3.4 GB from 413 bytes of a pre-2.3 KD-tree point cloud, which
// is refused). This reads those counts (header, metadata, then the encoder's own
// fields, for every bitstream version Draco 1.5 decodes) and returns the problem when a count is more than the bytes
// can hold, or "" when the stream may go to Draco. Malformed heads are left for Draco to report in its own words.
std::string draco_count_problem(const std::uint8_t* data, std::size_t size);

}  // namespace twinslam::twin::detail
