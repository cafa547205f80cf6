#include "analysis/table.h"

#include <charconv>
#include <fstream>
#include <sstream>
#include <utility>

#include "io/atomic_file.h"
#include "sim/error.h"
#include "sim/format.h"

namespace gs {

std::ptrdiff_t Table::find(std::string_view name) const {
  for (std::size_t j = 0; j < names.size(); ++j)
    if (names[j] == name) return std::ptrdiff_t(j);
  return -1;
}

const std::vector<double>& Table::column(std::string_view name) const {
  const auto j = find(name);
  if (j < 0) throw UserError("table has no column '" + std::string(name) + "'");
  return columns[std::size_t(j)];
}

std::vector<double>& Table::column(std::string_view name) {
  return const_cast<std::vector<double>&>(std::as_const(*this).column(name));
}

void Table::add_column(std::string name, std::vector<double> values) {
  if (name.empty() || name.find_first_of(",\"\r\n") != std::string::npos)
    throw UserError("invalid column name '" + name + "'");
  if (has(name)) throw UserError("duplicate column '" + name + "'");
  if (!columns.empty() && values.size() != rows())
    throw UserError("column '" + name + "' has " + std::to_string(values.size()) +
                    " rows, the table " + std::to_string(rows()));
  names.push_back(std::move(name));
  columns.push_back(std::move(values));
}

void Table::add_row(std::span<const double> row) {
  GS_CHECK_MSG(row.size() == columns.size(), "row length differs from the number of columns");
  for (std::size_t j = 0; j < row.size(); ++j) columns[j].push_back(row[j]);
}

std::string to_csv(const Table& table) {
  GS_CHECK(table.names.size() == table.columns.size());
  std::string out;
  for (std::size_t j = 0; j < table.names.size(); ++j) {
    if (j) out += ',';
    out += table.names[j];
  }
  out += '\n';
  for (std::size_t i = 0; i < table.rows(); ++i) {
    for (std::size_t j = 0; j < table.columns.size(); ++j) {
      GS_CHECK(table.columns[j].size() == table.rows());
      if (j) out += ',';
      out += format_double(table.columns[j][i]);
    }
    out += '\n';
  }
  return out;
}

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace

Table parse_csv(std::string_view text, const std::string& source) {
  Table table;
  std::size_t line_no = 0;
  bool header = true;
  while (!text.empty()) {
    const auto nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
    ++line_no;
    const std::string where = source + ":" + std::to_string(line_no) + ": ";
    if (trim(line).empty()) continue;
    const auto fields = split(line);
    if (header) {
      for (auto f : fields) {
        try {
          table.add_column(std::string(f), {});
        } catch (const UserError& e) {
          throw UserError(where + e.what());
        }
      }
      header = false;
      continue;
    }
    if (fields.size() != table.names.size())
      throw UserError(where + "expected " + std::to_string(table.names.size()) + " fields, got " +
                      std::to_string(fields.size()));
    for (std::size_t j = 0; j < fields.size(); ++j) {
      double x = 0;
      const auto f = fields[j];
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), x);
      if (ec != std::errc() || end != f.data() + f.size() || f.empty())
        throw UserError(where + "column '" + table.names[j] + "': not a number '" + std::string(f) +
                        "'");
      table.columns[j].push_back(x);
    }
  }
  if (header) throw UserError(source + ": empty file, expected a CSV header line");
  return table;
}

void write_csv(const Table& table, const std::filesystem::path& path) {
  write_file_atomic(path, to_csv(table));
}

Table read_csv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError("cannot read " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse_csv(text.str(), path.string());
}

}  // namespace gs
