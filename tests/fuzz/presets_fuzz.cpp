// libFuzzer target for the presets reader (issue 37): any text must parse or throw PresetError with
// one line naming the file; every preset it accepts must apply to settings that validate (the
// reader checks types and ranges as the command line does).
#include "ui/presets/presets.h"

#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    for (const pathlab::ui::NamedPreset& p : pathlab::ui::parsePresets(text, "fuzz.json")) {
      pathlab::RenderSettings base;
      base.width = 64;
      base.height = 48;
      pathlab::validateSettings(p.applyTo(base));  // throws only on a preset the reader should have refused
    }
  } catch (const pathlab::ui::PresetError& e) {
    const std::string what = e.what();
    if (what.find('\n') != std::string::npos || what.rfind("fuzz.json: ", 0) != 0) __builtin_trap();
  }
  return 0;
}
