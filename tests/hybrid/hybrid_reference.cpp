#include "tests/hybrid/hybrid_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "kernels/mblur/mblur_layout.h"
#include "kernels/shared/layer_layout.h"

namespace hmb::test::hybrid {

namespace {

using mblur::gatherVelocity;
using mblur::nearestPixel;
using mblur::sanitizeColor;
using mblur::sanitizeDepth;

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

// mblur_common.glsl's behindShareOf.
float behindShareOf(uint32_t sampleObject, float sampleDepth, uint32_t centreObject, float centreDepth,
                    float softZExtent) {
  if (sampleObject == centreObject) return 0.0f;
  return saturate((sampleDepth - centreDepth) / softZExtent);
}

// mblur_common.glsl's coverageSamplePixel.
glm::ivec2 coverageSamplePixel(uint32_t px, uint32_t py, glm::vec2 v, glm::vec2 q, uint32_t i, uint32_t samples,
                               float jitter, uint32_t width, uint32_t height) {
  const float u = (float(i) + 1.0f - jitter) / float(samples);
  return nearestPixel(glm::vec2(float(px) + 0.5f, float(py) + 0.5f) + u * v + (u * u) * q, width, height);
}

// range_check.comp's and composite.comp's own curved path of pixel (x, y): its record's terms
// with the change of velocity to X + a where that lies on the same surface (depth within
// softZExtent), through inversePath. False (v, q untouched) without a path.
template <class DepthAt, class VelocityAt>
bool ownCurvedPath(glm::uvec2 record, uint32_t x, uint32_t y, uint32_t width, uint32_t height, DepthAt depthAt,
                   VelocityAt velocityAt, float velocityScale, float maxSpeed, float softZExtent, glm::vec2& v,
                   glm::vec2& q) {
  glm::vec2 a, c;
  if (!mblur::shutterPathTerms(record, a, c)) return false;
  const glm::ivec2 ahead = nearestPixel(glm::vec2(float(x) + 0.5f, float(y) + 0.5f) + a, width, height);
  const size_t aheadIndex = size_t(uint32_t(ahead.y)) * width + uint32_t(ahead.x);
  const size_t index = size_t(y) * width + x;
  const bool sameSurface = std::abs(depthAt(aheadIndex) - depthAt(index)) < softZExtent;
  const glm::vec2 change = sameSurface ? (velocityAt(aheadIndex) - velocityAt(index)) * velocityScale : glm::vec2(0.0f);
  mblur::inversePath(a, c, change, maxSpeed, v, q);
  return true;
}
float length2(glm::vec2 v) { return std::sqrt(v.x * v.x + v.y * v.y); }
float dot3(glm::vec3 a, glm::vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

size_t indexOf(uint32_t width, glm::ivec2 p) { return size_t(uint32_t(p.y)) * width + uint32_t(p.x); }

}  // namespace

bool endsOnDeeperObject(uint32_t idHere, float depthHere, uint32_t idEnd, float depthEnd, float softZExtent) {
  return idEnd != idHere && sanitizeDepth(depthEnd) - sanitizeDepth(depthHere) > softZExtent;
}

float sobelSmooth(int k) { return k == 0 ? 6.0f : (std::abs(k) == 1 ? 4.0f : 1.0f); }

float sobelDerivative(int k) {
  if (k == 0) return 0.0f;
  return float(k > 0 ? 1 : -1) * (std::abs(k) == 1 ? 2.0f : 1.0f);
}

float normalizedEdge(float x) {
  if (std::isnan(x)) return 0.0f;
  if (std::isinf(x)) return x > 0.0f ? 1.0f : 0.0f;
  return std::clamp(1.0f - 1.0f / (std::max(x, 0.0f) + 1.0f), 0.0f, 1.0f);
}

glm::vec3 sanitizeNormal(glm::vec3 n) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(n[i])) return glm::vec3(0.0f);
  return {std::clamp(n.x, -1.0f, 1.0f), std::clamp(n.y, -1.0f, 1.0f), std::clamp(n.z, -1.0f, 1.0f)};
}

