/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
// loadCloud for .pcd and .ply: PCL's reader in a forked child process.
//
// Why a child and not a guard in front of PCL: Debian's PCL 1.13.0 crashes, aborts or
// allocates without bound on malformed files. On the ~9,800 hostile files this
// project's tests generate (lying headers, every truncation and random byte changes of
// valid files, header number sweeps) it segfaulted on 368 (random bytes, a truncated or
// missing FIELDS line, ...), aborted on 16 (PLY asserts: more vertices than the
// obj_info grid, an indented obj_info line, uchar blue before red) and asked for more
// than 1 GiB on 38 (point or vertex counts that lie). A guard for the named triggers
// (a 73-line prototype) still let 67 of the segfaults and 13 of the
// runaway allocations through: a guard has to know every trigger and follow every PCL
// release, as the 1,980 lines of header parsing it replaces did. The child turns any
// crash, abort, runaway allocation or hang into a clean error, whatever the trigger,
// for one fork and one copy of the cloud through a pipe per file (doc/benchmarks.md,
// *Reading cloud files*).
// A long-running tool forks those children from a small reader process instead
// (cloud_reader_process.h), so its own working memory is never copy-on-write.
#include "cloud_reading.h"

#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply/ply_parser.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <new>
#include <string>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tuple>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace detail {

bool fail(std::string* error, const std::string& message);
std::string quoted(const std::string& path);
bool checkCloudLayout(pcl::PCLPointCloud2& cloud, const std::string& path,
                      std::string* error);

namespace {

/** Exit codes of the reading child (a signal means PCL crashed or timed out). */
enum ChildExit : int {
  kChildOk = 0,
  kChildRejected = 10,
  kChildOutOfMemory = 11,
  kChildException = 12,
  kChildBadRangeGrid = 13,
  kChildPipeFailed = 14
};

template <typename T>
void put(std::string& out, T value)
{
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

} // namespace

bool writeAll(int fd, const void* data, std::size_t size)
{
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return (false);
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return (true);
}

void readAll(int fd, std::string& out)
{
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return;
    out.append(buffer, static_cast<std::size_t>(n));
  }
}

std::string cloudBytes(const pcl::PCLPointCloud2& cloud)
{
  std::string head;
  for (const std::uint32_t v : {cloud.width, cloud.height, cloud.point_step,
                                static_cast<std::uint32_t>(cloud.fields.size())})
    put(head, v);
  put(head, static_cast<std::uint8_t>(cloud.is_dense));
  put(head, cloud.is_bigendian);
  for (const pcl::PCLPointField& f : cloud.fields) {
    put(head, static_cast<std::uint32_t>(f.name.size()));
    head += f.name;
    put(head, f.offset);
    put(head, f.datatype);
    put(head, f.count);
  }
  put(head, static_cast<std::uint64_t>(cloud.data.size()));
  head.append(reinterpret_cast<const char*>(cloud.data.data()), cloud.data.size());
  return (head);
}

namespace {

/** Send a cloud through the pipe: layout, fields, then the data bytes. */
bool sendCloud(int fd, const pcl::PCLPointCloud2& cloud)
{
  const std::string bytes = cloudBytes(cloud);
  return (writeAll(fd, bytes.data(), bytes.size()));
}

/** Reads what sendCloud wrote, bounds-checked. */
class Unpacker {
public:
  explicit Unpacker(const std::string& bytes)
      : bytes_(bytes)
  {
  }
  template <typename T>
  bool get(T& value)
  {
    return (take(&value, sizeof(T)));
  }
  bool take(void* out, std::size_t size)
  {
    if (size > bytes_.size() - pos_)
      return (false);
    if (size > 0) // out may be the null data() of an empty vector
      std::memcpy(out, bytes_.data() + pos_, size);
    pos_ += size;
    return (true);
  }
  bool atEnd() const { return (pos_ == bytes_.size()); }

private:
  const std::string& bytes_;
  std::size_t pos_ = 0;
};

} // namespace

