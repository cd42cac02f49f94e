// A tolerance study's shards for Python (python_support.h): a worker's samples as arrays, and
// the gathered shards read back, each checked for the keys tolerance_shard writes and its seed.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "apps/python/python_support.h"
#include "apps/study/tolerance_study.h"
#include "lib/case_error.h"

namespace needle::python {
namespace {

using Bools = py::array_t<bool, py::array::c_style | py::array::forcecast>;
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The keys of tolerance_shard's dict, and those needle.shards.run_shard adds beside them.
const std::vector<std::string> kShardKeys = {
    "failing", "first_sample",   "input_keys", "input_present", "inputs",  "output_keys",
    "outputs", "output_present", "pass",       "refused",       "samples", "seed"};
const std::vector<std::string> kShardExtras = {"seconds", "worker", "case_digest"};

std::string ShardKeyList() {
  std::string list;
  for (const std::string& k : kShardKeys) list += (list.empty() ? "" : ", ") + k;
  return "expected the keys tolerance_shard writes: " + list +
         " (and case_digest, and run_shard's seconds, worker)";
}

bool Listed(const std::vector<std::string>& keys, const std::string& key) {
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

// Shard `where` (e.g. "shards[1]") as a dict with tolerance_shard's keys, and no other.
py::dict ShardDict(const py::handle& handle, const std::string& where) {
  if (!py::isinstance<py::dict>(handle))
    throw CaseError(where + ": expected a dict of tolerance_shard, got " + AType(handle));
  const py::dict shard = py::reinterpret_borrow<py::dict>(handle);
  for (const auto& [key, value] : shard) {
    const std::string name = py::isinstance<py::str>(key) ? key.cast<std::string>() : "";
    if (!Listed(kShardKeys, name) && !Listed(kShardExtras, name))
      throw CaseError(where + ": unknown key " + Repr(key) + "; " + ShardKeyList());
  }
  for (const std::string& k : kShardKeys)
    if (!shard.contains(k)) throw CaseError(where + ": no key '" + k + "'; " + ShardKeyList());
  return shard;
}

// shard[key] as T, or a one-line refusal naming the key and the type it holds.
template <typename T>
T Value(const py::dict& shard, const std::string& where, const char* key) {
  const py::object v = shard[key];
  try {
    return v.cast<T>();
  } catch (const py::cast_error&) {
    throw CaseError(where + "['" + key + "']: expected what tolerance_shard writes there, got " +
                    AType(v));
  }
}

// The shard's samples appended to `samples`.
void AppendShard(const py::dict& shard, const std::string& where,
                 std::vector<ToleranceSample>& samples) {
  const auto n = Value<py::ssize_t>(shard, where, "samples");
  const auto pass = Value<Bools>(shard, where, "pass");
  if (n < 0 || pass.ndim() != 1 || pass.shape(0) != n)
    throw CaseError(where + ": its samples (" + std::to_string(n) + ") and pass do not agree");
  const size_t base = samples.size();
  samples.resize(base + n);
  const auto table = [&](auto member, const char* keys_name, const char* values_name,
                         const char* present_name) {
    const auto keys = Value<std::vector<std::string>>(shard, where, keys_name);
    const auto values = Value<Doubles>(shard, where, values_name);
    const auto present = Value<Bools>(shard, where, present_name);
    const auto m = static_cast<py::ssize_t>(keys.size());
    if (values.ndim() != 2 || values.shape(0) != n || values.shape(1) != m || present.ndim() != 2 ||
        present.shape(0) != n || present.shape(1) != m)
      throw CaseError(where + ": its " + values_name + " is not samples × keys");
    const auto v = values.unchecked<2>();
    const auto p = present.unchecked<2>();
    for (py::ssize_t i = 0; i < n; ++i)
      for (py::ssize_t j = 0; j < m; ++j)
        if (p(i, j)) (samples[base + i].*member)[keys[j]] = v(i, j);
  };
  table(&ToleranceSample::inputs, "input_keys", "inputs", "input_present");
  table(&ToleranceSample::outputs, "output_keys", "outputs", "output_present");
  const auto failing = Value<std::vector<std::vector<std::string>>>(shard, where, "failing");
  const auto refused = Value<std::vector<std::string>>(shard, where, "refused");
  if (failing.size() != static_cast<size_t>(n) || refused.size() != static_cast<size_t>(n))
    throw CaseError(where + ": its failing or refused is not one per sample");
  for (py::ssize_t i = 0; i < n; ++i) {
    samples[base + i].pass = pass.data()[i];
    samples[base + i].failing = failing[i];
    samples[base + i].refused = refused[i];
  }
}

}  // namespace

std::string CaseDigest(const std::string& text) {
  // The text as load_case holds it: read into a dict and written back as needle writes a dict
  // (no comments, no inline tables, no layout), so a file and the dict made of it, a path and
  // its text, give one digest. FNV-1a, 64 bit.
  const std::string canonical =
      TomlText(FromToml(toml::parse(text)).cast<py::dict>(), "case_digest");
  uint64_t h = 14695981039346656037ull;
  for (const unsigned char ch : canonical) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, h);
  return hex;
}

py::dict ShardArrays(const std::vector<ToleranceSample>& samples, uint64_t seed, int first_sample,
                     const std::string& case_digest) {
  const auto table = [&](auto member, const char* keys_name, const char* values_name,
                         const char* present_name, py::dict& out) {
    std::vector<std::string> keys;
    for (const ToleranceSample& s : samples)
      for (const auto& [k, v] : s.*member)
        if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    std::sort(keys.begin(), keys.end());
    const auto n = static_cast<py::ssize_t>(samples.size());
    const auto m = static_cast<py::ssize_t>(keys.size());
    py::array_t<double> values({n, m});
    py::array_t<bool> present({n, m});
    auto v = values.mutable_unchecked<2>();
    auto p = present.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto& map = samples[i].*member;
      for (py::ssize_t j = 0; j < m; ++j) {
        const auto it = map.find(keys[j]);
        p(i, j) = it != map.end();
        v(i, j) = it != map.end() ? it->second : NAN;
      }
    }
    out[keys_name] = keys;
    out[values_name] = std::move(values);
    out[present_name] = std::move(present);
  };
  py::dict out;
  out["seed"] = seed;
  out["case_digest"] = case_digest;
  out["first_sample"] = first_sample;
  out["samples"] = samples.size();
  table(&ToleranceSample::inputs, "input_keys", "inputs", "input_present", out);
  table(&ToleranceSample::outputs, "output_keys", "outputs", "output_present", out);
  py::array_t<bool> pass(static_cast<py::ssize_t>(samples.size()));
  std::vector<std::vector<std::string>> failing;
  std::vector<std::string> refused;
  for (size_t i = 0; i < samples.size(); ++i) {
    pass.mutable_data()[i] = samples[i].pass;
    failing.push_back(samples[i].failing);
    refused.push_back(samples[i].refused);
  }
  out["pass"] = std::move(pass);
  out["failing"] = failing;
  out["refused"] = refused;
  return out;
}

