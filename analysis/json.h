#pragma once
// The JSON files of the outputs (summary.json, timing.json, bench figures) are built as
// nlohmann::ordered_json values: keys stay in the order they are set, strings are escaped by the
// library, doubles are written in their shortest round-trip form, and non-finite numbers become
// null (JSON has no NaN; nlohmann's default, which every JSON reader accepts).
#include <nlohmann/json.hpp>
#include <string>

#include "sim/config.h"

namespace gs {

using Json = nlohmann::ordered_json;

// The text of a JSON file: two-space indents and a final newline. Bytes that are not UTF-8 (a
// file name may hold any) are replaced by U+FFFD rather than failing the whole file.
inline std::string json_text(const Json& j) {
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

// The physics every summary.json names first, in the flags' words.
inline Json physics_json(const PhysicsConfig& p) {
  return {{"dim", p.dim},         {"particles", p.particles},
          {"density", p.density}, {"restitution", p.restitution},
          {"cutoff", p.cutoff},   {"seed", p.seed}};
}

}  // namespace gs
