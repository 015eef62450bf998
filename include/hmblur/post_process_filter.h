// The post-process filters: the gather that ends the blur after tile-max and neighbour-max.
// Each is one pass in its own file (a GatherFilter, gather_filter.h, over its kernel in
// kernels/mblur/), listed once in kFilters below, which gives its name, what it is and the tiles it wants; the settings,
// the command line's --filter and the report take them from there.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>

namespace hmb::vk {
class Context;
}  // namespace hmb::vk

namespace hmb::passes {

class GatherFilter;  // gather_filter.h

enum class PostProcessFilter {
  McGuire,  // McGuire et al. 2012 with the paper's appendix weights
  Jimenez,  // Jimenez 2014, the filter UE4 follows
};

enum class GatherRange {
  Centered,  // McGuire's original: half velocities, samples over X + t v_N, t in [-1, 1]
  Adapted,   // the paper (Fig. 3): full per-exposure velocity, samples over X + u v_N, u in (0, 1]
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
