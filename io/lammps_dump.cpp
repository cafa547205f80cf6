#include "io/lammps_dump.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "io/particle_types.h"
#include "io/text_scan.h"
#include "sim/error.h"
#include "sim/escaped.h"
#include "sim/stop.h"

namespace gs {
namespace {

struct DumpFrame {
  std::size_t first_line = 0, atoms_line = 0;
  std::int64_t step = 0;
  std::optional<double> time;
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  std::string_view columns;  // the names after ITEM: ATOMS
  std::size_t body = 0, end = 0;
  std::uint64_t n = 0;
};

// How a column's value is used.
struct Slot {
  enum Kind : std::uint8_t { Skip, Pos, Scaled, Image, Vel, Radius, Diameter, Extra };
  Kind kind = Skip;
  std::uint8_t axis = 0;
  std::uint32_t extra = 0;
};

class DumpSource final : public FrameSource {
 public:
  explicit DumpSource(MappedFile f);
  std::size_t frames() const override { return frames_.size(); }
  Snapshot read(std::size_t k, const ReadOptions& options) const override;
  const char* format() const override { return "LAMMPS dump"; }

 private:
  [[noreturn]] void fail(std::size_t line, std::string_view what) const {
    throw_at_line(file_.path(), line, what);
  }
  double real(std::string_view tok, std::size_t line, std::string_view name) const {
    return finite_at(file_.path(), line, tok, name);
  }

