// Output helpers shared by the subcommands: whole-or-nothing file writes,
// full-precision number formatting, aligned text tables, progress on stderr.
#pragma once
#include <chrono>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/format.h"

namespace revdist::cli {

// A run that could not do its job for a reason that is neither the input's nor
// a bug: an output that could not be written (no space left, an I/O error, a
// closed pipe), queries left without a finite bracket. One line, exit 1.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes a set of files whole or not at all (SPEC section 5): every content goes to a
// temporary opened exclusively (O_CREAT | O_EXCL, so a planted symlink or file is never
// followed) in the target's own directory; only when all are written and synced are
// they renamed into place. On failure, or on SIGINT / SIGTERM / SIGHUP / SIGPIPE while
// writing, the temporaries are removed. An unusable target (a file where a directory is
// expected, a read-only or special directory) is an InputError (exit 2); other I/O
// failures are RunError (exit 1).
void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& path_and_content);
void write_file_atomically(const std::string& path, const std::string& content);

// Creates dir (and parents) if needed; InputError naming it when it cannot be a
// directory we can write into. Returns true when it was created here.
bool prepare_output_dir(const std::string& dir);

// An output directory made by this run (prepare_output_dir returned true) is
// removed again, if still empty, unless keep() is called: a run refused or
// failed after making it leaves nothing behind.
class NewDirGuard {
 public:
  NewDirGuard(std::string dir, bool created) : dir_(std::move(dir)), armed_(created) {}
  NewDirGuard(const NewDirGuard&) = delete;
  NewDirGuard& operator=(const NewDirGuard&) = delete;
  ~NewDirGuard();
  void keep() { armed_ = false; }

 private:
  std::string dir_;
  bool armed_;
};

// An injective file name for any solid name: [A-Za-z0-9-] kept, every other byte
// (including '_') written as _XX, so "a.b", "a_b" and "a b" stay distinct; very long
// names are cut and keep a hash of the whole name.
std::string file_name_for(const std::string& name);

// Name cell for tables: control characters escaped, cut to max_len with "...".
std::string printable(const std::string& name, std::size_t max_len = 1000);

// %.17g: enough digits that the double reads back exactly.
std::string full(double v);
// (fixed_digits, digits_down, digits_up: core/format.h.)

// A plain text table: a header row and rows of cells, columns aligned.
class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  std::string str() const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

// Progress on stderr for work longer than about a second (SPEC section 5): nothing before
// 1 s; then on a terminal one line rewritten with \r at most 10 times a second, and
// elsewhere (a log file, a pipe) a plain line at most every 10 s.
class Progress {
 public:
  Progress(std::string what, std::size_t total);
  ~Progress();
  void update(std::size_t done, const std::string& note = "");
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_;
  std::size_t total_;
  bool tty_;
  bool shown_ = false;
  Clock::time_point start_, last_;
};

}  // namespace revdist::cli
