// The library's public API in one header, installed as <hmblur/hmblur.h>: a Vulkan context (its
// own device, or an engine's adopted one), scenes, the renderer and its report, and the engine
// backend (post-process blur recorded into an engine's command buffer).
#pragma once

#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "hmblur/engine_motion_blur.h"
#include "hmblur/engine_scene.h"
#include "hmblur/error.h"
#include "hmblur/frame_camera.h"
#include "hmblur/hit_shading.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "hmblur/report.h"
#include "hmblur/scene.h"
