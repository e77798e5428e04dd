// Whole-or-nothing output files, number formatting, text tables and progress for the CLI.
#include "cli/output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/input_error.h"

namespace revdist::cli {

namespace {

// Temporaries to remove if a signal ends the run while they exist. The handler only reads
// the C strings (fixed before the count is raised) and calls unlink, which is
// async-signal-safe.
std::vector<std::string> g_temps;
std::atomic<std::size_t> g_temp_count{0};

extern "C" void remove_temps_and_reraise(int sig) {
  const std::size_t n = g_temp_count.load();
  for (std::size_t i = 0; i < n; ++i) ::unlink(g_temps[i].c_str());
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

struct SignalGuard {
  struct sigaction old[4];
  SignalGuard() {
    struct sigaction sa {};
    sa.sa_handler = remove_temps_and_reraise;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 4; ++i) sigaction(kSignals[i], &sa, &old[i]);
  }
  ~SignalGuard() {
    for (int i = 0; i < 4; ++i) sigaction(kSignals[i], &old[i], nullptr);
  }
};

bool is_path_problem(int e) {
  return e == EACCES || e == EPERM || e == EROFS || e == ENOTDIR || e == EISDIR || e == ENOENT || e == ENAMETOOLONG ||
         e == ELOOP || e == EEXIST || e == EINVAL;
}

[[noreturn]] void fail_io(const std::string& path, const std::string& what, int e) {
  const std::string msg = path + ": " + what + " (" + std::strerror(e) + ")";
  if (is_path_problem(e)) throw InputError(msg);
  throw RunError(msg);
}

bool write_all(int fd, const std::string& s) {
  std::size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& given) {
  namespace fs = std::filesystem;
  // Where each file goes. A regular file (or none yet) is replaced by a
  // temporary renamed over it; through a symbolic link, the file it names
  // (the link stays a link); a device, FIFO or socket is written in place,
  // after every temporary is complete (a stream has no whole-or-nothing, and
  // a rename over it replaces the node itself: `--out /dev/full`, run as
  // root, once left a JSON file where the device was). A target that is a
  // directory would make its rename fail after others succeeded.
  std::vector<std::pair<std::string, std::string>> files, streams;
  for (const auto& f : given) {
    struct stat st {};
    if (::stat(f.first.c_str(), &st) != 0) {  // not there yet (or a link to nothing: replaced)
      files.push_back(f);
      continue;
    }
    if (S_ISDIR(st.st_mode)) throw InputError(f.first + ": is a directory, cannot write a file there");
    if (!S_ISREG(st.st_mode)) {
      streams.push_back(f);
      continue;
    }
    struct stat lst {};
    std::error_code ec;
    const fs::path real = ::lstat(f.first.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode) ? fs::canonical(f.first, ec)
                                                                                        : fs::path(f.first);
    if (ec) fail_io(f.first, "cannot follow the link", ec.value());
    files.emplace_back(real.string(), f.second);
  }
  g_temps.clear();
  g_temps.reserve(files.size());
  g_temp_count = 0;
  SignalGuard guard;
  auto cleanup = [] {
    for (std::size_t i = 0; i < g_temp_count.load(); ++i) ::unlink(g_temps[i].c_str());
    g_temp_count = 0;
  };
  try {
    for (const auto& f : files) {
      const fs::path target(f.first);
      const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
      std::string tmpl = (dir / ("." + target.filename().string() + ".XXXXXX")).string();
      std::vector<char> buf(tmpl.begin(), tmpl.end());
      buf.push_back('\0');
      // mkstemp: O_CREAT | O_EXCL with a fresh random name, mode 0600.
      const int fd = ::mkstemp(buf.data());
      if (fd < 0) fail_io(f.first, "cannot create a temporary file beside it", errno);
      g_temps.emplace_back(buf.data());
      g_temp_count = g_temps.size();
      const bool ok = write_all(fd, f.second) && ::fchmod(fd, 0644) == 0 && ::fsync(fd) == 0;
      const int e = errno;
      if (::close(fd) != 0 || !ok) fail_io(f.first, "write failed", ok ? errno : e);
    }
    for (const auto& f : streams) {
      const int fd = ::open(f.first.c_str(), O_WRONLY | O_CLOEXEC);
      if (fd < 0) fail_io(f.first, "cannot open for writing", errno);
      const bool ok = write_all(fd, f.second);
      const int e = errno;
      if (::close(fd) != 0 || !ok) fail_io(f.first, "write failed", ok ? errno : e);
    }
    for (std::size_t i = 0; i < files.size(); ++i)
      if (std::rename(g_temps[i].c_str(), files[i].first.c_str()) != 0)
        fail_io(files[i].first, "cannot rename the temporary file into place", errno);
    g_temp_count = 0;
  } catch (...) {
    cleanup();
    throw;
  }
}

void write_file_atomically(const std::string& path, const std::string& content) {
  write_files_atomically({{path, content}});
}

bool prepare_output_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  bool created = false;
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) throw InputError(dir + ": exists and is not a directory");
  } else {
    if (!fs::create_directories(dir, ec) || ec)
      throw InputError(dir + ": cannot create the directory (" + (ec ? ec.message() : std::string("unknown")) + ")");
    created = true;
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw InputError(dir + ": directory not writable (" + std::strerror(errno) + ")");
  return created;
}

