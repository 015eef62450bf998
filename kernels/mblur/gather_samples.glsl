// The sum over one pixel's samples of McGuire et al. 2012's reconstruction with the paper's
// appendix weights (eqs. 5-10):
//   w = w_f + w_b + w_s, z = (z_t - z_s) / SOFT_Z_EXTENT,
//   w_f = saturate(1 + z) saturate(1 - ds / v_s)   (sample in front, its blur reaches the pixel)
//   w_b = saturate(1 - z) saturate(1 - ds / v_t)   (sample behind, seen through the pixel's blur)
//   w_s = cylinder(v_s, ds) cylinder(v_t, ds) 2    (both blurred over each other)
// sampling along v_N, the neighbour-max velocity of the pixel's tile, S samples jittered per
// pixel by a hash of (pixel, seed), read at the nearest pixel clamped to the image.
//
// Two ranges (the paper's Figure 3):
//  - centred (McGuire's original): half per-exposure velocities, samples at X + t v_N with
//    t = mix(-1, 1, (i + j + 1) / (S + 1)), j in [-0.5, 0.5); for odd S the middle sample,
//    which lands on X itself, is skipped since X is already counted.
//  - adapted (the paper): full per-exposure velocities and the pixel at the end of its range,
//    samples at X + u v_N with u = (i + 1 - r) / S in (0, 1], r in [0, 1) (design convention:
//    X sees the points now at X + u v, u in [0, 1]).
// The pixel itself weighs 1 / max(|v_X|, 0.5) (McGuire: a pixel moving |v| px covers itself
// for 1/|v| of the exposure; 0.5 px bounds the weight of still pixels at 2). w_f is multiplied
// by a boost when the pixel is deeper than the sample by at least SOFT_Z_EXTENT (the paper's
// section 4: x30 for the adapted range): foregroundBoost, or, where foregroundBoostPixels is
// set (k; k / K with K time slices, as the host passes it), max(1, k / |v_N|) with |v_N| the
// tile's neighbour-max speed in pixels (at least 1):
// slow motion's outer blur is read at a few whole pixels and needs more of it (the hybrid's
// default; passes::PostProcessSettings::foregroundBoostAt is the host's twin).
//
// The curved path (HMB_GATHER_FLAG_CURVED_PATH, adapted range only): a pixel moving at least
// kOwnPathShare of its tile's neighbour-max speed samples along the path its own surface
// sweeps over it instead of the straight line along v_N. Its point's screen positions at t,
// t - E/2 and t - E (gbuffer/resolve_shutter_path.comp: m = X - p(t - E/2), o = X - p(t - E))
// give the quadratic p(t - uE) = X - u a - u^2 c with a = 4m - o, c = 2o - 4m. The point seen
// at X at shutter time u is the one whose path passes X then: p = X + u a(p) + u^2 c(p), to
// second order X + u a + u^2 (c + J_a a), where J_a a, the change of the path across it (what
// a rotation adds: the points a pixel sees come from around the circle, not from its tangent),
// is approximated by the velocity at X + a minus X's (frame velocities scaled to the
// exposure), when X + a lies on the same surface (depths within SOFT_Z_EXTENT). The path's
// length is kept within the tile size, as velocities are.
// Each sample then takes one more fixed-point step with its own terms (see gatherSamples).
//
// Shared by the post-process gather (mblur/gather.comp) and the hybrid's gathers
// (reveal/gather_background.comp, reveal/composite.comp). The including kernel declares
// `params` (GatherParams) and defines, before including this file, what a sample reads:
//   uvec4 blurSampleAt(uint i)  (pixel i's packed sample: colour, depth, velocity, one load;
//                                shared/layer_layout.h),
//   vec4 contributionOf(uint sampleIndex, vec4 sampleColor)  (the colour a sample adds),
//   vec4 neighborMaxAt(uint tile)  (the tile's neighbour-max velocity),
//   uvec2 shutterPathAt(uint i)  (pixel i's path, gbuffer/gbuffer_layout.h; read only with
//                                 the curved path).
#ifndef HMB_KERNELS_MBLUR_GATHER_SAMPLES_GLSL
#define HMB_KERNELS_MBLUR_GATHER_SAMPLES_GLSL

#include "mblur_common.glsl"
#include "../shared/layer_layout.h"

// What a gather reads of its own pixel.
struct GatherCentre {
  vec4 color;     // sanitized
  vec2 dominant;  // its tile's neighbour-max velocity
  float speed;    // its own, clamped to the tile size
  float depth;    // sanitized
  float jitter;   // of its samples
  float foregroundBoost;  // w_f's factor where the pixel lies past SOFT_Z_EXTENT behind a sample
  bool ownPath;   // the curved path: samples at X + u pathLinear + u^2 pathQuadratic
  vec2 pathLinear;
  vec2 pathQuadratic;
};