namespace {

// Eq. 3's x on a layer already as stored.
float strengthOf(const MaskLayer& layer, int x, int y, float depthHere) {
  const int lastX = int(layer.width) - 1, lastY = int(layer.height) - 1;
  glm::vec4 window[25];
  float largest = 0.0f;
  for (int k = 0; k < 25; ++k) {
    const glm::ivec2 p(std::clamp(x + k % 5 - 2, 0, lastX), std::clamp(y + k / 5 - 2, 0, lastY));
    const glm::vec4 nd = layer.normalDepth[indexOf(layer.width, p)];
    window[k] = glm::vec4(sanitizeNormal(glm::vec3(nd)), sanitizeDepth(nd.w));
    largest = std::max(largest, window[k].w);
  }
  glm::vec2 depthGradient(0.0f);
  glm::vec3 normalX(0.0f), normalY(0.0f);
  for (int k = 0; k < 25; ++k) {
    const int dx = k % 5 - 2, dy = k / 5 - 2;
    const float wx = sobelDerivative(dx) * sobelSmooth(dy);
    const float wy = sobelSmooth(dx) * sobelDerivative(dy);
    if (largest > 0.0f) {
      const float relative = window[k].w / largest;
      depthGradient.x += wx * relative;
      depthGradient.y += wy * relative;
    }
    const glm::vec3 n(window[k]);
    normalX += glm::vec3(wx * n.x, wx * n.y, wx * n.z);
    normalY += glm::vec3(wy * n.x, wy * n.y, wy * n.z);
  }
  const float gradient = length2(depthGradient);
  const float deltaD = gradient > 0.0f ? gradient * (largest / std::max(depthHere, 1e-30f)) : 0.0f;
  const float deltaN = std::sqrt(dot3(normalX, normalX) + dot3(normalY, normalY));
  return deltaD + deltaN;
}

// Eqs. 1 and 2 on a layer already as stored, each pixel moving by its velocity as the G-buffer's
// velocities hold it (the input's floats), as the hybrid's tile-max reads it.
std::vector<bool> candidatesOf(const MaskLayer& layer, const std::vector<glm::vec2>& velocity,
                               const passes::RayMaskParameters& p);

}  // namespace

MaskLayer stored(const MaskLayer& layer) {
  MaskLayer out = layer;
  out.color.resize(layer.objectId.size(), glm::vec3(0.0f));
  for (size_t i = 0; i < layer.objectId.size(); ++i) {
    out.color[i] = gpu::sampleColor(gpu::packLayerSample(out.color[i], layer.normalDepth[i].w, layer.velocity[i]));
    const glm::uvec4 surface =
        gpu::packLayerSurface(glm::vec3(layer.normalDepth[i]), layer.objectId[i], layer.normalDepth[i].w, layer.velocity[i]);
    out.normalDepth[i] = glm::vec4(gpu::surfaceNormal(surface), layer.normalDepth[i].w);  // depth: kept bit for bit
    out.velocity[i] = gpu::surfaceVelocity(surface);
    out.objectId[i] = gpu::surfaceObjectId(surface);
  }
  return out;
}

float edgeStrength(const MaskLayer& layer, int x, int y, float depthHere) {
  return strengthOf(stored(layer), x, y, depthHere);
}

std::vector<float> normalizedEdges(const MaskLayer& input) {
  const MaskLayer layer = stored(input);
  std::vector<float> out(size_t(layer.width) * layer.height);
  for (uint32_t y = 0; y < layer.height; ++y)
    for (uint32_t x = 0; x < layer.width; ++x) {
      const size_t index = size_t(y) * layer.width + x;
      out[index] = normalizedEdge(strengthOf(layer, int(x), int(y), sanitizeDepth(layer.normalDepth[index].w)));
    }
  return out;
}

std::vector<bool> edgeCandidates(const MaskLayer& layer, const passes::RayMaskParameters& p) {
  return candidatesOf(stored(layer), layer.velocity, p);
}

namespace {

std::vector<bool> candidatesOf(const MaskLayer& layer, const std::vector<glm::vec2>& velocity,
                               const passes::RayMaskParameters& p) {
  std::vector<bool> out(size_t(layer.width) * layer.height, false);
  for (uint32_t y = 0; y < layer.height; ++y)
    for (uint32_t x = 0; x < layer.width; ++x) {
      const size_t index = size_t(y) * layer.width + x;
      float speed;
      const glm::vec2 v = gatherVelocity(velocity[index], p.blur.velocityScale, p.blur.maxSpeed, speed);
      if (!(speed > 0.0f)) continue;
      const glm::ivec2 end = nearestPixel({float(x) + 0.5f + v.x, float(y) + 0.5f + v.y}, layer.width, layer.height);
      const size_t endIndex = indexOf(layer.width, end);
      out[index] = endsOnDeeperObject(layer.objectId[index], sanitizeDepth(layer.normalDepth[index].w),
                                      layer.objectId[endIndex], layer.normalDepth[endIndex].w, p.blur.softZExtent);
    }
  return out;
}

}  // namespace

