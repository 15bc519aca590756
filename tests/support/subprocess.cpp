#include "subprocess.hpp"

#include "twinslam/process/domain_claim.hpp"

#include <csignal>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

namespace twinslam::test {

namespace {
pid_t spawn(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
            const std::string& out_file, const std::string& err_file) {
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    setpgid(0, 0);
    for (const auto& [k, v] : env) setenv(k.c_str(), v.c_str(), 1);
    const int out = open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = err_file == out_file ? out : open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  return pid;
}

std::string slurp(const std::string& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string temp_name(const char* tag) {
  static int counter = 0;
  return "/tmp/twinslam_test_" + std::to_string(getpid()) + "_" + std::to_string(counter++) + tag;
}

int wait_exit(pid_t pid, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  while (true) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (std::chrono::steady_clock::now() > deadline) return -2;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}
}  // namespace

ProcessOutput run_process(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
                          std::chrono::seconds timeout) {
  const std::string out = temp_name(".out"), err = temp_name(".err");
  const pid_t pid = spawn(argv, env, out, err);
  ProcessOutput result;
  result.exit_code = wait_exit(pid, timeout);
  if (result.exit_code == -2) {
    kill(-pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    result.exit_code = -1;
  }
  result.out = slurp(out);
  result.err = slurp(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return result;
}

Background::Background(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env)
    : log_(temp_name(".log")) {
  pid_ = spawn(argv, env, log_, log_);
}

Background::~Background() {
  if (!exited_) {
    kill(-pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  std::remove(log_.c_str());
}

void Background::signal(int sig) const { kill(pid_, sig); }

int Background::wait(std::chrono::milliseconds timeout) {
  const int code = wait_exit(pid_, timeout);
  if (code != -2) exited_ = true;
  return code == -2 ? -1 : code;
}

std::string Background::output() const { return slurp(log_); }

std::string bin(const std::string& name) { return std::string(TWINSLAM_BIN_DIR) + "/" + name; }

// Claimed on this host (domain_claim.hpp), so parallel test processes never share one.
int test_domain() { return process::claim_dds_domain(10, 80, static_cast<unsigned>(getpid())); }

int free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw std::runtime_error("free_tcp_port: no socket");
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
                  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0;
  ::close(fd);
  if (!ok) throw std::runtime_error("free_tcp_port: bind failed");
  return ntohs(a.sin_port);
}

}  // namespace twinslam::test
