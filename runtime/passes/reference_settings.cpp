#include "hmblur/reference_settings.h"

#include <string>

#include "hmblur/error.h"

namespace hmb::passes {
namespace {

constexpr uint32_t kMaxSamplesPerPixel = 1u << 20;

}  // namespace

const settings::Table<ReferenceSettings, ReferenceSettings>& referenceSettingTable() {
  using namespace settings;
  using S = ReferenceSettings;
  static const Table<S, S> table = {
      number("spp", "reference", "samples (shutter times) per pixel", &S::samplesPerPixel, &S::samplesPerPixel,
             Range<uint32_t>{1, kMaxSamplesPerPixel}),
      number("seed", "reference", "seed of the shutter times' and pixel positions' jitter", &S::seed, &S::seed,
             Range<uint32_t>{}),
      flag("pixel-jitter", "reference", "a random point in the pixel per sample instead of its centre",
           &S::pixelJitter, &S::pixelJitter),
      path("checkpoint", "reference", "file to resume from and to save the sum to after every batch", &S::checkpoint,
           &S::checkpoint),
  };
  return table;
}

void validateReferenceSettings(const ReferenceSettings& settings) {
  settings::checkAll(referenceSettingTable(), settings, "reference settings");
  if (settings.timesPerBatch == 0 || settings.timesPerBatch > 4096)
    throw Error("reference batch of " + std::to_string(settings.timesPerBatch) + " times is out of range 1..4096");
  if (!settings.checkpoint.empty()) {
    const std::filesystem::path parent = settings.checkpoint.parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent))
      throw Error("--checkpoint '" + settings.checkpoint.string() + "': directory '" + parent.string() +
                  "' does not exist");
  }
}

}  // namespace hmb::passes