std::vector<uint32_t> shutterRays(const MaskLayer& input, const passes::RayMaskParameters& p, uint32_t strata,
                                  std::vector<uint32_t>* priorities) {
  const MaskLayer layer = stored(input);
  const uint32_t width = layer.width, height = layer.height, tileSize = p.blur.tileSize;
  const uint32_t tilesX = (width + tileSize - 1) / tileSize;
  const std::vector<glm::vec4> tiles = mblur::tileMax(input.velocity, width, height, tileSize, p.blur.velocityScale);
  std::vector<uint32_t> out(size_t(width) * height, 0u);
  if (priorities) priorities->assign(out.size(), 0u);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const glm::vec4 fastest = tiles[size_t(y / tileSize) * tilesX + x / tileSize];
      if (!(fastest.z >= gpu::kMinBlurPixels)) continue;  // list_moving_tiles
      const size_t index = size_t(y) * width + x;
      const uint32_t id = layer.objectId[index];
      const glm::vec3 key = gpu::shutterRayColorKey(layer.color[index]);
      // Another object, or a colour a step away: the largest step of the colour keys' channels;
      // -1 for neither.
      const auto difference = [&](glm::ivec2 q) {
        const size_t i = indexOf(width, q);
        const glm::vec3 there = gpu::shutterRayColorKey(layer.color[i]);
        const glm::vec3 step = glm::abs(there - key);
        const float contrast = std::max(step.x, std::max(step.y, step.z));
        return layer.objectId[i] != id || gpu::shutterRayColorsDiffer(there, key) ? contrast : -1.0f;
      };
      float speed;
      const glm::vec2 own = gatherVelocity(layer.velocity[index], p.blur.velocityScale, p.blur.maxSpeed, speed);
      const bool moves = speed >= 0.5f;
      const glm::vec2 v = moves ? own : glm::vec2(fastest);
      const float length = moves ? speed : fastest.z;
      // The path X + u v, u in [-1, 1], and a pixel past either end, in steps of at most a pixel.
      const glm::vec2 reach = v * (1.0f + 1.0f / length);
      const int steps = int(std::ceil(length + 1.0f));
      const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
      // Walked whole for the priority, else to the first sample that differs.
      uint32_t differing = 0;
      float contrast = 0.0f;
      for (int k = 1; k <= steps && (priorities || differing == 0); ++k) {
        const glm::vec2 along = reach * (float(k) / float(steps));
        const float ahead = difference(nearestPixel(centre + along, width, height));
        const float behind = difference(nearestPixel(centre - along, width, height));
        differing += uint32_t(ahead >= 0.0f) + uint32_t(behind >= 0.0f);
        contrast = std::max(contrast, std::max(ahead, behind));
      }
      if (differing == 0) continue;
      out[index] = gpu::shutterRaysFor(std::max(speed, fastest.z), strata);
      if (priorities)
        (*priorities)[index] = gpu::shutterRayPriorityBucket(
            gpu::shutterRayPriority(contrast, differing, 2u * uint32_t(steps), out[index]));
    }
  return out;
}

