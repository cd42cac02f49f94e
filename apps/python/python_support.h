#pragma once
/// @file
/// Internal to the Python module: Python values to and from the library's (JSON, TOML, numbers,
/// keywords with their messages), needle.Case (PyCase) and how a function runs a job (Run).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <toml++/toml.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "apps/case/case_file.h"
#include "apps/case/plausible_ranges.h"
#include "apps/report/command_output.h"
#include "apps/study/tolerance_study.h"
#include "lib/case_error.h"

namespace py = pybind11;

namespace needle::python {

// JSON → Python: objects to dicts, arrays to lists, null to None.
py::object ToPython(const nlohmann::json& j);

// What a command computed, for Python: its JSON object, with the columns and the exit status.
py::dict Result(const CommandOutput& r);

// Short repr of a Python value, for messages: what the user typed, as Python prints it.
std::string Repr(const py::handle& v);

std::string TypeName(const py::handle& v);

// "a bool", "an int": the type of a refused value, as Python would name it.
std::string AType(const py::handle& v);

// A range's end as Python writes a number: 50000, 0.001, 1e-14.
std::string PyNumber(double v);

// A bool, Python's or NumPy's (numpy.bool_ is no subclass of bool).
bool IsBool(const py::handle& v);

// A keyword's number, as Python would take it: None is absent; a bool or a non-number is
// refused; a value outside the option's range is refused as "KEY=VALUE: expected …".
std::optional<double> Number(const py::object& v, const std::string& key, const std::string& what,
                             const std::string& range, double lo, double hi);

std::optional<double> Number(const py::object& v, const std::string& key, const std::string& what,
                             const PlausibleRange& r);

std::optional<double> Speed(const py::object& v, const std::string& key);

// A keyword's whole number in [lo, hi] (a bool, a float or a string is refused).
unsigned long long Whole(const py::object& v, const std::string& key, const std::string& what,
                         const PlausibleRange& r);

// A keyword's string (None is absent).
std::optional<std::string> Text(const py::object& v, const std::string& key,
                                const std::string& what);

std::optional<std::string> MethodKeyword(const py::object& v);

std::optional<double> Rtol(const py::object& v);

bool Flag(const py::object& v, const std::string& key);

toml::table ToToml(const py::dict& d, const std::string& where);

toml::array ToTomlArray(const py::sequence& s, const std::string& where);

// A case from a dict: the same text the file would hold, read by the same loader.
std::string TomlText(const py::dict& d, const std::string& name);

// TOML → Python: tables to dicts, arrays to lists (what tomllib gives).
py::object FromToml(const toml::node& n);

bool IsPath(const py::handle& source);

std::string PathOf(const py::handle& source);

/// The keywords every tolerance function takes, checked in this order: the seed, the first
/// sample and the threads.
void SetStudyKeywords(ToleranceOptions& o, const py::object& seed, const py::object& first_sample,
                      const py::object& threads);

/// A file of the engine or synthesis format from a path (`load`) or a dict with its sections
/// (`parse` of its TOML text; `name`, "<dict>" by default, is its path in messages); anything
/// else is a TypeError naming `function`.
template <typename Load, typename Parse>
auto FromPathOrDict(const py::object& source, const std::optional<std::string>& name,
                    const std::string& function, Load load, Parse parse) {
  if (py::isinstance<py::dict>(source)) {
    const std::string path = name.value_or("<dict>");
    return parse(TomlText(source.cast<py::dict>(), path), path);
  }
  if (IsPath(source)) return load(PathOf(source));
  throw py::type_error(function + ": expected a path (str or os.PathLike) or a dict, got " +
                       AType(source));
}

// needle.Case: the case as the sections of its file (plain dicts, read and written like a
// dict), with the validated Case of the text it last was. A change is validated when assigned
// at the top level, and whenever the case is run.
struct PyCase {
  py::dict data;                       ///< the sections, as the file holds them
  std::string name;                    ///< its path: messages and relative paths
  std::string text;                    ///< the TOML text `loaded` was read from
  std::shared_ptr<const Case> loaded;  ///< the validated case of `text`
};

// The validated case of the sections as they are now (read again when they changed).
std::shared_ptr<const Case> Validated(PyCase& pc);

py::dict DeepCopy(const py::dict& d);

std::string NotCsv(const py::object& cycle);

// KeyError(key), as a dict raises it.
[[noreturn]] void NoKey(const py::object& key);

PyCase LoadAnyCase(const py::object& source, const std::optional<std::string>& name,
                   const py::object& cycle_arg, const std::string& function);

// The case a function was given: a needle.Case (validated as it is now), a path or a dict.
std::shared_ptr<const Case> CaseOf(const py::object& source, const std::string& function);

// A bare CSV lift table has no speed: the command's `rpm=` gives it (as --rpm does), else the
// case must state one.
void RequireSpeedOf(const Case& c, const std::optional<double>& rpm, const std::string& keyword);
// The same of the case `path` of rated speed `speed_rpm` (0: none).
void RequireSpeedOf(const std::string& path, double speed_rpm, const std::optional<double>& rpm,
                    const std::string& keyword);

// Runs `compute` without the GIL and returns its result as a dict. A message the command
// names an option in ("--spline: …", also after the case's path) names the keyword instead
// (`options`: option, keyword=value).
// Throws `e` again, its first option of `options` (option, keyword=value) named as the keyword.
[[noreturn]] void RethrowNamingKeywords(
    const CaseError& e, const std::vector<std::pair<std::string, std::string>>& options);

template <typename Compute>
py::dict Run(Compute compute,
             const std::vector<std::pair<std::string, std::string>>& options = {}) {
  CommandOutput r;
  try {
    py::gil_scoped_release release;
    r = compute();
  } catch (const CaseError& e) {
    RethrowNamingKeywords(e, options);
  }
  return Result(r);
}

// A shard's samples as arrays (python_shards.cc): each quantity a column (its keys in order),
// whether the sample has it (a refused sample has no outputs), pass, the failing items and the
// refusals, with the seed of its study and its first sample.
py::dict ShardArrays(const std::vector<ToleranceSample>& samples, uint64_t seed, int first_sample,
                     const std::string& case_digest);

// The identity of a case's TOML text as tolerance_shard records it (`case_digest`): the text
// read into a dict and written back as TomlText writes a dict (no comments, no inline tables),
// hashed (FNV-1a, 64 bit, hex).
std::string CaseDigest(const std::string& text);

// The samples of shards as ShardArrays gives them (or read back from its files), in order. A
// shard with a key it does not write, without one it does, of another seed than `seed`, of
// another case (its case_digest, when it has one, not `case_digest`), or not starting where the
// last ended (the first at `first_sample`) is refused (CaseError naming the shard and the key,
// both seeds, both digests or both starts).
std::vector<ToleranceSample> ShardSamples(const py::sequence& shards, uint64_t seed,
                                          int first_sample, const std::string& case_digest);

// The arguments a module function was defined with (its py::arg): their names in order, how
// many may come by position (those before py::kw_only) and those without a default.
struct Signature {
  std::vector<std::string> names;
  size_t positional = 0;
  std::vector<std::string> required;
};

// Replaces the module's function `name` by one that checks a call against `s` first: an
// unknown keyword, an argument too many by position, one given twice or one missing is a
// TypeError of one line naming it and the arguments the function takes (pybind11's own lists
// every signature over several lines). Then the function runs as it was.
void CheckCalls(py::module_& m, const char* name, const Signature& s);

// The same for method `name` of class `cls` (all its arguments after self as in `s`): a
// TypeError of one line naming "Class.name()" and the arguments it takes.
void CheckMethodCalls(py::object cls, const char* name, const Signature& s);

// The signature a function or method is defined with: its py::arg names in order, how many
// come before py::kw_only, and those without a default.
template <typename... Extra>
Signature SignatureOf(const Extra&... extra) {
  Signature s;
  bool keyword_only = false;
  const auto add = [&](const auto& e) {
    using E = std::decay_t<decltype(e)>;
    if constexpr (std::is_same_v<E, py::kw_only>) keyword_only = true;
    if constexpr (std::is_base_of_v<py::arg, E>) {
      s.names.emplace_back(e.name);
      if (!keyword_only) s.positional = s.names.size();
      if constexpr (!std::is_same_v<E, py::arg_v>) s.required.emplace_back(e.name);
    }
  };
  (add(extra), ...);
  return s;
}

// m.def(name, f, extra...), its calls checked (CheckCalls).
template <typename F, typename... Extra>
void Def(py::module_& m, const char* name, F&& f, const Extra&... extra) {
  m.def(name, std::forward<F>(f), extra...);
  CheckCalls(m, name, SignatureOf(extra...));
}

// cls.def(name, f, extra...) for a method (its arguments after self in `extra`), its calls
// checked (CheckMethodCalls).
template <typename Class, typename F, typename... Extra>
void DefMethod(Class& cls, const char* name, F&& f, const Extra&... extra) {
  cls.def(name, std::forward<F>(f), extra...);
  CheckMethodCalls(cls, name, SignatureOf(extra...));
}

// The folder of this module's file: needle.distributed and the package's Python files live in
// its subfolder `needle` (the module is a package whose __init__ is compiled).
std::string ModuleFolder();

}  // namespace needle::python
