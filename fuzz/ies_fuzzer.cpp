// An IES LM-63 file, parsed from memory; a profile that parses is also evaluated (flux, peak,
// intensity around the sphere), which must give finite, non-negative numbers.
#include <radiosity/ies_profile.h>

#include <cmath>
#include <cstdlib>

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rad::fuzz::acceptingInputErrors([&] {
    const rad::IesProfile profile = rad::parseIesProfile(text, "fuzz.ies");
    double total = profile.totalFlux() + profile.maxCandela();
    for (int i = 0; i < 64; ++i) {
      const double theta = M_PI * (i + 0.5) / 64, phi = 2.0 * M_PI * i * 0.618;
      total += profile.candelaToward(std::sin(theta) * std::cos(phi),
                                     std::sin(theta) * std::sin(phi), std::cos(theta));
    }
    if (!(total >= 0.0 && std::isfinite(total))) std::abort();
  });
  return 0;
}
