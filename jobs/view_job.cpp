#include "jobs/view_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <set>

#include "analysis/realisation.h"
#include "io/atomic_file.h"
#include "io/mapped_file.h"
#include "jobs/view_page.h"
#include "render/scene.h"
#include "sim/error.h"

namespace gs::jobs {
namespace fs = std::filesystem;
namespace {

// Where one frame comes from, and what it made.
struct FrameRef {
  std::function<Snapshot()> read;
  std::string name;         // the file (for messages)
  render::PageFrame frame;  // bytes dropped when over the budget, made again if kept
  std::size_t size = 0;
};

std::string read_bytes(const fs::path& p) {
  return std::string(MappedFile::open(p.string()).bytes());
}

std::string format_mb(double mb) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", mb);
  return b;
}

bool is_png(const fs::path& p) {
  return p.extension() == ".png";
}

// The regular files of `dir` in name order.
std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file()) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// A folder's snapshot files: those the readers take (others, such as CSV and PNG, skipped).
std::vector<std::string> snapshot_files(const fs::path& dir, const ReadOptions& read) {
  std::vector<std::string> out;
  for (const auto& p : files_in(dir)) {
    const auto ext = p.extension().string();
    if (ext == ".png" || ext == ".csv" || ext == ".json" || ext == ".toml" || ext == ".md" ||
        ext == ".mp4" || ext == ".html" || ext == ".bin" || ext == ".gp" || ext == ".svg" ||
        ext == ".pdf")
      continue;
    try {
      open_snapshots(p.string(), read);
      out.push_back(p.string());
    } catch (const UserError&) {
      // not a snapshot file: the folder's other files
    }
  }
  return out;
}

struct Gathered {
  std::vector<std::string> files;  // snapshot files
  PageContent page;
};

void gather_folder(const fs::path& dir, const ViewOptions& o, const fs::path& page_dir,
                   Gathered& g) {
  PageContent& c = g.page;
  const bool run = fs::exists(dir / "run.toml"), ensemble = fs::exists(dir / "ensemble.toml");
  const bool figures = fs::exists(dir / "report.md") || fs::exists(dir / "figures.toml");
  c.kind = run ? "run" : ensemble ? "ensemble" : figures ? "figures" : "files";
  if (fs::exists(dir / "timeseries.csv")) c.timeseries = read_bytes(dir / "timeseries.csv");
  if (fs::exists(dir / "timeseries_mean.csv")) {
    c.timeseries = read_bytes(dir / "timeseries_mean.csv");
    c.mean = true;
  }
  if (ensemble) {
    const EnsembleSpec spec = read_spec(dir / "ensemble.toml");
    c.alpha = theory_alpha(spec.physics);
    c.dim = spec.physics.dim;  // the slopes' d, with no frame to tell it
  }
  if (fs::exists(dir / "report.md")) c.report = read_bytes(dir / "report.md");
  for (const fs::path& sub : {dir, dir / "frames"})
    for (const auto& p : files_in(sub))
      if (is_png(p)) c.images.push_back({p.filename().string(), read_bytes(p)});
  const fs::path movie = dir / "movie.mp4";
  if (fs::exists(movie)) {
    c.movie = fs::relative(fs::absolute(movie), fs::absolute(page_dir)).generic_string();
    c.notes.push_back("The movie is the file " + c.movie +
                      " beside this page; moved alone, the page shows no movie.");
  }
  const fs::path snaps = fs::is_directory(dir / "snapshots") ? dir / "snapshots" : dir;
  for (auto& f : snapshot_files(snaps, o.read)) {
    // The elastic comparison (Fig. 1b, r = 1) is another run: its picture is among the pictures,
    // its snapshot not in this run's time slider.
    if (run && fs::path(f).filename().string().starts_with("elastic_")) continue;
    g.files.push_back(f);
  }
}

