/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// PCD and PLY files are read by PCL's reader in a forked child process: Debian's PCL
// 1.13.0 crashes, aborts (PLY asserts) or allocates without bound on malformed files
// (368, 16 and 38 of the ~9,800 hostile files of the tests), and a guard in front of it
// would have to know every trigger. The child turns any of them, and a hang, into a
// clean error, for one fork and one copy of the cloud per file (doc/benchmarks.md,
// *Reading cloud files*).
#include "cloud_reading.h"
#include "io_detail.h"

#include <pcl/io/pcd_io.h>
#include <pcl/io/ply/ply_parser.h>
#include <pcl/io/ply_io.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <new>
#include <optional>
#include <sstream>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <tuple>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace detail {
namespace {

/** Whether a PLY header (within the first MiB) declares a range_grid. */
bool declaresRangeGrid(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string head(1u << 20, '\0');
  head.resize(static_cast<std::size_t>(
      in.read(head.data(), static_cast<std::streamsize>(head.size())).gcount()));
  return (head.find("range_grid") < head.find("end_header"));
}

/** PCL 1.13.0's PLYReader finds a range_grid cell's vertex at the unsigned 32-bit
 * product index * point_step: an index outside [0, vertices) reads far past the buffer
 * or, when the product wraps to a small offset, silently copies the wrong bytes. So
 * the indices are checked first, with PCL's own PLY parser. */
bool checkRangeGrid(const std::string& path, std::string& why)
{
  using namespace pcl::io::ply;
  std::size_t vertices = 0;
  std::optional<double> bad;
  ply_parser parser;
  parser.element_definition_callback([&](const std::string& name, std::size_t count) {
    vertices = name == "vertex" ? count : vertices;
    return (ply_parser::element_callbacks_type{});
  });
  const auto check = [&](double index) {
    if (!bad && !(index >= 0.0 && index < static_cast<double>(vertices)))
      bad = index;
  };
  ply_parser::list_property_definition_callbacks_type lists;
  const auto watch = [&](auto size_tag, auto value_tag) {
    using S = decltype(size_tag);
    using V = decltype(value_tag);
    using Callbacks = std::tuple<std::function<void(S)>, std::function<void(V)>,
                                 std::function<void()>>;
    ply_parser::at<S, V>(lists) = [&](const std::string& element,
                                      const std::string& property) {
      if (element != "range_grid" ||
          (property != "vertex_indices" && property != "vertex_index"))
        return (Callbacks{});
      return (Callbacks{[](S) {}, [&](V v) { check(static_cast<double>(v)); }, [] {}});
    };
  };
  // The list types PCL 1.13.0's PLYReader reads.
  const auto watchAll = [&](auto size_tag, auto... value_tags) {
    (watch(size_tag, value_tags), ...);
  };
  watchAll(uint8{}, int32{}, uint32{});
  watchAll(uint32{}, float64{}, float32{}, uint32{}, int32{}, uint16{}, int16{},
           uint8{}, int8{});
  parser.list_property_definition_callbacks(lists);
  parser.parse(path); // a file it rejects is left to PCL's reader to reject
  char text[160];
  std::snprintf(text, sizeof(text),
                "range_grid vertex index %.17g is outside the %zu vertices",
                bad.value_or(0), vertices);
  why = text;
  return (!bad);
}

/** Caps the child's address space and time, so that a header that lies about its size
 * fails with bad_alloc (AddressSanitizer builds: an abort) or SIGALRM. The budget,
 * 1 GiB + 128 bytes per file byte, is above any expansion of a real cloud (ascii to
 * float64 is 4x, PCL's LZF at most ~90x). */
void limitChild(std::uintmax_t file_size)
{
  ::alarm(static_cast<unsigned>(60 + file_size / (1u << 20)));
  long pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  const std::uintmax_t total = static_cast<std::uintmax_t>(pages) * ::getpagesize() +
                               (std::uintmax_t{1} << 30) + 128 * file_size;
  const rlimit limit{total, total};
  if (pages > 0)
    ::setrlimit(RLIMIT_AS, &limit);
}

/** Send (\a out) or read \a size bytes whole; false at the end of the stream or on an
 * error. */
bool transfer(int fd, char* data, std::size_t size, bool out)
{
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = out ? ::send(fd, data + done, size - done, MSG_NOSIGNAL)
                          : ::read(fd, data + done, size - done);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return (false);
    done += static_cast<std::size_t>(n);
  }
  return (true);
}