NewDirGuard::~NewDirGuard() {
  std::error_code ec;
  if (armed_) std::filesystem::remove(dir_, ec);  // (a directory only while empty)
}

std::string file_name_for(const std::string& name) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '-') {
      out += static_cast<char>(c);
    } else {
      out += '_';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (out.empty()) return "_";
  if (out.size() > 180) {
    // FNV-1a of the whole name keeps long names apart after the cut.
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : name) h = (h ^ c) * 1099511628211ull;
    char buf[24];
    std::snprintf(buf, sizeof buf, "_%016llx", static_cast<unsigned long long>(h));
    out = out.substr(0, 160) + "__" + buf;
  }
  return out;
}

std::string printable(const std::string& name, std::size_t max_len) {
  std::string out;
  for (unsigned char c : name) {
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (c < 0x20 || c == 0x7f) out += '?';
    else out += static_cast<char>(c);
  }
  if (out.size() > max_len) out = out.substr(0, max_len > 3 ? max_len - 3 : 0) + "...";
  return out;
}

std::string full(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string Table::str() const {
  std::vector<std::size_t> width(header_.size(), 0);
  auto widen = [&](const std::vector<std::string>& row) {
    for (std::size_t i = 0; i < row.size() && i < width.size(); ++i)
      width[i] = std::max(width[i], row[i].size());
  };
  widen(header_);
  for (const auto& r : rows_) widen(r);
  std::string out;
  auto line = [&](const std::vector<std::string>& row) {
    for (std::size_t i = 0; i < width.size(); ++i) {
      const std::string cell = i < row.size() ? row[i] : "";
      out += cell;
      if (i + 1 < width.size()) out += std::string(width[i] - cell.size() + 2, ' ');
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    out += '\n';
  };
  line(header_);
  std::vector<std::string> rule;
  for (auto w : width) rule.push_back(std::string(w, '-'));
  line(rule);
  for (const auto& r : rows_) line(r);
  return out;
}

Progress::Progress(std::string what, std::size_t total)
    : what_(std::move(what)), total_(total), tty_(::isatty(STDERR_FILENO) == 1), start_(Clock::now()), last_(start_) {}

Progress::~Progress() { finish(); }

void Progress::update(std::size_t done, const std::string& note) {
  const Clock::time_point now = Clock::now();
  if (now - start_ < std::chrono::seconds(1)) return;
  if (shown_ && now - last_ < (tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(10000))) return;
  last_ = now;
  shown_ = true;
  const double s = std::chrono::duration<double>(now - start_).count();
  const std::string text = what_ + ": " + std::to_string(done) + "/" + std::to_string(total_) + " after " +
                           fixed_digits(s, 3) + " s" + (note.empty() ? "" : " (" + printable(note, 40) + ")");
  if (tty_) std::fprintf(stderr, "\r%s\033[K", text.c_str());
  else std::fprintf(stderr, "%s\n", text.c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (shown_ && tty_) std::fprintf(stderr, "\n");
  shown_ = false;
}

}  // namespace revdist::cli
