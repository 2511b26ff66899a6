/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// The reader process of startCloudReader(): a request is a framed path, the reply the
// framed readInChild() reply, over a socket pair.
#include "cloud_reading.h"
#include "io_detail.h"

#include <cerrno>
#include <csignal>
#include <exception>
#include <mutex>
#include <string>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace {

std::mutex reader_mutex; // guards the two below
int reader_fd = -1;
pid_t reader_pid = -1;

/** The reader's loop; it ends when the caller's end closes. */
[[noreturn]] void serve(int fd)
{
  ::prctl(PR_SET_PDEATHSIG, SIGKILL); // never outlive the caller
  std::signal(SIGINT, SIG_IGN);       // the caller decides when to stop
  std::signal(SIGTERM, SIG_IGN);
  for (std::string path; detail::readFramed(fd, path) &&
                         detail::sendFramed(fd, detail::readInChild(path));) {
  }
  ::_exit(0);
}

} // namespace

bool startCloudReader()
{
  std::lock_guard<std::mutex> lock(reader_mutex);
  int sv[2];
  if (reader_fd >= 0 || ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
    return (reader_fd >= 0);
  const pid_t pid = detail::forkKeeping(sv[1]);
  if (pid == 0)
    serve(sv[1]);
  ::close(sv[1]);
  if (pid < 0) {
    ::close(sv[0]);
    return (false);
  }
  reader_fd = sv[0];
  reader_pid = pid;
  return (true);
}

pid_t cloudReaderPid()
{
  std::lock_guard<std::mutex> lock(reader_mutex);
  return (reader_pid);
}

bool detail::readThroughReader(const std::string& path, std::string& reply)
{
  std::lock_guard<std::mutex> lock(reader_mutex);
  if (reader_fd < 0)
    return (false);
  bool answered = false;
  try {
    answered =
        sendFramed(reader_fd, path) && readFramed(reader_fd, reply) && !reply.empty();
  } catch (const std::exception&) { // a reply half read: the stream is lost
  }
  if (!answered) { // let it go: the caller reads the files itself from now on
    ::close(reader_fd);
    ::kill(reader_pid, SIGKILL);
    while (::waitpid(reader_pid, nullptr, 0) < 0 && errno == EINTR) {
    }
    reader_fd = reader_pid = -1;
  }
  return (answered);
}

} // namespace phaser
} // namespace pcl
