#include "twinslam/bridge/static_files.hpp"

#include <fstream>
#include <map>
#include <sstream>

namespace twinslam::bridge {
namespace {

StaticReply text_reply(unsigned status, std::string body) {
  return {status, "text/plain; charset=utf-8", std::move(body) + "\n"};
}

// The path part of a request target, or nothing when it could leave the root: a traversal must never be served.
bool safe_path(std::string_view path) {
  if (path.empty() || path.front() != '/') return false;
  if (path.find('\\') != std::string_view::npos || path.find('\0') != std::string_view::npos) return false;
  std::size_t start = 1;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    if (path.substr(start, end - start) == "..") return false;
    start = end + 1;
  }
  return true;
}

}  // namespace

std::string content_type_of(const std::filesystem::path& file) {
  static const std::map<std::string, std::string> types{
      {".html", "text/html; charset=utf-8"}, {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"}, {".css", "text/css; charset=utf-8"},
      {".json", "application/json"}, {".map", "application/json"}, {".png", "image/png"},
      {".svg", "image/svg+xml"}, {".ico", "image/x-icon"}, {".wasm", "application/wasm"}};
  const auto it = types.find(file.extension().string());
  return it == types.end() ? "application/octet-stream" : it->second;
}

StaticReply serve_static(const std::filesystem::path& root, std::string_view method, std::string_view target) {
  if (method != "GET" && method != "HEAD") return text_reply(405, "only GET and HEAD are served here");
  std::string_view path = target.substr(0, target.find_first_of("?#"));
  if (!safe_path(path)) return text_reply(400, "bad path");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(root / "index.html", ec)) {
    return text_reply(404, "twinslam web view not built: " + (root / "index.html").string() +
                               " is missing (the build bundles it with npm: run scripts/setup.sh with node and npm "
                               "installed, or give the bridge --web-root DIR)");
  }
  const std::filesystem::path file = root / (path == "/" ? std::string("index.html") : std::string(path.substr(1)));
  if (!std::filesystem::is_regular_file(file, ec)) return text_reply(404, "not found: " + std::string(path));
  std::ifstream in(file, std::ios::binary);
  if (!in) return text_reply(404, "cannot read: " + std::string(path));
  std::ostringstream body;
  body << in.rdbuf();
  return {200, content_type_of(file), std::move(body).str()};
}

}  // namespace twinslam::bridge
