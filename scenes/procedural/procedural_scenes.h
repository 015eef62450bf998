// The three reference scenes built in code, after the paper's shots (metres, seconds), and the
// motion studies (motion_studies.cpp).
#pragma once

#include "hmblur/scene.h"

namespace hmb::scene::procedural {

Scene makeLivingRoom();  // "living-room": red vase sliding past a sofa and a pink cushion
Scene makeTemple();      // "temple": colonnade, objects at several depths, spinning wheel
Scene makeBistro();      // "bistro": dense clutter, moving foreground, moving camera

// Motion studies, a sixth of a turn per exposure in front of a striped backdrop:
Scene makeSpinningPlate();  // "spinning-plate": a checkered plate spinning in the image plane
Scene makeTurntable();      // "turntable": a checkered plate spinning flat, seen from 45 degrees up
Scene makeSpinningBox();    // "spinning-box": a checkered box spinning about the vertical

}  // namespace hmb::scene::procedural
