// The JSON report of a render: device, driver, CPU, LP_NUM_THREADS, resolution, scene
// settings, and per pass its time or that it was skipped and why.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "hmblur/context.h"
#include "hmblur/renderer.h"
#include "hmblur/scene.h"
#include "hmblur/system_info.h"

namespace hmb {

// A number, or null when there is none.
nlohmann::json optionalNumber(const std::optional<double>& value);
nlohmann::json deviceJson(const vk::DeviceInfo& device);
nlohmann::json deviceProfileJson(const vk::DeviceProfile& profile);
// The device's facts and the profile its passes chose by ("profile").
nlohmann::json deviceJson(const vk::Context& context);
// "device: NAME; profile ..." for the tools' progress lines.
std::string deviceProgressLine(const vk::Context& context);
nlohmann::json systemJson(const SystemInfo& system);
nlohmann::json sceneJson(const scene::Scene& scene);
nlohmann::json passesJson(const FramePlan& plan);
// A frame's shape (vk::FrameShape): dispatches, indirect_dispatches, transfers, barriers,
// submissions, host_waits, dependent_chain.
nlohmann::json frameShapeJson(const vk::FrameShape& shape);
// The G-buffer rasterizer of a render (visibility scheme, counts); null for methods without one.
nlohmann::json rasterJson(const RenderResult& result);

// The settings of the method that was rendered (sample counts, seeds, tile sizes ...).
nlohmann::json methodSettingsJson(const RenderResult& result);

nlohmann::json renderReport(const vk::Context& context, const SystemInfo& system, const scene::Scene& scene,
                            const RenderResult& result);

// Writes pretty-printed JSON; throws hmb::Error naming the file on failure.
void writeJson(const std::filesystem::path& path, const nlohmann::json& json);

}  // namespace hmb
