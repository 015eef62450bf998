#include "tests/mblur/mblur_reference.h"

#include <algorithm>
#include <cmath>

#include <glm/packing.hpp>

#include "kernels/mblur/mblur_layout.h"
#include "kernels/shared/layer_layout.h"

namespace hmb::test::mblur {

namespace {
constexpr float kMaxColor = float(HMB_MBLUR_MAX_COLOR);  // the kernels' (mblur_layout.h)
constexpr float kMaxDepth = float(HMB_MBLUR_MAX_DEPTH);

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }
bool finite(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
float length2(glm::vec2 v) { return std::sqrt(v.x * v.x + v.y * v.y); }
}  // namespace

std::vector<glm::uvec4> packedSamples(const Layer& layer) {
  std::vector<glm::uvec4> samples(layer.color.size());
  for (size_t i = 0; i < samples.size(); ++i)
    samples[i] = gpu::packLayerSample(glm::vec3(layer.color[i]), layer.normalDepth[i].w, layer.velocity[i]);
  return samples;
}

glm::uvec2 packShutterPath(glm::vec2 fromMid, glm::vec2 fromOpen) {
  return {glm::packHalf2x16(fromMid), glm::packHalf2x16(fromOpen)};
}

bool shutterPathTerms(glm::uvec2 record, glm::vec2& a, glm::vec2& c) {
  const glm::vec2 m = glm::unpackHalf2x16(record.x), o = glm::unpackHalf2x16(record.y);
  a = 4.0f * m - o;
  c = 2.0f * o - 4.0f * m;
  const auto finite = [](glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); };
  return finite(m) && finite(o);
}

void inversePath(glm::vec2 a, glm::vec2 c, glm::vec2 change, float maxLength, glm::vec2& linear,
                 glm::vec2& quadratic) {
  const glm::vec2 k = std::isfinite(change.x) && std::isfinite(change.y) ? c + change : c;
  const auto overflowFreeLength = [](glm::vec2 x) {
    const float largest = std::max(std::abs(x.x), std::abs(x.y));
    return largest > 0.0f ? largest * length2(x / largest) : 0.0f;
  };
  const float reach = overflowFreeLength(a) + overflowFreeLength(k);
  const float scale = reach > maxLength ? maxLength / reach : 1.0f;
  linear = a * scale;
  quadratic = k * scale;
}

float pathReach(glm::ivec2 samplePixel, glm::uvec2 sampleRecord, glm::vec2 v, glm::vec2 x) {
  glm::vec2 a, c;
  if (!shutterPathTerms(sampleRecord, a, c)) {
    a = v;
    c = glm::vec2(0.0f);
  }
  const glm::vec2 start = glm::vec2(samplePixel) + 0.5f;
  float nearest = length2(x - start);
  glm::vec2 previous = start;
  for (uint32_t j = 1; j <= 8; ++j) {
    const float u = float(j) / 8.0f;
    const glm::vec2 next = start - u * a - (u * u) * c;
    const glm::vec2 segment = next - previous;
    const float along = std::clamp(glm::dot(x - previous, segment) / std::max(glm::dot(segment, segment), 1e-12f), 0.0f, 1.0f);
    nearest = std::min(nearest, length2(x - (previous + along * segment)));
    previous = next;
  }
  return std::clamp(2.0f - nearest, 0.0f, 1.0f);
}

Layer stored(const Layer& layer) {
  Layer out = layer;
  const std::vector<glm::uvec4> samples = packedSamples(layer);
  for (size_t i = 0; i < samples.size(); ++i) {
    out.color[i] = glm::vec4(gpu::sampleColor(samples[i]), 1.0f);
    out.normalDepth[i].w = gpu::sampleDepth(samples[i]);
    out.velocity[i] = gpu::sampleVelocity(samples[i]);
  }
  return out;
}

std::vector<glm::uvec4> packedSurfaces(const Layer& layer) {
  std::vector<glm::uvec4> surfaces(layer.velocity.size());
  for (size_t i = 0; i < surfaces.size(); ++i)
    surfaces[i] = gpu::packLayerSurface(glm::vec3(layer.normalDepth[i]), 1u, layer.normalDepth[i].w, layer.velocity[i]);
  return surfaces;
}

