#pragma once
// The reference path tracer behind the method seam (radiosity_method.h): a method that renders
// pictures by itself, registered as "pathtrace".

#include <radiosity/radiosity_method.h>

#include <memory>

namespace rad {

std::unique_ptr<RadiosityMethod> makePathTracerMethod();

}  // namespace rad
