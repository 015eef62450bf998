#include "bench/engine_suite.h"

#include <cstring>
#include <ostream>

#include <glm/glm.hpp>

#include "bench/bench_scenes.h"
#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "hmblur/engine_motion_blur.h"
#include "hmblur/error.h"
#include "hmblur/renderer.h"
#include "runtime/passes/hybrid_stage.h"

namespace hmb::bench {
namespace {

bool isBlurPass(const std::string& name) { return name == "tile-max" || name == "neighbor-max" || name == "gather"; }

template <class T>
vk::Buffer engineBuffer(const vk::Context& context, const std::vector<T>& values, const std::string& name) {
  return vk::uploadedBuffer(context, values, name);
}

EngineCase runCase(vk::Context& context, const scene::Scene& scene, const std::string& name, const ImageSize& size,
                   const EngineSuiteOptions& o) {
  Renderer renderer(context);
  RenderSettings settings;
  settings.width = size.width;
  settings.height = size.height;
  settings.reuseAcrossFrames = false;
  settings.method = Method::Sharp;
  const RenderResult sharp = renderer.render(scene, settings);
  settings.method = Method::PostProcess;
  const RenderResult first = renderer.render(scene, settings);
  if (!first.postprocess) throw Error("engine: the post-process frame of '" + name + "' has no settings");

  // The engine's G-buffer: the sharp frame's colour, camera-space depth and velocity.
  const size_t pixels = size_t(size.width) * size.height;
  const auto& rgba = sharp.image.find("")->values;
  const auto& z = sharp.image.find("depth")->values;
  const auto& v = sharp.image.find("velocity")->values;
  std::vector<glm::vec4> color(pixels);
  std::vector<float> depth(pixels);
  std::vector<glm::vec2> velocity(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    color[i] = {rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], rgba[4 * i + 3]};
    depth[i] = z[i];
    velocity[i] = {v[2 * i], v[2 * i + 1]};
  }
  const vk::Buffer colorBuffer = engineBuffer(context, color, "engine colour");
  const vk::Buffer depthBuffer = engineBuffer(context, depth, "engine depth");
  const vk::Buffer velocityBuffer = engineBuffer(context, velocity, "engine velocity");
  const vk::Buffer output(context, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, "engine output");
  EngineMotionBlur blur(context, size.width, size.height, *first.postprocess);
  // The hybrid's inputs: the same G-buffer with its normals and object ids, and the scene.
  RenderSettings hybridSettings = settings;
  hybridSettings.method = Method::Hybrid;
  const RenderResult firstHybrid = renderer.render(scene, hybridSettings);
  const auto& n = sharp.image.find("normal")->values;
  std::vector<glm::vec4> normal(pixels);
  for (size_t i = 0; i < pixels; ++i) normal[i] = {n[3 * i], n[3 * i + 1], n[3 * i + 2], 0.0f};
  const vk::Buffer normalBuffer = engineBuffer(context, normal, "engine normal");
  const vk::Buffer idBuffer = engineBuffer(context, sharp.image.find("objectId")->ids, "engine object id");
  EngineHybridMotionBlur hybrid(context, size.width, size.height, scene, firstHybrid.hybrid->settings);
  const auto recordHybrid = [&] {
    context.submitAndWait([&](VkCommandBuffer commands) {
      hybrid.record(commands,
                    {colorBuffer.handle(), depthBuffer.handle(), velocityBuffer.handle(), normalBuffer.handle(),
                     idBuffer.handle()},
                    output.handle());
    });
  };
  // The first frame builds the instances' tree inside the recorded frame; later ones keep it.
  hybrid.prepare(firstHybrid.frameTime);
  recordHybrid();
  double topLevel = 0;
  for (const EnginePassTime& pass : hybrid.timings().passes)
    if (pass.name == passes::HybridStage::kBvhInstances) topLevel += pass.milliseconds;

  std::vector<double> engineFrame, enginePack, engineBlur, cliFrame, cliBlur, engineHybridFrame, cliHybridFrame;
  bool same = true, sameHybrid = true;
  for (int i = 0; i < o.warmup + o.repeats; ++i) {
    // The engine path: recorded into a command buffer the caller submits.
    context.submitAndWait([&](VkCommandBuffer commands) {
      blur.record(commands, {colorBuffer.handle(), depthBuffer.handle(), velocityBuffer.handle()}, output.handle());
    });
    const EngineFrameTimes engine = blur.timings();
    const RenderResult cli = renderer.render(scene, settings);
    if (!engine.available() || !cli.frameMilliseconds)
      throw Error("engine: the device gives no timestamps: frame times cannot be measured");
    if (i < o.warmup) continue;
    engineFrame.push_back(engine.frameMilliseconds);
    double pack = 0, blurMs = 0, cliBlurMs = 0;
    for (const EnginePassTime& pass : engine.passes) (isBlurPass(pass.name) ? blurMs : pack) += pass.milliseconds;
    for (const PlannedPass& pass : cli.plan.passes())
      if (pass.run && isBlurPass(pass.name)) cliBlurMs += pass.milliseconds.value_or(0.0);
    enginePack.push_back(pack);
    engineBlur.push_back(blurMs);
    cliFrame.push_back(*cli.frameMilliseconds);
    cliBlur.push_back(cliBlurMs);
    const std::vector<glm::vec4> engineImage = output.download<glm::vec4>();
    const auto& cliImage = cli.image.find("")->values;
    same = same && std::memcmp(engineImage.data(), cliImage.data(), pixels * sizeof(glm::vec4)) == 0;

    hybrid.prepare(firstHybrid.frameTime);  // the first frame's trees serve: nothing moved since
    recordHybrid();
    const EngineFrameTimes engineHybrid = hybrid.timings();
    const RenderResult cliHybrid = renderer.render(scene, hybridSettings);
    engineHybridFrame.push_back(engineHybrid.frameMilliseconds);
    cliHybridFrame.push_back(cliHybrid.frameMilliseconds.value_or(0.0));
    const std::vector<glm::vec4> engineHybridImage = output.download<glm::vec4>();
    sameHybrid = sameHybrid && std::memcmp(engineHybridImage.data(), cliHybrid.image.find("")->values.data(),
                                           pixels * sizeof(glm::vec4)) == 0;
  }
  EngineCase c{name,
               size,
               summarize(engineFrame),
               summarize(enginePack),
               summarize(engineBlur),
               summarize(cliFrame),
               summarize(cliBlur),
               same};
  c.engineHybridFrame = summarize(engineHybridFrame);
  c.cliHybridFrame = summarize(cliHybridFrame);
  c.engineTopLevelMs = topLevel;
  c.sameHybridImage = sameHybrid;
  return c;
}

}  // namespace

