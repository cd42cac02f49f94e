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
#include "apps/case/case_file.h"

namespace py = pybind11;

namespace needle::python {

/// A needle.Scene: the case bound once. A snapshot: a needle.Case changed after the scene was
/// made does not change it.
struct PyScene {
  std::shared_ptr<const BoundCase> bound;
};

/// What a function of a case runs: a needle.Scene's bound case, or a case loaded (its file's
/// problems raised first, as the functions always did) and bound when it is run, after the
/// keywords are checked; kinematics' spline= sets its [lift] spline first (SetSpline).
class SceneSource {
 public:
  explicit SceneSource(const PyScene& scene) : bound_(scene.bound) {}
  SceneSource(const py::object& source, const std::string& function);
  /// Sets the case's [lift] spline before it is bound; a needle.Scene has its own (CaseError).
  void SetSpline(const std::string& spline);
  const std::string& path() const;
  double speed_rpm() const;  ///< [engine] speed_rpm (0: a bare CSV table's none)
  /// The bound case, bound at the first call (its CaseError names "--spline" for the spline).
  std::shared_ptr<const BoundCase> Shared();
  const BoundCase& Bound() { return *Shared(); }

 private:
  std::shared_ptr<const BoundCase> bound_;
  std::shared_ptr<const Case> loaded_;
  std::string function_;
  std::optional<std::string> spline_;
};

py::dict SceneKinematics(SceneSource s, const py::object& rpm, const py::object& step_deg,
                         const py::object& spline = py::none());
py::dict SceneSimulate(SceneSource s, const py::object& rpm, const py::object& method,
                       const py::object& rtol, const py::object& dynamic, const py::object& series,
                       const py::object& grid_deg);
py::dict SceneOverspeed(SceneSource s, const py::object& from_rpm, const py::object& to_rpm,
                        const py::object& step_rpm, const py::object& method,
                        const py::object& rtol, const py::object& threads);
py::dict SceneCheck(SceneSource s, const py::object& rpm);

/// Defines needle.Scene in module `m`.
void DefScene(py::module_& m);
// needle.fit (python_fit.cc).
void DefFit(py::module_& m);

}  // namespace needle::python
