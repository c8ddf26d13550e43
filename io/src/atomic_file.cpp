#include "imucal/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "imucal/io/errors.hpp"

namespace imucal::io {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int error) {
  throw OutputError("cannot write '" + path + "': " + what + ": " + std::strerror(error));
}

// Opens a new temporary file in the target's directory (rename is only atomic within one file system).
// O_EXCL plus a counter avoids clobbering another writer's temporary; mode 0666 lets the umask decide.
int openTemporary(const std::string& path, std::string& temp_path) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    temp_path = path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(attempt);
    const int fd = ::open(temp_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return fd;
    if (errno != EEXIST) fail(path, "cannot create temporary file '" + temp_path + "'", errno);
  }
  fail(path, "no free temporary file name", EEXIST);
}

}  // namespace

void writeFileAtomically(const std::string& path, std::string_view content) {
  std::string temp_path;
  const int fd = openTemporary(path, temp_path);
  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      ::close(fd);
      std::remove(temp_path.c_str());
      fail(path, "write failed", error);
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  // Without fsync the rename could reach the disk before the data, leaving an empty file after a crash.
  int error = ::fsync(fd) == 0 ? 0 : errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    std::remove(temp_path.c_str());
    fail(path, "flush failed", error);
  }
  if (std::rename(temp_path.c_str(), path.c_str()) != 0) {
    const int error = errno;
    std::remove(temp_path.c_str());
    fail(path, "rename from '" + temp_path + "' failed", error);
  }
}

}  // namespace imucal::io
