#include "runtime/passes/hybrid_settings.h"

#include <cmath>
#include <string>

#include "runtime/error.h"
#include "scenes/scene.h"

namespace hmb::passes {

HybridSettings HybridSettings::fromScene(const scene::Settings& sceneSettings) {
  HybridSettings settings;
  settings.edgeThreshold = sceneSettings.edgeThreshold;
  return settings;
}

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error("hybrid settings: " + message);
}

}  // namespace

void validate(const HybridSettings& s) {
  require(std::isfinite(s.edgeThreshold) && s.edgeThreshold >= 0.0f && s.edgeThreshold < 1.0f,
          "edge threshold must be in [0, 1) (got " + std::to_string(s.edgeThreshold) + ")");
  require(s.maxRecursion >= 1 && s.maxRecursion <= 64,
          "max recursion must be 1..64 (got " + std::to_string(s.maxRecursion) + ")");
  require(std::isfinite(s.luminanceThreshold) && s.luminanceThreshold > 0.0f && s.luminanceThreshold <= 1e6f,
          "luminance threshold must be finite and > 0 (got " + std::to_string(s.luminanceThreshold) + ")");
  for (const float factor : {s.maskBackgroundBoost, s.maskForegroundDivide, s.foregroundBoost})
    require(std::isfinite(factor) && factor > 0.0f && factor <= 1e6f,
            "boosts must be finite, > 0 and <= 1e6 (got " + std::to_string(factor) + ")");
}

std::string_view revealStopName(RevealStop stop) {
  return stop == RevealStop::Luminance ? "luminance" : "object-id";
}

std::string_view compositeName(HybridComposite composite) {
  return composite == HybridComposite::Weights ? "weights" : "coverage";
}

RevealStop parseRevealStop(std::string_view name) {
  if (name == "object-id") return RevealStop::ObjectId;
  if (name == "luminance") return RevealStop::Luminance;
  throw Error("unknown reveal stop '" + std::string(name) + "' (object-id|luminance)");
}

HybridComposite parseComposite(std::string_view name) {
  if (name == "coverage") return HybridComposite::Coverage;
  if (name == "weights") return HybridComposite::Weights;
  throw Error("unknown composite '" + std::string(name) + "' (coverage|weights)");
}

}  // namespace hmb::passes
