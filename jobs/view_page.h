#pragma once
// The one HTML file of `grainshock view`: the template under assets/view (HTML, CSS, JavaScript
// written for it, no library) with the data of the page embedded: a JSON header and each frame's
// bytes in base64, in <script> elements the page decodes when it shows them. Nothing in the page
// refers outside the file but the movie beside it.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "render/page_frame.h"

namespace gs::jobs {

// A picture shown in the page (a figure, a run's still), its PNG bytes embedded.
struct PageImage {
  std::string name;  // the file's name, which report.md refers to
  std::string png;
};

struct PageContent {
  std::string title, kind;  // kind: run, ensemble, figures or files
  int dim = 0;
  double alpha = 0;  // the paper's exponent for the plots' slopes; 0: none drawn
  bool colorbar = true;
  std::vector<std::uint8_t> lut;  // render::page_lut
  std::uint8_t background[3] = {255, 255, 255};
  std::vector<render::PageFrame> frames;  // in time order
  std::vector<std::string> dropped;       // labels of the frames left out for the size budget
  std::string timeseries;                 // timeseries.csv or an ensemble's timeseries_mean.csv
  bool mean = false;                      // the latter: columns c and c_sem
  std::string report;                     // a figures folder's report.md
  std::vector<PageImage> images;
  std::string movie;               // URL of the movie relative to the page; empty: none
  std::vector<std::string> notes;  // sentences shown at the top
};

std::string base64(std::string_view bytes);
// The bytes a frame adds to the page (its base64 and its header), for the size budget.
std::size_t page_bytes(const render::PageFrame& f);
// The whole page. Every text of the inputs (names, comments, labels, report.md) goes into the
// JSON header, where '<', '>' and '&' are written as \u escapes: no file can end a <script>
// element; the page's script shows them as text, never as markup.
std::string page_html(const PageContent& c);

}  // namespace gs::jobs
