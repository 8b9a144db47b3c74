#pragma once
// `radiosity bench patch`: the patch method's form-factor rays per second, table memory and
// solve times on fixed workloads (the Cornell box and a furnished room at ~10k patches, the
// Cornell box at ~100k).

#include <nlohmann/json.hpp>

#include "console.h"

namespace rad::cli {

/// Numbers as JSON, with a one-line "summary" for the text output.
nlohmann::json benchPatch(Console& console);

}  // namespace rad::cli
