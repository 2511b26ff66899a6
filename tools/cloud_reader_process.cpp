/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * The reader process: requests (path, format, size) and replies (ok, reason, the
 * cloud's bytes) over a socket pair, each length-prefixed.
 */
#include "cloud_reader_process.h"
#include "cloud_reading.h"

#include <pcl/PCLPointCloud2.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace detail {

bool loadWithPcl(const std::string& path, CloudFormat format, std::uintmax_t file_size,
                 pcl::PCLPointCloud2& cloud, std::string* error);
std::string cloudBytes(const pcl::PCLPointCloud2& cloud);
bool receiveCloud(const std::string& bytes, pcl::PCLPointCloud2& cloud);

} // namespace detail

namespace {

struct Reader {
  std::mutex mutex;
  int fd = -1;
  pid_t pid = -1;
};

Reader& reader()
{
  static Reader r;
  return r;
}

/** Repeat \a step(done) (a send or a read from byte \a done on) until \a size bytes
 *  moved; false at the end of the stream or on an error. */
template <typename Step>
bool moveAll(std::size_t size, const Step& step)
{
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = step(done);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

bool sendAll(int fd, const std::string& bytes)
{
  return moveAll(bytes.size(), [&](std::size_t done) {
    return ::send(fd, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
  });
}

bool readExact(int fd, std::string& out, std::size_t size)
{
  out.resize(size);
  return moveAll(size, [&](std::size_t done) {
    return ::read(fd, out.data() + done, size - done);
  });
}

/** A u64 length and the bytes. */
std::string framed(const std::string& bytes)
{
  const std::uint64_t size = bytes.size();
  return std::string(reinterpret_cast<const char*>(&size), sizeof(size)) + bytes;
}

bool readFramed(int fd, std::string& bytes)
{
  std::string head;
  if (!readExact(fd, head, sizeof(std::uint64_t)))
    return false;
  std::uint64_t size = 0;
  std::copy(head.begin(), head.end(), reinterpret_cast<char*>(&size));
  return size < (std::uint64_t{1} << 40) &&
         readExact(fd, bytes, static_cast<std::size_t>(size));
}

/** The reader's loop: a request is the framed path, format and file size; the reply
 *  the framed "1" or "0", reason and cloud bytes. Ends when the caller's end closes. */
[[noreturn]] void serve(int fd)
{
  ::prctl(PR_SET_PDEATHSIG, SIGKILL); // never outlive the caller
  std::signal(SIGINT, SIG_IGN);       // the caller decides when to stop
  std::signal(SIGTERM, SIG_IGN);
  for (std::string path, format, size;
       readFramed(fd, path) && readFramed(fd, format) && readFramed(fd, size);) {
    pcl::PCLPointCloud2 cloud;
    std::string error, bytes;
    bool ok = false;
    try {
      int code = 0;
      std::uintmax_t file_size = 0;
      ok = format.size() == sizeof(code) && size.size() == sizeof(file_size);
      if (ok) {
        std::memcpy(&code, format.data(), sizeof(code));
        std::memcpy(&file_size, size.data(), sizeof(file_size));
        ok = detail::loadWithPcl(path, static_cast<CloudFormat>(code), file_size, cloud,
                                 &error);
      }
      if (ok)
        bytes = detail::cloudBytes(cloud);
    } catch (const std::exception& e) {
      ok = false;
      error = "'" + path + "': the reader process: " + e.what();
    }
    if (!sendAll(fd, framed(ok ? "1" : "0") + framed(error)) ||
        !sendAll(fd, framed(ok ? bytes : std::string())))
      break;
  }
  ::_exit(0);
}

} // namespace

bool startCloudReader()
{
  Reader& r = reader();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (r.fd >= 0)
    return true;
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
    return false;
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) { // keep only stdio and the socket
    ::close_range(3, static_cast<unsigned>(sv[1]) - 1, 0);
    ::close_range(static_cast<unsigned>(sv[1]) + 1, ~0u, 0);
    serve(sv[1]);
  }
  ::close(sv[1]);
  if (pid < 0) {
    ::close(sv[0]);
    return false;
  }
  r.fd = sv[0];
  r.pid = pid;
  return true;
}

pid_t cloudReaderPid()
{
  Reader& r = reader();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.pid;
}

namespace detail {

/** loadWithPcl through the reader process; false in \a used when none runs or it
 *  stopped answering (then it is let go and the caller reads the file itself). */
bool loadThroughReader(const std::string& path, CloudFormat format,
                       std::uintmax_t file_size, pcl::PCLPointCloud2& cloud,
                       std::string* error, bool& used)
{
  Reader& r = reader();
  std::lock_guard<std::mutex> lock(r.mutex);
  used = false;
  if (r.fd < 0)
    return false;
  const int code = static_cast<int>(format);
  std::string ok, reason, bytes;
  bool answered = false;
  try {
    answered =
        sendAll(r.fd, framed(path) +
                          framed(std::string(reinterpret_cast<const char*>(&code),
                                             sizeof(code))) +
                          framed(std::string(reinterpret_cast<const char*>(&file_size),
                                             sizeof(file_size)))) &&
        readFramed(r.fd, ok) && readFramed(r.fd, reason) && readFramed(r.fd, bytes);
  } catch (const std::exception&) { // a reply half read: the stream is lost
    answered = false;
  }
  if (!answered) { // let it go: the caller reads the file itself from now on
    ::close(r.fd);
    ::kill(r.pid, SIGKILL);
    while (::waitpid(r.pid, nullptr, 0) < 0 && errno == EINTR) {
    }
    r.fd = -1;
    r.pid = -1;
    return false;
  }
  used = true;
  if (ok != "1") {
    if (error)
      *error = reason;
    return false;
  }
  if (!receiveCloud(bytes, cloud)) {
    if (error)
      *error = "'" + path + "': the cloud from the reader process did not arrive whole";
    return false;
  }
  return true;
}

} // namespace detail
} // namespace phaser
} // namespace pcl