// How nearly a sample's own path over the shutter passes the pixel centre x: 1 within one
// pixel, 0 past two, linear between. Its quadratic path where it has one, else the straight
// line back along its velocity v (pixels per exposure), followed as 8 segments.
float pathReach(ivec2 samplePixel, uint sampleIndex, vec2 v, vec2 x) {
  vec2 a, c;
  if (!shutterPathTerms(shutterPathAt(sampleIndex), a, c)) {
    a = v;
    c = vec2(0.0);
  }
  const vec2 start = vec2(samplePixel) + 0.5;
  float nearest = length(x - start);
  vec2 previous = start;
  for (uint j = 1u; j <= 8u; ++j) {
    const float u = float(j) / 8.0;
    const vec2 next = start - u * a - (u * u) * c;
    const vec2 segment = next - previous;
    const float along = clamp(dot(x - previous, segment) / max(dot(segment, segment), 1e-12), 0.0, 1.0);
    nearest = min(nearest, length(x - (previous + along * segment)));
    previous = next;
  }
  return clamp(2.0 - nearest, 0.0, 1.0);
}

// Sets centre.ownPath and its terms (see the top).
void readOwnPath(uvec2 pixel, uint index, inout GatherCentre centre) {
  centre.ownPath = false;
  vec2 a, c;
  if (!shutterPathTerms(shutterPathAt(index), a, c)) return;
  if (length(a) + length(c) < kOwnPathShare * max(length(centre.dominant), kMinBlurPixels)) return;
  const ivec2 ahead = nearestPixel(vec2(pixel) + 0.5 + a, params.width, params.height);
  const uvec4 there = blurSampleAt(uint(ahead.y) * params.width + uint(ahead.x));
  const bool sameSurface = abs(sanitizeDepth(sampleDepth(there)) - centre.depth) < params.softZExtent;
  const vec2 change =
      sameSurface ? (sampleVelocity(there) - sampleVelocity(blurSampleAt(index))) * params.velocityScale : vec2(0.0);
  centre.ownPath = true;
  inversePath(a, c, change, float(params.tileSize), centre.pathLinear, centre.pathQuadratic);
}

// Whether the curved path's code is compiled in: gather.comp compiles it only for a frame that
// takes the curved path (a specialization constant). On lavapipe every branch's code runs under
// the lanes' mask, whatever the condition, so the linear gather paid the curved path's reads
// and steps at every sample. Other kernels keep it, behind the run-time flag.
#ifndef HMB_GATHER_CURVED_PATH_CODE
#define HMB_GATHER_CURVED_PATH_CODE true
#endif
// The same for the range: gather.comp compiles the one its frame takes.
#ifndef HMB_GATHER_ADAPTED_RANGE
#define HMB_GATHER_ADAPTED_RANGE ((params.flags & HMB_GATHER_FLAG_ADAPTED_RANGE) != 0u)
#endif

// Reads the pixel; false (centre.color alone set) when under kMinBlurPixels of blur reach its
// whole neighbourhood, so that the gather leaves it its own colour.
bool readGatherCentre(uvec2 pixel, uint index, out GatherCentre centre) {
  const uvec4 own = blurSampleAt(index);
  centre.color = sanitizeColor(vec4(sampleColor(own), 1.0));
  const vec4 dominant = neighborMaxAt((pixel.y / params.tileSize) * params.tilesX + pixel.x / params.tileSize);
  if (dominant.z < kMinBlurPixels) return false;
  centre.dominant = dominant.xy;
  centre.foregroundBoost = params.foregroundBoostPixels > 0.0
                               ? max(1.0, params.foregroundBoostPixels / max(dominant.z, 1.0))
                               : params.foregroundBoost;
  centre.speed = gatherSpeed(sampleVelocity(own), params.velocityScale, float(params.tileSize));
  centre.depth = sanitizeDepth(sampleDepth(own));
  centre.jitter = unitFromHash(mblurHash(pixel.x, pixel.y, params.seed));
  centre.ownPath = false;
  const uint curved = HMB_GATHER_FLAG_ADAPTED_RANGE | HMB_GATHER_FLAG_CURVED_PATH;
  if (HMB_GATHER_CURVED_PATH_CODE && (params.flags & curved) == curved) readOwnPath(pixel, index, centre);
  return true;
}

// Sample i's place along the range (see the top): u in (0, 1] for the adapted range, t in
// (-1, 1) for the centred one. inverseSamples: 1 / S. The run of samples on one pixel is
// counted one sample after another, each step waiting on the last, so a multiplication
// stands where a division did.
float gatherSampleT(uint i, uint samples, float inverseSamples, float jitter, bool adapted) {
  return adapted ? (float(i) + 1.0 - jitter) * inverseSamples
                 : mix(-1.0, 1.0, (float(i) + jitter + 0.5) / float(samples + 1u));
}

