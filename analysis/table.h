#pragma once
// A time-series table: named columns of doubles, read from and written to CSV with a header line
// (the format of timeseries.csv in docs/formats.md). Numbers are written with format_double, the
// shortest text that reads back to the same double, so a write/read round trip is exact.
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gs {

struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  // columns[j][i]: row i of column names[j]

  std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
  // Index of the column, or -1.
  std::ptrdiff_t find(std::string_view name) const;
  bool has(std::string_view name) const { return find(name) >= 0; }
  // UserError naming the column if it is absent.
  const std::vector<double>& column(std::string_view name) const;
  std::vector<double>& column(std::string_view name);
  // UserError if the name is taken, empty or holds a comma, quote or line break, or if the
  // length differs from the rows already there.
  void add_column(std::string name, std::vector<double> values);
  // One value per column, in column order.
  void add_row(std::span<const double> row);
};

std::string to_csv(const Table& table);
// `source` names the input in error messages ("file:line: ...").
Table parse_csv(std::string_view text, const std::string& source);

// UserError naming the path if it cannot be read or written.
void write_csv(const Table& table, const std::filesystem::path& path);
Table read_csv(const std::filesystem::path& path);

}  // namespace gs