std::vector<bool> keptByBudget(const std::vector<uint32_t>& rays, const std::vector<uint32_t>& priorities,
                               uint32_t budgetRays) {
  // Pairs of rays per bucket, and the bucket where the budget runs out.
  std::vector<uint64_t> pairs(HMB_RAY_BUDGET_BUCKETS, 0);
  for (size_t i = 0; i < rays.size(); ++i)
    if (rays[i] != 0) pairs.at(priorities[i]) += rays[i] / 2;
  const uint64_t budgetPairs = budgetRays / 2;
  uint64_t spent = 0, allowance = std::numeric_limits<uint64_t>::max();
  uint32_t threshold = 0;
  for (uint32_t b = HMB_RAY_BUDGET_BUCKETS; b-- > 0;) {
    if (pairs[b] > budgetPairs - spent) {
      threshold = b;
      allowance = budgetPairs - spent;
      break;
    }
    spent += pairs[b];
  }
  // The threshold bucket's pairs per range of pixel indices, and the first range that does not fit.
  const uint32_t rangePixels = uint32_t((rays.size() + HMB_RAY_BUDGET_BUCKETS - 1) / HMB_RAY_BUDGET_BUCKETS);
  std::vector<uint64_t> ties(HMB_RAY_BUDGET_BUCKETS, 0);
  for (size_t i = 0; i < rays.size(); ++i)
    if (rays[i] != 0 && priorities[i] == threshold) ties[gpu::rayBudgetTieRange(uint32_t(i), rangePixels)] += rays[i] / 2;
  uint32_t tieRange = HMB_RAY_BUDGET_BUCKETS;
  spent = 0;
  for (uint32_t r = 0; r < HMB_RAY_BUDGET_BUCKETS; ++r) {
    if (ties[r] > allowance - spent) {
      tieRange = r;
      break;
    }
    spent += ties[r];
  }
  std::vector<bool> kept(rays.size(), false);
  for (size_t i = 0; i < rays.size(); ++i)
    kept[i] = rays[i] != 0 && (priorities[i] > threshold ||
                               (priorities[i] == threshold && gpu::rayBudgetTieRange(uint32_t(i), rangePixels) < tieRange));
  return kept;
}

std::vector<uint32_t> edgeMask(const MaskLayer& input, const passes::RayMaskParameters& p) {
  const MaskLayer layer = stored(input);
  const std::vector<bool> candidates = candidatesOf(layer, input.velocity, p);
  std::vector<uint32_t> out(candidates.size(), 0u);
  for (uint32_t y = 0; y < layer.height; ++y)
    for (uint32_t x = 0; x < layer.width; ++x) {
      const size_t index = size_t(y) * layer.width + x;
      if (!candidates[index]) continue;
      const float depthHere = sanitizeDepth(layer.normalDepth[index].w);
      if (normalizedEdge(strengthOf(layer, int(x), int(y), depthHere)) > p.edgeThreshold) out[index] = 1u;
    }
  return out;
}

