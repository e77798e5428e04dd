// Output helpers shared by the subcommands: whole-or-nothing file writes,
// full-precision number formatting, aligned text tables.
#pragma once
#include <string>
#include <vector>

namespace revdist::cli {

// Writes content to path via a temporary file and a rename, so the file is
// written whole or not at all. Throws std::runtime_error on failure.
void write_file_atomically(const std::string& path, const std::string& content);

// %.17g: enough digits that the double reads back exactly.
std::string full(double v);
// %.*g with the given significant digits, for tables.
std::string fixed_digits(double v, int digits);

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

}  // namespace revdist::cli
