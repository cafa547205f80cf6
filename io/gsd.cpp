#include "io/gsd.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "io/atomic_file.h"
#include "sim/error.h"

namespace gs {
namespace {

static_assert(std::endian::native == std::endian::little, "GSD files are little-endian");

constexpr std::uint64_t kMagic = 0x65DF65DF65DF65DFull;
constexpr std::size_t kHeaderSize = 256, kEntrySize = 32, kNameSegment = 64;

// Type ids of the file layer.
enum Type : std::uint8_t { U8 = 1, U16, U32, U64, I8, I16, I32, I64, F32, F64, Char };

std::size_t type_size(std::uint8_t t) {
  switch (t) {
    case U8:
    case I8:
    case Char:
      return 1;
    case U16:
    case I16:
      return 2;
    case U32:
    case I32:
    case F32:
      return 4;
    case U64:
    case I64:
    case F64:
      return 8;
    default:
      return 0;
  }
}

struct Entry {
  std::uint64_t frame = 0, n = 0;
  std::int64_t location = 0;
  std::uint32_t m = 0;
  std::uint16_t id = 0;
  std::uint8_t type = 0, flags = 0;
};

template <class T>
T load(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

class GsdSource final : public FrameSource {
 public:
  explicit GsdSource(MappedFile f);
  std::size_t frames() const override { return frames_; }
  Snapshot read(std::size_t k, const ReadOptions& options) const override;
  const char* format() const override { return "GSD"; }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw UserError("snapshot '" + file_.path() + "': " + what);
  }
  // The chunk of that name in frame k, else (when `fallback`) in frame 0, else nullptr.
  const Entry* find(std::size_t k, std::string_view name, bool fallback = true) const;
  // Its values as doubles (N x M, row major).
  std::vector<double> values(const Entry& e) const;
  // s.type from the typeid values, named by particles/types (default: one type, "A").
  void read_types(std::size_t k, const std::vector<double>& typeid_values, Snapshot& s) const;

  MappedFile file_;
  std::vector<std::string_view> names_;
  std::vector<Entry> index_;  // sorted by frame
  std::size_t frames_ = 0;
};

bool valid_name_char(char c) {
  return c >= 0x20 && c < 0x7f;
}

GsdSource::GsdSource(MappedFile f) : file_(std::move(f)) {
  const std::string_view b = file_.bytes();
  const std::size_t size = b.size();
  if (size < kHeaderSize) fail("too short for a GSD header");
  const char* h = b.data();
  if (load<std::uint64_t>(h) != kMagic) fail("bad GSD magic number");
  const auto index_location = load<std::uint64_t>(h + 8);
  const auto index_entries = load<std::uint64_t>(h + 16);
  const auto names_location = load<std::uint64_t>(h + 24);
  const auto names_segments = load<std::uint64_t>(h + 32);
  const auto version = load<std::uint32_t>(h + 44);
  const std::uint32_t major = version >> 16;
  if (major != 1 && major != 2)
    fail("GSD file layer version " + std::to_string(major) + "." +
         std::to_string(version & 0xffff) + " is not supported (1.x and 2.x are)");
  if (index_location < kHeaderSize || index_location > size ||
      index_entries > (size - index_location) / kEntrySize)
    fail("the index (at byte " + std::to_string(index_location) + ", " +
         std::to_string(index_entries) + " entries) lies outside the file of " +
         std::to_string(size) + " bytes");
  if (names_location < kHeaderSize || names_location > size ||
      names_segments > (size - names_location) / kNameSegment)
    fail("the chunk name list lies outside the file");

  // Names: 0-terminated, in 64-byte slots in version 1, packed in version 2; an empty name ends.
  const std::string_view list = b.substr(names_location, names_segments * kNameSegment);
  for (std::size_t p = 0; p < list.size();) {
    const std::size_t e = list.find('\0', p);
    if (e == std::string_view::npos || e == p) break;
    const std::string_view name = list.substr(p, e - p);
    if (!std::all_of(name.begin(), name.end(), valid_name_char) || names_.size() == 65535)
      fail("the chunk name list is corrupt");
    names_.push_back(name);
    p = major == 1 ? p + kNameSegment : e + 1;
  }

  for (std::uint64_t i = 0; i < index_entries; ++i) {
    const char* p = h + index_location + i * kEntrySize;
    Entry e;
    e.frame = load<std::uint64_t>(p);
    e.n = load<std::uint64_t>(p + 8);
    e.location = load<std::int64_t>(p + 16);
    e.m = load<std::uint32_t>(p + 24);
    e.id = load<std::uint16_t>(p + 28);
    e.type = load<std::uint8_t>(p + 30);
    if (e.location == 0) break;  // the end of the list
    const std::string where = "index entry " + std::to_string(i);
    const std::size_t ts = type_size(e.type);
    if (ts == 0) fail(where + " has unknown type " + std::to_string(e.type));
    if (e.id >= names_.size())
      fail(where + " names chunk " + std::to_string(e.id) + " of " + std::to_string(names_.size()));
    if (e.location < static_cast<std::int64_t>(kHeaderSize) ||
        static_cast<std::uint64_t>(e.location) > size || e.m == 0 ||
        e.n > (size - e.location) / ts / e.m)
      fail(where + " (" + std::string(names_[e.id]) + ") points outside the file");
    // Even an empty chunk (N = 0) cannot have more values per row than the file has bytes: a
    // per-particle log chunk becomes M columns (found by fuzzing: M = 4e9 and N = 0).
    if (e.m > size / ts)
      fail(where + " (" + std::string(names_[e.id]) + ") has " + std::to_string(e.m) +
           " values per row, more than the file holds");
    if (!index_.empty() && e.frame < index_.back().frame)
      fail(where + " is out of frame order: the index is corrupt");
    index_.push_back(e);
  }
  if (index_.empty()) fail("a GSD file without frames");
  // Frames without a chunk are legal, but a file of more frames than chunks is an index that
  // lies (a reader would play on frame 0's data for ever).
  if (index_.back().frame >= index_.size())
    fail("the index names frame " + std::to_string(index_.back().frame) + " but holds only " +
         std::to_string(index_.size()) + " chunks: it is corrupt");
  frames_ = static_cast<std::size_t>(index_.back().frame) + 1;
}

const Entry* GsdSource::find(std::size_t k, std::string_view name, bool fallback) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) return nullptr;
  const auto id = static_cast<std::uint16_t>(it - names_.begin());
  for (std::size_t frame : {k, std::size_t{0}}) {
    auto lo = std::lower_bound(index_.begin(), index_.end(), frame,
                               [](const Entry& e, std::uint64_t f) { return e.frame < f; });
    for (; lo != index_.end() && lo->frame == frame; ++lo)
      if (lo->id == id) return &*lo;
    if (!fallback || k == 0) break;
  }
  return nullptr;
}