std::vector<glm::vec2> packedVelocities(const Layer& layer) {
  std::vector<glm::vec2> velocities(HMB_LAYER_VELOCITY_ENTRIES(layer.velocity.size()), glm::vec2(0.0f));
  for (size_t i = 0; i < layer.velocity.size(); ++i) velocities[i] = gpu::layerVelocityEntry(layer.velocity[i]);
  return velocities;
}

std::vector<glm::vec2> storedVelocity(const std::vector<glm::vec2>& velocity) {
  std::vector<glm::vec2> out(velocity.size());
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = gpu::surfaceVelocity(gpu::packLayerSurface(glm::vec3(0.0f), 1u, 1.0f, velocity[i]));
  return out;
}

glm::vec2 gatherVelocity(glm::vec2 q, float velocityScale, float maxSpeed, float& speed) {
  const glm::vec2 v(q.x * velocityScale, q.y * velocityScale);
  speed = 0.0f;
  if (!finite(v)) return glm::vec2(0.0f);
  const float largest = std::max(std::abs(v.x), std::abs(v.y));
  if (!(largest >= 1e-30f)) return glm::vec2(0.0f);
  const glm::vec2 unit(v.x / largest, v.y / largest);
  const float unitLength = length2(unit);
  const float fullSpeed = largest * unitLength;
  if (fullSpeed <= maxSpeed) {
    speed = fullSpeed;
    return v;
  }
  speed = maxSpeed;
  const float scale = maxSpeed / unitLength;
  return {unit.x * scale, unit.y * scale};
}

float gatherSpeed(glm::vec2 q, float velocityScale, float maxSpeed) {
  const glm::vec2 v(q.x * velocityScale, q.y * velocityScale);
  if (!finite(v)) return 0.0f;
  const float speed = std::min(length2(v), maxSpeed);
  return speed >= 1e-30f ? speed : 0.0f;
}

glm::vec4 sanitizeColor(glm::vec4 c) {
  for (int i = 0; i < 4; ++i) c[i] = std::isnan(c[i]) ? 0.0f : std::clamp(c[i], -kMaxColor, kMaxColor);
  return c;
}

float sanitizeDepth(float z) { return std::isnan(z) ? kMaxDepth : std::clamp(z, 0.0f, kMaxDepth); }

glm::ivec2 nearestPixel(glm::vec2 position, uint32_t width, uint32_t height) {
  const glm::ivec2 p(int(std::floor(position.x)), int(std::floor(position.y)));
  return {std::clamp(p.x, 0, int(width) - 1), std::clamp(p.y, 0, int(height) - 1)};
}

float cone(float ds, float v) { return saturate(1.0f - ds / std::max(v, 1e-6f)); }

std::optional<float> gatherSampleParameter(uint32_t i, uint32_t samples, float jitter, bool adapted) {
  if (adapted) return (float(i) + 1.0f - jitter) * (1.0f / float(samples));  // as gatherSampleT
  if ((samples & 1u) == 1u && i == (samples - 1u) / 2u) return std::nullopt;
  const float a = (float(i) + jitter + 0.5f) / float(samples + 1u);
  return -1.0f * (1.0f - a) + 1.0f * a;  // mix(-1, 1, a) as GLSL evaluates it
}

float cylinder(float v, float s) {
  if (v <= 0.0f) return s <= 0.0f ? 1.0f : 0.0f;
  const float t = saturate((s - 0.95f * v) / (0.1f * v));
  return 1.0f - t * t * (3.0f - 2.0f * t);
}

AppendixWeights appendixWeights(float targetDepth, float sampleDepth, float targetSpeed, float sampleSpeed, float ds,
                                float softZExtent) {
  const float z = (targetDepth - sampleDepth) / softZExtent;
  return {saturate(1.0f + z) * cone(ds, sampleSpeed), saturate(1.0f - z) * cone(ds, targetSpeed),
          cylinder(sampleSpeed, ds) * cylinder(targetSpeed, ds) * 2.0f};
}

