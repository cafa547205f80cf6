#pragma once
// What the parts of the `_grainshock` extension share: each binds one concept into the module.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <vector>

#include "sim/config.h"

namespace gs::py {

namespace pb = pybind11;

void bind_snapshot(pb::module_& m);
void bind_simulation(pb::module_& m);
void bind_render(pb::module_& m);
void bind_movie(pb::module_& m);
void bind_analysis(pb::module_& m);
void bind_ensemble(pb::module_& m);
void bind_view(pb::module_& m);

// The physics flags as keyword arguments (names with underscores, the flags' defaults and
// checks: UserError with the command line's message). TypeError for an unknown keyword.
PhysicsConfig physics(const pb::kwargs& kw);

// A read-only numpy view of memory that `owner` keeps alive: no copy, and no way to change the
// C++ object's data from Python.
template <class T>
pb::array view(const T* data, std::vector<pb::ssize_t> shape, std::vector<pb::ssize_t> strides,
               pb::handle owner) {
  pb::array a(pb::dtype::of<T>(), std::move(shape), std::move(strides), data, owner);
  pb::detail::array_proxy(a.ptr())->flags &= ~pb::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// A numpy copy of a vector (small results: histograms, profiles).
template <class T>
pb::array_t<T> copy(const std::vector<T>& v) {
  return pb::array_t<T>(static_cast<pb::ssize_t>(v.size()), v.data());
}

}  // namespace gs::py
