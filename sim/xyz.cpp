#include "sim/xyz.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>

#include "sim/atomic_file.h"
#include "sim/error.h"

namespace gs {
namespace {

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

// Appending instead of chaining operator+ avoids GCC 12's false -Wrestrict on short literals.
std::string not_a(std::string_view tok, const char* kind, std::string_view name) {
  std::string m = "'";
  m.append(tok).append("' is not ").append(kind).append(" (").append(name).append(")");
  return m;
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    std::size_t j = i;
    while (j < s.size() && !is_space(s[j])) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// Errors carry "file:line:" so a user can open the file at the offending place.
class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}
  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw UserError("snapshot '" + path_ + "' line " + std::to_string(line) + ": " + what);
  }
  double real(std::string_view tok, std::size_t line, std::string_view name) const {
    double v = 0;
    auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc() || p != tok.data() + tok.size() || !std::isfinite(v))
      fail(line, not_a(tok, "a finite number", name));
    return v;
  }
  long long integer(std::string_view tok, std::size_t line, std::string_view name) const {
    long long v = 0;
    auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc() || p != tok.data() + tok.size())
      fail(line, not_a(tok, "an integer", name));
    return v;
  }
  bool logical(std::string_view tok, std::size_t line, std::string_view name) const {
    if (tok == "T" || iequals(tok, "true") || tok == "1") return true;
    if (tok == "F" || iequals(tok, "false") || tok == "0") return false;
    fail(line, not_a(tok, "a logical T/F", name));
  }

 private:
  std::string path_;
};

// key=value pairs of the comment line; values may be "quoted with spaces". Bare keys are flags.
std::vector<std::pair<std::string, std::string>> parse_comment(std::string_view s,
                                                               const Reader& r) {
  std::vector<std::pair<std::string, std::string>> kv;
  std::size_t i = 0;
  auto token = [&](bool stop_at_eq) {
    std::string out;
    if (i < s.size() && (s[i] == '"' || s[i] == '\'')) {
      const char q = s[i++];
      const std::size_t end = s.find(q, i);
      if (end == std::string_view::npos) r.fail(2, "unterminated quote in the comment line");
      out = std::string(s.substr(i, end - i));
      i = end + 1;
      return out;
    }
    while (i < s.size() && !is_space(s[i]) && !(stop_at_eq && s[i] == '=')) out += s[i++];
    return out;
  };
  while (true) {
    while (i < s.size() && is_space(s[i])) ++i;
    if (i >= s.size()) break;
    std::string key = token(true);
    std::string value;
    if (i < s.size() && s[i] == '=') {
      ++i;
      value = token(false);
    }
    if (key.empty()) r.fail(2, "malformed key=value pair in the comment line");
    kv.emplace_back(std::move(key), std::move(value));
  }
  return kv;
}

struct Column {
  std::string name;
  char type = 'R';
  int count = 1;
  int first = 0;  // index of its first token on a particle line
};

std::vector<Column> parse_properties(const std::string& spec, const Reader& r) {
  std::vector<Column> cols;
  std::vector<std::string> parts;
  std::stringstream ss(spec);
  for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
  if (parts.size() % 3 != 0 || parts.empty())
    r.fail(2, "Properties='" + spec + "' is not a list of name:type:count");
  int first = 0;
  for (std::size_t k = 0; k < parts.size(); k += 3) {
    Column c;
    c.name = parts[k];
    if (parts[k + 1].size() != 1 ||
        std::string_view("SRIL").find(parts[k + 1][0]) == std::string_view::npos)
      r.fail(2, "property '" + c.name + "' has unknown type '" + parts[k + 1] + "'");
    c.type = parts[k + 1][0];
    c.count = static_cast<int>(r.integer(parts[k + 2], 2, "property count"));
    if (c.count < 1) r.fail(2, "property '" + c.name + "' has count " + parts[k + 2]);
    c.first = first;
    first += c.count;
    cols.push_back(c);
  }
  return cols;
}