std::vector<double> GsdSource::values(const Entry& e) const {
  const std::size_t count = e.n * e.m, ts = type_size(e.type);
  std::vector<double> v(count);
  const char* p = file_.bytes().data() + e.location;
  for (std::size_t i = 0; i < count; ++i, p += ts) {
    switch (e.type) {
      case U8:
        v[i] = load<std::uint8_t>(p);
        break;
      case U16:
        v[i] = load<std::uint16_t>(p);
        break;
      case U32:
        v[i] = load<std::uint32_t>(p);
        break;
      case U64:
        v[i] = static_cast<double>(load<std::uint64_t>(p));
        break;
      case I8:
      case Char:
        v[i] = load<std::int8_t>(p);
        break;
      case I16:
        v[i] = load<std::int16_t>(p);
        break;
      case I32:
        v[i] = load<std::int32_t>(p);
        break;
      case I64:
        v[i] = static_cast<double>(load<std::int64_t>(p));
        break;
      case F32:
        v[i] = load<float>(p);
        break;
      case F64:
        v[i] = load<double>(p);
        break;
    }
  }
  return v;
}

void GsdSource::read_types(std::size_t k, const std::vector<double>& ids, Snapshot& s) const {
  s.type_names = {"A"};
  if (const Entry* e = find(k, "particles/types")) {
    if (e->type != I8 && e->type != U8 && e->type != Char)
      fail("frame " + std::to_string(k) + ": particles/types is not of characters");
    const std::vector<double> c = values(*e);
    s.type_names.assign(e->n, "");
    for (std::size_t t = 0; t < e->n; ++t)
      for (std::uint32_t j = 0; j < e->m && c[t * e->m + j] != 0; ++j)
        s.type_names[t] += static_cast<char>(c[t * e->m + j]);
  }
  s.type.resize(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (!(ids[i] >= 0 && ids[i] < static_cast<double>(s.type_names.size())))
      fail("frame " + std::to_string(k) + ": particle " + std::to_string(i) + " has typeid " +
           std::to_string(ids[i]) + ", beyond the " + std::to_string(s.type_names.size()) +
           " types named");
    s.type[i] = static_cast<std::uint32_t>(ids[i]);
  }
}