std::vector<ToleranceSample> ShardSamples(const py::sequence& shards, uint64_t seed,
                                          int first_sample, const std::string& case_digest) {
  std::vector<ToleranceSample> samples;
  for (size_t i = 0; i < shards.size(); ++i) {
    const std::string where = "shards[" + std::to_string(i) + "]";
    const py::dict shard = ShardDict(shards[i], where);
    const auto made_with = Value<unsigned long long>(shard, where, "seed");
    if (made_with != seed)
      throw CaseError("seed=" + std::to_string(seed) + ": " + where + " was made with seed=" +
                      std::to_string(made_with) + "; expected the seed its shards were made with");
    // The case it was made from (issue 51's trial: shards of another case were reduced as this
    // one's study). Shards read back from files written before the digest carry none; their
    // folder is checked by its case_sha256 (needle.shards).
    if (shard.contains("case_digest")) {
      const auto made_from = Value<std::string>(shard, where, "case_digest");
      if (made_from != case_digest)
        throw CaseError(where + " was made from another case (case_digest " + made_from +
                        ", this case's " + case_digest +
                        "); reduce shards with the case they were made from");
    }
    // The shards tile the study: each starts where the last ended, the first at first_sample (a
    // shard twice, a gap, shards out of order or another first_sample were reduced as if they
    // did, their samples miscounted or mislabelled: issue 51's trial).
    const long long expected = static_cast<long long>(first_sample) + samples.size();
    const auto starts = Value<long long>(shard, where, "first_sample");
    if (starts != expected)
      throw CaseError(where + ": starts at sample " + std::to_string(starts) + "; expected " +
                      std::to_string(expected) +
                      " (the shards in sample order, each where the last ended, the first at "
                      "first_sample=" +
                      std::to_string(first_sample) + ")");
    AppendShard(shard, where, samples);
  }
  return samples;
}

}  // namespace needle::python