std::vector<glm::vec4> tileMax(const std::vector<glm::vec2>& velocity, uint32_t width, uint32_t height,
                               uint32_t tileSize, float velocityScale) {
  const passes::TileGrid grid = passes::tileGridFor(width, height, tileSize);
  std::vector<glm::vec4> tiles(grid.count());
  for (uint32_t ty = 0; ty < grid.y; ++ty)
    for (uint32_t tx = 0; tx < grid.x; ++tx) {
      glm::vec2 best(0.0f);
      float bestSpeed = -1.0f;
      // Row-major order with a strict comparison: the first pixel keeps a tie.
      for (uint32_t y = ty * tileSize; y < std::min((ty + 1) * tileSize, height); ++y)
        for (uint32_t x = tx * tileSize; x < std::min((tx + 1) * tileSize, width); ++x) {
          float speed;
          const glm::vec2 v = gatherVelocity(velocity[y * width + x], velocityScale, float(tileSize), speed);
          if (speed > bestSpeed) {
            best = v;
            bestSpeed = speed;
          }
        }
      tiles[ty * grid.x + tx] = glm::vec4(best, std::max(bestSpeed, 0.0f), 0.0f);
    }
  return tiles;
}

std::vector<glm::vec4> neighborMax(const std::vector<glm::vec4>& tileMax, passes::TileGrid grid,
                                   uint32_t neighborhood) {
  std::vector<glm::vec4> out(grid.count());
  const int radius = int(neighborhood / 2);
  for (int ty = 0; ty < int(grid.y); ++ty)
    for (int tx = 0; tx < int(grid.x); ++tx) {
      glm::vec4 best(0.0f, 0.0f, -1.0f, 0.0f);
      for (int y = std::max(ty - radius, 0); y <= std::min(ty + radius, int(grid.y) - 1); ++y)
        for (int x = std::max(tx - radius, 0); x <= std::min(tx + radius, int(grid.x) - 1); ++x) {
          const glm::vec4 candidate = tileMax[size_t(y) * grid.x + x];
          if (candidate.z > best.z) best = candidate;
        }
      out[size_t(ty) * grid.x + tx] = best;
    }
  return out;
}