[[noreturn]] void runChild(const std::string& path, const std::string& reader, int fd)
{
  ::prctl(PR_SET_PDEATHSIG, SIGKILL); // a reader left alone never holds stdout long
  // A crash in PCL's reader ends the child at once: a sanitizer's handler would print
  // and symbolize a report in every such child (40 ms each, most of the fuzz tests'
  // time); the caller reports the signal.
  for (const int crash : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT})
    std::signal(crash, SIG_DFL);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  limitChild(ec ? 0 : size);
  std::string reply;
  try {
    pcl::PCLPointCloud2 cloud;
    std::string why;
    const bool pcd = getCloudFormat(path) == CloudFormat::PCD;
    if (!pcd && declaresRangeGrid(path) && !checkRangeGrid(path, why))
      reply = "0" + quoted(path) + ": " + why;
    else if ((pcd ? pcl::io::loadPCDFile(path, cloud)
                  : pcl::io::loadPLYFile(path, cloud)) != 0)
      reply = "0" + reader + " rejected it: not a valid cloud file";
    else if (!checkCloudLayout(cloud, path, &why))
      reply = "0" + why;
    else
      reply = binaryPcd(cloud, "1");
  } catch (const std::bad_alloc&) {
    reply = "0" + reader +
            " ran out of memory: its header announces more data than the file can hold";
  } catch (const std::exception& e) {
    reply = "0" + reader + " threw '" + printable(e.what(), 200) +
            "': not a valid cloud file";
  }
  ::_exit(sendFramed(fd, reply) ? 0 : 1);
}

} // namespace

pid_t forkKeeping(int fd)
{
  std::fflush(nullptr); // the child must not write the parent's buffered output
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close_range(3, static_cast<unsigned>(fd) - 1, 0);
    ::close_range(static_cast<unsigned>(fd) + 1, ~0u, 0);
  }
  return (pid);
}

std::string readInChild(const std::string& path)
{
  const std::string reader =
      quoted(path) + ": PCL's " +
      (getCloudFormat(path) == CloudFormat::PCD ? "PCD" : "PLY") + " reader";
  int fds[2] = {-1, -1};
  const pid_t pid = ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) == 0
                        ? forkKeeping(fds[1])
                        : -1;
  if (pid == 0)
    runChild(path, reader, fds[1]);
  const int failure = errno;
  ::close(fds[1]);
  std::string reply;
  const bool replied = pid > 0 && readFramed(fds[0], reply) && !reply.empty();
  ::close(fds[0]);
  if (pid < 0)
    return ("0" + reader + " could not start (" + std::strerror(failure) + ")");
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status))
    return ("0" + reader +
            (WTERMSIG(status) == SIGALRM
                 ? std::string(" took too long")
                 : std::string(" crashed (") + strsignal(WTERMSIG(status)) + ")") +
            ": not a valid cloud file");
  if (!replied || WEXITSTATUS(status) != 0)
    return ("0" + reader + " failed (exit code " + std::to_string(WEXITSTATUS(status)) +
            ")");
  return (reply);
}

bool takeReply(const std::string& path, const std::string& reply,
               pcl::PCLPointCloud2& cloud, std::string* error)
{
  if (reply[0] != '1')
    return (fail(error, reply.substr(1)));
  const std::size_t data = reply.find("\nDATA binary\n") + 13;
  std::istringstream header(reply.substr(1, data - 1));
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, type = 0;
  unsigned int index = 0;
  if (data < 13 || pcl::PCDReader().readHeader(header, cloud, origin, orientation,
                                               version, type, index) != 0)
    return (fail(error,
                 quoted(path) + ": the cloud from PCL's reader did not arrive whole"));
  cloud.data.assign(reply.begin() + static_cast<std::ptrdiff_t>(data), reply.end());
  return (checkCloudLayout(cloud, path, error));
}

bool sendFramed(int fd, const std::string& bytes)
{
  std::uint64_t size = bytes.size();
  return (transfer(fd, reinterpret_cast<char*>(&size), sizeof(size), true) &&
          transfer(fd, const_cast<char*>(bytes.data()), bytes.size(), true));
}

bool readFramed(int fd, std::string& bytes)
{
  std::uint64_t size = 0;
  if (!transfer(fd, reinterpret_cast<char*>(&size), sizeof(size), false) ||
      size >= (std::uint64_t{1} << 40))
    return (false);
  bytes.resize(static_cast<std::size_t>(size));
  return (transfer(fd, bytes.data(), bytes.size(), false));
}

} // namespace detail
} // namespace phaser
} // namespace pcl
