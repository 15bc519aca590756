#pragma once
// The web view's files, served over plain HTTP on the bridge's WebSocket port (a browser opens http://HOST:PORT/ and
// the page connects back to ws://HOST:PORT/). Only files under the root, only GET and HEAD; no directory listing.
#include <filesystem>
#include <string>
#include <string_view>

namespace twinslam::bridge {

struct StaticReply {
  unsigned status = 200;       // 200, 400, 404 or 405
  std::string content_type;    // e.g. "text/javascript; charset=utf-8"
  std::string body;            // the file, or a one-line reason
};

// The reply to `method` `target` (a request target: path, optional "?query" ignored) for files under `root`:
// "/" is index.html; a ".." segment, a backslash or a NUL is 400; a file that is not there is 404, and a root without
// index.html is 404 saying the web view was not built (it is bundled with npm at build time).
StaticReply serve_static(const std::filesystem::path& root, std::string_view method, std::string_view target);

// The Content-Type of a file name by its extension ("application/octet-stream" when unknown).
std::string content_type_of(const std::filesystem::path& file);

}  // namespace twinslam::bridge
