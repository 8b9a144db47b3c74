#pragma once
// The patch method behind the method seam (radiosity_method.h): its settings, its model and its
// relighting, registered as "patch".

#include <radiosity/radiosity_method.h>

#include <memory>

namespace rad {

std::unique_ptr<RadiosityMethod> makePatchMethod();

}  // namespace rad
