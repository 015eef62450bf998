#include "hmblur/post_process_settings.h"

#include <cmath>

#include "hmblur/error.h"
#include "hmblur/scene.h"
#include "kernels/mblur/mblur_layout.h"

namespace hmb::passes {
namespace {

settings::Names<PostProcessFilter> filterNames() {
  settings::Names<PostProcessFilter> names;
  for (const FilterDescription& d : kFilters) names.emplace_back(d.filter, d.name);
  return names;
}

const settings::Names<GatherRange> kRangeNames = {{GatherRange::Centered, "centered"},
                                                 {GatherRange::Adapted, "adapted"}};
const settings::Names<MotionPath> kMotionPathNames = {{MotionPath::Linear, "linear"}, {MotionPath::Curved, "curved"}};

// Tile sizes: a filter's default in pixels of 720 lines, as the command line says it.
std::string filterTileSizes() {
  std::string text;
  for (const FilterDescription& d : kFilters)
    text += (text.empty() ? "" : ", ") + std::string(d.name) + " " + std::to_string(d.tileSize);
  return text + " px per 720 image lines";
}

std::string defaultForegroundBoosts() {
  PostProcessSettings adapted, centered;
  adapted.range = GatherRange::Adapted;
  centered.range = GatherRange::Centered;
  return settings::formatNumber(adapted.effectiveForegroundBoost()) + " adapted, " +
         settings::formatNumber(centered.effectiveForegroundBoost()) +
         " centered; the hybrid's falls with the speed instead (foreground-boost-pixels)";
}

using Choices = PostProcessChoices;
using Settings = PostProcessSettings;
constexpr std::string_view kReaders = "postprocess, hybrid, hybrid-rays";

settings::Table<Choices, Settings> makeTable() {
  using namespace settings;
  constexpr float kMaxFactor = 1e6f;
  return {
      named("filter", "postprocess", "the gather that ends the blur", &Choices::filter, &Settings::filter,
            filterNames()),
      named("range", kReaders, "adapted: the pixel at the end of its range (the paper); centered: McGuire's",
            &Choices::range, &Settings::range, kRangeNames),
      number("samples", kReaders, "gather samples S", &Choices::samples, &Settings::samples,
             Range<uint32_t>{1, HMB_MBLUR_MAX_SAMPLES}),
      number("tile-size", kReaders, "tile size m in pixels", &Choices::tileSize, &Settings::tileSize,
             Range<uint32_t>{1, HMB_MBLUR_MAX_TILE_SIZE}, filterTileSizes()),
      number("neighborhood", kReaders, "neighbour-max over n x n tiles", &Choices::neighborhood,
             &Settings::neighborhood, Range<uint32_t>{1, HMB_MBLUR_MAX_NEIGHBORHOOD, false, false, true}),
      number("foreground-boost", kReaders, "w_f factor where the pixel is past SOFT_Z_EXTENT behind the sample",
             &Choices::foregroundBoost, &Settings::foregroundBoost, Range<float>{0.0f, kMaxFactor, true},
             defaultForegroundBoosts()),
      number("foreground-boost-pixels", kReaders,
             "k: a foreground boost that falls with the blur, max(1, k / |v_N|), |v_N| the tile's neighbour-max speed "
             "in pixels; replaces the constant foreground-boost",
             &Choices::foregroundBoostPixels, &Settings::foregroundBoostPixels, Range<float>{0.0f, kMaxFactor, true},
             "none"),
      number("soft-z-extent", kReaders, "SOFT_Z_EXTENT in scene units", &Choices::softZExtent,
             &Settings::softZExtent, Range<float>{0.0f, std::numeric_limits<float>::max(), true}, "the scene's"),
      number("seed", kReaders, "seed of the gathers' per-pixel sample jitter", &Choices::seed, &Settings::seed,
             Range<uint32_t>{}),
      number("time-slices", kReaders,
             "K: the shutter cut into K slices, each rasterized at its close and blurred over its own span; the "
             "frame is their mean (K times the work)",
             &Choices::timeSlices, &Settings::timeSlices, Range<uint32_t>{1, kMaxTimeSlices}),
      named("motion-path", kReaders,
            "linear: straight along the tiles' velocity (the paper); curved: moving pixels follow their own path "
            "through t, t - E/2 and t - E (adapted range)",
            &Choices::motionPath, &Settings::motionPath, kMotionPathNames),
  };
}

}  // namespace

const settings::Table<PostProcessChoices, PostProcessSettings>& postProcessSettingTable() {
  static const settings::Table<Choices, Settings> table = makeTable();
  return table;
}

PostProcessSettings PostProcessSettings::fromScene(const scene::Settings& sceneSettings) {
  PostProcessSettings settings;
  settings.exposure = sceneSettings.exposure;
  settings.fps = sceneSettings.fps;
  settings.softZExtent = sceneSettings.softZExtent;
  return settings;
}

float PostProcessSettings::effectiveForegroundBoost() const {
  if (foregroundBoost) return *foregroundBoost;
  return effectiveRange() == GatherRange::Adapted ? 30.0f : 1.0f;
}

float PostProcessSettings::foregroundBoostAt(float neighborMaxSpeed) const {
  if (!foregroundBoostPixels) return effectiveForegroundBoost();
  return std::max(1.0f, foregroundBoostPixelsPerSlice() / std::max(neighborMaxSpeed, 1.0f));
}

float PostProcessSettings::foregroundBoostPixelsPerSlice() const {
  return foregroundBoostPixels ? *foregroundBoostPixels / float(std::max(timeSlices, 1u)) : 0.0f;
}

uint32_t PostProcessSettings::effectiveTileSize() const { return tileSize.value_or(describe(filter).tileSize); }

GatherRange PostProcessSettings::effectiveRange() const { return describe(filter).onlyRange.value_or(range); }

float PostProcessSettings::velocityScale() const { return gatherVelocityScale(effectiveRange(), exposure, fps); }

float gatherVelocityScale(GatherRange range, float exposure, float fps) {
  const float perExposure = exposure * fps;
  return range == GatherRange::Centered ? 0.5f * perExposure : perExposure;
}

void validate(const PostProcessSettings& s) {
  settings::checkAll(postProcessSettingTable(), s, "post-process settings");
  const auto require = [](bool ok, const std::string& message) {
    if (!ok) throw Error("post-process settings: " + message);
  };
  require(!(s.foregroundBoost && s.foregroundBoostPixels),
          "foreground-boost and foreground-boost-pixels exclude each other: choose one");
  require(std::isfinite(s.exposure) && s.exposure >= 0.0f,
          "exposure must be finite and >= 0 s (got " + std::to_string(s.exposure) + ")");
  require(std::isfinite(s.fps) && s.fps > 0.0f, "fps must be finite and > 0 (got " + std::to_string(s.fps) + ")");
  require(std::isfinite(s.exposure * s.fps), "exposure * fps overflows");
  require(s.motionPath == MotionPath::Linear ||
              (s.filter == PostProcessFilter::McGuire && s.effectiveRange() == GatherRange::Adapted),
          "the curved motion path needs the mcguire filter over the adapted range");
  require(std::isfinite(s.jimenezTileJitter) && s.jimenezTileJitter >= 0.0f && s.jimenezTileJitter <= 1.0f,
          "Jimenez tile jitter must be in [0, 1] tiles (got " + std::to_string(s.jimenezTileJitter) + ")");
}

std::string_view filterName(PostProcessFilter filter) { return describe(filter).name; }

std::string_view rangeName(GatherRange range) { return settings::nameOf(kRangeNames, range); }

std::string_view motionPathName(MotionPath path) { return settings::nameOf(kMotionPathNames, path); }

TileGrid tileGridFor(uint32_t width, uint32_t height, uint32_t tileSize) {
  return {(width + tileSize - 1) / tileSize, (height + tileSize - 1) / tileSize};
}

}  // namespace hmb::passes
