// The library's public API in one header, installed as <hmblur/hmblur.h>: a Vulkan context (its
// own device, or an engine's adopted one), scenes, the renderer and its report, and the engine
// backend (post-process blur recorded into an engine's command buffer).
#pragma once

#include "runtime/device_scene/frame_camera.h"
#include "runtime/engine/engine_motion_blur.h"
#include "runtime/engine/engine_scene.h"
#include "runtime/error.h"
#include "runtime/passes/hit_shading.h"
#include "runtime/renderer.h"
#include "runtime/report.h"
#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/context.h"
#include "scenes/load_scene.h"
#include "scenes/scene.h"