std::vector<glm::vec4> gather(const Layer& input, const std::vector<glm::vec4>& neighborMaxTiles,
                              const std::vector<uint32_t>* mask, const passes::PostProcessSettings& settings,
                              passes::MaskWeights maskWeights) {
  const Layer layer = stored(input);
  const uint32_t width = layer.width, height = layer.height, m = settings.effectiveTileSize();
  const passes::TileGrid grid = passes::tileGridFor(width, height, m);
  const float velocityScale = passes::gatherVelocityScale(settings.range, settings.exposure, settings.fps);
  const bool adapted = settings.range == passes::GatherRange::Adapted;
  const float maxSpeed = float(m);
  const bool curved =
      adapted && settings.motionPath == passes::MotionPath::Curved && !layer.shutterPaths.empty();
  std::vector<glm::vec4> out(size_t(width) * height);
  for (uint32_t py = 0; py < height; ++py)
    for (uint32_t px = 0; px < width; ++px) {
      const uint32_t index = py * width + px;
      const glm::vec4 centreColor = sanitizeColor(layer.color[index]);
      const glm::vec4 dominant = neighborMaxTiles[(py / m) * grid.x + px / m];
      if (dominant.z < gpu::kMinBlurPixels) {
        out[index] = centreColor;
        continue;
      }
      const float foregroundBoost = settings.foregroundBoostAt(dominant.z);
      const float centreSpeed = gatherSpeed(layer.velocity[index], velocityScale, maxSpeed);
      const float centreDepth = sanitizeDepth(layer.normalDepth[index].w);
      const bool inMask = mask && (*mask)[index] != 0;
      const float backgroundScale = inMask ? maskWeights.backgroundBoost : 1.0f;
      const float foregroundScale = inMask ? 1.0f / maskWeights.foregroundDivide : 1.0f;

      float weightSum = 1.0f / std::max(centreSpeed, 0.5f);
      glm::vec4 sum = centreColor * weightSum;
      const float jitter = unitFromHash(mblurHash(px, py, settings.seed));
      const glm::vec2 centre(float(px) + 0.5f, float(py) + 0.5f);
      // The pixel's own path (readOwnPath).
      bool ownPath = false;
      glm::vec2 pathLinear(0.0f), pathQuadratic(0.0f);
      glm::vec2 a, c;
      if (curved && shutterPathTerms(layer.shutterPaths[index], a, c) &&
          !(length2(a) + length2(c) < gpu::kOwnPathShare * std::max(length2(glm::vec2(dominant)), gpu::kMinBlurPixels))) {
        const glm::ivec2 ahead = nearestPixel(centre + a, width, height);
        const uint32_t aheadIndex = uint32_t(ahead.y) * width + uint32_t(ahead.x);
        const bool sameSurface = std::abs(sanitizeDepth(layer.normalDepth[aheadIndex].w) - centreDepth) < settings.softZExtent;
        const glm::vec2 change =
            sameSurface ? (layer.velocity[aheadIndex] - layer.velocity[index]) * velocityScale : glm::vec2(0.0f);
        ownPath = true;
        inversePath(a, c, change, maxSpeed, pathLinear, pathQuadratic);
      }
      const uint32_t samples = settings.samples;
      for (uint32_t i = 0; i < samples; ++i) {
        const std::optional<float> parameter = gatherSampleParameter(i, samples, jitter, adapted);
        if (!parameter) continue;
        const float t = *parameter;
        const glm::vec2 along = ownPath ? t * pathLinear + (t * t) * pathQuadratic : t * glm::vec2(dominant);
        glm::ivec2 s = nearestPixel(centre + along, width, height);
        uint32_t sampleIndex = uint32_t(s.y) * width + uint32_t(s.x);
        // The fixed-point step along the sample's own path.
        glm::vec2 a1, c1;
        if (ownPath && std::abs(sanitizeDepth(layer.normalDepth[sampleIndex].w) - centreDepth) < settings.softZExtent &&
            shutterPathTerms(layer.shutterPaths[sampleIndex], a1, c1)) {
          const glm::vec2 refinedAlong = t * a1 + (t * t) * c1;
          if (length2(refinedAlong) <= maxSpeed) {
            const glm::ivec2 refined = nearestPixel(centre + refinedAlong, width, height);
            const uint32_t refinedIndex = uint32_t(refined.y) * width + uint32_t(refined.x);
            if (std::abs(sanitizeDepth(layer.normalDepth[refinedIndex].w) - centreDepth) < settings.softZExtent) {
              s = refined;
              sampleIndex = refinedIndex;
            }
          }
        }
        const float ds = length2(glm::vec2(float(s.x - int(px)), float(s.y - int(py))));
        const float sampleSpeed = gatherSpeed(layer.velocity[sampleIndex], velocityScale, maxSpeed);
        float unused;
        const glm::vec2 sampleV = gatherVelocity(layer.velocity[sampleIndex], velocityScale, maxSpeed, unused);
        const float sampleDepth = sanitizeDepth(layer.normalDepth[sampleIndex].w);
        AppendixWeights w =
            appendixWeights(centreDepth, sampleDepth, centreSpeed, sampleSpeed, ds, settings.softZExtent);
        if (centreDepth - sampleDepth >= settings.softZExtent) w.foreground *= foregroundBoost;
        const float z = (centreDepth - sampleDepth) / settings.softZExtent;
        if (curved && z > 0.0f)
          w.foreground *= glm::mix(1.0f, pathReach(s, layer.shutterPaths[sampleIndex], sampleV, centre), std::min(z, 1.0f));
        w.foreground *= foregroundScale;
        w.background *= backgroundScale;
        const float weight = w.foreground + w.background + w.simultaneous;
        weightSum += weight;
        sum += weight * sanitizeColor(layer.color[sampleIndex]);
      }
      out[index] = sum / weightSum;
    }
  return out;
}

namespace {

glm::vec2 depthCompare(float centreDepth, float sampleDepth, float softZExtent) {
  const float d = (sampleDepth - centreDepth) / softZExtent;
  return {saturate(0.5f + d), saturate(0.5f - d)};
}

float spreadCompare(float offset, float spread) { return saturate(spread - std::max(offset - 1.0f, 0.0f)); }

float jimenezWeight(float centreDepth, float sampleDepth, float offset, float centreSpread, float sampleSpread,
                    float softZExtent) {
  const glm::vec2 depth = depthCompare(centreDepth, sampleDepth, softZExtent);
  return depth.x * spreadCompare(offset, centreSpread) + depth.y * spreadCompare(offset, sampleSpread);
}

}  // namespace