Snapshot GsdSource::read(std::size_t k, const ReadOptions& options) const {
  const std::string where = "frame " + std::to_string(k);
  auto bad = [&](const std::string& what) { fail(where + ": " + what); };
  Snapshot s;
  auto scalar = [&](const char* name, double dflt) {
    const Entry* e = find(k, name);
    if (!e) return dflt;
    if (e->n * e->m != 1) bad(std::string(name) + " is not a single value");
    return values(*e)[0];
  };
  const double dims = scalar("configuration/dimensions", 3);
  if (dims != 2 && dims != 3) bad("configuration/dimensions is not 2 or 3");
  s.info.dim = static_cast<int>(dims);
  // Counts held as doubles (any chunk type is accepted) are checked before the integer cast.
  auto count = [&](const char* name) {
    const double v = scalar(name, 0);
    if (!(v >= 0 && v < 0x1p53 && v == std::floor(v)))
      bad(std::string(name) + " is not a count (" + std::to_string(v) + ")");
    return static_cast<std::uint64_t>(v);
  };
  s.info.step = static_cast<std::int64_t>(count("configuration/step"));
  // The time where OVITO shows it (log/Time: its global attribute Time) or, in files of
  // earlier versions, ours; HOOMD itself keeps none.
  const Entry* t = find(k, "log/Time", false);
  if (!t) t = find(k, "log/grainshock/time", false);
  if (t && t->n * t->m == 1) s.info.time = values(*t)[0];
  s.info.has_time = t && t->n * t->m == 1;
  // A snapshot of the unbounded medium (SnapshotInfo::unbounded): its box is only the grid the
  // engine addresses, which a reader must not frame.
  if (const Entry* e = find(k, "log/Unbounded")) {
    const std::vector<double> v = values(*e);
    if (v.size() != 1 || (v[0] != 0 && v[0] != 1)) bad("log/Unbounded is not one 0 or 1");
    s.info.unbounded = v[0] == 1;
  }
  // A kick's snapshot (SnapshotInfo::kick), coloured by v/v_rms even without its resting particles.
  if (const Entry* e = find(k, "log/Kick")) {
    const std::vector<double> v = values(*e);
    if (v.size() != 1 || (v[0] != 0 && v[0] != 1)) bad("log/Kick is not one 0 or 1");
    s.info.kick = v[0] == 1;
  }
  std::vector<double> box = {1, 1, 1, 0, 0, 0};
  if (const Entry* e = find(k, "configuration/box")) {
    if (e->n * e->m != 6) bad("configuration/box does not have 6 values");
    box = values(*e);
  }
  if (box[3] != 0 || box[4] != 0 || box[5] != 0)
    bad("the box is triclinic (non-zero tilt); only rectangular boxes are supported");
  for (int a = 0; a < 3; ++a) {
    if (!(box[a] >= 0) || !std::isfinite(box[a])) bad("the box has a negative or non-finite edge");
    s.info.box[a] = box[a];
    s.info.origin[a] = -box[a] / 2;  // HOOMD centres the box on the origin
  }

  const std::uint64_t n = count("particles/N");
  // N is believed only as far as the position chunk holds it.
  const Entry* pos = find(k, "particles/position");
  if (n > 0 && (!pos || pos->n != n || pos->m != 3))
    bad("particles/N is " + std::to_string(n) + " but particles/position " +
        (pos ? "has " + std::to_string(pos->n) + " x " + std::to_string(pos->m) + " values"
             : "is missing"));
  auto per_particle = [&](const char* name, std::uint32_t m, bool fallback) -> const Entry* {
    const Entry* e = find(k, name, fallback);
    if (!e) return nullptr;
    if (e->n == n && e->m == m) return e;
    if (e->frame != k) return nullptr;  // frame 0's value for another N: use the default
    fail(where + ": " + name + " has " + std::to_string(e->n) + " x " + std::to_string(e->m) +
         " values for " + std::to_string(n) + " particles");
  };
  s.position.assign(n, Eigen::Vector3d::Zero());
  if (n > 0) {
    const auto p = values(*pos);
    for (std::size_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) {
        s.position[i][a] = p[3 * i + a];
        if (!std::isfinite(p[3 * i + a]))
          bad("particle " + std::to_string(i) + " has a non-finite position");
      }
  }
  // Ours are unwrapped by their image counts (our snapshots are unwrapped); others' only when
  // asked, as OVITO draws them in the cell by default, with the counts as columns.
  const bool ours = file_.bytes().substr(48, 11) == std::string_view("grainshock\0", 11);
  // A chunk left out is the schema's default (image 0, typeid 0, mass 1, charge 0): gsd.hoomd
  // leaves a chunk of defaults out of frame 0, so others' files get their columns either way.
  const Entry* img = per_particle("particles/image", 3, true);
  if (!ours && options.unwrap && !img) s.notes.push_back(kNothingToUnwrap);
  if (img || !ours) {
    const auto v = img ? values(*img) : std::vector<double>(3 * n, 0.0);
    if (ours || options.unwrap) {
      for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < 3; ++a) s.position[i][a] += v[3 * i + a] * box[a];
    } else {
      for (int a = 0; a < 3; ++a) {
        Column c{std::string("image_") + "xyz"[a], std::vector<double>(n)};
        for (std::size_t i = 0; i < n; ++i) c.values[i] = v[3 * i + a];
        s.columns.push_back(std::move(c));
      }
      if (std::any_of(v.begin(), v.end(), [](double x) { return x != 0; }))
        s.notes.push_back("positions in the cell, as OVITO draws them (--unwrap adds the image "
                          "counts times the box)");
    }
  }
  // The schema's default velocity is 0: writers leave the chunk out of a frame when all are at
  // rest. A file with no velocity chunk in any frame (HOOMD's unless asked) has no velocities.
  const bool has_velocity = std::find(names_.begin(), names_.end(), "particles/velocity") != names_.end();
  if (has_velocity) s.velocity.assign(n, Eigen::Vector3d::Zero());
  if (const Entry* vel = has_velocity ? per_particle("particles/velocity", 3, true) : nullptr) {
    const auto v = values(*vel);
    for (std::size_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) {
        s.velocity[i][a] = v[3 * i + a];
        if (!std::isfinite(v[3 * i + a]))
          bad("particle " + std::to_string(i) + " has a non-finite velocity");
      }
  }
  s.radius.assign(n, 0.5);
  if (const Entry* d = per_particle("particles/diameter", 1, true)) {
    const auto v = values(*d);
    for (std::size_t i = 0; i < n; ++i) {
      if (!(v[i] > 0) || !std::isfinite(v[i]))
        bad("particle " + std::to_string(i) + " has a diameter that is not positive");
      s.radius[i] = v[i] / 2;
    }
  }
  for (auto [name, dflt] : {std::pair{"particles/typeid", 0.0}, std::pair{"particles/mass", 1.0},
                            std::pair{"particles/charge", 0.0}}) {
    const Entry* e = per_particle(name, 1, true);
    if (e || !ours)
      s.columns.push_back({std::string(name).substr(10), e ? values(*e) : std::vector<double>(n, dflt)});
  }
  if (const Column* id = s.column("typeid")) read_types(k, id->values, s);
  check_extent(s, file_.path(), k,
               {"particles/position", "particles/position", "particles/position"},
               "particles/diameter");
  // Logged per-particle quantities of this frame: ours, then anyone's as extra columns.
  for (auto it = std::lower_bound(index_.begin(), index_.end(), k,
                                  [](const Entry&e, std::uint64_t f) { return e.frame < f; });
       it != index_.end() && it->frame == k; ++it) {
    const std::string_view name = names_[it->id];
    if (!name.starts_with("log/particles/") || it->n != n) continue;
    const std::string col(name.substr(14));
    auto v = values(*it);
    if (col == "active" && it->m == 1) {
      s.active.resize(n);
      for (std::size_t i = 0; i < n; ++i) s.active[i] = v[i] != 0;
    } else if (col == "first_collision" && it->m == 1) {
      s.first_collision = std::move(v);
    } else {
      for (std::uint32_t c = 0; c < it->m; ++c) {
        Column out{it->m == 1 ? col : col + "_" + std::to_string(c), std::vector<double>(n)};
        for (std::size_t i = 0; i < n; ++i) out.values[i] = v[i * it->m + c];
        s.columns.push_back(std::move(out));
      }
    }
  }
  return s;
}

