#include "twinslam/process/supervisor.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iostream>
#include <mutex>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "twinslam/core/error.hpp"
#include "twinslam/core/shutdown.hpp"

extern char** environ;

namespace twinslam::process {
namespace fs = std::filesystem;

std::string describe_end(const std::optional<int>& exit_code, const std::optional<int>& signal) {
  return exit_code ? "exit code " + std::to_string(*exit_code) : "signal " + std::to_string(signal.value_or(0));
}

fs::path resolve_executable(const std::string& exec) {
  if (exec.find('/') != std::string::npos) return fs::exists(exec) ? fs::absolute(exec) : fs::path();
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && fs::exists(self.parent_path() / exec)) return self.parent_path() / exec;
  const char* path = std::getenv("PATH");
  std::string dirs = path == nullptr ? "" : path;
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const auto end = dirs.find(':', start);
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / exec;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return {};
}

using Clock = std::chrono::steady_clock;

struct Child {
  ProcessSpec spec;
  pid_t pid = -1;
  int out_fd = -1, err_fd = -1;
  std::string out_buf, err_buf;
  std::unique_ptr<std::ofstream> log;
  ChildResult result;
  int restarts = 0;                             // restarts of this service before this process
  bool replaced = false;                        // a restart took its place
  std::optional<Clock::time_point> restart_at;  // failed, restart due then
  bool done() const { return result.exit_code || result.signal; }
};

struct Supervisor::Impl {
  OutputPolicy output;
  std::vector<std::unique_ptr<Child>> children;
  std::vector<RestartEvent> restarts;
  Clock::time_point created = Clock::now();
  mutable std::mutex mutex;
  std::atomic<bool> stop_pump{false};
  std::thread pump;

  // Forwards complete lines from every child pipe, prefixed with the child's name.
  void pump_loop() {
    while (!stop_pump.load()) {
      std::vector<pollfd> fds;
      std::vector<std::pair<Child*, bool>> owners;
      {
        std::lock_guard lock(mutex);
        for (auto& c : children) {
          if (c->out_fd >= 0) { fds.push_back({c->out_fd, POLLIN, 0}); owners.emplace_back(c.get(), false); }
          if (c->err_fd >= 0) { fds.push_back({c->err_fd, POLLIN, 0}); owners.emplace_back(c.get(), true); }
        }
      }
      if (fds.empty()) { std::this_thread::sleep_for(std::chrono::milliseconds(10)); continue; }
      if (poll(fds.data(), fds.size(), 20) <= 0) continue;
      for (std::size_t i = 0; i < fds.size(); ++i) {
        if ((fds[i].revents & (POLLIN | POLLHUP | POLLERR)) == 0) continue;
        drain(*owners[i].first, owners[i].second);
      }
    }
  }

  void drain(Child& c, bool is_err) {
    char buf[4096];
    int& fd = is_err ? c.err_fd : c.out_fd;
    std::string& acc = is_err ? c.err_buf : c.out_buf;
    const ssize_t n = read(fd, buf, sizeof(buf));
    if (n <= 0) {
      if (!acc.empty()) emit(c, acc, is_err);
      acc.clear();
      std::lock_guard lock(mutex);
      close(fd);
      fd = -1;
      return;
    }
    acc.append(buf, static_cast<std::size_t>(n));
    std::size_t pos;
    while ((pos = acc.find('\n')) != std::string::npos) {
      emit(c, acc.substr(0, pos), is_err);
      acc.erase(0, pos + 1);
    }
  }

  void emit(Child& c, const std::string& line, bool is_err) {
    if (c.log) {
      *c.log << line << '\n';
      c.log->flush();
      return;
    }
    static std::mutex console;
    std::lock_guard lock(console);
    (is_err ? std::cerr : std::cout) << c.spec.name << " | " << line << std::endl;
  }

  // Starts the failed services whose restart is due (ProcessSpec::restart_on_failure).
  void restart_due();