bool receiveCloud(const std::string& bytes, pcl::PCLPointCloud2& cloud)
{
  Unpacker in(bytes);
  std::uint32_t fields = 0;
  std::uint8_t dense = 0;
  if (!in.get(cloud.width) || !in.get(cloud.height) || !in.get(cloud.point_step) ||
      !in.get(fields) || !in.get(dense) || !in.get(cloud.is_bigendian))
    return (false);
  cloud.is_dense = dense;
  cloud.fields.clear();
  for (std::uint32_t i = 0; i < fields; ++i) {
    pcl::PCLPointField f;
    std::uint32_t length = 0;
    if (!in.get(length) || length > bytes.size())
      return (false);
    f.name.resize(length);
    if (!in.take(f.name.data(), length) || !in.get(f.offset) || !in.get(f.datatype) ||
        !in.get(f.count))
      return (false);
    cloud.fields.push_back(f);
  }
  std::uint64_t size = 0;
  if (!in.get(size) || size > bytes.size())
    return (false);
  cloud.data.resize(static_cast<std::size_t>(size));
  cloud.row_step = cloud.width * cloud.point_step; // the layout every loaded cloud has
  return (in.take(cloud.data.data(), cloud.data.size()) && in.atEnd());
}

namespace {

/** PCL 1.13.0's PLYReader::read (ply_io.cpp) maps each range_grid cell to its vertex
 * with `(*range_grid_)[r][0] * cloud_->point_step`, an unsigned 32-bit product, and
 * checks the wrapped offset against the buffer. An index outside [0, vertices) then
 * reads gigabytes past the buffer (a crash, caught by the child) or, when the product
 * wraps to a small offset (357913942 * 12 = 8 mod 2^32), silently copies the wrong
 * bytes: no crash for the child to catch. So the indices are checked first, walking
 * the file with PCL's own PLY parser. */
bool checkRangeGridIndices(const std::string& path, std::string& why)
{
  using pcl::io::ply::ply_parser;
  std::size_t vertices = 0;
  bool found = false;
  double bad = 0.0;
  ply_parser parser;
  parser.element_definition_callback([&](const std::string& name, std::size_t count) {
    if (name == "vertex")
      vertices = count;
    return (ply_parser::element_callbacks_type{});
  });
  const auto check = [&](double index) {
    if (!found && !(index >= 0.0 && index < static_cast<double>(vertices))) {
      found = true;
      bad = index;
    }
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
  // The list types PCL 1.13.0's PLYReader::parse registers.
  using namespace pcl::io::ply;
  watch(uint8{}, int32{});
  watch(uint8{}, uint32{});
  watch(uint32{}, float64{});
  watch(uint32{}, float32{});
  watch(uint32{}, uint32{});
  watch(uint32{}, int32{});
  watch(uint32{}, uint16{});
  watch(uint32{}, int16{});
  watch(uint32{}, uint8{});
  watch(uint32{}, int8{});
  parser.list_property_definition_callbacks(lists);
  parser.parse(path); // a file it rejects is left to PCL's reader to reject
  if (!found)
    return (true);
  char text[160];
  std::snprintf(text, sizeof(text),
                "range_grid vertex index %.17g is outside the %zu vertices", bad,
                vertices);
  why = text;
  return (false);
}

/** Whether a PLY header (up to end_header, at most 1 MiB) declares a range_grid. */
bool declaresRangeGrid(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (std::size_t read = 0; read < (1u << 20) && std::getline(in, line);
       read += line.size() + 1) {
    if (line.rfind("end_header", 0) == 0)
      return (false);
    if (line.find("range_grid") != std::string::npos)
      return (true);
  }
  return (false);
}

/** Caps the child's address space and wall time: a header that lies about its size
 * then fails with bad_alloc (AddressSanitizer builds: an abort) or SIGALRM instead of
 * taking the machine. The budget, 1 GiB + 128 bytes per file byte, is above any
 * expansion of a real cloud (ascii to float64 is 4x, PCL's LZF at most ~90x). */
void limitChild(std::uintmax_t file_size)
{
  ::alarm(static_cast<unsigned>(60 + file_size / (1u << 20)));
  long pages = 0;
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld", &pages) != 1)
      pages = 0;
    std::fclose(statm);
  }
  const std::uintmax_t budget = (std::uintmax_t{1} << 30) + 128 * file_size;
  if (pages > 0 && budget / 128 >= file_size) {
    const std::uintmax_t total = static_cast<std::uintmax_t>(pages) *
                                     static_cast<std::uintmax_t>(::getpagesize()) +
                                 budget;
    const rlimit limit{total, total};
    ::setrlimit(RLIMIT_AS, &limit);
  }
}

[[noreturn]] void runChild(const std::string& path, CloudFormat format,
                           std::uintmax_t file_size, int fd)
{
  ::prctl(PR_SET_PDEATHSIG, SIGKILL); // a reader left alone never holds stdout long
  limitChild(file_size);
  int code = kChildException;
  try {
    std::string why;
    pcl::PCLPointCloud2 cloud;
    if (format == CloudFormat::PLY && declaresRangeGrid(path) &&
        !checkRangeGridIndices(path, why)) {
      code =
          writeAll(fd, why.data(), why.size()) ? kChildBadRangeGrid : kChildPipeFailed;
    } else if ((format == CloudFormat::PCD ? pcl::io::loadPCDFile(path, cloud)
                                           : pcl::io::loadPLYFile(path, cloud)) != 0) {
      code = kChildRejected;
    } else {
      code = sendCloud(fd, cloud) ? kChildOk : kChildPipeFailed;
    }
  } catch (const std::bad_alloc&) {
    code = kChildOutOfMemory;
  } catch (const std::exception& e) {
    writeAll(fd, e.what(), std::strlen(e.what()));
    code = kChildException;
  } catch (...) {
    code = kChildException;
  }
  ::_exit(code);
}

} // namespace

