// imucald as a process: it tells systemd it is ready (sd_notify on NOTIFY_SOCKET) and ends cleanly, exit
// status 0, on SIGTERM. Uses memq:// so nothing touches a network.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <string>
#include <vector>

extern char** environ;

namespace {

TEST(ImucaldProcess, NotifiesReadyAndStopsCleanlyOnSigterm) {
  const std::string sock_path = "/tmp/imucald_notify_" + std::to_string(::getpid());
  ::unlink(sock_path.c_str());
  const int sock = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(sock, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, sock_path.c_str(), sizeof addr.sun_path - 1);
  ASSERT_EQ(::bind(sock, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  timeval tv{20, 0};
  ::setsockopt(sock, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);

  std::vector<std::string> env_strings{"NOTIFY_SOCKET=" + sock_path, "PATH=/usr/bin:/bin"};
  std::vector<char*> envp;
  for (auto& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::string exe = IMUCALD_PATH, url_flag = "--lcm-url", url = "memq://";
  char* argv[] = {exe.data(), url_flag.data(), url.data(), nullptr};
  pid_t pid = 0;
  ASSERT_EQ(::posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv, envp.data()), 0);

  char buf[256] = {};
  const ssize_t n = ::recv(sock, buf, sizeof buf - 1, 0);
  ASSERT_GT(n, 0) << "no sd_notify message within 20 s";
  EXPECT_NE(std::string(buf, static_cast<std::size_t>(n)).find("READY=1"), std::string::npos);

  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const ssize_t m = ::recv(sock, buf, sizeof buf - 1, 0);
  ASSERT_GT(m, 0);
  EXPECT_NE(std::string(buf, static_cast<std::size_t>(m)).find("STOPPING=1"), std::string::npos);
  ::close(sock);
  ::unlink(sock_path.c_str());
}

}  // namespace