// The chunks of a file's frames: their bytes (from byte 256 on; a trajectory hands them on to
// its file after each frame), the index and the names.
struct Writer {
  std::string data;
  std::uint64_t written = 0;  // bytes of data already handed on
  std::uint64_t frame = 0;
  std::vector<Entry> index;
  std::vector<std::string> names;

  template <class T>
  void chunk(const std::string& name, Type type, std::uint64_t n, std::uint32_t m,
             const std::vector<T>& v) {
    GS_CHECK(v.size() == n * m && type_size(type) == sizeof(T));
    Entry e;
    e.frame = frame;
    e.n = n;
    e.m = m;
    e.type = type;
    const auto known = std::find(names.begin(), names.end(), name);
    e.id = static_cast<std::uint16_t>(known - names.begin());
    if (known == names.end()) names.push_back(name);
    e.location = static_cast<std::int64_t>(kHeaderSize + written + data.size());
    data.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    index.push_back(e);
  }

  // One frame in the hoomd schema. A lone frame leaves out the chunks at the schema's defaults
  // (image 0, diameter 1); a trajectory's frames hold them all, since a reader takes a chunk a
  // frame lacks from frame 0 (HOOMD's rule), not from the schema.
  void add_frame(const Snapshot& s, bool every_chunk) {
    const std::size_t n = s.size();
    GS_CHECK(s.info.dim >= 2 && s.radius.size() == n && s.active.size() == n);
    chunk("configuration/step", U64, 1, 1,
          std::vector<std::uint64_t>{static_cast<std::uint64_t>(std::max<std::int64_t>(
              0, s.info.step.value_or(0)))});
    chunk("configuration/dimensions", U8, 1, 1,
          std::vector<std::uint8_t>{static_cast<std::uint8_t>(s.info.dim)});
    std::vector<float> box = {1, 1, 0, 0, 0, 0};
    for (int a = 0; a < 3; ++a) box[a] = static_cast<float>(s.info.box[a]);
    chunk("configuration/box", F32, 6, 1, box);
    chunk("particles/N", U32, 1, 1, std::vector<std::uint32_t>{static_cast<std::uint32_t>(n)});
    // HOOMD keeps positions in the box centred on the origin and counts the wraps in image.
    std::vector<float> pos(3 * n), vel(s.has_velocity() ? 3 * n : 0), diameter(n);
    std::vector<std::int32_t> image(3 * n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      for (int a = 0; a < 3; ++a) {
        double x = s.position[i][a];
        const double edge = s.info.box[a];
        if (edge > 0) {
          const double u = x - s.info.origin[a];
          const double wraps = std::floor(u / edge);
          image[3 * i + a] = static_cast<std::int32_t>(wraps);
          x = u - wraps * edge - edge / 2;
        }
        pos[3 * i + a] = static_cast<float>(x);
        if (!vel.empty()) vel[3 * i + a] = static_cast<float>(s.velocity[i][a]);
      }
      diameter[i] = static_cast<float>(2 * s.radius[i]);
    }
    // Left out of a lone frame at their defaults, as HOOMD does: a 2e6-sphere snapshot is 28 MB
    // smaller.
    chunk("particles/position", F32, n, 3, pos);
    if (every_chunk || std::any_of(image.begin(), image.end(), [](std::int32_t i) { return i; }))
      chunk("particles/image", I32, n, 3, image);
    if (!vel.empty())
      chunk("particles/velocity", F32, n, 3, vel);
    else if (every_chunk)
      chunk("particles/velocity", F32, n, 3, std::vector<float>(3 * n, 0.0f));
    if (every_chunk || std::any_of(diameter.begin(), diameter.end(), [](float d) { return d != 1; }))
      chunk("particles/diameter", F32, n, 1, diameter);
    chunk("log/particles/active", U8, n, 1, s.active);
    if (!s.first_collision.empty())
      chunk("log/particles/first_collision", F64, n, 1, s.first_collision);
    // OVITO makes a global attribute of each log/NAME chunk (one slash): log/Time is its Time,
    // and gsd.hoomd's frame.log['Time'].
    if (s.info.has_time) chunk("log/Time", F64, 1, 1, std::vector<double>{s.info.time});
    // Only when set, so that box snapshots keep their bytes (OVITO shows it as attribute
    // Unbounded).
    if (s.info.unbounded) chunk("log/Unbounded", U8, 1, 1, std::vector<std::uint8_t>{1});
    if (s.info.kick) chunk("log/Kick", U8, 1, 1, std::vector<std::uint8_t>{1});
    ++frame;
  }

