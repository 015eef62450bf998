// The rendering methods, named by an enum. Each is one class in its own file (a FrameMethod,
// runtime/methods/frame_method.h) listed once in the registry (method.cpp), which gives its
// name for the CLI and the report, what it is, whether the demo runs it, and how its settings
// are checked.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hmb {

struct RenderSettings;
struct FrameResources;
class FrameMethod;

enum class Method {
  Sharp,        // the G-buffer's shaded colour, no blur
  PostProcess,  // McGuire 2012 (or Jimenez 2014) over the G-buffer
  Hybrid,       // the paper's method: post-process with ray-traced reveal in the ray mask
  HybridRays,   // this project's extension: the hybrid's blur with stratified shutter rays at edges
  Reference,    // distributed ray tracing over the shutter: the judge
  TestPattern,  // proves the runtime without a scene
};

struct MethodDescription {
  Method method;
  std::string_view name;     // as the CLI and the report spell it
  std::string_view summary;  // one line, for help texts
  bool inDemo;               // rendered by `hmblur demo` (debug methods are not)
  // Throws hmb::Error (one line) for settings this method cannot render with.
  void (*validate)(const RenderSettings& settings);
  // The method's frames on a renderer's shared stages (runtime/methods/frame_method.h).
  std::unique_ptr<FrameMethod> (*make)(FrameResources& resources);
};

// Every method, in the order the demo renders them.
std::span<const MethodDescription> methodDescriptions();
const MethodDescription& describe(Method method);
std::string_view methodName(Method method);
// Throws hmb::Error naming the methods there are.
Method parseMethod(std::string_view name);
std::optional<Method> findMethod(std::string_view name);

}  // namespace hmb
