// Settings of the post-process motion blur (tile-max -> neighbour-max -> gather), shared by its
// passes, its stage and the C++ reference in the tests, and the choices a user makes of them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "hmblur/post_process_filter.h"
#include "hmblur/setting.h"

namespace hmb::scene {
struct Settings;
}

namespace hmb::passes {

inline constexpr uint32_t kMaxTimeSlices = 64;

// The screen path a moving pixel's gather follows.
enum class MotionPath {
  Linear,  // McGuire's: straight, along the tile's neighbour-max velocity (the paper)
  Curved,  // a pixel moving about as fast as its neighbourhood samples along its own quadratic
           // path through its points at t, t - E/2 and t - E (mblur/gather_samples.glsl);
           // adapted range only; the G-buffer stage then computes those points
};

struct PostProcessSettings {
  PostProcessFilter filter = PostProcessFilter::McGuire;
  GatherRange range = GatherRange::Adapted;  // for filters that have no onlyRange
  uint32_t samples = 15;                     // gather samples S, 1..255 (Jimenez: ceil(S/2) pairs)
  std::optional<uint32_t> tileSize;          // pixels; unset: the filter's (post_process_filter.h)
  float jimenezTileJitter = 0.25f;           // Jimenez neighbour-max lookup jitter, tiles, [0, 1]
  uint32_t neighborhood = 3;                 // n x n tiles of the neighbour-max, odd, 1..31
  uint32_t seed = 0;                         // per-pixel sample jitter
  // Multiplies w_f where the pixel is deeper than the sample by at least SOFT_Z_EXTENT. Unset:
  // 30 for the adapted range (the paper, section 4: the range ends at the pixel, so a pixel
  // just behind a moving silhouette gathers foreground from one side only, and the boost makes
  // the outer blur fade smoothly from the object's edge) and 1 for the centred range (McGuire's
  // weights are balanced for symmetric ranges; 1 is his filter unchanged).
  std::optional<float> foregroundBoost;
  // Set (k pixels): the boost falls with the blur's length instead, max(1, k / |v_N|) per pixel,
  // |v_N| its tile's neighbour-max speed in pixels (at least 1). Slow motion's outer blur is read
  // at a few whole pixels, and needs more of a boost than fast motion's (the hybrid's default:
  // kHybridForegroundBoostPixels). Exclusive with foregroundBoost. With time slices the boost
  // follows the whole shutter's blur, K times a slice's: k / K per slice (measured against k:
  // bench/results/hybrid-foreground-boost/).
  std::optional<float> foregroundBoostPixels;
  // E, seconds: the span a gather blurs over, the shutter [t - E, t] (with time slices, one
  // slice of it: the scene's exposure / timeSlices).
  float exposure = 1.0f / 60.0f;
  float fps = 120.0f;             // velocity q is per frame of 1/fps seconds
  float softZExtent = 0.03f;      // SOFT_Z_EXTENT, camera-space depth units
  // The shutter cut into this many equal slices, each a frame of its own (rasterized at the
  // slice's close, blurred over the slice alone) and the frame their mean: K times the work for
  // blur lengths K times shorter (Renderer::render). 1: the paper's one G-buffer. The
  // renderer's settings of a sliced frame hold the slice's exposure.
  uint32_t timeSlices = 1;
  MotionPath motionPath = MotionPath::Linear;

  // exposure, fps and SOFT_Z_EXTENT from a scene's settings (after scene::deriveDefaults), the
  // rest at their defaults.
  static PostProcessSettings fromScene(const scene::Settings& sceneSettings);

  // The constant boost (foregroundBoost or its default); foregroundBoostAt gives the one a pixel
  // gets, which is this unless foregroundBoostPixels is set.
  float effectiveForegroundBoost() const;
  // The boost of a pixel whose tile's neighbour-max speed is neighborMaxSpeed pixels (the
  // gathers' kernels compute the same: mblur/gather_samples.glsl).
  float foregroundBoostAt(float neighborMaxSpeed) const;
  // k / timeSlices where foregroundBoostPixels is set (what the gathers get), else 0.
  float foregroundBoostPixelsPerSlice() const;
  // The tile size, or the selected filter's.
  uint32_t effectiveTileSize() const;
  // The selected filter's range where it has only one.
  GatherRange effectiveRange() const;
  // G-buffer velocity (pixels per frame) -> the gather's velocity: E * fps, halved when centred.
  float velocityScale() const;

  bool operator==(const PostProcessSettings&) const = default;
};

// What a user chose of the post-process settings; the rest come from the scene (exposure, frame
// rate, SOFT_Z_EXTENT), the image (tile sizes scale with its height) and the defaults above.
struct PostProcessChoices {
  std::optional<PostProcessFilter> filter;
  std::optional<GatherRange> range;
  std::optional<uint32_t> samples;
  std::optional<uint32_t> tileSize;
  std::optional<uint32_t> neighborhood;
  std::optional<float> foregroundBoost;
  std::optional<float> foregroundBoostPixels;
  std::optional<float> softZExtent;
  std::optional<uint32_t> seed;
  std::optional<uint32_t> timeSlices;
  std::optional<MotionPath> motionPath;
};

// Every post-process setting a user can choose, each described once (include/hmblur/setting.h).
const settings::Table<PostProcessChoices, PostProcessSettings>& postProcessSettingTable();

// Throws hmb::Error with a one-line message naming the first value outside what its setting
// accepts (the table's checks, then exposure, fps and the Jimenez tile jitter).
void validate(const PostProcessSettings& settings);

std::string_view filterName(PostProcessFilter filter);  // "mcguire" | "jimenez"
std::string_view rangeName(GatherRange range);          // "centered" | "adapted"
std::string_view motionPathName(MotionPath path);       // "linear" | "curved"

// G-buffer velocity (pixels per frame) -> a gather's velocity for a range: E * fps, halved
// when centred (McGuire's half velocities).
float gatherVelocityScale(GatherRange range, float exposure, float fps);

// Tiles covering an image: partial tiles at the right and bottom borders.
struct TileGrid {
  uint32_t x = 0;
  uint32_t y = 0;
  uint32_t count() const { return x * y; }
};
TileGrid tileGridFor(uint32_t width, uint32_t height, uint32_t tileSize);

}  // namespace hmb::passes