namespace {

bool curvedFlag(const passes::RayMaskParameters& p) { return (p.blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u; }
auto depthOf(const MaskLayer& layer) {
  return [&layer](size_t i) { return sanitizeDepth(layer.normalDepth[i].w); };
}
auto velocityOf(const MaskLayer& layer) {
  return [&layer](size_t i) { return layer.velocity[i]; };
}

}  // namespace

uint32_t rangeBlockEntryOf(uint32_t ox, uint32_t oy, uint32_t tileSize) {
  const uint32_t lastX = (tileSize - 1) / HMB_MASK_TILE_GROUP_X * HMB_MASK_TILE_GROUP_X;
  const uint32_t lastY = (tileSize - 1) / HMB_MASK_TILE_GROUP_Y * HMB_MASK_TILE_GROUP_Y;
  return gpu::rangeBlockEntry(glm::uvec2(ox, oy), ox % tileSize == lastX, oy % tileSize == lastY);
}

std::vector<uint32_t> rangeBlocks(const MaskLayer& input, const std::vector<uint32_t>& edges,
                                  const passes::RayMaskParameters& p) {
  const MaskLayer layer = stored(input);
  const uint32_t width = layer.width, height = layer.height, tileSize = p.blur.tileSize;
  const uint32_t tilesX = (width + tileSize - 1) / tileSize, tilesY = (height + tileSize - 1) / tileSize;
  const std::vector<glm::vec4> tiles = mblur::tileMax(input.velocity, width, height, tileSize, p.blur.velocityScale);
  // edge_mask's coarse image: a block is flagged when an edge pixel lies within a pixel of it.
  const uint32_t coarseX = HMB_EDGE_BLOCKS_ACROSS(width), coarseY = HMB_EDGE_BLOCKS_ACROSS(height);
  std::vector<bool> coarse(size_t(coarseX) * coarseY, false);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      if (edges[size_t(y) * width + x] == 0u) continue;
      for (uint32_t by = (y == 0 ? 0 : y - 1) / HMB_EDGE_BLOCK; by <= std::min(y + 1, height - 1) / HMB_EDGE_BLOCK; ++by)
        for (uint32_t bx = (x == 0 ? 0 : x - 1) / HMB_EDGE_BLOCK; bx <= std::min(x + 1, width - 1) / HMB_EDGE_BLOCK;
             ++bx)
          coarse[size_t(by) * coarseX + bx] = true;
    }
  std::vector<uint32_t> out;
  for (uint32_t ty = 0; ty < tilesY; ++ty)
    for (uint32_t tx = 0; tx < tilesX; ++tx) {
      const float reach = tiles[size_t(ty) * tilesX + tx].z;
      if (!(reach >= gpu::kMinBlurPixels)) continue;  // list_moving_tiles
      const bool bounded = !curvedFlag(p) && reach < float(tileSize);
      const int margin = int(std::ceil(reach)) + 1;
      for (uint32_t oy = ty * tileSize; oy < std::min((ty + 1) * tileSize, height); oy += HMB_MASK_TILE_GROUP_Y)
        for (uint32_t ox = tx * tileSize; ox < std::min((tx + 1) * tileSize, width); ox += HMB_MASK_TILE_GROUP_X) {
          bool listed = !bounded;
          if (bounded) {
            const auto coarseOf = [&](int v, uint32_t size) {
              return uint32_t(std::clamp(v, 0, int(size) - 1)) / HMB_EDGE_BLOCK;
            };
            const uint32_t x0 = coarseOf(int(ox) - margin, width), y0 = coarseOf(int(oy) - margin, height);
            const uint32_t x1 = coarseOf(int(ox) + HMB_MASK_TILE_GROUP_X - 1 + margin, width);
            const uint32_t y1 = coarseOf(int(oy) + HMB_MASK_TILE_GROUP_Y - 1 + margin, height);
            // Too wide a reach to test: listed.
            const uint32_t side = HMB_RANGE_BLOCKS_MAX_TEST_SIDE;
            listed = x1 - x0 >= side || y1 - y0 >= side;
            for (uint32_t by = y0; by <= y1 && !listed; ++by)
              for (uint32_t bx = x0; bx <= x1 && !listed; ++bx) listed = coarse[size_t(by) * coarseX + bx];
          }
          if (listed) out.push_back(rangeBlockEntryOf(ox, oy, tileSize));
        }
    }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<uint32_t> rangeCheck(const MaskLayer& input, const std::vector<uint32_t>& edges,
                                 const passes::RayMaskParameters& p) {
  const MaskLayer layer = stored(input);
  const uint32_t width = layer.width, height = layer.height;
  std::vector<uint32_t> out(size_t(width) * height, 0u);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t index = size_t(y) * width + x;
      float speed;
      glm::vec2 v = gatherVelocity(layer.velocity[index], p.blur.velocityScale, p.blur.maxSpeed, speed);
      if (!(speed > 0.0f)) continue;
      glm::vec2 q(0.0f);
      const bool curved = curvedFlag(p) && ownCurvedPath(layer.shutterPaths[index], x, y, width, height, depthOf(layer),
                                                         velocityOf(layer), p.blur.velocityScale, p.blur.maxSpeed,
                                                         p.blur.softZExtent, v, q);
      const auto steps =
          uint32_t(std::ceil(curved ? std::max(length2(v), length2(v + 2.0f * q)) : speed));
      const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
      for (uint32_t i = 0; i <= steps; ++i) {
        const float s = curved ? (steps == 0 ? 0.0f : float(i) / float(steps)) : float(i) / float(steps);
        const glm::ivec2 r = nearestPixel(curved ? centre + s * v + (s * s) * q : centre + v * s, width, height);
        if (edges[indexOf(width, r)] != 0u) {
          out[index] = 1u;
          break;
        }
      }
    }
  return out;
}

std::vector<uint32_t> rangeCheck(const std::vector<glm::vec2>& input, const std::vector<uint32_t>& edges,
                                 uint32_t width, uint32_t height, const passes::RayMaskParameters& p) {
  const std::vector<glm::vec2> velocity = mblur::storedVelocity(input);
  std::vector<uint32_t> out(size_t(width) * height, 0u);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t index = size_t(y) * width + x;
      float speed;
      const glm::vec2 v = gatherVelocity(velocity[index], p.blur.velocityScale, p.blur.maxSpeed, speed);
      if (!(speed > 0.0f)) continue;
      const auto steps = uint32_t(std::ceil(speed));
      const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
      for (uint32_t i = 0; i <= steps; ++i) {
        const float u = float(i) / float(steps);
        const glm::ivec2 q = nearestPixel({centre.x + v.x * u, centre.y + v.y * u}, width, height);
        if (edges[indexOf(width, q)] != 0u) {
          out[index] = 1u;
          break;
        }
      }
    }
  return out;
}

