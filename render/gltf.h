#pragma once
// A snapshot as a glTF 2.0 binary scene (.glb) that Blender and three.js-based viewers open:
// one unit sphere mesh instanced at every particle `render` draws (EXT_mesh_gpu_instancing:
// TRANSLATION, SCALE by the radius, and _COLOR_0, the colour of the PNG, per instance).
#include <string>

#include "render/style.h"
#include "sim/snapshot.h"

namespace gs::render {

// The .glb bytes; the particles and colours of build_scene with `style` (all of them: no slab,
// no culling), at their world positions.
std::string glb_scene(const Snapshot& s, const Style& style);

}  // namespace gs::render