bool loadWithPcl(const std::string& path, CloudFormat format, std::uintmax_t file_size,
                 pcl::PCLPointCloud2& cloud, std::string* error)
{
  const std::string reader =
      format == CloudFormat::PCD ? "PCL's PCD reader" : "PCL's PLY reader";
  int fds[2];
  if (::pipe(fds) != 0)
    return (fail(error, quoted(path) + ": cannot create a pipe (" +
                            std::strerror(errno) + ")"));
  std::fflush(nullptr); // the child must not write the parent's buffered output
  const pid_t pid = ::fork();
  if (pid == 0) { // keep only stdio and the pipe: another thread's pipes must see EOF
    ::close_range(3, static_cast<unsigned>(fds[1]) - 1, 0);
    ::close_range(static_cast<unsigned>(fds[1]) + 1, ~0u, 0);
    runChild(path, format, file_size, fds[1]);
  }
  ::close(fds[1]);
  if (pid < 0) {
    ::close(fds[0]);
    return (fail(error, quoted(path) + ": cannot fork (" + std::strerror(errno) + ")"));
  }
  std::string bytes;
  readAll(fds[0], bytes);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return (fail(error, quoted(path) + ": " + reader +
                            (signal == SIGALRM ? " took too long"
                                               : std::string(" crashed (") +
                                                     strsignal(signal) + ")") +
                            ": not a valid cloud file"));
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : kChildException;
  switch (code) {
  case kChildOk:
    if (!receiveCloud(bytes, cloud))
      return (fail(error, quoted(path) + ": the cloud read by " + reader +
                              " did not arrive whole"));
    return (checkCloudLayout(cloud, path, error));
  case kChildRejected:
    return (fail(error, quoted(path) + ": " + reader +
                            " rejected it: not a valid cloud file"));
  case kChildOutOfMemory:
    return (fail(error, quoted(path) + ": " + reader +
                            " ran out of memory: its header announces more data "
                            "than the file can hold"));
  case kChildBadRangeGrid:
    return (fail(error, quoted(path) + ": " + bytes));
  case kChildException:
    bytes.resize(std::min<std::size_t>(bytes.size(), 200));
    for (char& c : bytes)
      c = (c >= 32 && c < 127) ? c : '?';
    return (fail(error, quoted(path) + ": " + reader + " threw '" + bytes +
                            "': not a valid cloud file"));
  default:
    return (fail(error, quoted(path) + ": " + reader + " failed (exit code " +
                            std::to_string(code) + ")"));
  }
}

} // namespace detail
} // namespace phaser
} // namespace pcl