const Column* find_column(const std::vector<Column>& cols,
                          std::initializer_list<const char*> names) {
  for (const auto& c : cols)
    for (const char* n : names)
      if (iequals(c.name, n)) return &c;
  return nullptr;
}

void append_number(std::string& out, double x) {
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, end);
}

}  // namespace

Snapshot read_xyz(const std::string& path) {
  const Reader r(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError("cannot open snapshot '" + path + "'");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw UserError("cannot read snapshot '" + path + "'");

  std::size_t pos = 0, line_no = 0;
  auto next_line = [&](std::string_view& line) {
    if (pos >= text.size()) return false;
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    line = std::string_view(text).substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    return true;
  };

  std::string_view line;
  if (!next_line(line)) throw UserError("snapshot '" + path + "' is empty");
  const auto count_tok = split_ws(line);
  if (count_tok.size() != 1) r.fail(1, "expected the particle count alone on the first line");
  const long long n = r.integer(count_tok[0], 1, "particle count");
  if (n < 0) r.fail(1, "negative particle count");
  if (!next_line(line)) r.fail(2, "file ends before the comment line");

  Snapshot s;
  s.info.dim = 3;
  std::string properties = "species:S:1:pos:R:3";
  for (const auto& [key, value] : parse_comment(line, r)) {
    auto num = [&](const char* name) { return r.real(value, 2, name); };
    if (iequals(key, "Lattice")) {
      const auto t = split_ws(value);
      if (t.size() != 9) r.fail(2, "Lattice must have 9 numbers");
      s.info.box = r.real(t[0], 2, "Lattice");
      if (s.info.box <= 0) r.fail(2, "Lattice side must be positive");
    } else if (iequals(key, "Properties")) {
      properties = value;
    } else if (iequals(key, "Time")) {
      s.info.time = num("Time");
    } else if (iequals(key, "Dim")) {
      const long long d = r.integer(value, 2, "Dim");
      if (d < 1 || d > 3) r.fail(2, "Dim must be 1, 2 or 3");
      s.info.dim = static_cast<int>(d);
    } else if (iequals(key, "Density")) {
      s.info.density = num("Density");
    } else if (iequals(key, "Restitution")) {
      s.info.restitution = num("Restitution");
    } else if (iequals(key, "Cutoff")) {
      s.info.cutoff = num("Cutoff");
    } else if (iequals(key, "Speed")) {
      s.info.speed = num("Speed");
    } else if (iequals(key, "Seed")) {
      std::uint64_t seed = 0;
      auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), seed);
      if (ec != std::errc() || p != value.data() + value.size())
        r.fail(2, "Seed '" + value + "' is not an unsigned integer");
      s.info.seed = seed;
    }
  }
  const auto cols = parse_properties(properties, r);
  const Column* c_pos = find_column(cols, {"pos", "positions"});
  const Column* c_vel = find_column(cols, {"velo", "vel", "velocities"});
  const Column* c_rad = find_column(cols, {"radius", "radii"});
  const Column* c_act = find_column(cols, {"active"});
  const Column* c_first = find_column(cols, {"first_collision"});
  if (!c_pos || c_pos->type != 'R' || c_pos->count != 3) r.fail(2, "Properties needs pos:R:3");
  if (c_vel && (c_vel->type != 'R' || c_vel->count != 3)) r.fail(2, "velo must be R:3");
  if (c_rad && (c_rad->type != 'R' || c_rad->count != 1)) r.fail(2, "radius must be R:1");
  if (c_act && ((c_act->type != 'I' && c_act->type != 'L') || c_act->count != 1))
    r.fail(2, "active must be I:1 or L:1");
  if (c_first && (c_first->type != 'R' || c_first->count != 1))
    r.fail(2, "first_collision must be R:1");
  const std::size_t ntok = static_cast<std::size_t>(cols.back().first + cols.back().count);

  const auto un = static_cast<std::size_t>(n);
  s.position.resize(un);
  if (c_vel) s.velocity.resize(un);
  s.radius.assign(un, 0.5);
  s.active.assign(un, 1);  // a hand-written file without the column shows every particle
  if (c_first) s.first_collision.resize(un);

  std::vector<std::string_view> tok;
  for (std::size_t i = 0; i < un; ++i) {
    if (!next_line(line))
      throw UserError("snapshot '" + path + "' is truncated: expected " + std::to_string(n) +
                      " particle lines, found " + std::to_string(i));
    tok = split_ws(line);
    if (tok.size() != ntok)
      r.fail(line_no,
             "expected " + std::to_string(ntok) + " columns, found " + std::to_string(tok.size()));
    for (int k = 0; k < 3; ++k) s.position[i][k] = r.real(tok[c_pos->first + k], line_no, "pos");
    if (c_vel)
      for (int k = 0; k < 3; ++k) s.velocity[i][k] = r.real(tok[c_vel->first + k], line_no, "velo");
    if (c_rad) {
      s.radius[i] = r.real(tok[c_rad->first], line_no, "radius");
      if (s.radius[i] <= 0) r.fail(line_no, "radius must be positive");
    }
    if (c_act)
      s.active[i] = c_act->type == 'L' ? r.logical(tok[c_act->first], line_no, "active")
                                       : r.integer(tok[c_act->first], line_no, "active") != 0;
    if (c_first) s.first_collision[i] = r.real(tok[c_first->first], line_no, "first_collision");
    for (int k = s.info.dim; k < 3; ++k)
      if (s.position[i][k] != 0 || (c_vel && s.velocity[i][k] != 0))
        r.fail(line_no,
               "Dim=" + std::to_string(s.info.dim) + " but a component beyond it is not 0");
  }
  return s;
}

