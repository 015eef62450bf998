// Settings of the hybrid method (paper, sections 3.2 and 4): the post-process blur it extends
// (McGuire's filter), the ray mask, the ray reveal and the composite; and the choices a user
// makes of them.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "hmblur/post_process_settings.h"
#include "hmblur/setting.h"

namespace hmb::scene {
struct Settings;
}

namespace hmb::passes {

enum class RevealStop {
  ObjectId,   // the first surface of another object (default; one trace)
  Luminance,  // the paper's mode: step past hits until the shaded luminance differs
};

enum class HybridComposite {
  Coverage,  // C = alpha F + (1 - alpha) B, alpha the foreground share of the range (default)
  Weights,   // background samples' colours replaced by B inside McGuire's weighted sum
};

// w_f's boost where the pixel is deeper than the sample by SOFT_Z_EXTENT, in both layers'
// gathers (adapted post-process keeps the paper's constant 30): max(1, k / |v_N|) with this k,
// |v_N| the tile's neighbour-max speed in pixels (PostProcessSettings::foregroundBoostPixels).
// The paper's boost makes a silhouette's outer blur opaque; with the inner blur revealed, 30
// over-darkens it, and the boost that does not falls with the blur's length in pixels (slow
// motion's outer blur is read at a few whole pixels). Measured against references on every
// scene at two sizes and several frame times and on a shrinking mesh at three sizes, k = 80 has
// the smallest worst-case loss against each case's best boost, smaller than the constants':
// bench/results/hybrid-foreground-boost/.
// --foreground-boost (a constant) or --foreground-boost-pixels overrides it.
inline constexpr float kHybridForegroundBoostPixels = 80.0f;

// hybrid-rays' shutter strata unless chosen (HybridSettings::shutterRays): 4 keep most of 8's
// gain for less time, 16 add little (bench/results/error-vs-time/).
inline constexpr uint32_t kHybridRaysStrata = 8;

struct HybridSettings {
  // The blur of both layers: the McGuire filter, the adapted range (the coverage composite needs
  // it) and the hybrid's foreground boost.
  PostProcessSettings blur = [] {
    PostProcessSettings s;
    s.foregroundBoostPixels = kHybridForegroundBoostPixels;
    return s;
  }();
  float edgeThreshold = 0.9f;          // e of eq. 4 (the scene's: 0.90 / 0.98 / 0.96 in the paper)
  RevealStop stop = RevealStop::ObjectId;
  uint32_t maxRecursion = 5;           // luminance stop: hits stepped past at most, 1..64
  float luminanceThreshold = 0.1f;     // luminance stop: relative difference that ends the recursion
  HybridComposite composite = HybridComposite::Coverage;
  // Inside the mask (paper, section 4): background weight x3, foreground weight /3. Only the
  // weights composite uses McGuire's weights there.
  float maskBackgroundBoost = 3.0f;
  float maskForegroundDivide = 3.0f;
  // Shutter rays, the hybrid-rays method (kernels/shutter_rays/list_shutter_rays.comp): the
  // shutter is cut into this many strata (a power of two up to 16; 0, the paper's hybrid, traces
  // none), and the moving pixels whose path crosses another object or a colour step trace a ray
  // at up to that many of them, one per 2 px of blur around them, in place of the ray mask's
  // reveal. A gather of one frame cannot place an edge between pixel centres; where the camera
  // moves, that is most of the error (docs/hybrid.md, "Shutter rays").
  uint32_t shutterRays = 0;
  // The rays a frame traces at most (0: every listed pixel's): the listed pixels are taken in
  // order of the error each is expected to remove per ray (shutterRayPriority), the others keep
  // the blur's colour.
  uint32_t rayBudget = 0;

  // The blur's exposure, fps and SOFT_Z_EXTENT and the edge threshold from a scene's settings,
  // the rest at their defaults.
  static HybridSettings fromScene(const scene::Settings& sceneSettings);
};

// What a user chose of the hybrid's own settings (its blur takes PostProcessChoices); the rest
// come from the scene (edge threshold) and the defaults above.
struct HybridChoices {
  std::optional<float> edgeThreshold;
  std::optional<RevealStop> stop;
  std::optional<uint32_t> maxRecursion;
  std::optional<float> luminanceThreshold;
  std::optional<HybridComposite> composite;
  std::optional<float> maskBackgroundBoost;
  std::optional<float> maskForegroundDivide;
  std::optional<uint32_t> shutterRays;
  std::optional<uint32_t> rayBudget;
};

// Every hybrid setting a user can choose, each described once (include/hmblur/setting.h), with
// the methods that read it: the reveal's belong to hybrid, the shutter rays' to hybrid-rays.
const settings::Table<HybridChoices, HybridSettings>& hybridSettingTable();

// Throws hmb::Error with a one-line message naming the first absurd value, the blur's included
// (which must be the McGuire filter, over the adapted range for the coverage composite).
void validate(const HybridSettings& settings);

std::string_view revealStopName(RevealStop stop);           // "object-id" | "luminance"
std::string_view compositeName(HybridComposite composite);  // "coverage" | "weights"

}  // namespace hmb::passes