  // The header for data of `written` bytes followed by the index and the names, and the index
  // and names themselves.
  std::pair<std::string, std::string> header_and_tail() const {
    std::string list;
    for (const auto& nm : names) list.append(nm).push_back('\0');
    list.push_back('\0');
    list.resize((list.size() + kNameSegment - 1) / kNameSegment * kNameSegment, '\0');
    const std::uint64_t index_location = kHeaderSize + written;
    const std::uint64_t names_location = index_location + index.size() * kEntrySize;
    std::string head(kHeaderSize, '\0');
    auto put = [&](std::size_t at, auto v) { std::memcpy(head.data() + at, &v, sizeof v); };
    put(0, kMagic);
    put(8, index_location);
    put(16, static_cast<std::uint64_t>(index.size()));
    put(24, names_location);
    put(32, static_cast<std::uint64_t>(list.size() / kNameSegment));
    put(40, std::uint32_t{(1u << 16) | 4u});  // hoomd schema 1.4
    put(44, std::uint32_t{2u << 16});         // file layer 2.0
    std::memcpy(head.data() + 48, "grainshock", 10);
    std::memcpy(head.data() + 112, "hoomd", 5);
    std::string tail;
    for (const Entry& e : index) {
      char rec[kEntrySize] = {};
      std::memcpy(rec, &e.frame, 8);
      std::memcpy(rec + 8, &e.n, 8);
      std::memcpy(rec + 16, &e.location, 8);
      std::memcpy(rec + 24, &e.m, 4);
      std::memcpy(rec + 28, &e.id, 2);
      std::memcpy(rec + 30, &e.type, 1);
      tail.append(rec, kEntrySize);
    }
    tail += list;
    return {head, tail};
  }
};

}  // namespace