void write_xyz(const std::string& path, const Snapshot& s) {
  const std::size_t n = s.size();
  GS_CHECK(s.velocity.empty() || s.velocity.size() == n);
  GS_CHECK(s.radius.size() == n && s.active.size() == n);
  GS_CHECK(s.first_collision.empty() || s.first_collision.size() == n);

  std::string out;
  out.reserve(64 + n * (s.has_velocity() ? 120 : 60));
  out += std::to_string(n);
  out += "\nLattice=\"";
  for (int k = 0; k < 9; ++k) {
    if (k) out += ' ';
    if (k % 4 == 0)
      append_number(out, s.info.box);
    else
      out += '0';
  }
  out += "\" Properties=species:S:1:pos:R:3";
  if (s.has_velocity()) out += ":velo:R:3";
  out += ":radius:R:1:active:I:1";
  if (!s.first_collision.empty()) out += ":first_collision:R:1";
  out += " Time=";
  append_number(out, s.info.time);
  out += " pbc=\"T T T\" Dim=" + std::to_string(s.info.dim);
  auto opt = [&](const char* key, const std::optional<double>& v) {
    if (!v) return;
    out += ' ';
    out += key;
    out += '=';
    append_number(out, *v);
  };
  opt("Density", s.info.density);
  opt("Restitution", s.info.restitution);
  opt("Cutoff", s.info.cutoff);
  opt("Speed", s.info.speed);
  if (s.info.seed) out += " Seed=" + std::to_string(*s.info.seed);
  out += '\n';
  for (std::size_t i = 0; i < n; ++i) {
    out += 'X';  // ASE's dummy element: readers that map species to elements accept it
    for (int k = 0; k < 3; ++k) out += ' ', append_number(out, s.position[i][k]);
    if (s.has_velocity())
      for (int k = 0; k < 3; ++k) out += ' ', append_number(out, s.velocity[i][k]);
    out += ' ';
    append_number(out, s.radius[i]);
    out += s.active[i] ? " 1" : " 0";
    if (!s.first_collision.empty()) out += ' ', append_number(out, s.first_collision[i]);
    out += '\n';
  }

  write_file_atomic(path, out);
}

}  // namespace gs
