// grainshock.view's pages (jobs/view_job.h): the HTML of `grainshock view` for snapshots held in
// Python or for folders and files, as text; grainshock/__init__.py wraps it for notebooks.
#include <memory>
#include <string>
#include <vector>

#include "jobs/view_job.h"
#include "python/py_module.h"

namespace gs::py {

void bind_view(pb::module_& m) {
  auto options = [](const std::string& color_by, const std::string& colormap,
                    const std::string& background, double max_mb, bool show_inactive) {
    jobs::ViewOptions o;
    o.choices.colour_by = color_by;
    o.choices.colormap = colormap;
    o.choices.background = background;
    o.choices.style.show_inactive = show_inactive;
    o.max_mb = max_mb;
    return o;
  };
  m.def(
      "_view_snapshots",
      [options](const std::vector<std::shared_ptr<Snapshot>>& snaps, const std::string& color_by,
                const std::string& colormap, const std::string& background, double max_mb,
                bool show_inactive) {
        std::vector<const Snapshot*> ptrs;
        for (const auto& s : snaps) ptrs.push_back(s.get());
        const auto o = options(color_by, colormap, background, max_mb, show_inactive);
        pb::gil_scoped_release release;
        return jobs::view_page(ptrs, o);
      },
      pb::arg("snapshots"), pb::arg("color_by"), pb::arg("colormap"), pb::arg("background"),
      pb::arg("max_mb"), pb::arg("show_inactive"));
  m.def(
      "_view_paths",
      [options](const std::vector<std::string>& paths, const std::string& color_by,
                const std::string& colormap, const std::string& background, double max_mb,
                bool show_inactive) {
        auto o = options(color_by, colormap, background, max_mb, show_inactive);
        o.inputs = paths;
        o.out = "page.html";  // movie links are relative to the working folder
        pb::gil_scoped_release release;
        return jobs::view_page(o);
      },
      pb::arg("paths"), pb::arg("color_by"), pb::arg("colormap"), pb::arg("background"),
      pb::arg("max_mb"), pb::arg("show_inactive"));
}

}  // namespace gs::py
