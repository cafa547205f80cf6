// render --out scene.glb: the glTF 2.0 rules checkable offline (GLB header and chunks, every
// accessor within its buffer view and every view within the buffer, instance attributes of one
// count), and the round trip of the particles' positions, radii and PNG colours.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "render/gltf.h"
#include "render/overlay.h"
#include "render/scene.h"

namespace gs::render {
namespace {

using Json = nlohmann::json;

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// The first rule the accessors and views break, or "" (glTF 2.0 sections 3.6 and 5).
std::string check(const Json& j, std::size_t bin) {
  const std::size_t length = j["buffers"][0]["byteLength"];
  if (length > bin || bin - length > 3) return "buffer length against the BIN chunk";
  for (const auto& v : j["bufferViews"]) {
    const std::size_t off = v["byteOffset"], len = v["byteLength"];
    if (off + len > length || off % 4) return "a buffer view outside the buffer or unaligned";
  }
  for (const auto& a : j["accessors"]) {
    const auto& v = j["bufferViews"][a["bufferView"].get<std::size_t>()];
    const int c = a["componentType"];
    const std::size_t size = c == 5126 ? 4 : c == 5123 ? 2 : c == 5121 ? 1 : 0;
    const std::string type = a["type"];
    const std::size_t n = type == "VEC3" ? 3 : type == "VEC4" ? 4 : type == "SCALAR" ? 1 : 0;
    if (!size || !n) return "an accessor of unknown type";
    if (a["count"].get<std::size_t>() * size * n > v["byteLength"].get<std::size_t>())
      return "an accessor longer than its view";
  }
  const auto& inst = j["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  const std::size_t count = j["accessors"][inst["TRANSLATION"].get<int>()]["count"];
  for (const char* k : {"SCALE", "_COLOR_0"})
    if (j["accessors"][inst[k].get<int>()]["count"] != count) return "instance counts differ";
  if (j["extensionsUsed"][0] != "EXT_mesh_gpu_instancing") return "extension not declared";
  return "";
}

Snapshot shell() {
  Snapshot s;
  s.info.dim = 3;
  for (int i = 0; i < 500; ++i) {
    const double z = 1 - 2 * (i + 0.5) / 500, r = std::sqrt(1 - z * z), a = i * 2.399963;
    s.position.emplace_back(30 + 20 * r * std::cos(a), -5 + 20 * r * std::sin(a), 20 * z);
    s.velocity.emplace_back(0.01 * (i % 5 + 1), 0, 0);
    s.radius.push_back(0.5);
    s.active.push_back(i % 4 != 0);
  }
  return s;
}

TEST(Gltf, ValidGlbRoundTripsParticles) {
  const Snapshot s = shell();
  Style style;
  const std::string glb = glb_scene(s, style);
  ASSERT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_EQ(u32(glb, 4), 2u);
  ASSERT_EQ(u32(glb, 8), glb.size());
  const std::uint32_t json_len = u32(glb, 12);
  ASSERT_EQ(glb.substr(16, 4), "JSON");
  ASSERT_EQ(json_len % 4, 0u);
  const Json j = Json::parse(glb.substr(20, json_len));
  const std::size_t bin_at = 20 + json_len;
  const std::uint32_t bin_len = u32(glb, bin_at);
  ASSERT_EQ(glb.substr(bin_at + 4, 4), std::string("BIN\0", 4));
  ASSERT_EQ(bin_at + 8 + bin_len, glb.size());
  EXPECT_EQ(j["asset"]["version"], "2.0");
  EXPECT_EQ(check(j, bin_len), "");
  // Seen to fail: an accessor claiming one instance more than its view holds.
  Json wrong = j;
  const int t =
      wrong["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"];
  wrong["accessors"][t]["count"] = wrong["accessors"][t]["count"].get<int>() + 1;
  EXPECT_NE(check(wrong, bin_len), "");

  // Round trip: the active spheres at their positions with the PNG scene's colours.
  OverlayPainter painter(style.font);
  Style plain = style;
  plain.colorbar = plain.inset = plain.occlusion_cull = false;
  const Scene sc = build_scene({&s}, plain, View{}, painter);
  const auto& inst = j["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  auto data = [&](const char* name) {
    const auto& a = j["accessors"][inst[name].get<int>()];
    const auto& v = j["bufferViews"][a["bufferView"].get<int>()];
    return glb.data() + bin_at + 8 + v["byteOffset"].get<std::size_t>();
  };
  ASSERT_EQ(j["accessors"][t]["count"], 375);
  const auto* at = reinterpret_cast<const float*>(data("TRANSLATION"));
  const auto* colour = reinterpret_cast<const std::uint8_t*>(data("_COLOR_0"));
  const auto* scale = reinterpret_cast<const float*>(data("SCALE"));
  std::size_t k = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.active[i]) continue;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(at[3 * k + c], s.position[i][c], 1e-4);
    EXPECT_EQ(scale[3 * k], 0.5f);
    // glTF colours are linear light (glTF 2.0, 3.9.2): the PNG's sRGB bytes decoded by the
    // IEC 61966-2-1 curve, so that sRGB 128 is stored as 55.
    for (int c = 0; c < 3; ++c) {
      const double u = sc.sprites[k].rgba[c] / 255.0;
      const double linear = u <= 0.04045 ? u / 12.92 : std::pow((u + 0.055) / 1.055, 2.4);
      EXPECT_EQ(colour[4 * k + c], std::lround(255 * linear));
    }
    ++k;
  }
}

}  // namespace
}  // namespace gs::render
