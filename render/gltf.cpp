#include "render/gltf.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <vector>

#include "render/colormap.h"
#include "render/overlay.h"
#include "render/scene.h"

namespace gs::render {
namespace {

using Json = nlohmann::ordered_json;

// An sRGB byte as a linear-light byte.
std::uint8_t linear_byte(std::uint8_t srgb) {
  return static_cast<std::uint8_t>(std::lround(255 * srgb_to_linear(srgb / 255.0)));
}

// A UV sphere of unit radius: positions (= normals) and triangle indices.
void unit_sphere(std::vector<float>& pos, std::vector<std::uint16_t>& tri) {
  constexpr int kRings = 8, kSegments = 12;
  for (int i = 0; i <= kRings; ++i) {
    const double th = std::numbers::pi * i / kRings;
    for (int j = 0; j <= kSegments; ++j) {
      const double ph = 2 * std::numbers::pi * j / kSegments;
      pos.insert(pos.end(), {static_cast<float>(std::sin(th) * std::cos(ph)),
                             static_cast<float>(std::sin(th) * std::sin(ph)),
                             static_cast<float>(std::cos(th))});
    }
  }
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSegments; ++j) {
      const auto a = static_cast<std::uint16_t>(i * (kSegments + 1) + j);
      const auto b = static_cast<std::uint16_t>(a + kSegments + 1);
      tri.insert(tri.end(), {a, b, static_cast<std::uint16_t>(a + 1)});
      tri.insert(tri.end(),
                 {static_cast<std::uint16_t>(a + 1), b, static_cast<std::uint16_t>(b + 1)});
    }
}

// Appends a buffer view (4-byte aligned) and its accessor; returns the accessor's index.
struct Builder {
  std::string bin;
  Json views = Json::array(), accessors = Json::array();
  template <class T>
  int add(const std::vector<T>& data, int component, const char* type, std::size_t count,
          bool normalized = false, int target = 0) {
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    Json view = {
        {"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", data.size() * sizeof(T)}};
    if (target) view["target"] = target;
    bin.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(T));
    views.push_back(view);
    Json acc = {{"bufferView", views.size() - 1},
                {"componentType", component},
                {"count", count},
                {"type", type}};
    if (normalized) acc["normalized"] = true;
    accessors.push_back(acc);
    return static_cast<int>(accessors.size() - 1);
  }
};

void min_max(Json& acc, const std::vector<float>& v) {
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < v.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], v[i]), hi[i % 3] = std::max(hi[i % 3], v[i]);
  acc["min"] = {lo[0], lo[1], lo[2]};
  acc["max"] = {hi[0], hi[1], hi[2]};
}

void put_u32(std::string& out, std::uint32_t v) {
  out.append(reinterpret_cast<const char*>(&v), 4);
}

}  // namespace

std::string glb_scene(const Snapshot& s, const Style& style) {
  Style st = style;
  st.colorbar = st.inset = st.occlusion_cull = st.legend = false;
  OverlayPainter painter(st.font);
  const Scene sc = build_scene({&s}, st, View{}, painter);
  std::vector<float> sphere, at, scale;
  std::vector<std::uint16_t> tri;
  std::vector<std::uint8_t> colour;
  unit_sphere(sphere, tri);
  const Eigen::Vector3d o = sc.camera.origin;
  for (const Sprite& p : sc.sprites) {
    at.insert(at.end(), {static_cast<float>(p.x + o.x()), static_cast<float>(p.y + o.y()),
                         static_cast<float>(p.z + (sc.dim == 3 ? o.z() : 0.0))});
    scale.insert(scale.end(), {p.r, p.r, p.r});
    // The PNG's sRGB colour as the linear light glTF colours are (three.js and Blender read
    // _COLOR_0 so): written as sRGB bytes it would show washed out.
    for (int c = 0; c < 3; ++c) colour.push_back(linear_byte(p.rgba[c]));
    colour.push_back(255);
  }
  Builder b;
  const int pos = b.add(sphere, 5126, "VEC3", sphere.size() / 3, false, 34962);
  min_max(b.accessors[pos], sphere);
  const int normal = b.add(sphere, 5126, "VEC3", sphere.size() / 3, false, 34962);
  const int index = b.add(tri, 5123, "SCALAR", tri.size(), false, 34963);
  const int translation = b.add(at, 5126, "VEC3", sc.sprites.size());
  if (!at.empty()) min_max(b.accessors[translation], at);
  const int size = b.add(scale, 5126, "VEC3", sc.sprites.size());
  const int rgba = b.add(colour, 5121, "VEC4", sc.sprites.size(), true);
  b.bin.resize((b.bin.size() + 3) / 4 * 4, '\0');
  const Json instancing = {
      {"attributes", {{"TRANSLATION", translation}, {"SCALE", size}, {"_COLOR_0", rgba}}}};
  Json j = {
      {"asset", {{"version", "2.0"}, {"generator", "grainshock render"}}},
      {"extensionsUsed", {"EXT_mesh_gpu_instancing"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"extensions", {{"EXT_mesh_gpu_instancing", instancing}}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", pos}, {"NORMAL", normal}}},
            {"indices", index},
            {"material", 0}}}}}}},
      {"materials",
       {{{"pbrMetallicRoughness",
          {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.5}}}}}},
      {"buffers", {{{"byteLength", b.bin.size()}}}},
      {"bufferViews", b.views},
      {"accessors", b.accessors}};
  std::string text = j.dump(-1, ' ', false, Json::error_handler_t::replace);
  text.resize((text.size() + 3) / 4 * 4, ' ');
  std::string out = "glTF";
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + b.bin.size()));
  put_u32(out, static_cast<std::uint32_t>(text.size()));
  out += "JSON";
  out += text;
  put_u32(out, static_cast<std::uint32_t>(b.bin.size()));
  out.append("BIN\0", 4);
  out += b.bin;
  return out;
}

}  // namespace gs::render