Gathered gather(const ViewOptions& o) {
  Gathered g;
  const fs::path page_dir =
      fs::path(o.out).parent_path().empty() ? fs::path(".") : fs::path(o.out).parent_path();
  for (const auto& in : o.inputs) {
    if (fs::is_directory(in)) {
      gather_folder(in, o, page_dir, g);
    } else if (fs::is_regular_file(in)) {
      open_snapshots(in, o.read);  // a UserError naming a file the readers do not take
      g.files.push_back(in);
      g.page.kind = "files";
    } else {
      throw UserError("'" + in + "' is neither a snapshot file nor a folder");
    }
  }
  // A file named twice (alone and in its folder) is shown once.
  std::set<std::string> seen;
  std::vector<std::string> files;
  for (const auto& f : g.files)
    if (seen.insert(fs::weakly_canonical(f).string()).second) files.push_back(f);
  g.files = std::move(files);
  g.page.title = o.inputs.size() == 1 ? o.inputs.front() : o.inputs.front() + " and others";
  // A folder's own page names nothing outside it, so that the same results in two folders (a
  // run and its resumed twin) have the same page, byte for byte.
  if (o.folder_page) g.page.title = "the " + g.page.kind + " folder of this page";
  return g;
}

render::PageFrame make_frame(const ViewOptions& o, const Snapshot& s, const std::string& name,
                             double* alpha = nullptr) {
  if (alpha && *alpha == 0 && s.info.restitution && s.info.dim > 1) {
    PhysicsConfig p;
    p.dim = s.info.dim;
    p.restitution = *s.info.restitution;
    *alpha = theory_alpha(p);  // the plots' slopes, for a run folder or its files
  }
  render::RenderChoices c = o.choices;
  // A page shows any file: one without velocities is drawn in one colour, where `render`
  // would ask for --color-by none.
  if (c.colour_by == "auto" && !s.has_velocity()) c.colour_by = "none";
  render::settle_for_snapshots(c, {&s}, name);
  return render::make_page_frame(s, c.style);
}

// Sorting key: time, or the step of files that give none.
double order_key(const render::PageFrame& f) {
  return f.has_time ? f.t : static_cast<double>(f.step);
}

// The most frames, evenly spread in time (first and last kept), whose bytes fit `budget`.
std::vector<std::size_t> fit_frames(const std::vector<FrameRef>& refs, std::size_t budget) {
  const std::size_t n = refs.size();
  for (std::size_t k = n; k >= 1; --k) {
    std::vector<std::size_t> pick;
    for (std::size_t j = 0; j < k; ++j) {
      const std::size_t i =
          k == 1 ? n - 1 : static_cast<std::size_t>(std::llround(double(j) * (n - 1) / (k - 1)));
      if (pick.empty() || pick.back() != i) pick.push_back(i);
    }
    std::size_t total = 0;
    for (std::size_t i : pick) total += refs[i].size;
    if (total <= budget) return pick;
  }
  return {};
}

// The frames that fit the budget, in time order, into c.frames; the page's size beyond them is
// `fixed`.
void choose_frames(const ViewOptions& o, std::vector<FrameRef>& refs, std::size_t fixed,
                   PageContent& c, ViewResult& result) {
  const std::size_t budget = static_cast<std::size_t>(o.max_mb * 1e6);
  if (fixed > budget)
    throw UserError("the pictures and tables alone take " + std::to_string(fixed / 1000000 + 1) +
                    " MB, over --max-mb " + format_mb(o.max_mb));
  std::size_t held = 0;
  for (FrameRef& r : refs) {
    r.frame = make_frame(o, r.read(), r.name, &c.alpha);
    r.frame.source = r.name;
    r.size = page_bytes(r.frame);
    held += r.size;
    if (held > budget) r.frame.bytes = std::string();  // made again if kept
  }
  std::stable_sort(refs.begin(), refs.end(), [](const FrameRef& a, const FrameRef& b) {
    return order_key(a.frame) < order_key(b.frame);
  });
  std::vector<std::size_t> keep(refs.size());
  for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = i;
  if (held > budget - fixed) {
    keep = fit_frames(refs, budget - fixed);
    if (keep.empty())
      throw UserError("one frame alone takes " + std::to_string(refs.back().size / 1000000 + 1) +
                      " MB, over --max-mb " + format_mb(o.max_mb));
  }
  const std::set<std::size_t> kept(keep.begin(), keep.end());
  std::string said;
  for (std::size_t i = 0; i < refs.size(); ++i) {
    if (!kept.count(i)) {
      result.dropped.push_back(refs[i].frame.label.empty() ? refs[i].name : refs[i].frame.label);
      said += (said.empty() ? "" : "; ") + result.dropped.back();
      continue;
    }
    if (refs[i].frame.bytes.empty() && refs[i].frame.count > 0)
      refs[i].frame = make_frame(o, refs[i].read(), refs[i].name);
    refs[i].frame.source = refs[i].name;
    c.frames.push_back(std::move(refs[i].frame));
  }
  c.dropped = result.dropped;
  if (!c.dropped.empty())
    c.notes.push_back(std::to_string(c.dropped.size()) + " of " + std::to_string(refs.size()) +
                      " frames were left out, evenly in time, to keep the page under " +
                      format_mb(o.max_mb) + " MB (--max-mb): " + said);
}

