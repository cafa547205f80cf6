#include "jobs/view_page.h"

#include "analysis/json.h"
#include "render/shader_files.h"
#include "sim/error.h"

namespace gs::jobs {
namespace page_assets {
std::string_view html();
std::string_view css();
std::string_view js();
}  // namespace page_assets

namespace {

Json frame_json(const render::PageFrame& f) {
  auto triple = [&](const double* v) { return Json::array({v[0], v[1], v[2]}); };
  Json j = {{"label", f.label},
            {"source", f.source},
            {"count", f.count},
            {"origin", triple(f.origin)},
            {"lo", triple(f.lo)},
            {"hi", triple(f.hi)},
            {"fit_lo", triple(f.fit_lo)},
            {"fit_hi", triple(f.fit_hi)},
            {"r_max", f.r_max},
            {"sphere", f.sphere},
            {"uniform_radius", f.uniform_radius},
            {"error_diameters", f.error_diameters},
            {"range", Json::array({f.range.first, f.range.second})},
            {"bar_label", f.bar_label},
            {"bar_note", f.bar_note},
            {"colorbar", f.colorbar},
            {"columns", f.columns},
            {"column_exact", f.column_exact},
            {"bytes", f.bytes.size()}};
  j["t"] = f.has_time ? Json(f.t) : Json(nullptr);
  j["t_paper"] = f.has_t_paper ? Json(f.t_paper) : Json(nullptr);
  j["step"] = f.step >= 0 ? Json(f.step) : Json(nullptr);
  return j;
}

// JSON that may sit inside a <script> element: '<', '>' and '&' only occur in strings, where
// their \u escapes mean the same; non-ASCII is escaped too (U+2028 ends a line in old parsers).
std::string script_safe(const Json& j) {
  const std::string text = j.dump(-1, ' ', true, Json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else if (c == '>')
      out += "\\u003e";
    else if (c == '&')
      out += "\\u0026";
    else
      out += c;
  }
  return out;
}

Json header_json(const PageContent& c) {
  Json frames = Json::array();
  for (const auto& f : c.frames) frames.push_back(frame_json(f));
  Json images = Json::array();
  for (const auto& im : c.images) images.push_back(im.name);
  return {{"title", c.title},
          {"kind", c.kind},
          {"dim", c.dim},
          {"alpha", c.alpha},
          {"colorbar", c.colorbar},
          {"background", {c.background[0], c.background[1], c.background[2]}},
          {"frames", frames},
          {"dropped", c.dropped},
          {"timeseries", c.timeseries},
          {"mean", c.mean},
          {"report", c.report},
          {"images", images},
          {"movie", c.movie},
          {"notes", c.notes}};
}

void replace_marker(std::string& page, std::string_view marker, const std::string& with) {
  const auto at = page.find(marker);
  GS_CHECK(at != std::string::npos);
  page.replace(at, marker.size(), with);
}

}  // namespace

std::string base64(std::string_view in) {
  static constexpr char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v =
        std::uint8_t(in[i]) << 16 | std::uint8_t(in[i + 1]) << 8 | std::uint8_t(in[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out += k[(v >> s) & 63];
  }
  if (i < in.size()) {
    const bool two = i + 1 < in.size();
    const unsigned v = std::uint8_t(in[i]) << 16 | (two ? std::uint8_t(in[i + 1]) << 8 : 0);
    out += k[v >> 18 & 63];
    out += k[v >> 12 & 63];
    out += two ? k[v >> 6 & 63] : '=';
    out += '=';
  }
  return out;
}

std::size_t page_bytes(const render::PageFrame& f) {
  return (f.bytes.size() + 2) / 3 * 4 + 600;  // a frame's header is a few hundred bytes
}

std::string page_html(const PageContent& c) {
  std::string data = "<script type=\"application/json\" id=\"gs-header\">" +
                     script_safe(header_json(c)) + "</script>\n";
  data += "<script type=\"application/octet-stream\" id=\"gs-lut\">" +
          base64({reinterpret_cast<const char*>(c.lut.data()), c.lut.size()}) + "</script>\n";
  for (std::size_t k = 0; k < c.frames.size(); ++k)
    data += "<script type=\"application/octet-stream\" id=\"gs-frame-" + std::to_string(k) + "\">" +
            base64(c.frames[k].bytes) + "</script>\n";
  for (std::size_t k = 0; k < c.images.size(); ++k)
    data += "<script type=\"application/octet-stream\" id=\"gs-image-" + std::to_string(k) + "\">" +
            base64(c.images[k].png) + "</script>\n";
  // The GLSL the renderer draws its spheres with, which page.js compiles as WebGL 2: raw text,
  // as a script element of a type not JavaScript holds it up to its first "</script".
  for (const auto& [id, glsl] :
       {std::pair{"gs-sphere-billboard", render::shader_files::sphere_billboard()},
        std::pair{"gs-sphere-frag", render::shader_files::sphere_impostor_frag()}}) {
    GS_CHECK(glsl.find("</") == std::string_view::npos);
    data += std::string("<script type=\"x-shader\" id=\"") + id + "\">" + std::string(glsl) +
            "</script>\n";
  }
  std::string page(page_assets::html());
  replace_marker(page, "<!--GS:STYLE-->",
                 "<style>\n" + std::string(page_assets::css()) + "</style>");
  replace_marker(page, "<!--GS:SCRIPT-->",
                 "<script>\n" + std::string(page_assets::js()) + "</script>");
  replace_marker(page, "<!--GS:DATA-->", data);
  return page;
}

}  // namespace gs::jobs
