#include "runtime/passes/post_process_settings.h"

#include <cmath>

#include "kernels/mblur/mblur_layout.h"
#include "runtime/error.h"
#include "scenes/scene.h"

namespace hmb::passes {

PostProcessSettings PostProcessSettings::fromScene(const scene::Settings& sceneSettings) {
  PostProcessSettings settings;
  settings.exposure = sceneSettings.exposure;
  settings.fps = sceneSettings.fps;
  settings.softZExtent = sceneSettings.softZExtent;
  return settings;
}

float PostProcessSettings::effectiveForegroundBoost() const {
  if (foregroundBoost) return *foregroundBoost;
  return range == GatherRange::Adapted ? 30.0f : 1.0f;
}

uint32_t PostProcessSettings::effectiveTileSize() const {
  return filter == PostProcessFilter::Jimenez ? jimenezTileSize : tileSize;
}

GatherRange PostProcessSettings::effectiveRange() const {
  return filter == PostProcessFilter::Jimenez ? GatherRange::Centered : range;
}

float PostProcessSettings::velocityScale() const { return gatherVelocityScale(effectiveRange(), exposure, fps); }

float gatherVelocityScale(GatherRange range, float exposure, float fps) {
  const float perExposure = exposure * fps;
  return range == GatherRange::Centered ? 0.5f * perExposure : perExposure;
}

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error("post-process settings: " + message);
}

void requireFactor(float value, const char* name) {
  require(std::isfinite(value) && value > 0.0f && value <= 1e6f,
          std::string(name) + " must be finite, > 0 and <= 1e6 (got " + std::to_string(value) + ")");
}

}  // namespace

void validate(const PostProcessSettings& s) {
  require(s.samples >= 1 && s.samples <= HMB_MBLUR_MAX_SAMPLES,
          "samples must be 1.." + std::to_string(HMB_MBLUR_MAX_SAMPLES) + " (got " + std::to_string(s.samples) + ")");
  require(s.tileSize >= 1 && s.tileSize <= HMB_MBLUR_MAX_TILE_SIZE,
          "tile size must be 1.." + std::to_string(HMB_MBLUR_MAX_TILE_SIZE) + " px (got " +
              std::to_string(s.tileSize) + ")");
  require(s.jimenezTileSize >= 1 && s.jimenezTileSize <= HMB_MBLUR_MAX_TILE_SIZE,
          "Jimenez tile size must be 1.." + std::to_string(HMB_MBLUR_MAX_TILE_SIZE) + " px (got " +
              std::to_string(s.jimenezTileSize) + ")");
  require(s.neighborhood % 2 == 1 && s.neighborhood <= HMB_MBLUR_MAX_NEIGHBORHOOD,
          "neighbourhood must be odd and 1.." + std::to_string(HMB_MBLUR_MAX_NEIGHBORHOOD) + " tiles (got " +
              std::to_string(s.neighborhood) + ")");
  require(std::isfinite(s.exposure) && s.exposure >= 0.0f,
          "exposure must be finite and >= 0 s (got " + std::to_string(s.exposure) + ")");
  require(std::isfinite(s.fps) && s.fps > 0.0f, "fps must be finite and > 0 (got " + std::to_string(s.fps) + ")");
  require(std::isfinite(s.exposure * s.fps), "exposure * fps overflows");
  require(std::isfinite(s.softZExtent) && s.softZExtent > 0.0f,
          "SOFT_Z_EXTENT must be finite and > 0 (got " + std::to_string(s.softZExtent) + ")");
  requireFactor(s.effectiveForegroundBoost(), "foreground boost");
  requireFactor(s.maskBackgroundBoost, "mask background boost");
  requireFactor(s.maskForegroundDivide, "mask foreground divide");
  require(std::isfinite(s.jimenezTileJitter) && s.jimenezTileJitter >= 0.0f && s.jimenezTileJitter <= 1.0f,
          "Jimenez tile jitter must be in [0, 1] tiles (got " + std::to_string(s.jimenezTileJitter) + ")");
}

std::string_view filterName(PostProcessFilter filter) {
  return filter == PostProcessFilter::Jimenez ? "jimenez" : "mcguire";
}

std::string_view rangeName(GatherRange range) { return range == GatherRange::Centered ? "centered" : "adapted"; }

PostProcessFilter parseFilter(std::string_view name) {
  if (name == "mcguire") return PostProcessFilter::McGuire;
  if (name == "jimenez") return PostProcessFilter::Jimenez;
  throw Error("unknown post-process filter '" + std::string(name) + "' (mcguire|jimenez)");
}

GatherRange parseRange(std::string_view name) {
  if (name == "centered") return GatherRange::Centered;
  if (name == "adapted") return GatherRange::Adapted;
  throw Error("unknown gather range '" + std::string(name) + "' (centered|adapted)");
}

TileGrid tileGridFor(uint32_t width, uint32_t height, uint32_t tileSize) {
  return {(width + tileSize - 1) / tileSize, (height + tileSize - 1) / tileSize};
}

}  // namespace hmb::passes
