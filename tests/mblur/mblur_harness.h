// Runs the motion blur passes on the test device on host data and reads the results back.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/post_process_settings.h"
#include "tests/mblur/mblur_reference.h"

namespace hmb::vk {
class Context;
}

namespace hmb::test::mblur {

std::vector<glm::vec4> runTileMax(vk::Context& context, const std::vector<glm::vec2>& velocity, uint32_t width,
                                  uint32_t height, uint32_t tileSize, float velocityScale);
std::vector<glm::vec4> runNeighborMax(vk::Context& context, const std::vector<glm::vec4>& tileMax,
                                      passes::TileGrid grid, uint32_t neighborhood);
// The gather alone, on given neighbour-max tiles (grid at settings.tileSize).
std::vector<glm::vec4> runGather(vk::Context& context, const Layer& layer, const std::vector<glm::vec4>& neighborMax,
                                 const passes::PostProcessSettings& settings);
// The Jimenez gather alone (grid at settings.jimenezTileSize).
std::vector<glm::vec4> runJimenezGather(vk::Context& context, const Layer& layer,
                                        const std::vector<glm::vec4>& neighborMax,
                                        const passes::PostProcessSettings& settings);
// The whole PostProcessStage.
std::vector<glm::vec4> runStage(vk::Context& context, const Layer& layer, const passes::PostProcessSettings& settings);

// A layer of the given size, every pixel at rest: colour 0.5 grey, depth 1.
Layer stillLayer(uint32_t width, uint32_t height);

// A textured background a little in motion, with a few rectangles moving over it at their own
// depths and velocities.
Layer randomLayer(uint32_t width, uint32_t height, std::mt19937& rng);

// Paths over the shutter (Layer::shutterPaths) for these velocities (pixels per frame): each
// pixel's straight motion over exposureFrames frames bent by a random offset at mid-shutter,
// and among them the adversarial records: none (NaN halves), infinite and the largest halves,
// zero, a path that turns back on itself.
std::vector<glm::uvec2> randomShutterPaths(const std::vector<glm::vec2>& velocity, std::mt19937& rng,
                                           float exposureFrames);

// The C++ reference's neighbour-max tiles of a layer, at the selected filter's tile size.
std::vector<glm::vec4> referenceTiles(const Layer& layer, const passes::PostProcessSettings& settings);

// Largest |a - b| over all channels; non-finite values in either count as infinite.
float maxAbsDifference(glm::vec4 a, glm::vec4 b);
bool allFinite(const std::vector<glm::vec4>& values);

// Every output finite; every pixel within `tolerance` of the reference (colours are O(1)),
// except pixels where a sample position rounds to the other neighbouring pixel on the device
// (positions a rounding step from a pixel edge): at most 0.5% of them. Gtest expectations.
void expectMatchesReference(const std::vector<glm::vec4>& device, const std::vector<glm::vec4>& reference,
                            float tolerance = 2e-4f);

}  // namespace hmb::test::mblur
