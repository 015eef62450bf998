#include "hmblur/hybrid_settings.h"

#include <limits>
#include <string>
#include <utility>

#include "hmblur/error.h"
#include "hmblur/scene.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"

namespace hmb::passes {
namespace {

const settings::Names<RevealStop> kStopNames = {{RevealStop::ObjectId, "object-id"},
                                                {RevealStop::Luminance, "luminance"}};
const settings::Names<HybridComposite> kCompositeNames = {{HybridComposite::Coverage, "coverage"},
                                                          {HybridComposite::Weights, "weights"}};

using Choices = HybridChoices;
using Settings = HybridSettings;

settings::Table<Choices, Settings> makeTable() {
  using namespace settings;
  constexpr float kMaxFactor = 1e6f;
  const Range<float> factor{0.0f, kMaxFactor, true};
  // The paper's hybrid holds 0 strata (no rays); what a user may choose is a power of two
  // (validate()).
  auto strata = number("shutter-rays", "hybrid-rays",
                       "shutter strata for the rays of pixels whose path crosses an edge (another object, a colour "
                       "step), traced in place of the ray mask's reveal (under a ray budget, over it)",
                       &Choices::shutterRays, &Settings::shutterRays, Range<uint32_t>{0, HMB_MAX_SHUTTER_STRATA}, "8");
  strata.accepts = "2, 4, 8 or 16";
  return {
      number("edge-threshold", "hybrid", "ray-mask edge threshold e (eq. 4)", &Choices::edgeThreshold,
             &Settings::edgeThreshold, Range<float>{0.0f, 1.0f, false, true}, "the scene's"),
      named("reveal-stop", "hybrid", "reveal rays stop on another object, or on a luminance change (the paper)",
            &Choices::stop, &Settings::stop, kStopNames),
      number("max-recursion", "hybrid", "luminance stop: hits stepped past at most", &Choices::maxRecursion,
             &Settings::maxRecursion, Range<uint32_t>{1, 64}),
      number("luminance-threshold", "hybrid", "luminance stop: relative difference that ends a reveal",
             &Choices::luminanceThreshold, &Settings::luminanceThreshold, factor),
      named("composite", "hybrid", "coverage: alpha F + (1 - alpha) B; weights: the paper's weighted sum (see README)",
            &Choices::composite, &Settings::composite, kCompositeNames),
      number("mask-background-boost", "hybrid", "weights composite: background weight factor in the mask",
             &Choices::maskBackgroundBoost, &Settings::maskBackgroundBoost, factor),
      number("mask-foreground-divide", "hybrid", "weights composite: foreground weight divisor in the mask",
             &Choices::maskForegroundDivide, &Settings::maskForegroundDivide, factor),
      std::move(strata),
      number("ray-budget", "hybrid-rays",
             "shutter rays a frame traces at most, spent on the listed pixels in order of the error each is expected "
             "to remove per ray, over the paper's composite (0: every listed pixel's, in place of it)",
             &Choices::rayBudget, &Settings::rayBudget, Range<uint32_t>{0, std::numeric_limits<uint32_t>::max()}),
  };
}

}  // namespace

const settings::Table<HybridChoices, HybridSettings>& hybridSettingTable() {
  static const settings::Table<Choices, Settings> table = makeTable();
  return table;
}

HybridSettings HybridSettings::fromScene(const scene::Settings& sceneSettings) {
  HybridSettings settings;
  const PostProcessSettings defaults = settings.blur;
  settings.blur = PostProcessSettings::fromScene(sceneSettings);
  settings.blur.foregroundBoost = defaults.foregroundBoost;
  settings.blur.foregroundBoostPixels = defaults.foregroundBoostPixels;
  settings.edgeThreshold = sceneSettings.edgeThreshold;
  return settings;
}

void validate(const HybridSettings& s) {
  validate(s.blur);
  settings::checkAll(hybridSettingTable(), s, "hybrid settings");
  if (s.blur.filter != PostProcessFilter::McGuire)
    throw Error("hybrid settings: the hybrid method blurs with the McGuire filter (filter mcguire)");
  if (s.composite == HybridComposite::Coverage && s.blur.effectiveRange() != GatherRange::Adapted)
    throw Error("hybrid settings: the coverage composite needs the adapted range (range adapted)");
  if (s.shutterRays != 0 && (s.shutterRays < 2 || (s.shutterRays & (s.shutterRays - 1)) != 0))
    throw Error("hybrid settings: shutter-rays must be 2, 4, 8 or 16, not " + std::to_string(s.shutterRays));
  if (s.rayBudget != 0 && s.shutterRays == 0)
    throw Error("hybrid settings: a ray budget needs shutter rays (the hybrid-rays method)");
  // The weights form's gather would follow the paths but its mask weights assume straight ones.
  if (s.composite == HybridComposite::Weights && s.blur.motionPath == MotionPath::Curved)
    throw Error("hybrid settings: the weights composite follows straight paths only (motion-path linear)");
}

std::string_view revealStopName(RevealStop stop) { return settings::nameOf(kStopNames, stop); }

std::string_view compositeName(HybridComposite composite) { return settings::nameOf(kCompositeNames, composite); }

}  // namespace hmb::passes
