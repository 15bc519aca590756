// PLY writer: doubles for positions (metres in W need more than float's 7 digits far from the origin), floats for
// unit normals, `list uchar int vertex_indices` for triangles.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/ply.hpp"

namespace twinslam::twin {
namespace {

class Writer {
 public:
  Writer(std::ostream& out, PlyFormat format) : out_(out), format_(format) {
    out_ << std::setprecision(std::numeric_limits<double>::max_digits10);
  }
  template <typename T>
  void put(T value, bool last = false) {
    if (format_ == PlyFormat::kAscii) {
      if constexpr (sizeof(T) == 1) out_ << static_cast<int>(value);
      else out_ << value;
      out_ << (last ? '\n' : ' ');
      return;
    }
    unsigned char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    const bool swap = (format_ == PlyFormat::kBinaryBigEndian) == (std::endian::native == std::endian::little);
    if (swap) std::reverse(b, b + sizeof(T));
    out_.write(reinterpret_cast<const char*>(b), sizeof(T));
  }

 private:
  std::ostream& out_;
  PlyFormat format_;
};

}  // namespace

void write_ply(const std::string& path, const Mesh& mesh, PlyFormat format, const std::optional<GeoOrigin>& origin) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(where(path, 0, "cannot open PLY file for writing"));
  const bool normals = !mesh.n_W.empty() && mesh.n_W.size() == mesh.p_W.size();
  std::ostringstream h;
  h << std::setprecision(std::numeric_limits<double>::max_digits10);
  h << "ply\nformat "
    << (format == PlyFormat::kAscii ? "ascii" : format == PlyFormat::kBinaryLittleEndian ? "binary_little_endian"
                                                                                          : "binary_big_endian")
    << " 1.0\n";
  if (origin) h << "comment twinslam_origin " << origin->lat_deg << ' ' << origin->lon_deg << ' ' << origin->alt_m << '\n';
  h << "element vertex " << mesh.p_W.size() << "\nproperty double x\nproperty double y\nproperty double z\n";
  if (normals) h << "property float nx\nproperty float ny\nproperty float nz\n";
  h << "element face " << mesh.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  out << h.str();
  Writer w(out, format);
  for (std::size_t i = 0; i < mesh.p_W.size(); ++i) {
    const Eigen::Vector3d& p = mesh.p_W[i];
    w.put(p.x());
    w.put(p.y());
    w.put(p.z(), !normals);
    if (normals) {
      w.put(static_cast<float>(mesh.n_W[i].x()));
      w.put(static_cast<float>(mesh.n_W[i].y()));
      w.put(static_cast<float>(mesh.n_W[i].z()), true);
    }
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    w.put(static_cast<std::uint8_t>(3));
    w.put(static_cast<std::int32_t>(t[0]));
    w.put(static_cast<std::int32_t>(t[1]));
    w.put(static_cast<std::int32_t>(t[2]), true);
  }
  if (!out) throw InputError(where(path, 0, "writing the PLY file failed"));
}

}  // namespace twinslam::twin