std::vector<EngineCase> runEngineSuite(vk::Context& context, const EngineSuiteOptions& options,
                                       const Progress& progress) {
  if (options.repeats < 1) throw Error("engine: repeats must be at least 1");
  if (options.scenes.empty() || options.sizes.empty()) throw Error("engine: no scenes or sizes");
  std::vector<EngineCase> cases;
  for (const std::string& name : options.scenes) {
    const scene::Scene scene = loadBenchScene(name);
    for (const ImageSize& size : options.sizes) {
      progress(name + " " + sizeName(size));
      cases.push_back(runCase(context, scene, name, size, options));
    }
  }
  return cases;
}

nlohmann::json engineCaseJson(const EngineCase& c) {
  return {{"scene", c.scene},
          {"width", c.size.width},
          {"height", c.size.height},
          {"engine_frame_ms", summaryJson(c.engineFrame)},
          {"engine_pack_ms", summaryJson(c.enginePack)},
          {"engine_blur_ms", summaryJson(c.engineBlur)},
          {"cli_postprocess_frame_ms", summaryJson(c.cliFrame)},
          {"cli_blur_ms", summaryJson(c.cliBlur)},
          {"same_image", c.sameImage},
          {"engine_hybrid_frame_ms", summaryJson(c.engineHybridFrame)},
          {"engine_hybrid_top_level_ms", c.engineTopLevelMs},
          {"cli_hybrid_frame_ms", summaryJson(c.cliHybridFrame)},
          {"same_hybrid_image", c.sameHybridImage}};
}

void writeEngineCsv(std::ostream& out, const std::vector<EngineCase>& cases) {
  out << "scene,width,height,what,median_ms,q1_ms,q3_ms\n";
  for (const EngineCase& c : cases)
    for (const auto& [what, t] : {std::pair{"engine_frame", c.engineFrame}, std::pair{"engine_pack", c.enginePack},
                                  std::pair{"engine_blur", c.engineBlur}, std::pair{"cli_postprocess_frame", c.cliFrame},
                                  std::pair{"cli_blur", c.cliBlur}, std::pair{"engine_hybrid_frame", c.engineHybridFrame},
                                  std::pair{"cli_hybrid_frame", c.cliHybridFrame}})
      out << c.scene << ',' << c.size.width << ',' << c.size.height << ',' << what << ',' << t.median << ',' << t.q1
          << ',' << t.q3 << '\n';
}

void writeEngineMarkdown(std::ostream& out, const std::vector<EngineCase>& cases, const std::string& context) {
  out << context << "\n\n"
      << "| scene | size | engine frame ms | of it: pack-engine-gbuffer | of it: blur | command line post-process "
         "frame ms | of it: blur | same image |\n|---|---|---:|---:|---:|---:|---:|---|\n";
  for (const EngineCase& c : cases)
    out << "| " << c.scene << " | " << sizeName(c.size) << " | " << fixed(c.engineFrame.median, 2) << " | "
        << fixed(c.enginePack.median, 2) << " | " << fixed(c.engineBlur.median, 2) << " | "
        << fixed(c.cliFrame.median, 2) << " | " << fixed(c.cliBlur.median, 2) << " | "
        << (c.sameImage ? "yes" : "no") << " |\n";
  out << "\nHybrid:\n\n| scene | size | engine hybrid frame ms | engine top-level tree ms (when instances move) "
         "| command line hybrid frame ms | same image |\n|---|---|---:|---:|---:|---|\n";
  for (const EngineCase& c : cases)
    out << "| " << c.scene << " | " << sizeName(c.size) << " | " << fixed(c.engineHybridFrame.median, 2) << " | "
        << fixed(c.engineTopLevelMs, 2) << " | " << fixed(c.cliHybridFrame.median, 2) << " | "
        << (c.sameHybridImage ? "yes" : "no") << " |\n";
  out << "\nblur: tile-max + neighbor-max + gather. The engine frame is what an engine adds to its own frame "
         "(its G-buffer is its own); the command line's frame also rasterizes and shades the G-buffer and encodes "
         "the display image. The engine's hybrid frames keep the first frame's top-level tree (nothing moved "
         "since); a frame whose instances moved builds it inside the recorded frame, at the cost listed apart "
         "(its passes in the first recorded frame). The command line's hybrid frame includes it.\n";
}

}  // namespace hmb::bench
