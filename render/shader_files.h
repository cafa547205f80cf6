#pragma once
// The GLSL shared by the offscreen renderer and the page of `grainshock view`, from the files under
// assets/shaders compiled in at build time (cmake/EmbedFiles.cmake): one body, so that the page's
// spheres are drawn as the PNG's are. Each is without its #version line, which differs between
// OpenGL 3.3 core and WebGL 2.
#include <string_view>

namespace gs::render::shader_files {

// `vec3 sphere_billboard(vec3 c, float r, vec2 corner, float px_per_depth)`: a vertex shader's
// corner of the billboard holding a sphere's silhouette.
std::string_view sphere_billboard();
// The sphere impostor's fragment shader (its inputs, uniforms and main).
std::string_view sphere_impostor_frag();

}  // namespace gs::render::shader_files