std::vector<bool> revealedPixels(const MaskLayer& input, const std::vector<uint32_t>& mask,
                                 const passes::RayMaskParameters& p) {
  const MaskLayer layer = stored(input);
  std::vector<bool> out(mask.size(), false);
  for (uint32_t y = 0; y < layer.height; ++y)
    for (uint32_t x = 0; x < layer.width; ++x) {
      const size_t index = size_t(y) * layer.width + x;
      if (mask[index] == 0u) continue;
      float speed;
      glm::vec2 v = gatherVelocity(layer.velocity[index], p.blur.velocityScale, p.blur.maxSpeed, speed);
      glm::vec2 q(0.0f);
      if (curvedFlag(p) && speed > 0.0f)
        ownCurvedPath(layer.shutterPaths[index], x, y, layer.width, layer.height, depthOf(layer), velocityOf(layer),
                      p.blur.velocityScale, p.blur.maxSpeed, p.blur.softZExtent, v, q);
      const float jitter = mblur::unitFromHash(mblur::mblurHash(x, y, p.blur.seed));
      const float centreDepth = sanitizeDepth(layer.normalDepth[index].w);
      for (uint32_t i = 0; i < p.blur.samples && !out[index]; ++i) {
        const size_t sample =
            indexOf(layer.width, coverageSamplePixel(x, y, v, q, i, p.blur.samples, jitter, layer.width, layer.height));
        out[index] = behindShareOf(layer.objectId[sample], sanitizeDepth(layer.normalDepth[sample].w),
                                   layer.objectId[index], centreDepth, p.blur.softZExtent) > 0.0f;
      }
    }
  return out;
}

gpu::RayMaskCounters dispatchFor(uint32_t maskCount) { return dispatchFor(maskCount, 0u); }

gpu::RayMaskCounters dispatchFor(uint32_t maskCount, uint32_t unrevealed) {
  const auto rows = [](uint32_t count) {
    const uint32_t groups = (count + HMB_MASK_LIST_GROUP - 1u) / HMB_MASK_LIST_GROUP;
    return gpu::IndirectDispatch{groups == 0u ? 0u : std::min(groups, 65535u),
                                 groups == 0u ? 0u : (groups + 65534u) / 65535u, 1u};
  };
  gpu::RayMaskCounters c{};
  c.maskCount = maskCount;
  c.unrevealedCount = unrevealed;
  c.maskPixels = maskCount + unrevealed;
  c.dispatches[HMB_RAY_MASK_DISPATCH_MASK] = rows(maskCount);
  c.dispatches[HMB_RAY_MASK_DISPATCH_UNREVEALED] = rows(unrevealed);
  return c;
}

gpu::RayMaskCounters coverageDispatchFor(uint32_t maskPixels) {
  gpu::RayMaskCounters c = dispatchFor(maskPixels);
  // The range check's count; mask_coverage moves each pixel to the front or the back. Either
  // side may take them all: the passes over each are dispatched for all (they read the counts).
  c.coverageCount = maskPixels;
  c.dispatches[HMB_RAY_MASK_DISPATCH_COVERAGE] = c.dispatches[HMB_RAY_MASK_DISPATCH_UNREVEALED] =
      c.dispatches[HMB_RAY_MASK_DISPATCH_MASK];
  c.maskCount = 0u;
  return c;
}

