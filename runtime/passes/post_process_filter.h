// The post-process filters: the gather that ends the blur after tile-max and neighbour-max.
// Each is one pass in its own file (a GatherFilter over its kernel in kernels/mblur/), listed
// once in kFilters below, which gives its name, what it is and the tiles it wants; the settings,
// the command line's --filter and the report take them from there.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>

#include "runtime/vulkan/binding.h"

namespace hmb {
class FramePlan;
}  // namespace hmb

namespace hmb::vk {
class Context;
class FrameRecorder;
}  // namespace hmb::vk

namespace hmb::passes {

struct PostProcessSettings;

enum class PostProcessFilter {
  McGuire,  // McGuire et al. 2012 with the paper's appendix weights
  Jimenez,  // Jimenez 2014, the filter UE4 follows
};

enum class GatherRange {
  Centered,  // McGuire's original: half velocities, samples over X + t v_N, t in [-1, 1]
  Adapted,   // the paper (Fig. 3): full per-exposure velocity, samples over X + u v_N, u in (0, 1]
};

// One layer to blur (kernels/shared/layer_layout.h), width * height pixels, row 0 at the top: its
// samples (colour, depth, velocity: what the gathers read) and surfaces (the exact velocity,
// which tile-max ranks).
struct MotionBlurInputs {
  const vk::Buffer* samples = nullptr;
  const vk::Buffer* surfaces = nullptr;
  uint32_t width = 0;
  uint32_t height = 0;
  // Each pixel's path over the shutter (kernels/gbuffer/gbuffer_layout.h), for the curved
  // motion path; null: the gathers follow straight lines.
  const vk::Buffer* shutterPaths = nullptr;
};

// What every filter's kernel binds (kernels/mblur/filter_bindings.glsl).
vk::Bindings filterBindings(const MotionBlurInputs& inputs, const vk::Buffer& neighborMax, const vk::Buffer& output);

class GatherFilter {
 public:
  virtual ~GatherFilter() = default;
  // Its pass in the frame plan.
  virtual std::string_view passName() const = 0;
  // Its passes in the frame plan: passName() and any it records beside it.
  virtual void plan(FramePlan& plan) const;
  // neighborMax: the tile passes' at settings.effectiveTileSize() and settings.velocityScale();
  // output: width * height vec4.
  virtual void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                      const vk::Buffer& output, const PostProcessSettings& settings) const = 0;
};

std::unique_ptr<GatherFilter> makeMcGuireGather(const vk::Context& context);  // gather_pass.cpp
std::unique_ptr<GatherFilter> makeJimenezGather(const vk::Context& context);  // jimenez_gather_pass.cpp

struct FilterDescription {
  PostProcessFilter filter;
  std::string_view name;     // as --filter and the report spell it
  std::string_view summary;  // one line, for help texts
  uint32_t tileSize;         // default tile size, in pixels of a 720-line image
  std::optional<GatherRange> onlyRange;  // the range it always gathers over, if it has no choice
  std::unique_ptr<GatherFilter> (*make)(const vk::Context& context);
};

inline constexpr FilterDescription kFilters[] = {
    {PostProcessFilter::McGuire, "mcguire", "McGuire et al. 2012 with the paper's weights (tile size 40 in the paper)",
     40, std::nullopt, makeMcGuireGather},
    {PostProcessFilter::Jimenez, "jimenez", "Jimenez 2014, the filter UE4 follows (centred, jittered tiles)", 20,
     GatherRange::Centered, makeJimenezGather},
};

constexpr const FilterDescription& describe(PostProcessFilter filter) {
  for (const FilterDescription& description : kFilters)
    if (description.filter == filter) return description;
  return kFilters[0];  // every enumerator has a row: unreachable
}

}  // namespace hmb::passes
