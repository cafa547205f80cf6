#pragma once
// The job of `grainshock view` (and of the pages `run`, `ensemble` and `figures` leave): one
// self-contained HTML page of a run, ensemble, figures or movie folder, or of snapshot files.
#include <string>
#include <vector>

#include "io/snapshot_file.h"
#include "render/render_choices.h"
#include "sim/messages.h"

namespace gs::jobs {

struct ViewOptions {
  // Folders (a run's, an ensemble's, a figures folder, any folder of snapshot files) or snapshot
  // files of any format `render` reads, several frames each too.
  std::vector<std::string> inputs;
  std::string out;     // NAME.html
  double max_mb = 50;  // the page's size budget: frames are dropped evenly in time beyond it
  ReadOptions read;
  render::RenderChoices choices;  // colours as `render` takes them (--color-by, --colormap, ...)
  bool quiet = false;
  // The page a command leaves in its folder (inputs: that folder): names relative to it.
  bool folder_page = false;
};

struct ViewResult {
  std::size_t bytes = 0, frames = 0;
  std::vector<std::string> dropped;  // labels of the frames left out
};

// Checks the options (UserError naming the flag or input) before any file is written; the page
// is written whole or not at all (io/atomic_file.h).
ViewResult write_view(const ViewOptions& o);
// The page of o.inputs, or of snapshots in memory (Python's grainshock.view), as text.
std::string view_page(const ViewOptions& o, ViewResult* result = nullptr);
std::string view_page(const std::vector<const Snapshot*>& snaps, const ViewOptions& o,
                      ViewResult* result = nullptr);

// The page a command leaves in its folder: DIR/index.html of a run or ensemble, report.html of
// a figures folder. Quiet; a failure is reported to `messages` as a warning and leaves the rest of
// the folder as it is (the results are written already). Its size budget is 20 MB.
void write_folder_page(const std::string& dir, const std::string& page,
                       const MessageSink& messages);

}  // namespace gs::jobs
