#include "hmblur/report.h"

#include <fstream>

#include "hmblur/error.h"

namespace hmb {

nlohmann::json optionalNumber(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json deviceJson(const vk::DeviceInfo& device) {
  return {
      {"index", device.index},
      {"name", device.name},
      {"type", device.type},
      {"driver", device.driverName},
      {"driver_info", device.driverInfo},
      {"api_version", device.apiVersion},
      {"int64_buffer_atomics", device.int64BufferAtomics},
      {"timestamps", device.timestamps},
      {"subgroup_size", device.subgroupSize},
      {"max_storage_buffer_bytes", device.maxStorageBufferRange},
      {"device_local_bytes", device.deviceLocalBytes},
  };
}

nlohmann::json deviceProfileJson(const vk::DeviceProfile& profile) {
  return {
      {"name", profile.name},
      {"forced", profile.forced},
      {"loop_budget", profile.loopBudget ? nlohmann::json(*profile.loopBudget) : nlohmann::json(nullptr)},
      {"uniform_atomic_rounds", profile.uniformAtomicRounds},
      {"raster_tile_lists", profile.rasterTileLists},
      {"bvh_level_group", profile.bvhLevelGroup},
      {"bvh_lane_bins", profile.bvhLaneBins},
      {"top_level_small_task", profile.topLevelSmallTask},
      {"linear_top_level", profile.linearTopLevel},
      {"treelet_mesh_builds", profile.treeletMeshBuilds},
      {"gather_skips_ray_mask", profile.gatherSkipsRayMask},
      {"edge_candidates_in_tile_max", profile.edgeCandidatesInTileMax},
      {"range_check_groups", profile.rangeCheckGroups},
      {"shutter_list_groups", profile.shutterListGroups},
  };
}

nlohmann::json deviceJson(const vk::Context& context) {
  nlohmann::json json = deviceJson(context.info());
  json["profile"] = deviceProfileJson(context.profile());
  return json;
}

nlohmann::json frameShapeJson(const vk::FrameShape& shape) {
  return {
      {"dispatches", shape.dispatches},   {"indirect_dispatches", shape.indirectDispatches},
      {"transfers", shape.transfers},     {"barriers", shape.barriers},
      {"submissions", shape.submissions}, {"host_waits", shape.hostWaits},
      {"dependent_chain", shape.dependentChain},
  };
}

std::string deviceProgressLine(const vk::Context& context) {
  return "device: " + context.info().name + "; profile " + context.profile().describe();
}

nlohmann::json systemJson(const SystemInfo& system) {
  return {
      {"cpu", system.cpu},
      {"hardware_threads", system.hardwareThreads},
      {"LP_NUM_THREADS", system.lpNumThreads},
      {"version", system.version},
      {"git_revision", system.gitRevision},
  };
}

nlohmann::json sceneJson(const scene::Scene& scene) {
  nlohmann::json camera = nullptr;
  if (scene.camera)
    camera = {{"yfov", scene.camera->yfov}, {"znear", scene.camera->znear}, {"zfar", scene.camera->zfar},
              {"animated", scene.camera->node >= 0 && scene.isAnimated(static_cast<uint32_t>(scene.camera->node))}};
  return {
      {"name", scene.name},
      {"triangles", scene.triangleCount()},
      {"meshes", scene.meshes.size()},
      {"instances", scene.instances.size()},
      {"materials", scene.materials.size()},
      {"textures", scene.textures.size()},
      {"animation_channels", scene.channels.size()},
      {"camera", camera},
      {"settings",
       {{"soft_z_extent", scene.settings.softZExtent},
        {"edge_threshold", scene.settings.edgeThreshold},
        {"fps", scene.settings.fps},
        {"exposure_s", scene.settings.exposure},
        {"shutter_angle_deg", scene.settings.exposure * scene.settings.fps * 360.0f},
        {"frame_time_s", scene.settings.frameTime}}},
      {"skipped",
       {{"line_primitives", scene.stats.linePrimitives},
        {"point_primitives", scene.stats.pointPrimitives},
        {"degenerate_triangles", scene.stats.degenerateTriangles}}},
      {"warnings", scene.stats.warnings},
  };
}

nlohmann::json passesJson(const FramePlan& plan) {
  nlohmann::json passes = nlohmann::json::array();
  for (const PlannedPass& pass : plan.passes()) {
    nlohmann::json entry = {{"name", pass.name}, {"status", pass.run ? "run" : "skipped"}};
    if (pass.run) {
      entry["ms"] = optionalNumber(pass.milliseconds);
      if (!pass.noWork.empty()) entry["no_work"] = pass.noWork;
      if (!pass.within.empty()) entry["within"] = pass.within;
    } else
      entry["reason"] = pass.reason;
    passes.push_back(std::move(entry));
  }
  return passes;
}

nlohmann::json rasterJson(const RenderResult& result) {
  if (result.visibilityScheme.empty()) return nullptr;
  return {{"visibility_scheme", result.visibilityScheme},
          {"setup_triangles", result.raster.setupTriangles},
          {"tile_pairs", result.raster.tilePairs},
          {"large_triangles", result.raster.largeTriangles},
          {"clipped_triangles", result.raster.clippedTriangles},
          {"buffer_regrowths", result.raster.regrowths}};
}

nlohmann::json methodSettingsJson(const RenderResult& result) {
  if (result.method == Method::Reference) {
    const passes::ReferenceSettings& r = result.settings.reference;
    nlohmann::json json = {{"spp", r.samplesPerPixel},
                           {"seed", r.seed},
                           {"pixel_jitter", r.pixelJitter},
                           {"times_per_batch", r.timesPerBatch},
                           {"checkpoint", r.checkpoint.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.checkpoint)}};
    if (result.reference) {
      json["samples_done"] = result.reference->samplesDone;
      json["samples_resumed"] = result.reference->samplesResumed;
      json["pixel_samples"] = result.reference->pixelSamples;
      // Pixels that took every sample (the rest see one surface all shutter long); null: all.
      json["moving_pixels"] = result.reference->movingPixels ? nlohmann::json(*result.reference->movingPixels)
                                                             : nlohmann::json(nullptr);
    }
    return json;
  }
  if (result.postprocess) {
    const passes::PostProcessSettings& p = *result.postprocess;
    nlohmann::json json = {{"filter", passes::filterName(p.filter)},
            {"range", passes::rangeName(p.effectiveRange())},
            {"samples", p.samples},
            {"tile_size", p.effectiveTileSize()},
            {"neighborhood", p.neighborhood},
            // A constant boost, or null where it falls with the speed: max(1, pixels / |v_N|).
            {"foreground_boost", p.foregroundBoostPixels ? nlohmann::json(nullptr)
                                                         : nlohmann::json(p.effectiveForegroundBoost())},
            {"foreground_boost_pixels", optionalNumber(p.foregroundBoostPixels)},
            {"soft_z_extent", p.softZExtent},
            {"exposure_s", p.exposure},
            {"fps", p.fps},
            {"seed", p.seed},
            {"time_slices", p.timeSlices},
            {"motion_path", std::string(passes::motionPathName(p.motionPath))}};
    if (result.hybrid) {
      const passes::HybridSettings& h = result.hybrid->settings;
      json["edge_threshold"] = h.edgeThreshold;
      json["reveal_stop"] = passes::revealStopName(h.stop);
      json["max_recursion"] = h.maxRecursion;
      json["luminance_threshold"] = h.luminanceThreshold;
      json["composite"] = passes::compositeName(h.composite);
      json["mask_background_boost"] = h.maskBackgroundBoost;
      json["mask_foreground_divide"] = h.maskForegroundDivide;
      json["edge_candidates"] = result.hybrid->edgeCandidates;
      json["range_blocks"] = result.hybrid->rangeBlocks;
      json["mask_pixels"] = result.hybrid->maskPixels;
      json["revealed_pixels"] = result.hybrid->revealedPixels;
      json["reveal_rays"] = result.hybrid->revealRays;
      json["shutter_rays"] = h.shutterRays;
      json["ray_budget"] = h.rayBudget;
      json["shutter_ray_pixels"] = result.hybrid->shutterRayPixels;
      json["shutter_ray_pixels_traced"] = result.hybrid->shutterRayPixelsTraced;
      json["shutter_rays_traced"] = result.hybrid->shutterRays;
      // The trace scene's mesh trees: built once per scene, so not in the frame time.
      json["scene_setup_ms"] = optionalNumber(result.hybrid->setupMilliseconds);
    }
    return json;
  }
  return nlohmann::json::object();
}

nlohmann::json renderReport(const vk::Context& context, const SystemInfo& system, const scene::Scene& scene,
                            const RenderResult& result) {
  return {
      {"tool", "hmblur"},
      {"date", utcTimestamp()},
      {"device", deviceJson(context)},
      {"system", systemJson(system)},
      {"method", methodName(result.method)},
      {"resolution", {{"width", result.width}, {"height", result.height}}},
      {"frame_time_s", result.frameTime},
      {"settings", methodSettingsJson(result)},
      {"scene", sceneJson(scene)},
      {"passes", passesJson(result.plan)},
      {"frame_ms", optionalNumber(result.frameMilliseconds)},
      {"frame", frameShapeJson(result.frameShape)},
      {"setup", result.setupShape ? frameShapeJson(*result.setupShape) : nlohmann::json(nullptr)},
      {"cut_traces", result.cutTraces},
      {"raster", rasterJson(result)},
      {"device_memory",
       {{"peak_bytes", result.memory.peakBytes},
        {"gbuffer_bytes_per_pixel", result.memory.gbufferBytesPerPixel},
        {"bvh_allocated_bytes_per_triangle", optionalNumber(result.memory.bvhAllocatedBytesPerTriangle)},
        {"bvh_built_bytes_per_triangle", optionalNumber(result.memory.bvhBuiltBytesPerTriangle)}}},
  };
}

void writeJson(const std::filesystem::path& path, const nlohmann::json& json) {
  std::ofstream out(path);
  if (!out) throw Error(path.string() + ": cannot open for writing");
  out << json.dump(2) << '\n';
  if (!out) throw Error(path.string() + ": write failed");
}

}  // namespace hmb
