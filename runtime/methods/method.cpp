#include "hmblur/method.h"

#include "hmblur/error.h"
#include "runtime/methods/frame_method.h"

namespace hmb {
namespace {

void noSettingsOfItsOwn(const RenderSettings&) {}

// The registry: a new method is an enum value, a file with its FrameMethod, and a row here.
const MethodDescription kMethods[] = {
    {Method::Sharp, "sharp", "the G-buffer's shaded colour, the shutter-close instant without blur", true,
     noSettingsOfItsOwn, makeSharpMethod},
    {Method::PostProcess, "postprocess", "post-process blur of the G-buffer (McGuire 2012 or Jimenez 2014)", true,
     validatePostProcessMethod, makePostProcessMethod},
    {Method::Hybrid, "hybrid", "post-process blur with the hidden background ray traced in the ray mask (the paper)",
     true, validateHybridMethod, makeHybridMethod},
    {Method::HybridRays, "hybrid-rays",
     "the hybrid's blur with rays at stratified shutter times where a path crosses an edge (this project's "
     "extension)",
     true, validateHybridMethod, makeHybridMethod},
    {Method::Reference, "reference", "distributed ray tracing over the shutter (the ground truth)", true,
     validateReferenceMethod, makeReferenceMethod},
    {Method::TestPattern, "test-pattern", "a test pattern that proves the runtime without a scene", false,
     noSettingsOfItsOwn, makeTestPatternMethod},
};

}  // namespace

std::span<const MethodDescription> methodDescriptions() { return kMethods; }

const MethodDescription& describe(Method method) {
  for (const MethodDescription& d : kMethods)
    if (d.method == method) return d;
  throw Error("method " + std::to_string(int(method)) + " is not registered");
}

std::string_view methodName(Method method) { return describe(method).name; }

std::optional<Method> findMethod(std::string_view name) {
  for (const MethodDescription& d : kMethods)
    if (d.name == name) return d.method;
  return std::nullopt;
}

Method parseMethod(std::string_view name) {
  if (const auto method = findMethod(name)) return *method;
  std::string list;
  for (const MethodDescription& d : kMethods) list += (list.empty() ? "" : ", ") + std::string(d.name);
  throw Error("unknown method '" + std::string(name) + "'; available: " + list);
}

}  // namespace hmb
