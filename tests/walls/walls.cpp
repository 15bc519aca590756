#include "walls.hpp"

#include <fstream>
#include <regex>
#include <set>

namespace twinslam::testing {
namespace fs = std::filesystem;
namespace {

bool is_source(const fs::path& p) {
  static const std::set<std::string> ext{".cpp", ".hpp", ".h", ".cc", ".cxx", ".hxx", ".ipp"};
  return ext.count(p.extension().string()) != 0;
}
bool is_cmake(const fs::path& p) { return p.filename() == "CMakeLists.txt" || p.extension() == ".cmake"; }

std::set<std::string> services_of(const fs::path& root) {
  std::set<std::string> out;
  if (!fs::is_directory(root / "services")) return out;
  for (const auto& e : fs::directory_iterator(root / "services")) {
    if (e.is_directory()) out.insert(e.path().filename().string());
  }
  return out;
}

// The service a path belongs to ("" outside services/).
std::string owner_service(const fs::path& rel) {
  auto it = rel.begin();
  if (it == rel.end() || *it != "services") return "";
  ++it;
  return it == rel.end() ? "" : it->string();
}

struct Line {
  fs::path rel;
  std::size_t number;
  std::string text;
};

void check_line(const Line& l, const std::set<std::string>& services, bool cmake, std::vector<std::string>& out) {
  const std::string owner = owner_service(l.rel);
  const bool in_common = *l.rel.begin() == "common";
  const auto report = [&](const std::string& rule) {
    out.push_back(l.rel.string() + ":" + std::to_string(l.number) + ": " + rule + ": " + l.text);
  };
  static const std::regex include_re(R"(^\s*#\s*include\s*[<"]twinslam/([a-z_]+)/)");
  static const std::regex target_re(R"(twinslam_([a-z]+)_(core|node)\b)");
  std::smatch m;
  std::vector<std::string> used;  // services this line refers to
  if (!cmake && std::regex_search(l.text, m, include_re)) used.push_back(m[1]);
  if (cmake) {
    for (auto it = std::sregex_iterator(l.text.begin(), l.text.end(), target_re); it != std::sregex_iterator(); ++it) {
      used.push_back((*it)[1]);
    }
  }
  for (const auto& s : used) {
    if (services.count(s) == 0) continue;
    if (in_common) report("common/ depends on service '" + s + "'");
    if (!owner.empty() && s != owner) report("service '" + owner + "' depends on service '" + s + "'");
  }
  if (cmake) return;
  const bool estimator_lib = l.rel.string().rfind("services/estimator/lib/", 0) == 0;
  static const std::regex pixels_re(R"(^\s*#\s*include\s*[<"](opencv2/|twinslam/camera/))");
  if (estimator_lib && std::regex_search(l.text, pixels_re)) report("the estimator library sees bearings, not pixels");
  static const std::regex pcl_re(R"(^\s*#\s*include\s*[<"]pcl/)");
  if (std::regex_search(l.text, pcl_re)) {
    const std::string r = l.rel.string();
    const bool allowed_place = r.rfind("services/registration/", 0) == 0 || r.rfind("common/twin/", 0) == 0 ||
                               r.rfind("tests/registration/", 0) == 0 || r.rfind("bench/registration/", 0) == 0 ||
                               r.rfind("tests/twin", 0) == 0 || r.rfind("bench/twin", 0) == 0;
    const bool header = r.find("/include/") != std::string::npos;
    if (!allowed_place || header) report("PCL only in registration/twin sources, never in a public header");
  }
}

}  // namespace

std::vector<std::string> wall_violations(const fs::path& root) {
  std::vector<std::string> out;
  const std::set<std::string> services = services_of(root);
  for (const char* top : {"common", "services", "tests", "bench", "tools"}) {
    if (!fs::is_directory(root / top)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / top)) {
      if (!e.is_regular_file() || !(is_source(e.path()) || is_cmake(e.path()))) continue;
      std::ifstream in(e.path());
      std::string text;
      const fs::path rel = fs::relative(e.path(), root);
      for (std::size_t n = 1; std::getline(in, text); ++n) check_line({rel, n, text}, services, is_cmake(e.path()), out);
    }
  }
  return out;
}

}  // namespace twinslam::testing
