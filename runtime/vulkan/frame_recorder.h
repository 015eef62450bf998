// One command buffer per frame: each pass is a dispatch (or a fill, copy or write) followed by a
// timestamp and a barrier, so the next pass sees its writes. A pass's time runs from the stamp
// before it (the frame's start, or the end of the pass before) to its own: the drain and launch
// between two passes count to the pass that waited, and the passes add up to the frame.
// submitAndWait() returns the time of every pass as the device measured it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "hmblur/frame_timings.h"
#include "kernels/shared/dispatch.h"
#include "runtime/vulkan/binding.h"

namespace hmb::vk {

class Buffer;
class ComputeKernel;
class Context;

// Work groups needed to cover `items` with groups of `groupSize`.
inline uint32_t groupsFor(uint32_t items, uint32_t groupSize) {
  return static_cast<uint32_t>((uint64_t(items) + groupSize - 1) / groupSize);
}

// A 1D run of groups folded into rows of at most 65535, as the kernels that size their own
// dispatches fold them (kernels/shared/dispatch.h).
using gpu::foldedGroups;

class FrameRecorder {
 public:
  explicit FrameRecorder(const Context& context, uint32_t maxPasses = 256);
  ~FrameRecorder();
  FrameRecorder(const FrameRecorder&) = delete;
  FrameRecorder& operator=(const FrameRecorder&) = delete;

  // Starts a new frame in the recorder's own command buffer; the previous frame's command buffer
  // and descriptor sets are reused.
  void begin();
  // Starts a frame in a command buffer someone else owns and submits (an engine's): recording,
  // outside a render pass, for a queue of the context's queue family. A barrier first makes
  // every earlier write on that queue visible to the passes. The descriptor sets are reused per
  // frame, so the frame this recorder recorded before must have completed on the device.
  void beginInto(VkCommandBuffer commandBuffer);
  // Ends a frame begun with beginInto(): a barrier makes the passes' writes visible to every
  // later command. Submitting is the owner's.
  void endInto();
  // The device time of the last frame's passes, once it completed on the device (submitAndWait()
  // returns them itself); empty times when the queue has no timestamps.
  FrameTimings readTimings() const;

  // bindings: a buffer at each binding number the kernel declares (its layout header's names).
  void dispatch(std::string_view pass, const ComputeKernel& kernel, std::span<const Binding> bindings,
                std::span<const std::byte> pushConstants, glm::uvec3 groups);
  template <class Push>
  void dispatch(std::string_view pass, const ComputeKernel& kernel, std::initializer_list<Binding> bindings,
                const Push& push, glm::uvec3 groups) {
    dispatch(pass, kernel, std::span<const Binding>(bindings.begin(), bindings.size()),
             std::as_bytes(std::span<const Push>(&push, 1)), groups);
  }
  template <class Push>
  void dispatch(std::string_view pass, const ComputeKernel& kernel, const Bindings& bindings, const Push& push,
                glm::uvec3 groups) {
    dispatch(pass, kernel, std::span<const Binding>(bindings), std::as_bytes(std::span<const Push>(&push, 1)), groups);
  }

  // A dispatch whose group counts the device reads from `indirect` at `offset` when the pass
  // runs (a VkDispatchIndirectCommand written by an earlier pass of the same frame).
  void dispatchIndirect(std::string_view pass, const ComputeKernel& kernel, std::span<const Binding> bindings,
                        std::span<const std::byte> pushConstants, const Buffer& indirect, VkDeviceSize offset);
  template <class Push>
  void dispatchIndirect(std::string_view pass, const ComputeKernel& kernel, std::initializer_list<Binding> bindings,
                        const Push& push, const Buffer& indirect, VkDeviceSize offset) {
    dispatchIndirect(pass, kernel, std::span<const Binding>(bindings.begin(), bindings.size()),
                     std::as_bytes(std::span<const Push>(&push, 1)), indirect, offset);
  }
  template <class Push>
  void dispatchIndirect(std::string_view pass, const ComputeKernel& kernel, const Bindings& bindings,
                        const Push& push, const Buffer& indirect, VkDeviceSize offset) {
    dispatchIndirect(pass, kernel, std::span<const Binding>(bindings), std::as_bytes(std::span<const Push>(&push, 1)),
                     indirect, offset);
  }

  // Fills a whole buffer with a 32-bit value (clears, sentinels).
  void fill(std::string_view pass, const Buffer& buffer, uint32_t value);
  // Copies the first `bytes` of `from` to the start of `to`.
  void copy(std::string_view pass, const Buffer& from, const Buffer& to, VkDeviceSize bytes);
  // Writes host data into `buffer` at `offset` when the frame runs: the bytes travel in the
  // command buffer (vkCmdUpdateBuffer, 64 KiB a command), so nothing is staged or waited for.
  // For the frame's small inputs (transforms, cameras, build roots); sizes and offsets are
  // multiples of 4 bytes.
  void write(std::string_view pass, const Buffer& buffer, std::span<const std::byte> bytes, VkDeviceSize offset = 0);
  template <class T>
  void write(std::string_view pass, const Buffer& buffer, std::span<const T> values) {
    write(pass, buffer, std::as_bytes(values));
  }

  // Ends the command buffer, submits it, waits, and reads the timestamps.
  FrameTimings submitAndWait();

  // The shape of what was recorded and submitted since a mark (FrameShape): take a mark before
  // a frame, and the shape once its last submission completed. Its host waits are the
  // context's from the mark up to the recorder's last submission since it (staging and
  // read-backs between a frame's submissions included, the reads of its results after it
  // not), or up to now (a part of a frame that ends with its reads, such as scene setup).
  struct ShapeMark {
    FrameShape recorded;
    uint64_t hostRoundTrips = 0;
  };
  enum class HostWaitsUntil { LastSubmission, Now };
  ShapeMark mark() const;
  FrameShape shapeSince(const ShapeMark& mark, HostWaitsUntil until = HostWaitsUntil::LastSubmission) const;

 private:
  // Checks the bindings, binds pipeline, descriptors and push constants, opens the pass.
  uint32_t bindAndBeginPass(std::string_view pass, const ComputeKernel& kernel, std::span<const Binding> bindings,
                            std::span<const std::byte> pushConstants);
  void startFrame(VkCommandBuffer commandBuffer, bool external);
  uint32_t beginPass(std::string_view pass);
  void endPass(uint32_t index);
  // A bottom-of-pipe timestamp into query `query`: 0 the frame's start, i + 1 pass i's end.
  void writeStamp(uint32_t query);
  // Records a memory barrier into the frame and counts it (FrameShape).
  void recordBarrier(VkPipelineStageFlags srcStages, VkAccessFlags srcAccess, VkPipelineStageFlags dstStages,
                     VkAccessFlags dstAccess);
  void recordDispatch(bool indirect);

  const Context& context_;
  uint32_t maxPasses_;
  VkCommandBuffer ownCommandBuffer_ = VK_NULL_HANDLE;
  VkCommandBuffer commandBuffer_ = VK_NULL_HANDLE;  // the frame's: the own one or the owner's (beginInto)
  bool external_ = false;
  VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
  VkQueryPool queryPool_ = VK_NULL_HANDLE;
  std::vector<std::string> passNames_;
  bool recording_ = false;
  FrameShape shape_;                   // since creation; host waits left to shapeSince()
  bool dispatchSinceBarrier_ = false;  // a dispatch recorded after the last barrier
  uint64_t roundTripsAtLastSubmit_ = 0;  // the context's host round trips after the last submission
};

}  // namespace hmb::vk