namespace {

struct CompositeInputs {
  const mblur::Layer& layer;                        // as the gathers read it (mblur::stored)
  const std::vector<glm::vec2>& surfaceVelocity;    // as the coverage form reads it (exact)
  const std::vector<glm::vec4>& background;
  const std::vector<uint32_t>& objectId;
  float softZExtent;
};

// composite.comp's behindShare.
float behindShare(const CompositeInputs& in, size_t sampleIndex, uint32_t centreObject, float centreDepth) {
  return behindShareOf(in.objectId[sampleIndex], sanitizeDepth(in.layer.normalDepth[sampleIndex].w), centreObject,
                       centreDepth, in.softZExtent);
}

// mask_coverage.comp at one mask pixel.
MaskCoverage coverageAt(const CompositeInputs& in, uint32_t px, uint32_t py, float velocityScale, float maxSpeed,
                        uint32_t samples, uint32_t seed, bool curved) {
  const mblur::Layer& layer = in.layer;
  const size_t index = size_t(py) * layer.width + px;
  const float centreDepth = sanitizeDepth(layer.normalDepth[index].w);
  const float jitter = mblur::unitFromHash(mblur::mblurHash(px, py, seed));
  float speed;
  glm::vec2 v = gatherVelocity(in.surfaceVelocity[index], velocityScale, maxSpeed, speed);
  glm::vec2 q(0.0f);
  if (curved)
    ownCurvedPath(
        layer.shutterPaths[index], px, py, layer.width, layer.height,
        [&](size_t i) { return sanitizeDepth(layer.normalDepth[i].w); }, [&](size_t i) { return in.surfaceVelocity[i]; },
        velocityScale, maxSpeed, in.softZExtent, v, q);
  const uint32_t centreObject = in.objectId[index];
  glm::vec4 foregroundSum = sanitizeColor(layer.color[index]);
  float foregroundCount = 0.0f;
  MaskCoverage out;
  for (uint32_t i = 0; i < samples; ++i) {
    const size_t sampleIndex =
        indexOf(layer.width, coverageSamplePixel(px, py, v, q, i, samples, jitter, layer.width, layer.height));
    const float behind = behindShare(in, sampleIndex, centreObject, centreDepth);
    out.meetsBackground = out.meetsBackground || behind > 0.0f;
    const float onObject = 1.0f - behind;
    foregroundSum += onObject * sanitizeColor(layer.color[sampleIndex]);
    foregroundCount += onObject;
  }
  out.foreground = glm::vec3(foregroundSum) / (1.0f + foregroundCount);
  out.alpha = foregroundCount / float(samples);
  return out;
}

// The coverage form of composite.comp: F (opaque) over the blurred background by alpha.
glm::vec4 coverageComposite(const MaskCoverage& c, glm::vec4 background) {
  return c.alpha * glm::vec4(c.foreground, 1.0f) + (1.0f - c.alpha) * sanitizeColor(background);
}

glm::vec4 mixColor(glm::vec4 a, glm::vec4 b, float t) { return a * (1.0f - t) + b * t; }

// The weighted sum of composite.comp at a mask pixel with the weights form.
glm::vec4 weightsComposite(const CompositeInputs& in, uint32_t px, uint32_t py, glm::vec4 dominant,
                           glm::vec4 centreColor, float centreDepth, float jitter,
                           const passes::PostProcessSettings& settings, passes::MaskWeights maskWeights) {
  const mblur::Layer& layer = in.layer;
  const size_t index = size_t(py) * layer.width + px;
  const float velocityScale = passes::gatherVelocityScale(settings.range, settings.exposure, settings.fps);
  const float maxSpeed = float(settings.effectiveTileSize());
  const bool adapted = settings.range == passes::GatherRange::Adapted;
  const float centreSpeed = mblur::gatherSpeed(layer.velocity[index], velocityScale, maxSpeed);
  const glm::vec4 revealed = sanitizeColor(in.background[index]);
  const uint32_t centreObject = in.objectId[index];
  const float backgroundScale = maskWeights.backgroundBoost;
  const float foregroundScale = 1.0f / maskWeights.foregroundDivide;
  const float foregroundBoost = settings.foregroundBoostAt(dominant.z);

  float weightSum = 1.0f / std::max(centreSpeed, 0.5f);
  glm::vec4 sum = centreColor * weightSum;
  const glm::vec2 centre(float(px) + 0.5f, float(py) + 0.5f);
  const uint32_t samples = settings.samples;
  for (uint32_t i = 0; i < samples; ++i) {
    const std::optional<float> parameter = mblur::gatherSampleParameter(i, samples, jitter, adapted);
    if (!parameter) continue;
    const float t = *parameter;
    const glm::ivec2 s =
        nearestPixel({centre.x + t * dominant.x, centre.y + t * dominant.y}, layer.width, layer.height);
    const size_t sampleIndex = indexOf(layer.width, s);
    const float ds = length2(glm::vec2(float(s.x - int(px)), float(s.y - int(py))));
    const float sampleSpeed = mblur::gatherSpeed(layer.velocity[sampleIndex], velocityScale, maxSpeed);
    const float sampleDepth = sanitizeDepth(layer.normalDepth[sampleIndex].w);
    mblur::AppendixWeights w =
        mblur::appendixWeights(centreDepth, sampleDepth, centreSpeed, sampleSpeed, ds, settings.softZExtent);
    if (centreDepth - sampleDepth >= settings.softZExtent) w.foreground *= foregroundBoost;
    w.foreground *= foregroundScale;
    w.background *= backgroundScale;
    const float weight = w.foreground + w.background + w.simultaneous;
    const glm::vec4 sampleColor = sanitizeColor(layer.color[sampleIndex]);
    weightSum += weight;
    sum += weight * mixColor(sampleColor, revealed, behindShare(in, sampleIndex, centreObject, centreDepth));
  }
  return sum / weightSum;
}

}  // namespace

