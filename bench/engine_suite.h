// The `engine` suite: the engine backend's per-frame cost (EngineMotionBlur and
// EngineHybridMotionBlur recorded into a command buffer the caller submits, from an engine's
// G-buffer) beside the command line's post-process and hybrid frames on the same scene,
// interleaved in one loop. The engine's G-buffer is the renderer's own (its sharp frame's
// layers), so both paths blur the same input with the same settings.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/raster_suite.h"

namespace hmb::vk {
class Context;
}

namespace hmb::bench {

struct EngineSuiteOptions {
  std::vector<std::string> scenes;
  std::vector<ImageSize> sizes = {{1280, 720}};
  int warmup = 2;
  int repeats = 9;
};

struct EngineCase {
  std::string scene;
  ImageSize size;
  Summary engineFrame;   // the engine path: pack-engine-gbuffer, tile-max, neighbor-max, gather
  Summary enginePack;    // of it, reading the engine's buffers into the packed layer
  Summary engineBlur;    // of it, tile-max + neighbor-max + gather
  Summary cliFrame;      // the renderer's post-process frame: G-buffer, blur, display encoding
  Summary cliBlur;       // of it, tile-max + neighbor-max + gather
  bool sameImage = false;  // the two blurred images equal, bit for bit, in every timed frame
  // The hybrid: the engine's recorded frame (its top-level tree, built by prepare() when
  // instances move, apart), the command line's hybrid frame (which includes that tree).
  Summary engineHybridFrame, cliHybridFrame;
  double engineTopLevelMs = 0;
  bool sameHybridImage = false;
};

std::vector<EngineCase> runEngineSuite(vk::Context& context, const EngineSuiteOptions& options,
                                       const Progress& progress);
nlohmann::json engineCaseJson(const EngineCase& c);
// One row per case and measured time: scene, width, height, what, median ms, q1, q3.
void writeEngineCsv(std::ostream& out, const std::vector<EngineCase>& cases);
void writeEngineMarkdown(std::ostream& out, const std::vector<EngineCase>& cases, const std::string& context);

}  // namespace hmb::bench