  MappedFile file_;
  std::vector<DumpFrame> frames_;
};

// "ITEM: NAME rest" -> NAME rest, trimmed; nullopt if the line is no ITEM line.
std::optional<std::string_view> item_of(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && is_space(line[i])) ++i;
  line.remove_prefix(i);
  if (!line.starts_with("ITEM:")) return std::nullopt;
  line.remove_prefix(5);
  while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
  while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
  return line;
}

DumpSource::DumpSource(MappedFile f) : file_(std::move(f)) {
  const std::string_view b = file_.bytes();
  LineCursor c(b);
  std::string_view line;
  while (c.next(line)) {
    if (is_blank(line)) continue;
    throw_if_stopped();  // a file of many frames takes a while to index
    DumpFrame fr;
    fr.first_line = c.line();
    const std::string frame_name = "frame " + std::to_string(frames_.size());
    bool have_step = false, have_n = false, have_box = false;
    auto value_line = [&](std::string_view item) {
      std::string_view v;
      if (!c.next(v)) fail(c.line() + 1, "file ends after ITEM: " + std::string(item));
      return v;
    };
    auto single = [&](std::string_view item) {
      const std::string_view v = value_line(item);
      std::size_t t = 0;
      const std::string_view tok = next_token(v, t);
      if (!is_blank(v.substr(t)))
        fail(c.line(), "expected one value after ITEM: " + std::string(item));
      return tok;
    };
    std::optional<std::string_view> item = item_of(line);
    while (true) {
      if (!item) {
        if (frames_.empty() || fr.first_line != c.line()) fail(c.line(), "expected an ITEM: line");
        fail(c.line(), "expected ITEM: TIMESTEP of " + frame_name +
                           " (does NUMBER OF ATOMS of frame " + std::to_string(frames_.size() - 1) +
                           " match its lines?)");
      }
      const std::string_view it = *item;
      if (it == "TIMESTEP") {
        const auto tok = single(it);
        if (!parse_integer(tok, fr.step)) fail(c.line(), not_a(tok, "an integer", "TIMESTEP"));
        have_step = true;
      } else if (it == "TIME") {
        fr.time = real(single(it), c.line(), "TIME");
      } else if (it == "UNITS") {
        value_line(it);
      } else if (it == "NUMBER OF ATOMS") {
        const auto tok = single(it);
        if (!parse_integer(tok, fr.n)) fail(c.line(), not_a(tok, "a count", "NUMBER OF ATOMS"));
        have_n = true;
      } else if (it.starts_with("BOX BOUNDS")) {
        const bool general = it.find("abc") != std::string_view::npos;
        const bool tilted = it.find("xy") != std::string_view::npos;
        if (general)
          fail(c.line(),
               "a general triclinic box (BOX BOUNDS abc origin) is not supported; "
               "only rectangular boxes are");
        for (int k = 0; k < 3; ++k) {
          const std::string_view v = value_line(it);
          std::size_t t = 0;
          const auto lo = next_token(v, t), hi = next_token(v, t),
                     tilt = tilted ? next_token(v, t) : std::string_view();
          if (hi.empty() || (tilted && tilt.empty()) || !is_blank(v.substr(t)))
            fail(c.line(),
                 std::string("expected ") + (tilted ? "lo hi tilt" : "lo hi") + " of the box");
          fr.lo[k] = real(lo, c.line(), "BOX BOUNDS");
          fr.hi[k] = real(hi, c.line(), "BOX BOUNDS");
          if (fr.hi[k] < fr.lo[k]) fail(c.line(), "BOX BOUNDS has hi < lo");
          if (tilted && real(tilt, c.line(), "tilt") != 0)
            fail(c.line(),
                 "the box is triclinic (non-zero tilt); only rectangular boxes are "
                 "supported");
        }
        have_box = true;
      } else if (it.starts_with("ATOMS")) {
        fr.atoms_line = c.line();
        const char* missing = !have_step  ? "TIMESTEP"
                              : !have_n   ? "NUMBER OF ATOMS"
                              : !have_box ? "BOX BOUNDS"
                                          : nullptr;
        if (missing)
          fail(c.line(), frame_name + " has no ITEM: " + missing + " before ITEM: ATOMS");
        fr.columns = it.substr(5);
        if (is_blank(fr.columns)) fail(c.line(), "ITEM: ATOMS names no columns");
        fr.body = c.pos();
        const std::size_t found = c.skip(fr.n);
        if (found < fr.n)
          throw UserError("snapshot '" + file_.path() + "' " + frame_name +
                          " is truncated: " + "NUMBER OF ATOMS is " + std::to_string(fr.n) + ", " +
                          std::to_string(found) + " lines follow ITEM: ATOMS on line " +
                          std::to_string(fr.atoms_line));
        fr.end = c.pos();
        break;
      } else {
        fail(c.line(), "unknown section ITEM: " + escaped(it, 40) +
                           " (only particle dumps, `dump atom` or `dump custom`, are read)");
      }
      if (!c.next(line)) fail(c.line() + 1, "file ends before ITEM: ATOMS of " + frame_name);
      item = item_of(line);
    }
    frames_.push_back(fr);
  }
  if (frames_.empty()) throw UserError("snapshot '" + file_.path() + "' is empty");
}

Snapshot DumpSource::read(std::size_t k, const ReadOptions& options) const {
  const DumpFrame& f = frames_[k];
  Snapshot s;
  s.info.dim = 0;  // a dump does not say; z = 0 throughout makes it 2D
  s.info.step = f.step;
  if (f.time) s.info.time = *f.time;
  s.info.has_time = f.time.has_value();
  s.info.origin = f.lo;
  s.info.box = f.hi - f.lo;

  // Position columns per axis: unwrapped (xu, xsu) before wrapped (x, xs) plus image flags.
  std::vector<std::string_view> names;
  for (std::size_t i = 0;;) {
    const auto t = next_token(f.columns, i);
    if (t.empty()) break;
    names.push_back(t);
  }
  const std::size_t ntok = names.size();
  const std::uint64_t n = f.n;
  if (n > 0 && ntok > (f.end - f.body + 1) / n)  // every token takes two bytes
    fail(f.atoms_line, std::to_string(ntok) + " columns are more than the " + std::to_string(n) +
                           " lines of the frame hold");
  static constexpr const char* axes = "xyz";
  // Forms 0-3: xu, xsu, x, xs (each for x, y, z). Unwrapped: that order, image flags added to
  // the wrapped ones. In the cell (OVITO's default): x, xs, then xu, xsu folded into the cell.
  static constexpr const char* forms[4] = {"u", "su", "", "s"};
  static constexpr int unwrapped_order[4] = {0, 1, 2, 3}, cell_order[4] = {2, 3, 0, 1};
  const int* order = options.unwrap ? unwrapped_order : cell_order;
  int chosen[3] = {-1, -1, -1}, form_of[3] = {-1, -1, -1}, image[3] = {-1, -1, -1};
  for (int a = 0; a < 3; ++a) {
    for (int o = 0; o < 4 && chosen[a] < 0; ++o)
      for (std::size_t t = 0; t < ntok; ++t)
        if (names[t] == std::string(1, axes[a]) + forms[order[o]]) {
          chosen[a] = static_cast<int>(t), form_of[a] = order[o];
          break;
        }
    for (std::size_t t = 0; t < ntok; ++t)
      if (names[t] == std::string("i") + axes[a]) image[a] = static_cast<int>(t);
  }
  if (chosen[0] < 0 || chosen[1] < 0)
    fail(f.atoms_line, "ITEM: ATOMS has no x, xs, xu or xsu column for both x and y");
  bool unwrappable = false;
  for (int a = 0; a < 3; ++a) unwrappable |= chosen[a] >= 0 && (form_of[a] < 2 || image[a] >= 0);
  if (options.unwrap && !unwrappable) s.notes.push_back(kNothingToUnwrap);

  std::vector<Slot> slots(ntok);
  bool velocity = false, has_radius = false;
  int radius_col = -1, diameter_col = -1;
  for (std::size_t t = 0; t < ntok; ++t) {
    if (names[t] == "radius") radius_col = static_cast<int>(t);
    if (names[t] == "diameter") diameter_col = static_cast<int>(t);
  }
  for (std::size_t t = 0; t < ntok; ++t) {
    const std::string_view nm = names[t];
    Slot& sl = slots[t];
    bool used = false;
    for (std::uint8_t a = 0; a < 3; ++a) {
      if (chosen[a] == static_cast<int>(t)) {
        sl = {form_of[a] == 1 || form_of[a] == 3 ? Slot::Scaled : Slot::Pos, a, 0};
        used = true;
      } else if (image[a] == static_cast<int>(t) && form_of[a] >= 2 && options.unwrap) {
        sl = {Slot::Image, a, 0};
        used = true;
      } else if (nm == std::string("v") + axes[a]) {
        sl = {Slot::Vel, a, 0};
        velocity = used = true;
      }
    }
    if (used) continue;
    if (static_cast<int>(t) == radius_col) {
      sl.kind = Slot::Radius;
      has_radius = true;
    } else if (static_cast<int>(t) == diameter_col && radius_col < 0) {
      sl.kind = Slot::Diameter;
      has_radius = true;
    } else if (nm == "element") {
      sl.kind = Slot::Skip;  // names, not numbers
    } else {
      sl = {Slot::Extra, 0, static_cast<std::uint32_t>(s.columns.size())};
      s.columns.push_back({std::string(nm), {}});
    }
  }
  if (n > 0 && ntok == 0) fail(f.atoms_line, "ITEM: ATOMS names no columns");

  s.position.assign(n, Eigen::Vector3d::Zero());
  if (velocity) s.velocity.assign(n, Eigen::Vector3d::Zero());
  if (has_radius) s.radius.resize(n);
  for (auto& col : s.columns) col.values.resize(n);
  // Image flags per row, so that the two halves of a large frame can be scanned at once.
  const bool has_image = std::any_of(slots.begin(), slots.end(),
                                     [](const Slot& sl) { return sl.kind == Slot::Image; });
  std::vector<Eigen::Vector3d> img(has_image ? n : 0, Eigen::Vector3d::Zero());
  bool scaled[3] = {form_of[0] % 2 == 1, form_of[1] % 2 == 1, form_of[2] % 2 == 1};
  const Eigen::Vector3d edge = f.hi - f.lo;
  // In the cell: unwrapped columns are folded into it (image flags are then only columns).
  bool fold[3] = {};
  for (int a = 0; a < 3; ++a) fold[a] = !options.unwrap && chosen[a] >= 0 && form_of[a] < 2 && edge[a] > 0;
  if (!options.unwrap && (fold[0] || fold[1] || fold[2] || image[0] >= 0 || image[1] >= 0 ||
                          image[2] >= 0))
    s.notes.push_back("positions in the cell, as OVITO draws them (--unwrap uses xu or the image "
                      "flags)");
  static constexpr const char* kAxis[3] = {"x =", "y =", "z ="};
  const std::string_view b = file_.bytes();
  scan_rows(
      b.substr(f.body, f.end - f.body), n, ntok, f.atoms_line + 1, file_.path(),
      [&](std::size_t i, std::size_t t, std::string_view tok, std::size_t line) {
        const Slot& sl = slots[t];
        switch (sl.kind) {
          case Slot::Skip:
            break;
          case Slot::Pos:
          case Slot::Scaled:
            s.position[i][sl.axis] = real(tok, line, names[t]);
            break;
          case Slot::Image: {
            std::int64_t v = 0;
            if (!parse_integer(tok, v)) fail(line, not_a(tok, "an integer", names[t]));
            img[i][sl.axis] = static_cast<double>(v);
            break;
          }
          case Slot::Vel:
            s.velocity[i][sl.axis] = real(tok, line, names[t]);
            break;
          case Slot::Radius:
          case Slot::Diameter: {
            const double r = real(tok, line, names[t]) * (sl.kind == Slot::Diameter ? 0.5 : 1);
            if (!(r > 0)) fail(line, std::string(names[t]) + " must be positive");
            s.radius[i] = r;
            break;
          }
          case Slot::Extra: {
            double v = 0;
            if (!parse_real(tok, v)) fail(line, not_a(tok, "a number", names[t]));
            s.columns[sl.extra].values[i] = v;
            break;
          }
        }
      },
      [&](std::size_t i, std::size_t) {
        for (int a = 0; a < 3; ++a) {
          if (chosen[a] < 0) continue;
          double& x = s.position[i][a];
          // As written (folding would hide it) and as placed (a huge box scales it).
          if (beyond_extent(x)) refuse_extent(file_.path(), k, names[chosen[a]], i, kAxis[a], x);
          if (scaled[a]) x = f.lo[a] + x * edge[a];
          if (form_of[a] >= 2 && has_image) x += img[i][a] * edge[a];
          if (beyond_extent(x)) refuse_extent(file_.path(), k, names[chosen[a]], i, kAxis[a], x);
          if (fold[a]) x -= edge[a] * std::floor((x - f.lo[a]) / edge[a]);
        }
      },
      true);
  // The positions were checked row by row, before folding.
  const int radius_from = radius_col >= 0 ? radius_col : diameter_col;
  if (has_radius)
    for (std::size_t i = 0; i < n; ++i)
      if (beyond_extent(s.radius[i]))
        refuse_extent(file_.path(), k, names[radius_from], i, "radius", s.radius[i]);
  // LAMMPS types are numbers; they name the particle types (what OVITO colours by).
  if (const Column* t = s.column("type")) assign_types(s, t->values);
  return s;
}

}  // namespace

std::unique_ptr<FrameSource> open_lammps_dump(MappedFile file) {
  return std::make_unique<DumpSource>(std::move(file));
}

}  // namespace gs
