#include "io/xyz.h"

#include "io/particle_types.h"
#include <algorithm>
#include <charconv>
#include <cmath>
#include <exception>
#include <map>
#include <thread>
#include <vector>

#include "io/atomic_file.h"
#include "io/atomic_masses.h"
#include "io/particle_types.h"
#include "io/text_scan.h"
#include "sim/error.h"
#include "sim/format.h"
#include "sim/stop.h"

namespace gs {
namespace {

// A frame's byte ranges, found by the opening scan.
struct FrameSpan {
  std::size_t count_line = 0;  // line number of the count line
  std::size_t comment = 0, body = 0, end = 0;
  std::uint64_t n = 0;
};

// Where each token of a particle line goes.
struct Slot {
  enum Kind : std::uint8_t { Skip, Pos, Vel, Momentum, Mass, Radius, Active, First, Extra, Species };
  Kind kind = Skip;
  char type = 'R';
  std::uint32_t index = 0;  // component, or the extra column
};

// What a frame's Properties say: a slot per token of a particle line, and which fields exist.
struct Layout {
  std::vector<Slot> slots;
  std::vector<std::string> extra;  // names of the extra columns, in slot order
  int pos_count = 0;
  std::string pos_name, radius_name;  // as the file spells them, for messages
  int z_column = -1;  // the extra column holding ASE's atomic numbers Z, if any
  bool has_species = false;
  bool has_vel = false, has_mom = false, has_mass = false, has_radius = false, has_active = false,
       has_first = false;
  bool velocity() const { return has_vel || has_mom; }
};

struct Header {
  std::string properties = "species:S:1:pos:R:3";
  bool lattice = false;
  double cell[9] = {};
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  bool pbc_given = false, pbc[3] = {true, true, true};
  int dim = 0;  // stated by Dim, 0 if not
  SnapshotInfo info;
};

class XyzSource final : public FrameSource {
 public:
  explicit XyzSource(MappedFile f);
  std::size_t frames() const override { return frames_.size(); }
  Snapshot read(std::size_t k, const ReadOptions& options) const override;
  const char* format() const override { return "extended XYZ"; }

 private:
  [[noreturn]] void fail(std::size_t line, std::string_view what) const {
    throw_at_line(file_.path(), line, what);
  }
  Header parse_comment(std::string_view s, std::size_t line) const;
  Layout parse_properties(const std::string& properties, std::size_t line,
                          std::size_t max_tokens) const;
  // The box and origin of a rectangular Lattice; true if its third vector is zero.
  bool apply_lattice(const Header& h, SnapshotInfo& info, std::size_t line) const;
  double real(std::string_view tok, std::size_t line, std::string_view name) const {
    return finite_at(file_.path(), line, tok, name);
  }

