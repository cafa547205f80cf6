#include "io/particle_types.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <string>
#include <unordered_map>

namespace gs {
namespace {

bool integer(std::string_view v, long long& out) {
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
  return ec == std::errc() && end == v.data() + v.size();
}

}  // namespace

void assign_types(Snapshot& s, const std::vector<std::string_view>& labels) {
  std::unordered_map<std::string_view, std::uint32_t> index;
  std::vector<std::string_view> names;
  for (std::string_view l : labels)
    if (index.emplace(l, 0).second) names.push_back(l);
  const bool numbers = std::all_of(names.begin(), names.end(), [](std::string_view v) {
    long long x = 0;
    return integer(v, x);
  });
  std::sort(names.begin(), names.end(), [&](std::string_view a, std::string_view b) {
    long long x = 0, y = 0;
    if (numbers && integer(a, x) && integer(b, y)) return x < y;
    return a < b;
  });
  s.type_names.assign(names.begin(), names.end());
  for (std::uint32_t k = 0; k < names.size(); ++k) index[names[k]] = k;
  s.type.resize(labels.size());
  std::string_view last;
  std::uint32_t last_k = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {  // runs of one label are the common case
    if (i == 0 || labels[i] != last) last = labels[i], last_k = index[last];
    s.type[i] = last_k;
  }
}

void assign_types(Snapshot& s, const std::vector<double>& numbers) {
  std::map<double, std::uint32_t> index;
  for (double v : numbers) {
    if (!(v == std::floor(v) && std::abs(v) < 0x1p53)) return;
    index.emplace(v, 0);
  }
  s.type_names.clear();
  for (auto& [v, k] : index) {
    k = static_cast<std::uint32_t>(s.type_names.size());
    s.type_names.push_back(std::to_string(static_cast<long long>(v)));
  }
  s.type.resize(numbers.size());
  for (std::size_t i = 0; i < numbers.size(); ++i) s.type[i] = index[numbers[i]];
}

}  // namespace gs
