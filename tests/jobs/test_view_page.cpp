// The page of `grainshock view` without a browser: base64 as RFC 4648 gives it, a frame's bytes
// decoded back to the positions and colours `render` draws (within the stated quantisation
// error), texts of hostile files unable to end a <script>, and the size budget's even choice.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "jobs/view_job.h"
#include "jobs/view_page.h"
#include "render/colormap.h"
#include "render/overlay.h"
#include "render/scene.h"

namespace gs::jobs {
namespace {

Snapshot disc_gas(int n, double spread) {
  Snapshot s;
  s.info.dim = 2;
  s.info.time = 7;
  for (int i = 0; i < n; ++i) {
    const double a = i * 2.399963, r = spread * std::sqrt((i + 0.5) / n);
    s.position.emplace_back(100 + r * std::cos(a), 50 + r * std::sin(a), 0);
    s.velocity.emplace_back(0.01 * (i % 7 + 1), 0.002 * i, 0);
    s.radius.push_back(0.5);
    s.active.push_back(i % 3 != 0);  // a third never hit: not drawn
  }
  return s;
}

TEST(ViewPage, Base64IsRfc4648) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

TEST(ViewPage, FrameHoldsWhatRenderDraws) {
  const Snapshot s = disc_gas(3000, 40);
  render::Style style;
  style.field = render::Field::Speed;
  const render::PageFrame f = render::make_page_frame(s, style);
  // The scene the PNG is drawn from, its colours and order.
  render::OverlayPainter painter(style.font);
  render::Style plain = style;
  plain.colorbar = plain.inset = false;
  const render::Scene sc = render::build_scene({&s}, plain, render::View{}, painter);
  ASSERT_EQ(f.count, sc.sprites.size());
  ASSERT_EQ(f.count, 2000u);
  const auto* q = reinterpret_cast<const std::uint16_t*>(f.bytes.data());
  const auto* colour = reinterpret_cast<const std::uint8_t*>(f.bytes.data() + 4 * f.count);
  const auto* index = reinterpret_cast<const std::uint32_t*>(f.bytes.data() + 5 * f.count);
  const std::vector<std::uint8_t> lut = render::page_lut(style);
  double worst = 0;
  int worst_colour = 0;
  for (std::size_t i = 0; i < f.count; ++i) {
    const std::uint32_t k = index[i];
    ASSERT_TRUE(s.active[k]);
    for (int a = 0; a < 2; ++a) {
      const double x = f.origin[a] + f.lo[a] + q[2 * i + a] / 65535.0 * (f.hi[a] - f.lo[a]);
      worst = std::max(worst, std::abs(x - s.position[k][a]));
    }
    for (int c = 0; c < 3; ++c)
      worst_colour = std::max(worst_colour,
                              std::abs(int(lut[3 * colour[i] + c]) - int(sc.sprites[i].rgba[c])));
  }
  // Half a step of 16 bits over the frame's extent (plus float rounding of the scene's sprites).
  EXPECT_LE(worst / (2 * f.r_max), f.error_diameters * 1.01 + 1e-5);
  EXPECT_LT(f.error_diameters, 1e-3);
  // The colour byte's 255 levels against the 256-entry map: at most half a map step apart.
  EXPECT_LE(worst_colour, 6);
  // Seen to fail: another colormap's table.
  render::Style other = style;
  other.colormap = "viridis";
  const std::vector<std::uint8_t> wrong = render::page_lut(other);
  int off = 0;
  for (std::size_t i = 0; i < f.count; ++i)
    for (int c = 0; c < 3; ++c)
      off = std::max(off, std::abs(int(wrong[3 * colour[i] + c]) - int(sc.sprites[i].rgba[c])));
  EXPECT_GT(off, 6);
}

TEST(ViewPage, HostileTextsCannotEndTheScript) {
  PageContent c;
  c.title = "</script><script>alert(1)</script><!--";
  c.report = "# </SCRIPT>\n<img src=x onerror=alert(2)> & \xe2\x80\xa8";
  c.notes.push_back("bad utf-8 \xff\xfe </script>");
  c.lut.assign(768, 0);
  const std::string page = page_html(c);
  const auto data = page.find("id=\"gs-header\">");
  ASSERT_NE(data, std::string::npos);
  const auto end = page.find("</script>", data);
  const std::string header = page.substr(data, end - data);
  EXPECT_EQ(header.find('<'), std::string::npos);
  EXPECT_EQ(header.find('>', std::strlen("id=\"gs-header\">")), std::string::npos);
  EXPECT_NE(header.find("\\u003c/script\\u003e"), std::string::npos);
  EXPECT_NE(header.find("\\u2028"), std::string::npos);
}

}  // namespace
}  // namespace gs::jobs
