// The three reference scenes built in code, after the paper's shots (metres, seconds).
#pragma once

#include "scenes/scene.h"

namespace hmb::scene::procedural {

Scene makeLivingRoom();  // "living-room": red vase sliding past a sofa and a pink cushion
Scene makeTemple();      // "temple": colonnade, objects at several depths, spinning wheel
Scene makeBistro();      // "bistro": dense clutter, moving foreground, moving camera

}  // namespace hmb::scene::procedural