  MappedFile file_;
  std::vector<FrameSpan> frames_;
};

XyzSource::XyzSource(MappedFile f) : file_(std::move(f)) {
  const std::string_view b = file_.bytes();
  LineCursor c(b);
  std::string_view line;
  while (c.next(line)) {
    if (is_blank(line)) continue;  // between frames and at the end
    throw_if_stopped();  // a file of many frames takes a while to index
    FrameSpan s;
    s.count_line = c.line();
    std::size_t t = 0;
    const std::string_view tok = next_token(line, t);
    if (!parse_integer(tok, s.n) || !is_blank(line.substr(t))) {
      if (frames_.empty())
        fail(s.count_line, "expected the particle count alone on the first line");
      fail(s.count_line, "expected the particle count of frame " + std::to_string(frames_.size()) +
                             " alone on this line (does the count of frame " +
                             std::to_string(frames_.size() - 1) + " match its lines?)");
    }
    s.comment = c.pos();
    if (!c.next(line)) fail(s.count_line + 1, "file ends before the comment line");
    s.body = c.pos();
    const std::size_t found = c.skip(s.n);
    if (found < s.n)
      throw UserError("snapshot '" + file_.path() + "' frame " + std::to_string(frames_.size()) +
                      " is truncated: line " + std::to_string(s.count_line) + " counts " +
                      std::to_string(s.n) + " particles, " + std::to_string(found) +
                      " lines follow the comment");
    s.end = c.pos();
    frames_.push_back(s);
  }
  if (frames_.empty()) throw UserError("snapshot '" + file_.path() + "' is empty");
}

// key=value pairs of the comment line; values may be quoted ("", '') or bracketed ({}, [])
// with spaces inside, and '=' may have spaces around it (ASE accepts both). Bare keys are flags.
Header XyzSource::parse_comment(std::string_view s, std::size_t line) const {
  Header h;
  bool time_given = false;
  std::size_t i = 0;
  auto skip_space = [&] {
    while (i < s.size() && is_space(s[i])) ++i;
  };
  auto value_token = [&]() -> std::string_view {
    if (i < s.size() && (s[i] == '"' || s[i] == '\'' || s[i] == '{' || s[i] == '[')) {
      const char close = s[i] == '{' ? '}' : s[i] == '[' ? ']' : s[i];
      const std::size_t b = ++i;
      const std::size_t e = s.find(close, b);
      if (e == std::string_view::npos) fail(line, "unterminated quote in the comment line");
      i = e + 1;
      return s.substr(b, e - b);
    }
    const std::size_t b = i;
    while (i < s.size() && !is_space(s[i])) ++i;
    return s.substr(b, i - b);
  };
  auto numbers = [&](std::string_view v, double* out, int n, const char* name) {
    std::size_t k = 0;
    int got = 0;
    for (std::string_view t = next_token(v, k); !t.empty(); t = next_token(v, k)) {
      if (got == n) fail(line, std::string(name) + " must have " + std::to_string(n) + " numbers");
      out[got++] = real(t, line, name);
    }
    if (got != n) fail(line, std::string(name) + " must have " + std::to_string(n) + " numbers");
  };
  while (true) {
    skip_space();
    if (i >= s.size()) break;
    const std::size_t kb = i;
    while (i < s.size() && !is_space(s[i]) && s[i] != '=') ++i;
    const std::string_view key = s.substr(kb, i - kb);
    skip_space();
    std::string_view value;
    bool has_value = false;
    if (i < s.size() && s[i] == '=') {
      ++i;
      skip_space();
      value = value_token();
      has_value = true;
    }
    if (!has_value) continue;  // a flag, or words of a free-text comment
    auto num = [&](const char* name) { return real(value, line, name); };
    if (iequals(key, "Lattice")) {
      numbers(value, h.cell, 9, "Lattice");
      h.lattice = true;
    } else if (iequals(key, "Origin") || iequals(key, "cell_origin")) {
      numbers(value, h.origin.data(), 3, "Origin");
    } else if (iequals(key, "Properties")) {
      h.properties = std::string(value);
    } else if (iequals(key, "pbc")) {
      std::size_t k = 0;
      int got = 0;
      bool v[3] = {};
      for (std::string_view t = next_token(value, k); !t.empty(); t = next_token(value, k)) {
        const bool yes = t == "T" || t == "1" || iequals(t, "true");
        if (!yes && !(t == "F" || t == "0" || iequals(t, "false")))
          fail(line, not_a(t, "a logical T/F", "pbc"));
        if (got == 3) fail(line, "pbc must have 3 logicals");
        v[got++] = yes;
      }
      if (got == 1)
        v[1] = v[2] = v[0];
      else if (got != 3)
        fail(line, "pbc must have 3 logicals");
      h.pbc_given = true;
      std::copy(v, v + 3, h.pbc);
    } else if (iequals(key, "Time") || iequals(key, "t") || iequals(key, "sim_time")) {
      h.info.time = num("Time");
      time_given = true;
    } else if (iequals(key, "Timestep") || iequals(key, "step")) {
      std::int64_t step = 0;
      if (!parse_integer(value, step)) fail(line, not_a(value, "an integer", "Timestep"));
      h.info.step = step;
    } else if (iequals(key, "Dim")) {
      if (!parse_integer(value, h.dim) || h.dim < 1 || h.dim > 3)
        fail(line, "Dim must be 1, 2 or 3");
    } else if (iequals(key, "Density")) {
      h.info.density = num("Density");
    } else if (iequals(key, "Restitution")) {
      h.info.restitution = num("Restitution");
    } else if (iequals(key, "Cutoff")) {
      h.info.cutoff = num("Cutoff");
    } else if (iequals(key, "Speed")) {
      h.info.speed = num("Speed");
    } else if (iequals(key, "Seed")) {
      std::uint64_t seed = 0;
      if (!parse_integer(value, seed) || value.starts_with('+'))
        fail(line, not_a(value, "an unsigned integer", "Seed"));
      h.info.seed = seed;
    } else if (iequals(key, "Medium")) {
      if (value != "box" && value != "unbounded")
        fail(line, not_a(value, "box or unbounded", "Medium"));
      h.info.unbounded = value == "unbounded";
    } else if (iequals(key, "Initial")) {
      if (value != "kick" && value != "thermal")
        fail(line, not_a(value, "kick or thermal", "Initial"));
      h.info.kick = value == "kick";
    }
  }
  h.info.has_time = time_given;
  return h;
}

// Components of a vector property in the extra columns' names.
std::string component_name(const std::string& name, int k, int count) {
  if (count == 1) return name;
  if (count <= 3) return name + "_" + "xyz"[k];
  return name + "_" + std::to_string(k);
}

bool logical(std::string_view t, bool& v) {
  if (t == "T" || t == "1" || iequals(t, "true")) return v = true, true;
  if (t == "F" || t == "0" || iequals(t, "false")) return v = false, true;
  return false;
}

Layout XyzSource::parse_properties(const std::string& properties, std::size_t line,
                                   std::size_t max_tokens) const {
  // name:type:count triples, each token of a line mapped to a slot.
  std::vector<std::string_view> parts;
  const std::string_view text = properties;
  for (std::size_t a = 0;;) {
    const std::size_t e = text.find(':', a);
    parts.push_back(text.substr(a, e == std::string_view::npos ? e : e - a));
    if (e == std::string_view::npos) break;
    a = e + 1;
  }
  if (parts.size() % 3 != 0)
    fail(line, "Properties='" + properties.substr(0, 200) + "' is not a list of name:type:count");
  Layout l;
  for (std::size_t p = 0; p < parts.size(); p += 3) {
    const std::string name(parts[p]);
    const std::string_view type = parts[p + 1];
    std::uint32_t count = 0;
    if (type.size() != 1 || std::string_view("SRIL").find(type[0]) == std::string_view::npos)
      fail(line, "property '" + name + "' has unknown type '" + std::string(type) +
                     "' (use S, R, I or L)");
    if (!parse_integer(parts[p + 2], count) || count < 1 || count > max_tokens ||
        l.slots.size() + count > max_tokens)
      fail(line, "property '" + name + "' has count '" + std::string(parts[p + 2]) +
                     "', more columns than the frame's lines can hold");
    const char t = type[0];
    auto add = [&](Slot::Kind kind) {
      for (std::uint32_t c = 0; c < count; ++c) l.slots.push_back({kind, t, c});
    };
    auto need = [&](bool ok, const char* what) {
      if (!ok) fail(line, "property '" + name + "' must be " + what);
    };
    if (iequals(name, "pos") || iequals(name, "positions")) {
      need(t == 'R' && count <= 3 && l.pos_count == 0, "R:1, R:2 or R:3 and given once");
      l.pos_count = static_cast<int>(count);
      l.pos_name = std::string(name);
      add(Slot::Pos);
    } else if (!l.has_vel &&
               (iequals(name, "velo") || iequals(name, "vel") || iequals(name, "velocities"))) {
      need(t == 'R' && count <= 3, "R:1, R:2 or R:3");
      l.has_vel = true;
      add(Slot::Vel);
    } else if (!l.has_mom && iequals(name, "momenta")) {
      need(t == 'R' && count <= 3, "R:1, R:2 or R:3");
      l.has_mom = true;
      add(Slot::Momentum);
    } else if (!l.has_mass && (iequals(name, "masses") || iequals(name, "mass"))) {
      need(t == 'R' && count == 1, "R:1");
      l.has_mass = true;
      add(Slot::Mass);
    } else if (!l.has_radius && (iequals(name, "radius") || iequals(name, "radii"))) {
      need(t == 'R' && count == 1, "R:1");
      l.has_radius = true;
      l.radius_name = std::string(name);
      add(Slot::Radius);
    } else if (!l.has_active && iequals(name, "active")) {
      need((t == 'I' || t == 'L') && count == 1, "I:1 or L:1");
      l.has_active = true;
      add(Slot::Active);
    } else if (!l.has_first && iequals(name, "first_collision")) {
      need(t == 'R' && count == 1, "R:1");
      l.has_first = true;
      add(Slot::First);
    } else if (t == 'S' && count == 1 && !l.has_species &&
               (iequals(name, "species") || iequals(name, "symbols"))) {
      l.has_species = true;  // ASE's element symbols: the masses of momenta without masses
      add(Slot::Species);
    } else if (t == 'S') {
      add(Slot::Skip);  // labels
    } else {
      if ((name == "Z" || name == "numbers") && (t == 'I' || t == 'R') && count == 1)
        l.z_column = static_cast<int>(l.extra.size());
      for (std::uint32_t c = 0; c < count; ++c) {
        l.slots.push_back({Slot::Extra, t, static_cast<std::uint32_t>(l.extra.size())});
        l.extra.push_back(component_name(name, static_cast<int>(c), static_cast<int>(count)));
      }
    }
  }
  if (l.pos_count == 0) fail(line, "Properties has no pos column");
  if (l.has_vel && l.has_mom)  // velo wins; momenta is then an extra column
    for (auto& sl : l.slots)
      if (sl.kind == Slot::Momentum) sl.kind = Slot::Skip;
  return l;
}

bool XyzSource::apply_lattice(const Header& h, SnapshotInfo& info, std::size_t line) const {
  // Rectangular, its vectors in any order along the axes.
  bool zero_third = true;
  bool axis_used[3] = {};
  for (int v = 0; v < 3; ++v) {
    const double* a = h.cell + 3 * v;
    int nonzero = 0, axis = -1;
    for (int c = 0; c < 3; ++c)
      if (a[c] != 0) ++nonzero, axis = c;
    if (nonzero > 1)
      fail(line,
           "the Lattice is triclinic (a cell vector has more than one non-zero component); "
           "only rectangular boxes are supported");
    if (nonzero == 0) continue;
    if (axis_used[axis]) fail(line, "the Lattice has two cell vectors along one axis");
    axis_used[axis] = true;
    if (v == 2) zero_third = false;
    info.box[axis] = std::abs(a[axis]);
    info.origin[axis] = h.origin[axis] + std::min(a[axis], 0.0);
  }
  for (int c = 0; c < 3; ++c)
    if (!axis_used[c]) info.origin[c] = h.origin[c];
  return zero_third;
}

// Divides the momenta by each particle's element mass (ASE's table, io/atomic_masses.h): from
// the Z column when there is one (ASE's reader lets Z win over the species), else the species;
// a name that is no element, X and a file with neither keep mass 1. The log's note lists them.
void divide_by_element_masses(Snapshot& s, const std::vector<std::string_view>& species,
                              const std::vector<double>* z) {
  std::map<std::string, double, std::less<>> seen;  // name -> mass used (1 when none)
  std::string_view last;
  double last_mass = 1;
  for (std::size_t i = 0; i < s.size(); ++i) {
    double m = 1;
    if (z) {
      const double zi = (*z)[i];
      const auto am = zi == std::floor(zi) ? atomic_mass(static_cast<long long>(zi)) : std::nullopt;
      m = am.value_or(1.0);
      if (seen.size() < 200)
        seen.emplace(am ? "Z=" + format_number(zi) + " (" + std::string(element_symbol(
                                                               static_cast<long long>(zi))) + ")"
                        : "Z=" + format_number(zi),
                     m);
    } else if (!species.empty()) {
      if (i > 0 && species[i] == last) {
        m = last_mass;
      } else {
        const auto zs = atomic_number(species[i]);
        m = zs ? atomic_mass(*zs).value_or(1.0) : 1.0;
        last = species[i];
        last_mass = m;
        if (seen.size() < 200) seen.emplace(std::string(species[i]), m);
      }
    }
    if (m != 1) s.velocity[i] /= m;
  }
  // Only X (ASE's dummy element, mass 1 there too, what we write): nothing was assumed.
  if (!seen.empty() && std::all_of(seen.begin(), seen.end(), [](const auto& e) {
        return e.first == "X" || e.first == "x" || e.first == "Z=0";
      }))
    return;
  std::string with, without;
  for (const auto& [name, m] : seen) {
    if (m == 1)
      without += (without.empty() ? "" : ", ") + name;
    else
      with += (with.empty() ? "" : ", ") + name + " " + format_number(m);
  }
  std::string note = "momenta without masses: ";
  if (!with.empty()) note += "masses from the elements (ASE's table, IUPAC 2016): " + with;
  if (!without.empty())
    note += std::string(with.empty() ? "" : "; ") + "mass 1 for " + without + " (no element)";
  if (seen.empty()) note += "mass 1 (no species or Z column)";
  s.notes.push_back(std::move(note));
}

Snapshot XyzSource::read(std::size_t k, const ReadOptions& options) const {
  const FrameSpan& f = frames_[k];
  const std::string_view b = file_.bytes();
  const std::size_t comment_line = f.count_line + 1;
  std::string_view comment = b.substr(f.comment, f.body - f.comment);
  if (!comment.empty() && comment.back() == '\n') comment.remove_suffix(1);
  Header h = parse_comment(comment, comment_line);

  Snapshot s;
  s.info = h.info;
  if (options.unwrap) s.notes.push_back(kNothingToUnwrap);

  // A line has at most one token per 2 bytes, so a count beyond that cannot be right.
  // A frame of no particles has no lines to bound its columns by.
  const std::size_t max_tokens = std::min<std::size_t>(
      f.n == 0 ? std::size_t{1} << 24 : f.end - f.body + 1, std::size_t{1} << 24);
  const Layout l = parse_properties(h.properties, comment_line, max_tokens);
  for (const std::string& name : l.extra) s.columns.push_back({name, {}});
  const bool zero_third = h.lattice ? apply_lattice(h, s.info, comment_line) : true;
  // The dimension as the file states it (0: not stated).
  int stated = h.dim;
  if (stated == 0 && l.pos_count < 3) stated = l.pos_count;
  if (stated == 0 && h.lattice && h.pbc_given && h.pbc[0] && h.pbc[1] && !h.pbc[2] && zero_third)
    stated = 2;
  s.info.dim = stated;

  // Allocation is bounded by the bytes of the frame: every token takes at least two, so more
  // tokens than bytes is a lie told before anything is allocated (short lines are found below).
  const std::uint64_t n = f.n;
  const std::size_t ntok = l.slots.size();
  if (n > 0 && ntok > (f.end - f.body + 1) / n)
    fail(comment_line, "Properties declares " + std::to_string(ntok) + " columns, more than the " +
                           std::to_string(n) + " lines of the frame hold");
  s.position.assign(n, Eigen::Vector3d::Zero());
  if (l.velocity()) s.velocity.assign(n, Eigen::Vector3d::Zero());
  if (l.has_radius) s.radius.resize(n);
  if (l.has_active) s.active.resize(n);
  if (l.has_first) s.first_collision.resize(n);
  std::vector<double> mass;
  if (l.has_mom && !l.has_vel && l.has_mass) mass.resize(n);
  // Momenta without masses: ASE's rule, each mass from the element (Z if given, else species).
  const bool element_masses = l.has_mom && !l.has_vel && !l.has_mass;
  std::vector<std::string_view> species;
  if (l.has_species) species.resize(n);  // the types, and the masses of momenta
  for (auto& c : s.columns) c.values.resize(n);
  const int check_from = stated > 0 && stated < 3 ? stated : 3;

  // The arrays as plain pointers: the byte stores of `active` may alias anything, and would
  // otherwise make every token reload the vectors' and the layout's data pointers.
  const Slot* const slots = l.slots.data();
  Eigen::Vector3d* const position = s.position.data();
  Eigen::Vector3d* const velocity = s.velocity.data();
  scan_rows(
      b.substr(f.body, f.end - f.body), n, ntok, f.count_line + 2, file_.path(),
      [&, slots, position, velocity](std::size_t i, std::size_t t, std::string_view tok,
                                     std::size_t line_no) {
        const Slot& sl = slots[t];
        switch (sl.kind) {
          case Slot::Skip:
            break;
          case Slot::Species:
            if (!species.empty()) species[i] = tok;  // a view into the mapped file
            break;
          case Slot::Pos:
            position[i][sl.index] = real(tok, line_no, "pos");
            break;
          case Slot::Vel:
            velocity[i][sl.index] = real(tok, line_no, "velo");
            break;
          case Slot::Momentum:
            velocity[i][sl.index] = real(tok, line_no, "momenta");
            break;
          case Slot::Mass: {
            const double m = real(tok, line_no, "masses");
            if (!(m > 0)) fail(line_no, "masses must be positive");
            if (!mass.empty()) mass[i] = m;
            break;
          }
          case Slot::Radius:
            s.radius[i] = real(tok, line_no, "radius");
            if (!(s.radius[i] > 0)) fail(line_no, "radius must be positive");
            break;
          case Slot::Active: {
            bool v = false;
            long long iv = 0;
            if (sl.type == 'L' ? !logical(tok, v) : !parse_integer(tok, iv))
              fail(line_no, not_a(tok, sl.type == 'L' ? "a logical T/F" : "an integer", "active"));
            s.active[i] = sl.type == 'L' ? v : iv != 0;
            break;
          }
          case Slot::First:
            s.first_collision[i] = real(tok, line_no, "first_collision");
            break;
          case Slot::Extra: {
            double v = 0;
            bool lv = false;
            long long iv = 0;
            const auto& name = s.columns[sl.index].name;
            if (sl.type == 'R') {
              if (!parse_real(tok, v)) fail(line_no, not_a(tok, "a number", name));
            } else if (sl.type == 'I') {
              if (!parse_integer(tok, iv)) fail(line_no, not_a(tok, "an integer", name));
              v = static_cast<double>(iv);
            } else {
              if (!logical(tok, lv)) fail(line_no, not_a(tok, "a logical T/F", name));
              v = lv;
            }
            s.columns[sl.index].values[i] = v;
            break;
          }
        }
      },
      [&](std::size_t i, std::size_t line_no) {
        for (int c = check_from; c < 3; ++c)
          if (s.position[i][c] != 0 || (l.velocity() && s.velocity[i][c] != 0))
            fail(line_no,
                 "the file is " + std::to_string(stated) + "D but a component beyond it is not 0");
      },
      true);
  if (!mass.empty())
    for (std::size_t i = 0; i < n; ++i) s.velocity[i] /= mass[i];
  if (element_masses && n > 0)
    divide_by_element_masses(s, l.z_column < 0 ? species : std::vector<std::string_view>{},
                             l.z_column < 0 ? nullptr : &s.columns[l.z_column].values);
  // Species are types, but for our own files' "X" (ASE's dummy element: no element at all).
  if (!species.empty() &&
      std::any_of(species.begin(), species.end(), [](std::string_view v) { return v != "X"; }))
    assign_types(s, species);
  check_extent(s, file_.path(), k, {l.pos_name, l.pos_name, l.pos_name}, l.radius_name);
  return s;
}

void append_number(std::string& out, double x) {
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, end);
}

// Appends particle lines [begin, end) of the file to `out`, numbers in shortest round-trip form.
void append_particle_lines(std::string& out, const Snapshot& s, std::size_t begin, std::size_t end,
                           int pos_count, const std::vector<const Column*>& extra) {
  out.reserve(out.size() + (end - begin) * (32 + 20 * pos_count * (s.has_velocity() ? 2 : 1)));
  char buf[32];
  auto num = [&](double x) {
    out += ' ';
    const auto [e, ec] = std::to_chars(buf, buf + sizeof buf, x);
    out.append(buf, e);
  };
  for (std::size_t i = begin; i < end; ++i) {
    out += 'X';  // ASE's dummy element (mass 1): readers that map species to elements accept it
    for (int k = 0; k < pos_count; ++k) num(s.position[i][k]);
    if (s.has_velocity())
      for (int k = 0; k < pos_count; ++k) num(s.velocity[i][k]);
    num(s.radius[i]);
    out += s.active[i] ? " 1" : " 0";
    if (!s.first_collision.empty()) num(s.first_collision[i]);
    for (const Column* c : extra) num(c->values[i]);
    out += '\n';
  }
}

}  // namespace

