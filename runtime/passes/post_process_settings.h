// Settings of the post-process motion blur (tile-max -> neighbour-max -> gather), shared by its
// passes, its stage and the C++ reference in the tests.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hmb::scene {
struct Settings;
}

namespace hmb::passes {

enum class PostProcessFilter {
  McGuire,  // McGuire et al. 2012 with the paper's appendix weights (kernels/mblur/gather.comp)
  Jimenez,  // Jimenez 2014, the filter UE4 follows (kernels/mblur/gather_jimenez.comp)
};

enum class GatherRange {
  Centered,  // McGuire's original: half velocities, samples over X + t v_N, t in [-1, 1]
  Adapted,   // the paper (Fig. 3): full per-exposure velocity, samples over X + u v_N, u in (0, 1]
};

struct PostProcessSettings {
  PostProcessFilter filter = PostProcessFilter::McGuire;
  GatherRange range = GatherRange::Adapted;  // McGuire filter only: Jimenez's filter is centred
  uint32_t samples = 15;                     // gather samples S, 1..255 (Jimenez: ceil(S/2) pairs)
  uint32_t tileSize = 40;                    // McGuire tile size m (paper: 40), 1..1024 px
  uint32_t jimenezTileSize = 20;             // Jimenez filter's tile size, 1..1024 px
  float jimenezTileJitter = 0.25f;           // Jimenez neighbour-max lookup jitter, tiles, [0, 1]
  uint32_t neighborhood = 3;                 // n x n tiles of the neighbour-max, odd, 1..31
  uint32_t seed = 0;                         // per-pixel sample jitter
  // Multiplies w_f where the pixel is deeper than the sample by at least SOFT_Z_EXTENT. Unset:
  // 30 for the adapted range (the paper, section 4: the range ends at the pixel, so a pixel
  // just behind a moving silhouette gathers foreground from one side only, and the boost makes
  // the outer blur fade smoothly from the object's edge) and 1 for the centred range (McGuire's
  // weights are balanced for symmetric ranges; 1 is his filter unchanged).
  std::optional<float> foregroundBoost;
  float exposure = 1.0f / 60.0f;  // E, seconds: shutter open over [t - E, t]
  float fps = 120.0f;             // velocity q is per frame of 1/fps seconds
  float softZExtent = 0.03f;      // SOFT_Z_EXTENT, camera-space depth units
  // Inside the hybrid method's ray mask (paper, section 4: x3 and /3); 1 = off.
  float maskBackgroundBoost = 1.0f;
  float maskForegroundDivide = 1.0f;

  // exposure, fps and SOFT_Z_EXTENT from a scene's settings (after scene::deriveDefaults), the
  // rest at their defaults.
  static PostProcessSettings fromScene(const scene::Settings& sceneSettings);

  float effectiveForegroundBoost() const;
  // Tile size of the selected filter.
  uint32_t effectiveTileSize() const;
  // The selected filter's range: Jimenez's is always centred.
  GatherRange effectiveRange() const;
  // G-buffer velocity (pixels per frame) -> the gather's velocity: E * fps, halved when centred.
  float velocityScale() const;
};

// Throws hmb::Error with a one-line message naming the first absurd value: samples 0 or over
// 255, a tile size 0 or over 1024, an even, zero or over-31 neighbourhood, a non-finite or
// negative exposure, fps <= 0 or non-finite, SOFT_Z_EXTENT <= 0 or non-finite, a boost or
// divide <= 0, non-finite or over 1e6, a tile jitter outside [0, 1].
void validate(const PostProcessSettings& settings);

std::string_view filterName(PostProcessFilter filter);  // "mcguire" | "jimenez"
std::string_view rangeName(GatherRange range);          // "centered" | "adapted"
// Parse those names; throw hmb::Error on anything else.
PostProcessFilter parseFilter(std::string_view name);
GatherRange parseRange(std::string_view name);

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
