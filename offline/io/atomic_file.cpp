// atomic_file.cpp -- crash-safe file output: temporary file in the target's
// directory, write, fsync, rename(2), fsync of the directory. A failure at
// any point removes the temporary file and leaves an existing target intact.
#include "io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {
namespace {

int g_fault_stage = 0;

bool inject(int stage) {
  if (g_fault_stage == stage) {
    g_fault_stage = 0;
    errno = EIO;
    return true;
  }
  return false;
}


// The process umask without changing it (umask(2) can only be read by
// setting it, which races with other threads); 022 if unknown.
mode_t current_umask() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, 6, "Umask:") == 0) return (mode_t)std::strtol(line.c_str() + 6, nullptr, 8);
  return 022;
}

[[noreturn]] void fail(const std::string &what, const std::string &path, int err) {
  throw std::runtime_error("cannot write " + path + ": " + what + ": " + std::strerror(err));
}

}  // namespace

std::string dir_of(const std::string &path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string base_of(const std::string &path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

void set_atomic_write_fault_for_testing(int stage) { g_fault_stage = stage; }

std::string read_file_bytes(const std::string &path) {
  FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
  std::string out;
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  const bool bad = std::ferror(f) != 0;
  const int err = errno;
  std::fclose(f);
  if (bad) throw InputError(path + ": cannot read: " + std::strerror(err));
  return out;
}

void write_file_atomic(const std::string &path, const std::string &content) {
  if (path.empty()) throw std::runtime_error("cannot write: empty output path");
  if (!path.empty() && path.back() == '/') fail("path names a directory", path, EISDIR);
  const std::string dir = dir_of(path);
  // Keep the mode of an existing target, else the usual 0666 & ~umask.
  struct stat st;
  mode_t mode = 0666 & ~current_umask();
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) fail("path names a directory", path, EISDIR);
    mode = st.st_mode & 07777;
  }

  std::string tmpl = dir + "/." + base_of(path) + ".tmp.XXXXXX";
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  int fd = ::mkstemp(name.data());
  if (fd < 0) fail("cannot create a temporary file in " + dir, path, errno);
  const std::string tmp(name.data());
  auto cleanup_fail = [&](const std::string &what, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    fail(what, path, err);
  };

  if (inject(1) || ::fchmod(fd, mode) != 0) cleanup_fail("chmod", errno);
  const char *p = content.data();
  size_t left = content.size();
  while (left > 0) {
    if (inject(2)) cleanup_fail("write", errno);
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      cleanup_fail("write", errno);
    }
    p += n;
    left -= (size_t)n;
  }
  if (inject(3) || ::fsync(fd) != 0) cleanup_fail("fsync", errno);
  const int fdc = fd;
  fd = -1;
  if (::close(fdc) != 0) cleanup_fail("close", errno);
  if (inject(4) || ::rename(tmp.c_str(), path.c_str()) != 0) cleanup_fail("rename", errno);
  // Persist the directory entry (best effort: some file systems refuse).
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (dfd >= 0) {
    (void)::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace rtb
