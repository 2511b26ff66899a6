/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 */
#include "trajectory_plot.h"

#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <system_error>
#include <unistd.h>

namespace pcl {
namespace phaser {
namespace graph {

namespace {

const char* const kInstall = "the PNG needs gnuplot: apt-get install gnuplot-nox";

/** \a text as a gnuplot single-quoted string ('' is a quote), newlines as "\n". */
std::string quoted(const std::string& text)
{
  std::string out = "'";
  for (const char c : text)
    if (c == '\'')
      out += "''";
    else if (c == '\n')
      out += "'.\"\\n\".'";
    else if (static_cast<unsigned char>(c) >= ' ')
      out += c;
  return out + "'";
}

/** The gnuplot script: pngcairo when built in (else png), to plot.png beside it. */
std::string script(const std::string& title, const std::vector<Series>& series,
                   int size)
{
  std::ostringstream gp;
  const std::string dims = "size " + std::to_string(size) + "," + std::to_string(size);
  gp << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
     << "  set terminal pngcairo " << dims << " noenhanced font 'sans,11'\n"
     << "} else {\n  set terminal png " << dims << " noenhanced\n}\n"
     << "set output 'plot.png'\nset title " << quoted(title) << "\n"
     << "set xlabel 'x [m]'\nset ylabel 'y [m]'\nset size ratio -1\n"
     << "set grid lc rgb '#e0e0e0'\nset bmargin 8\n"
     << "set key at screen 0.5,0.02 center bottom Left reverse box\nplot ";
  const char* separator = "";
  for (std::size_t k = 0; k < series.size(); ++k)
    if (!series[k].points.empty()) {
      gp << separator << "'series" << k << ".dat' with lines lw " << series[k].width
         << " lc rgb " << quoted(series[k].color) << " title "
         << quoted(series[k].title);
      separator = ", \\\n     ";
    }
  gp << "\n";
  return gp.str();
}

/** The points of \a s, one x y a line; a blank line ends each segment when not
 *  connected. */
std::string data(const Series& s)
{
  std::ostringstream out;
  out.precision(10);
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    out << s.points[k].x() << " " << s.points[k].y() << "\n";
    if (!s.connected && k % 2 == 1)
      out << "\n";
  }
  return out.str();
}

/** The first lines of \a path, on one line. */
std::string head(const std::string& path)
{
  std::ifstream in(path);
  std::string text, line;
  for (int n = 0; n < 4 && std::getline(in, line); ++n)
    text += (n ? " | " : "") + line;
  return text.empty() ? "no message" : text;
}

/** Run `gnuplot plot.gp` in \a folder, its output to gnuplot.log there.
 *  \return the reason on failure, else empty */
std::string runGnuplot(const std::string& folder)
{
  const pid_t pid = ::fork();
  if (pid < 0)
    return std::string("cannot start gnuplot (fork failed); ") + kInstall;
  if (pid == 0) { // only async-signal-safe calls until exec
    if (::chdir(folder.c_str()) == 0) {
      const int log = ::open("gnuplot.log", O_WRONLY | O_CREAT | O_TRUNC, 0600);
      if (log >= 0 && ::dup2(log, 1) >= 0 && ::dup2(log, 2) >= 0) {
        ::execlp("gnuplot", "gnuplot", "plot.gp", static_cast<char*>(nullptr));
        const char missing[] = "gnuplot not found on PATH";
        [[maybe_unused]] const ssize_t n = ::write(2, missing, sizeof(missing) - 1);
      }
    }
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      return std::string("lost the gnuplot process; ") + kInstall;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
    return {};
  const std::string how = WIFEXITED(status)
                              ? "exit code " + std::to_string(WEXITSTATUS(status))
                              : "signal " + std::to_string(WTERMSIG(status));
  return "gnuplot failed (" + how + ": " + head(folder + "/gnuplot.log") + "); " +
         kInstall;
}

/** Write the data and script into \a folder, run gnuplot, copy its PNG to \a path. */
std::string plotIn(const std::string& folder, const std::string& path,
                   const std::string& title, const std::vector<Series>& series,
                   int size)
{
  for (std::size_t k = 0; k < series.size(); ++k)
    if (!(std::ofstream(folder + "/series" + std::to_string(k) + ".dat")
          << data(series[k])))
      return "cannot write to the temporary directory '" + folder + "'";
  if (!(std::ofstream(folder + "/plot.gp") << script(title, series, size)))
    return "cannot write to the temporary directory '" + folder + "'";
  if (const std::string error = runGnuplot(folder); !error.empty())
    return error;
  std::error_code ec;
  if (std::filesystem::file_size(folder + "/plot.png", ec) == 0 || ec)
    return std::string("gnuplot wrote no PNG; ") + kInstall;
  std::filesystem::copy_file(folder + "/plot.png", path,
                             std::filesystem::copy_options::overwrite_existing, ec);
  return ec ? "cannot write '" + path + "': " + ec.message() : "";
}

} // namespace

std::string writeTopView(const std::string& path, const std::string& title,
                         const std::vector<Series>& series, int size)
{
  bool empty = true;
  for (const Series& s : series)
    empty = empty && s.points.empty();
  if (empty)
    return "nothing to draw";
  std::error_code ec;
  const std::string base = std::filesystem::temp_directory_path(ec).string();
  std::string name = (ec ? "/tmp" : base) + "/pcl_phaser_plot_XXXXXX";
  if (!::mkdtemp(name.data()))
    return "cannot create a temporary directory for gnuplot ('" + name + "')";
  const std::string error = plotIn(name, path, title, series, size);
  std::filesystem::remove_all(name, ec);
  return error;
}

} // namespace graph
} // namespace phaser
} // namespace pcl
