// What a frame cost: each pass's device time, and its shape (dispatches, barriers, host
// waits), as a frame recorder (frame_recorder.h) measures and counts them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace hmb::vk {

struct PassTiming {
  std::string name;
  // From the end of the pass before (or the frame's start) to this pass's end, the barrier
  // between them included; empty when the queue has no timestamps.
  std::optional<double> milliseconds;
};

// What a frame asks of the device and the host, counted as it is recorded: on a GPU every
// dispatch behind a barrier pays its launch and drain whatever its work, and every host wait a
// round trip. Shapes of a frame's parts add up (a submission waits for the one before).
struct FrameShape {
  uint32_t dispatches = 0;          // compute dispatches recorded, the indirect ones included
  uint32_t indirectDispatches = 0;  // of those, the ones whose group counts an earlier pass wrote
  uint32_t transfers = 0;           // fills, copies and buffer writes
  uint32_t barriers = 0;            // pipeline barriers
  uint32_t submissions = 0;         // command buffers the library submitted
  // Round trips of the host through the device: each submission the library waited for, and
  // its staging uploads and read-backs between them (vk::Context::hostWaits, hostReadbacks). A
  // frame the library submits has at least the wait at its end; a frame recorded into an
  // engine's command buffer has none.
  uint32_t hostWaits = 0;
  // The longest chain of dispatches each of which waits for the one before (a barrier between
  // them, or a host wait): the frame's latency in launches on a device that could run the
  // rest side by side.
  uint32_t dependentChain = 0;

  FrameShape& operator+=(const FrameShape& other);
  FrameShape operator-(const FrameShape& other) const;
  bool operator==(const FrameShape&) const = default;
};

struct FrameTimings {
  std::vector<PassTiming> passes;
  std::optional<double> frameMilliseconds;  // the frame's start to its last pass's end: the passes' sum
};

// Adds the passes and device time of a later submission to those of a frame made of several.
void appendTimings(FrameTimings& total, const FrameTimings& part);

}  // namespace hmb::vk