std::vector<glm::vec4> compositeGather(const mblur::Layer& input, const std::vector<glm::vec4>& neighborMax,
                                       const std::vector<uint32_t>& mask, const std::vector<glm::vec4>& background,
                                       const std::vector<uint32_t>& objectId,
                                       const passes::PostProcessSettings& settings, passes::HybridComposite composite,
                                       passes::MaskWeights maskWeights) {
  // Outside the mask (and inside it where the neighbourhood is still) the kernel is the plain
  // gather with the mask flag on.
  const mblur::Layer layer = mblur::stored(input);
  std::vector<glm::vec4> out = mblur::gather(layer, neighborMax, &mask, settings, maskWeights);
  const std::vector<glm::vec2> surfaceVelocity = mblur::storedVelocity(input.velocity);
  const CompositeInputs in{layer, surfaceVelocity, background, objectId, settings.softZExtent};
  const uint32_t m = settings.effectiveTileSize();
  const passes::TileGrid grid = passes::tileGridFor(layer.width, layer.height, m);
  // The coverage form blends mask_coverage's alpha and foreground, as the hybrid's passes do.
  const std::vector<MaskCoverage> coverage = composite == passes::HybridComposite::Coverage
                                                 ? maskCoverage(input, mask, objectId, settings)
                                                 : std::vector<MaskCoverage>{};
  for (uint32_t py = 0; py < layer.height; ++py)
    for (uint32_t px = 0; px < layer.width; ++px) {
      const size_t index = size_t(py) * layer.width + px;
      if (mask[index] == 0u) continue;
      const glm::vec4 dominant = neighborMax[size_t(py / m) * grid.x + px / m];
      if (dominant.z < gpu::kMinBlurPixels) continue;
      if (composite == passes::HybridComposite::Coverage) {
        out[index] = coverageComposite(coverage[index], background[index]);
        continue;
      }
      const glm::vec4 centreColor = sanitizeColor(layer.color[index]);
      const float centreDepth = sanitizeDepth(layer.normalDepth[index].w);
      const float jitter = mblur::unitFromHash(mblur::mblurHash(px, py, settings.seed));
      out[index] = weightsComposite(in, px, py, dominant, centreColor, centreDepth, jitter, settings, maskWeights);
    }
  return out;
}

std::vector<MaskCoverage> maskCoverage(const mblur::Layer& input, const std::vector<uint32_t>& mask,
                                       const std::vector<uint32_t>& objectId,
                                       const passes::PostProcessSettings& settings) {
  const mblur::Layer layer = mblur::stored(input);
  const std::vector<glm::vec2> surfaceVelocity = mblur::storedVelocity(input.velocity);
  const std::vector<glm::vec4> noBackground;
  const CompositeInputs in{layer, surfaceVelocity, noBackground, objectId, settings.softZExtent};
  const float velocityScale = passes::gatherVelocityScale(settings.range, settings.exposure, settings.fps);
  const float maxSpeed = float(std::max(layer.width, layer.height));
  const bool curved = settings.motionPath == passes::MotionPath::Curved && !layer.shutterPaths.empty();
  std::vector<MaskCoverage> out(mask.size());
  for (uint32_t py = 0; py < layer.height; ++py)
    for (uint32_t px = 0; px < layer.width; ++px)
      if (const size_t index = size_t(py) * layer.width + px; mask[index] != 0u)
        out[index] = coverageAt(in, px, py, velocityScale, maxSpeed, settings.samples, settings.seed, curved);
  return out;
}

}  // namespace hmb::test::hybrid
