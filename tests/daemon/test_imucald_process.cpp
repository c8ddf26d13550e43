// imucald as a process: it tells systemd it is ready (sd_notify on NOTIFY_SOCKET) and ends cleanly, exit
// status 0, on SIGTERM; a state file it cannot trust does not stop it. Uses memq:// so nothing touches a
// network.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scratch_dir.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;

// imucald with NOTIFY_SOCKET set to a socket of the test's; its log goes to a file.
class NotifiedImucald {
 public:
  NotifiedImucald(const imucal::testing::ScratchDir& dir, std::vector<std::string> args)
      // sun_path holds 108 bytes, less than a scratch directory's path may take.
      : sock_path_("/tmp/imucald_notify_" + std::to_string(::getpid()) + "_" + std::to_string(++count_)),
        log_path_(dir / "imucald.log") {
    ::unlink(sock_path_.c_str());
    sock_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, sock_path_.c_str(), sizeof addr.sun_path - 1);
    bound_ = sock_ >= 0 && ::bind(sock_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    timeval tv{20, 0};
    ::setsockopt(sock_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);

    std::vector<std::string> env_strings{"NOTIFY_SOCKET=" + sock_path_, "PATH=/usr/bin:/bin"};
    std::vector<char*> envp;
    for (auto& e : env_strings) envp.push_back(e.data());
    envp.push_back(nullptr);
    args.insert(args.begin(), IMUCALD_PATH);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    spawned_ = ::posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data()) == 0;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~NotifiedImucald() {
    if (spawned_ && !reaped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (sock_ >= 0) ::close(sock_);
    ::unlink(sock_path_.c_str());
  }
  bool started() const { return bound_ && spawned_; }
  // The next sd_notify message ("" after 20 s without one).
  std::string nextNotification() {
    char buf[256] = {};
    const ssize_t n = ::recv(sock_, buf, sizeof buf - 1, 0);
    return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
  }
  // SIGTERM, then its exit status (-1 if it did not exit normally).
  int terminate() {
    ::kill(pid_, SIGTERM);
    int status = 0;
    if (::waitpid(pid_, &status, 0) != pid_) return -1;
    reaped_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string log() const { return imucal::testing::readFile(log_path_); }

 private:
  std::string sock_path_, log_path_;
  int sock_ = -1;
  bool bound_ = false, spawned_ = false, reaped_ = false;
  pid_t pid_ = 0;
  static inline int count_ = 0;
};

TEST(ImucaldProcess, NotifiesReadyAndStopsCleanlyOnSigterm) {
  imucal::testing::ScratchDir dir;
  NotifiedImucald daemon(dir, {"--lcm-url", "memq://"});
  ASSERT_TRUE(daemon.started());
  EXPECT_NE(daemon.nextNotification().find("READY=1"), std::string::npos) << "no READY=1 within 20 s";
  EXPECT_EQ(daemon.terminate(), 0);
  EXPECT_NE(daemon.nextNotification().find("STOPPING=1"), std::string::npos);
}

TEST(ImucaldProcess, CorruptStateFileIsLoggedMovedAsideAndTheDaemonRuns) {
  // Each shared corrupt state file once made imucald exit 1 at start (a restart loop under systemd).
  for (const char* name : {"state_file_1e999.json", "state_file_checksum_null.json", "state_file_truncated.json"}) {
    imucal::testing::ScratchDir dir(name);
    const std::string state = dir / "calibration-imu0.json";
    fs::copy_file(imucal::testing::hostile(name), state);
    NotifiedImucald daemon(dir, {"--lcm-url", "memq://", "--state-dir", dir.path().string(), "--restore", "imu0"});
    ASSERT_TRUE(daemon.started());
    EXPECT_NE(daemon.nextNotification().find("READY=1"), std::string::npos) << name << ": " << daemon.log();
    EXPECT_EQ(daemon.terminate(), 0) << name;
    const std::string log = daemon.log();
    EXPECT_NE(log.find("sensor imu0: starting without its persisted calibration: " + state + ": "), std::string::npos)
        << name << ": " << log;
    EXPECT_NE(log.find("moved aside to " + state + ".corrupt-"), std::string::npos) << name << ": " << log;
    EXPECT_FALSE(fs::exists(state)) << name;
  }
}

}  // namespace
