// The `_grainshock` extension: the libraries bound into one module, which python/grainshock
// wraps. UserError (a wrong input, one line naming it) becomes ValueError with the same message.
#include "python/py_module.h"
#include "sim/error.h"

PYBIND11_MODULE(_grainshock, m) {
  m.doc() = "grainshock's libraries (sim, io, analysis, render) bound for Python";
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const gs::UserError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  gs::py::bind_snapshot(m);
  gs::py::bind_simulation(m);
  gs::py::bind_render(m);
  gs::py::bind_movie(m);
  gs::py::bind_analysis(m);
  gs::py::bind_ensemble(m);
  gs::py::bind_view(m);
}
