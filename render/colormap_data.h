#pragma once
// 256-entry RGB tables of the published matplotlib colormaps (colormap_data.cpp).

namespace gs::render {

extern const float kViridisData[256][3];
extern const float kInfernoData[256][3];
extern const float kMagmaData[256][3];
extern const float kCividisData[256][3];
extern const float kTurboData[256][3];

}  // namespace gs::render