bool is_gsd(std::string_view bytes) {
  return bytes.size() >= 8 && load<std::uint64_t>(bytes.data()) == kMagic;
}

std::unique_ptr<FrameSource> open_gsd(MappedFile file) {
  return std::make_unique<GsdSource>(std::move(file));
}

void write_gsd(const std::string& path, const Snapshot& s) {
  Writer w;
  w.add_frame(s, false);
  w.written = w.data.size();
  const auto [head, tail] = w.header_and_tail();
  write_file_atomic(path, {head, w.data, tail});
}

namespace {

class GsdTrajectory final : public TrajectoryWriter {
 public:
  explicit GsdTrajectory(const std::string& path) {
    file_.open(path);
    file_.write(std::string(kHeaderSize, '\0'));  // the header goes in last
  }
  void add(const Snapshot& s) override {
    if (s.info.dim < 2) throw UserError("GSD holds 2D and 3D systems only; use .xyz in 1D");
    w_.add_frame(s, true);
    file_.write(w_.data);
    w_.written += w_.data.size();
    w_.data.clear();
  }
  void finish() override {
    const auto [head, tail] = w_.header_and_tail();
    file_.write(tail);
    file_.finish(head);
  }

 private:
  Writer w_;
  AtomicFileWriter file_;
};

}  // namespace

std::unique_ptr<TrajectoryWriter> open_gsd_trajectory(const std::string& path) {
  return std::make_unique<GsdTrajectory>(path);
}

}  // namespace gs