std::unique_ptr<FrameSource> open_xyz(MappedFile file) {
  return std::make_unique<XyzSource>(std::move(file));
}

namespace {

// A frame's text in two pieces (its second half formatted on a second thread).
std::pair<std::string, std::string> xyz_pieces(const Snapshot& s, XyzFlavour flavour) {
  const std::size_t n = s.size();
  const int dim = s.info.dim;
  GS_CHECK(dim >= 1 && dim <= 3);
  GS_CHECK(s.velocity.empty() || s.velocity.size() == n);
  GS_CHECK(s.radius.size() == n && s.active.size() == n);
  GS_CHECK(s.first_collision.empty() || s.first_collision.size() == n);
  const bool ovito = flavour == XyzFlavour::Ovito;
  const int pos_count = ovito ? dim : 3;

  std::string head = std::to_string(n);
  // OVITO takes a cell only when all three vectors are non-zero: the axes beyond the dimension
  // get a unit edge (one diameter), not periodic (pbc F), which ASE keeps as the cell too.
  head += "\nLattice=\"";
  for (int k = 0; k < 9; ++k) {
    if (k) head += ' ';
    if (k % 4 == 0)
      append_number(head, k / 4 < dim && s.info.box[k / 4] > 0 ? s.info.box[k / 4] : 1.0);
    else
      head += '0';
  }
  head += '"';
  if (s.info.origin != Eigen::Vector3d::Zero()) {
    head += " Origin=\"";
    for (int k = 0; k < 3; ++k) {
      if (k) head += ' ';
      append_number(head, s.info.origin[k]);
    }
    head += '"';
  }
  const std::string count = std::to_string(pos_count);
  head += " Properties=species:S:1:pos:R:" + count;
  // ASE's get_velocities() divides its momenta by the masses (1 for X); OVITO maps velo.
  if (s.has_velocity()) head += (ovito ? ":velo:R:" : ":momenta:R:") + count;
  head += ":radius:R:1:active:I:1";
  if (!s.first_collision.empty()) head += ":first_collision:R:1";
  std::vector<const Column*> extra;
  for (const auto& c : s.columns) {
    GS_CHECK(c.values.size() == n);
    std::string name = c.name;  // a property name is one token without ':'
    for (char& ch : name)
      if (ch == ':' || is_space(ch) || ch == '"') ch = '_';
    head += ":" + name + ":R:1";
    extra.push_back(&c);
  }
  if (s.info.has_time) {
    head += " Time=";
    append_number(head, s.info.time);
  }
  head += dim == 3 ? " pbc=\"T T T\"" : dim == 2 ? " pbc=\"T T F\"" : " pbc=\"T F F\"";
  head += " Dim=" + std::to_string(dim);
  auto opt = [&](const char* key, const std::optional<double>& v) {
    if (!v) return;
    head += ' ';
    head += key;
    head += '=';
    append_number(head, *v);
  };
  if (s.info.step) head += " Timestep=" + std::to_string(*s.info.step);
  opt("Density", s.info.density);
  opt("Restitution", s.info.restitution);
  opt("Cutoff", s.info.cutoff);
  opt("Speed", s.info.speed);
  if (s.info.seed) head += " Seed=" + std::to_string(*s.info.seed);
  if (s.info.unbounded) head += " Medium=unbounded";
  if (s.info.kick) head += " Initial=kick";
  head += '\n';

  // Formatting the numbers is the cost: two threads format halves of the particles (the machine
  // has two cores), then the pieces go out in order.
  const std::size_t half = n > 100000 ? n / 2 : n;
  std::string second;
  std::exception_ptr failed;
  std::thread helper;
  if (half < n)
    helper = std::thread([&] {
      try {
        append_particle_lines(second, s, half, n, pos_count, extra);
      } catch (...) {  // bad_alloc: rethrown below, not std::terminate
        failed = std::current_exception();
      }
    });
  std::string out = std::move(head);
  try {
    append_particle_lines(out, s, 0, half, pos_count, extra);
  } catch (...) {
    if (helper.joinable()) helper.join();
    throw;
  }
  if (helper.joinable()) helper.join();
  if (failed) std::rethrow_exception(failed);
  return {std::move(out), std::move(second)};
}

}  // namespace

void write_xyz(const std::string& path, const Snapshot& s, XyzFlavour flavour) {
  const auto [first, second] = xyz_pieces(s, flavour);
  write_file_atomic(path, {first, second});
}

namespace {

class XyzTrajectory final : public TrajectoryWriter {
 public:
  XyzTrajectory(const std::string& path, XyzFlavour flavour) : flavour_(flavour) {
    file_.open(path);
  }
  void add(const Snapshot& s) override {
    const auto [first, second] = xyz_pieces(s, flavour_);
    file_.write(first);
    file_.write(second);
  }
  void finish() override { file_.finish(); }

 private:
  XyzFlavour flavour_;
  AtomicFileWriter file_;
};

}  // namespace

std::unique_ptr<TrajectoryWriter> open_xyz_trajectory(const std::string& path,
                                                      XyzFlavour flavour) {
  return std::make_unique<XyzTrajectory>(path, flavour);
}

}  // namespace gs