// The blurred colour of `pixel`; the scales multiply w_f and w_b (the hybrid's mask boosts,
// else 1).
vec4 gatherSamples(uvec2 pixel, GatherCentre c, float foregroundScale, float backgroundScale) {
  const vec4 centreColor = c.color;
  const float centreSpeed = c.speed, centreDepth = c.depth, jitter = c.jitter;
  const vec2 dominant = c.dominant;
  const float maxSpeed = float(params.tileSize);
  const bool adapted = HMB_GATHER_ADAPTED_RANGE;
  const bool curved = HMB_GATHER_CURVED_PATH_CODE && adapted && (params.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u;
  float weightSum = 1.0 / max(centreSpeed, 0.5);
  vec4 sum = centreColor * weightSum;

  const vec2 centre = vec2(pixel) + 0.5;
  const uint samples = params.samples;
  const float inverseSamples = 1.0 / float(samples);
  // McGuire's centred range skips its middle sample for odd S: X itself is already counted.
  const uint skipped = adapted || (samples & 1u) == 0u ? samples : (samples - 1u) / 2u;
  const bool ownPath = HMB_GATHER_CURVED_PATH_CODE && c.ownPath;
  uint i = skipped == 0u ? 1u : 0u;
  while (i < samples) {
    const float t = gatherSampleT(i, samples, inverseSamples, jitter, adapted);
    vec2 along = ownPath ? t * c.pathLinear + (t * t) * c.pathQuadratic : t * dominant;
    ivec2 samplePixel = nearestPixel(centre + along, params.width, params.height);
    // Samples that land on the same pixel add the same term: the straight path counts the
    // samples after this one that do, and weighs the term by their number. A blur of a few
    // pixels then reads each pixel once where it read it S / |v_N| times. The same pixels as
    // one sample at a time: each later sample's pixel is found as its own would be.
    float count = 1.0;
    i += i + 1u == skipped ? 2u : 1u;
    if (!ownPath) {
      while (i < samples && nearestPixel(centre + gatherSampleT(i, samples, inverseSamples, jitter, adapted) * dominant, params.width,
                                         params.height) == samplePixel) {
        count += 1.0;
        i += i + 1u == skipped ? 2u : 1u;
      }
    }
    uint sampleIndex = uint(samplePixel.y) * params.width + uint(samplePixel.x);
    uvec4 packed = blurSampleAt(sampleIndex);
    // One more step of p = X + u a(p) + u^2 c(p) from there: the sample's own terms, where it
    // lies on the pixel's surface, correct the second-order guess where rotation is fast (a
    // sixth of a turn per exposure bends a path by a radian). Kept only if it lands on that
    // surface too, within the tile's reach.
    if (ownPath) {
      vec2 a1, c1;
      if (abs(sanitizeDepth(sampleDepth(packed)) - centreDepth) < params.softZExtent &&
          shutterPathTerms(shutterPathAt(sampleIndex), a1, c1)) {
        const vec2 refinedAlong = t * a1 + (t * t) * c1;
        if (length(refinedAlong) <= maxSpeed) {
          const ivec2 refined = nearestPixel(centre + refinedAlong, params.width, params.height);
          const uint refinedIndex = uint(refined.y) * params.width + uint(refined.x);
          const uvec4 refinedPacked = blurSampleAt(refinedIndex);
          if (abs(sanitizeDepth(sampleDepth(refinedPacked)) - centreDepth) < params.softZExtent) {
            samplePixel = refined;
            sampleIndex = refinedIndex;
            packed = refinedPacked;
          }
        }
      }
    }
    const float ds = length(vec2(samplePixel - ivec2(pixel)));
    const float sampleSpeed = gatherSpeed(sampleVelocity(packed), params.velocityScale, maxSpeed);
    const float sampleDepth = sanitizeDepth(sampleDepth(packed));

    const float z = (centreDepth - sampleDepth) / params.softZExtent;
    float wf = clamp(1.0 + z, 0.0, 1.0) * cone(ds, sampleSpeed);
    float wb = clamp(1.0 - z, 0.0, 1.0) * cone(ds, centreSpeed);
    const float ws = cylinder(sampleSpeed, ds) * cylinder(centreSpeed, ds) * 2.0;
    if (centreDepth - sampleDepth >= params.softZExtent) wf *= c.foregroundBoost;
    // Along curved paths a sample in front blurs over the pixel only if its own path crosses
    // it: near it is not enough where motion turns (a spinning plate's corner sweeps an arc,
    // not the tile's straight line).
    if (curved && z > 0.0) {
      float unused;
      const vec2 sampleV = gatherVelocity(sampleVelocity(packed), params.velocityScale, maxSpeed, unused);
      wf *= mix(1.0, pathReach(samplePixel, sampleIndex, sampleV, centre), min(z, 1.0));
    }
    wf *= foregroundScale;
    wb *= backgroundScale;
    const float w = (wf + wb + ws) * count;
    const vec4 sampleColor = sanitizeColor(vec4(sampleColor(packed), 1.0));
    weightSum += w;
    sum += w * contributionOf(sampleIndex, sampleColor);
  }
  return sum / weightSum;
}

#endif