std::string page_of(const ViewOptions& o, Gathered& g, std::vector<FrameRef>& refs,
                    ViewResult& result) {
  if (!(o.max_mb > 0)) throw UsageError("--max-mb must be positive");
  render::RenderChoices choices = o.choices;
  render::settle_choices(choices);
  PageContent& c = g.page;
  c.lut = render::page_lut(choices.style);
  const auto bg = render::palette(choices.style.background).background;
  std::copy(bg.begin(), bg.end(), c.background);
  // The page without frames: the template, the tables, report and pictures.
  const std::size_t fixed = page_html(c).size();
  choose_frames(o, refs, fixed, c, result);
  if (!c.frames.empty()) c.dim = c.frames.front().dim;
  c.colorbar = choices.style.field != render::Field::None;
  std::string html = page_html(c);
  result.bytes = html.size();
  result.frames = c.frames.size();
  return html;
}

}  // namespace

std::string view_page(const ViewOptions& o, ViewResult* result) {
  if (o.inputs.empty()) throw UsageError("view needs a folder or snapshot files");
  Gathered g = gather(o);
  if (g.files.empty() && g.page.timeseries.empty() && g.page.report.empty() &&
      g.page.images.empty())
    throw UserError("'" + g.page.title +
                    "' holds nothing to view (no snapshot files, timeseries.csv, report.md or "
                    "pictures)");
  std::vector<FrameRef> refs;
  for (const auto& path : g.files) {
    const auto file = std::make_shared<SnapshotFile>(open_snapshots(path, o.read));
    const std::string name =
        o.folder_page ? fs::relative(path, o.inputs.front()).generic_string() : path;
    for (std::size_t k = 0; k < file->frame_count(); ++k)
      refs.push_back({[file, k] { return file->read(k); },
                      file->frame_count() > 1 ? name + " frame " + std::to_string(k) : name,
                      {},
                      0});
  }
  ViewResult r;
  std::string html = page_of(o, g, refs, r);
  if (result) *result = r;
  return html;
}

std::string view_page(const std::vector<const Snapshot*>& snaps, const ViewOptions& o,
                      ViewResult* result) {
  if (snaps.empty()) throw UserError("view: no snapshot given");
  Gathered g;
  g.page.kind = "files";
  g.page.title = o.inputs.empty() ? "snapshots" : o.inputs.front();
  std::vector<FrameRef> refs;
  for (const Snapshot* s : snaps) refs.push_back({[s] { return *s; }, "a snapshot", {}, 0});
  ViewResult r;
  std::string html = page_of(o, g, refs, r);
  if (result) *result = r;
  return html;
}

ViewResult write_view(const ViewOptions& o) {
  if (fs::path(o.out).extension() != ".html")
    throw UsageError("--out '" + o.out + "' must name an .html file");
  ViewResult r;
  const std::string html = view_page(o, &r);
  write_file_atomic(o.out, html);
  return r;
}

void write_folder_page(const std::string& dir, const std::string& page,
                       const MessageSink& messages) {
  ViewOptions o;
  o.inputs = {dir};
  o.out = (fs::path(dir) / page).string();
  o.quiet = true;
  o.max_mb = 20;
  o.folder_page = true;  // a folder's page is opened often and copied around: frames left out beyond
  try {
    write_view(o);
  } catch (const UserError& e) {
    tell(messages, MessageKind::Warning, "no " + o.out + " written: " + e.what());
  }
}

}  // namespace gs::jobs
