// libFuzzer target for every loader: any bytes as a case file (and its lift law), an engine
// file for `needle design`, and a synthesis file for `needle synth`. A rejection must be a
// CaseError whose message is one line naming the file; anything else (another exception, a
// crash, a hang, a sanitizer report) is a finding.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "apps/scene/case_file.h"

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

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Expect([&] {
    const needle::Case c = needle::ParseCase(text, "fuzz.toml");
    const needle::LiftLaw law = needle::MakeLiftLaw(c);
    (void)law.MeanLift();
  });
  Expect([&] { (void)needle::ParseDesignInputs(text, "fuzz.toml"); });
  Expect([&] { (void)needle::ParseSynthesisFile(text, "fuzz.toml"); });
  return 0;
}
