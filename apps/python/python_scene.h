#pragma once
/// @file
/// Internal to the Python module: needle.Scene, a case bound once (apps/case/bound_case.h) and
/// run many times: scene.simulate(rpm=…), scene.check(), scene.overspeed(), scene.kinematics().
/// The module's functions of a case (needle.simulate(case, …), …) bind the case and call the
/// same code: one wording of every keyword and message.

#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>

#include "apps/case/bound_case.h"

namespace py = pybind11;

namespace needle::python {

/// A needle.Scene: the case bound once. A snapshot: a needle.Case changed after the scene was
/// made does not change it.
struct PyScene {
  std::shared_ptr<const BoundCase> bound;
};

/// The scene of `source`: a needle.Scene's own, else the case (a path, a needle.Case or a dict)
/// loaded and bound; with `spline` (kinematics' keyword, shown as `spline_repr` in messages) its
/// [lift] spline set first.
PyScene SceneOf(const py::object& source, const std::string& function,
                const std::optional<std::string>& spline = std::nullopt,
                const std::string& spline_repr = "");

py::dict SceneKinematics(const PyScene& s, const py::object& rpm, const py::object& step_deg);
py::dict SceneSimulate(const PyScene& s, const py::object& rpm, const py::object& method,
                       const py::object& rtol, const py::object& dynamic, const py::object& series);
py::dict SceneOverspeed(const PyScene& s, const py::object& from_rpm, const py::object& to_rpm,
                        const py::object& step_rpm, const py::object& method,
                        const py::object& rtol, const py::object& threads);
py::dict SceneCheck(const PyScene& s, const py::object& rpm);

/// Defines needle.Scene in module `m`.
void DefScene(py::module_& m);

}  // namespace needle::python