  void reap() {
    std::lock_guard lock(mutex);
    for (auto& c : children) {
      if (c->done()) continue;
      int status = 0;
      const pid_t r = waitpid(c->pid, &status, WNOHANG);
      if (r != c->pid) continue;
      if (WIFEXITED(status)) c->result.exit_code = WEXITSTATUS(status);
      if (WIFSIGNALED(status)) c->result.signal = WTERMSIG(status);
    }
  }
};

Supervisor::Supervisor(OutputPolicy output) : impl_(std::make_unique<Impl>()) {
  impl_->output = std::move(output);
  if (!impl_->output.log_dir.empty()) fs::create_directories(impl_->output.log_dir);
  impl_->pump = std::thread([this] { impl_->pump_loop(); });
}

Supervisor::~Supervisor() {
  stop_all();
  // Let the pump flush the last lines the children wrote before they exited.
  for (int i = 0; i < 50; ++i) {
    bool open = false;
    {
      std::lock_guard lock(impl_->mutex);
      for (auto& c : impl_->children) open = open || c->out_fd >= 0 || c->err_fd >= 0;
    }
    if (!open) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  impl_->stop_pump.store(true);
  impl_->pump.join();
}

namespace {

// fork + exec of one service with its output piped to the supervisor (the pump reads it).
std::unique_ptr<Child> spawn(const ProcessSpec& spec, const OutputPolicy& output, bool append_log) {
  const fs::path exe = resolve_executable(spec.exec);
  if (exe.empty()) throw UsageError("service '" + spec.name + "': executable '" + spec.exec + "' not found");
  int out[2], err[2];
  if (pipe2(out, O_CLOEXEC) != 0 || pipe2(err, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  std::vector<std::string> argv_s{exe.string()};
  argv_s.insert(argv_s.end(), spec.args.begin(), spec.args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::map<std::string, std::string> env_map;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string kv(*e);
    const auto eq = kv.find('=');
    if (eq != std::string::npos) env_map[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  for (const auto& [k, v] : spec.env) env_map[k] = v;
  std::vector<std::string> env_s;
  for (const auto& [k, v] : env_map) env_s.push_back(k + "=" + v);
  std::vector<char*> envp;
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);

  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    setpgid(0, 0);  // own process group: terminal Ctrl-C goes to the supervisor only
    // If the supervisor dies without stopping us (SIGKILL, crash), stop cleanly instead of living on as an orphan.
    prctl(PR_SET_PDEATHSIG, SIGINT);
    if (getppid() != parent) _exit(127);  // the supervisor died before prctl took effect
    dup2(out[1], STDOUT_FILENO);
    dup2(err[1], STDERR_FILENO);
    if (!spec.cwd.empty() && chdir(spec.cwd.c_str()) != 0) _exit(127);
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
  setpgid(pid, pid);
  close(out[1]);
  close(err[1]);
  auto child = std::make_unique<Child>();
  child->spec = spec;
  child->pid = pid;
  child->out_fd = out[0];
  child->err_fd = err[0];
  child->result.name = spec.name;
  child->result.pid = pid;
  if (!output.log_dir.empty()) {
    // A restarted service appends to its log: what it wrote before the failure is the evidence.
    child->log = std::make_unique<std::ofstream>(output.log_dir / (spec.name + ".log"),
                                                 append_log ? std::ios::app : std::ios::trunc);
  }
  return child;
}

// A failure worth a restart: not a clean exit, not exit code 2 (the service refused its input or arguments, which a
// restart would only refuse again: kExitBadInput of main_guard.hpp), and restarts left.
bool restartable(const Child& c) {
  return c.done() && c.spec.restart_on_failure && !c.result.ok() && c.result.exit_code != 2 &&
         c.restarts < c.spec.max_restarts;
}

}  // namespace

void Supervisor::start(const ProcessSpec& spec) {
  auto child = spawn(spec, impl_->output, false);
  std::lock_guard lock(impl_->mutex);
  impl_->children.push_back(std::move(child));
}

void Supervisor::Impl::restart_due() {
  // Under the lock: which failed services are due; the fork happens outside it (the pump takes the lock).
  std::vector<Child*> due;
  {
    std::lock_guard lock(mutex);
    const auto now = Clock::now();
    for (auto& c : children) {
      if (c->replaced || !restartable(*c)) continue;
      if (!c->restart_at) {
        const double delay_s = c->spec.restart_delay_s * static_cast<double>(1 << std::min(c->restarts, 4));
        c->restart_at = now + std::chrono::microseconds(static_cast<long long>(delay_s * 1e6));
        std::cerr << "supervisor: " << c->spec.name << " (pid " << c->pid << ") ended with "
                  << describe_end(c->result.exit_code, c->result.signal)
                  << "; restarting in " << delay_s << " s (restart " << c->restarts + 1 << " of at most "
                  << c->spec.max_restarts << ")" << std::endl;
      }
      if (now >= *c->restart_at) due.push_back(c.get());
    }
  }
  for (Child* old : due) {
    auto child = spawn(old->spec, output, true);
    child->restarts = old->restarts + 1;
    RestartEvent e{old->spec.name, std::chrono::duration<double>(Clock::now() - created).count(), child->restarts,
                   old->result.exit_code, old->result.signal, old->pid, child->pid};
    std::lock_guard lock(mutex);
    old->replaced = true;
    restarts.push_back(e);
    children.push_back(std::move(child));
  }
}

Supervisor::Event Supervisor::watch(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (shutdown_requested()) return Event::Shutdown;
    impl_->reap();
    impl_->restart_due();
    {
      std::lock_guard lock(impl_->mutex);
      bool all = !impl_->children.empty();
      for (auto& c : impl_->children) {
        if (c->replaced) continue;
        // A failed service with restarts left is waiting for its restart: neither failed nor exited yet.
        const bool done = c->done() && !restartable(*c);
        all = all && done;
        if (done && !c->result.ok()) return Event::ChildFailed;
        if (done && c->spec.required) return Event::RequiredExited;
      }
      if (all) return Event::AllExited;
    }
    if (std::chrono::steady_clock::now() > deadline) return Event::Timeout;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

std::optional<ChildResult> Supervisor::exited(const std::string& name) {
  impl_->reap();
  std::lock_guard lock(impl_->mutex);
  for (auto& c : impl_->children) {
    if (c->spec.name == name && !c->replaced && c->done()) return c->result;
  }
  return std::nullopt;
}

std::vector<ChildResult> Supervisor::stop_all(std::chrono::milliseconds grace) {
  impl_->reap();
  {
    std::lock_guard lock(impl_->mutex);
    for (auto& c : impl_->children) {
      if (!c->result.exit_code && !c->result.signal) kill(c->pid, SIGINT);
    }
  }
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (std::chrono::steady_clock::now() < deadline) {
    impl_->reap();
    bool running = false;
    {
      std::lock_guard lock(impl_->mutex);
      for (auto& c : impl_->children) running = running || !(c->result.exit_code || c->result.signal);
    }
    if (!running) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  {
    std::lock_guard lock(impl_->mutex);
    for (auto& c : impl_->children) {
      if (!c->result.exit_code && !c->result.signal) {
        kill(c->pid, SIGKILL);
        int status = 0;
        waitpid(c->pid, &status, 0);
        c->result.signal = SIGKILL;
      }
    }
  }
  return results();
}

std::vector<ChildResult> Supervisor::results() const {
  std::lock_guard lock(impl_->mutex);
  std::vector<ChildResult> out;
  for (auto& c : impl_->children) {
    if (!c->replaced) out.push_back(c->result);
  }
  return out;
}

std::vector<RestartEvent> Supervisor::restarts() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->restarts;
}

}  // namespace twinslam::process