std::vector<glm::vec4> gatherJimenez(const Layer& input, const std::vector<glm::vec4>& neighborMaxTiles,
                                     const passes::PostProcessSettings& settings) {
  const Layer layer = stored(input);
  const uint32_t width = layer.width, height = layer.height, tileSize = settings.effectiveTileSize();
  const passes::TileGrid grid = passes::tileGridFor(width, height, tileSize);
  const float velocityScale = passes::gatherVelocityScale(passes::GatherRange::Centered, settings.exposure, settings.fps);
  const float m = float(tileSize);
  std::vector<glm::vec4> out(size_t(width) * height);
  for (uint32_t py = 0; py < height; ++py)
    for (uint32_t px = 0; px < width; ++px) {
      const uint32_t index = py * width + px;
      const glm::vec4 centreColor = sanitizeColor(layer.color[index]);
      uint32_t h = mblurHash(px, py, settings.seed);
      const float sampleJitter = unitFromHash(h);
      h = nextHash(h);
      const float jitterX = unitFromHash(h);
      h = nextHash(h);
      const float jitterY = unitFromHash(h);
      const glm::vec2 centre(float(px) + 0.5f, float(py) + 0.5f);
      const glm::vec2 lookup(centre.x / m + (jitterX * 2.0f - 1.0f) * settings.jimenezTileJitter,
                             centre.y / m + (jitterY * 2.0f - 1.0f) * settings.jimenezTileJitter);
      const int tx = std::clamp(int(std::floor(lookup.x)), 0, int(grid.x) - 1);
      const int ty = std::clamp(int(std::floor(lookup.y)), 0, int(grid.y) - 1);
      const glm::vec4 dominant = neighborMaxTiles[size_t(ty) * grid.x + tx];
      if (dominant.z < gpu::kMinBlurPixels) {
        out[index] = centreColor;
        continue;
      }
      const uint32_t pairs = (settings.samples + 1u) / 2u;
      const float pixelsToSampleUnits = float(pairs) / dominant.z;
      float centreSpeed;
      gatherVelocity(layer.velocity[index], velocityScale, m, centreSpeed);
      const float centreSpread = centreSpeed * pixelsToSampleUnits;
      const float centreDepth = sanitizeDepth(layer.normalDepth[index].w);

      glm::vec4 sum(0.0f);
      float weightSum = 0.0f;
      for (uint32_t k = 0; k < pairs; ++k) {
        const float offset = float(k) + 1.0f - sampleJitter;
        const float along = offset / float(pairs);
        const glm::vec2 step(along * dominant.x, along * dominant.y);
        const glm::ivec2 a = nearestPixel({centre.x + step.x, centre.y + step.y}, width, height);
        const glm::ivec2 b = nearestPixel({centre.x - step.x, centre.y - step.y}, width, height);
        const uint32_t indexA = uint32_t(a.y) * width + uint32_t(a.x);
        const uint32_t indexB = uint32_t(b.y) * width + uint32_t(b.x);
        float speedA, speedB;
        gatherVelocity(layer.velocity[indexA], velocityScale, m, speedA);
        gatherVelocity(layer.velocity[indexB], velocityScale, m, speedB);
        const float depthA = sanitizeDepth(layer.normalDepth[indexA].w);
        const float depthB = sanitizeDepth(layer.normalDepth[indexB].w);
        const float spreadA = speedA * pixelsToSampleUnits, spreadB = speedB * pixelsToSampleUnits;
        float weightA = jimenezWeight(centreDepth, depthA, offset, centreSpread, spreadA, settings.softZExtent);
        float weightB = jimenezWeight(centreDepth, depthB, offset, centreSpread, spreadB, settings.softZExtent);
        if (depthA > depthB && spreadB > spreadA)
          weightA = weightB;
        else if (depthB > depthA && spreadA > spreadB)
          weightB = weightA;
        sum += weightA * sanitizeColor(layer.color[indexA]) + weightB * sanitizeColor(layer.color[indexB]);
        weightSum += weightA + weightB;
      }
      const float sampleCount = float(2u * pairs);
      out[index] = (sum + std::max(sampleCount - weightSum, 0.0f) * centreColor) / sampleCount;
    }
  return out;
}

std::vector<glm::vec4> postProcess(const Layer& layer, const std::vector<uint32_t>* mask,
                                   const passes::PostProcessSettings& settings) {
  const uint32_t tileSize = settings.effectiveTileSize();
  const std::vector<glm::vec4> tiles =
      tileMax(layer.velocity, layer.width, layer.height, tileSize, settings.velocityScale());
  const std::vector<glm::vec4> neighbors =
      neighborMax(tiles, passes::tileGridFor(layer.width, layer.height, tileSize), settings.neighborhood);
  if (settings.filter == passes::PostProcessFilter::Jimenez) return gatherJimenez(layer, neighbors, settings);
  return gather(layer, neighbors, mask, settings);
}

}  // namespace hmb::test::mblur
