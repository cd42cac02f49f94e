// libFuzzer target for every loader: any bytes as a case file (and its lift law), an engine
// file for `needle design`, a synthesis file for `needle synth`, and a CSV lift table. A
// rejection must be a CaseError whose message is one line naming the file; anything else
// (another exception, a crash, a hang, a sanitizer report) is a finding. The environment
// variable NEEDLE_FUZZ_LOADER (case, engine, synth or csv) fuzzes one loader alone (the long
// runs, scripts/fuzz.sh SECONDS LOADER); unset, every input goes through all four.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "apps/case/case_file.h"
#include "lib/lift_data.h"

namespace {

template <class Load>
void Expect(const Load& load) {
  try {
    load();
  } catch (const needle::CaseError& e) {
    const std::string m = e.what();
    if (m.rfind("fuzz.toml", 0) != 0 || m.find('\n') != std::string::npos) __builtin_trap();
  } catch (...) {
    __builtin_trap();  // every rejection must be a CaseError
  }
}

}  // namespace

// The loader chosen by NEEDLE_FUZZ_LOADER ("" for all), read once.
const std::string& Loader() {
  static const std::string loader = [] {
    const char* v = std::getenv("NEEDLE_FUZZ_LOADER");
    const std::string s = v == nullptr ? "" : v;
    if (!s.empty() && s != "case" && s != "engine" && s != "synth" && s != "csv") std::abort();
    return s;
  }();
  return loader;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string& only = Loader();
  const auto on = [&](const char* name) { return only.empty() || only == name; };
  if (on("case")) {
    Expect([&] {
      const needle::Case c = needle::ParseCase(text, "fuzz.toml");
      const needle::LiftLaw law = needle::MakeLiftLaw(c);
      (void)law.MeanLift();
    });
  }
  if (on("engine")) Expect([&] { (void)needle::ParseDesignInputs(text, "fuzz.toml"); });
  if (on("synth")) Expect([&] { (void)needle::ParseSynthesisFile(text, "fuzz.toml"); });
  if (on("csv")) {
    Expect([&] {
      (void)needle::ParseLiftCsv(
          text, "fuzz.toml",
          size % 2 == 0 ? needle::EngineCycle::kFourStroke : needle::EngineCycle::kTwoStroke);
    });
  }
  return 0;
}
