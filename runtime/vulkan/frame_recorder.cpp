#include "runtime/vulkan/frame_recorder.h"

#include <algorithm>
#include <iterator>
#include <vector>

#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "runtime/vulkan/check.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {

FrameShape& FrameShape::operator+=(const FrameShape& other) {
  dispatches += other.dispatches;
  indirectDispatches += other.indirectDispatches;
  transfers += other.transfers;
  barriers += other.barriers;
  submissions += other.submissions;
  hostWaits += other.hostWaits;
  dependentChain += other.dependentChain;
  return *this;
}

FrameShape FrameShape::operator-(const FrameShape& other) const {
  FrameShape d;
  d.dispatches = dispatches - other.dispatches;
  d.indirectDispatches = indirectDispatches - other.indirectDispatches;
  d.transfers = transfers - other.transfers;
  d.barriers = barriers - other.barriers;
  d.submissions = submissions - other.submissions;
  d.hostWaits = hostWaits - other.hostWaits;
  d.dependentChain = dependentChain - other.dependentChain;
  return d;
}

void appendTimings(FrameTimings& total, const FrameTimings& part) {
  total.passes.insert(total.passes.end(), part.passes.begin(), part.passes.end());
  if (part.frameMilliseconds) total.frameMilliseconds = total.frameMilliseconds.value_or(0.0) + *part.frameMilliseconds;
}
namespace {

constexpr uint32_t kMaxBindingsPerPass = 16;
// Passes of a frame that bind an engine's images: its G-buffer's reading and its output's writing.
constexpr uint32_t kMaxImagePasses = 4;

// What a pass may write.
constexpr VkPipelineStageFlags kPassStages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
constexpr VkAccessFlags kPassWrites = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;

}  // namespace

FrameRecorder::FrameRecorder(const Context& context, uint32_t maxPasses)
    : context_(context), maxPasses_(maxPasses) {
  const VkDevice device = context.device();
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = context.commandPool();
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  HMB_VK_CHECK(vkAllocateCommandBuffers(device, &allocInfo, &ownCommandBuffer_));

  const VkDescriptorPoolSize poolSizes[] = {
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, maxPasses * kMaxBindingsPerPass},
      {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, maxPasses * kMaxBindingsPerPass},
      {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, kMaxImagePasses * kMaxBindingsPerPass},
      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kMaxImagePasses}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = maxPasses;
  poolInfo.poolSizeCount = uint32_t(std::size(poolSizes));
  poolInfo.pPoolSizes = poolSizes;
  HMB_VK_CHECK(vkCreateDescriptorPool(device, &poolInfo, nullptr, &descriptorPool_));

  if (context.info().timestamps) {
    VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = maxPasses + 1;  // the frame's start, then each pass's end
    HMB_VK_CHECK(vkCreateQueryPool(device, &queryInfo, nullptr, &queryPool_));
  }
}

FrameRecorder::~FrameRecorder() {
  const VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  if (queryPool_) vkDestroyQueryPool(device, queryPool_, nullptr);
  if (descriptorPool_) vkDestroyDescriptorPool(device, descriptorPool_, nullptr);
  if (ownCommandBuffer_) vkFreeCommandBuffers(device, context_.commandPool(), 1, &ownCommandBuffer_);
}

void FrameRecorder::begin() {
  HMB_VK_CHECK(vkResetCommandBuffer(ownCommandBuffer_, 0));
  VkCommandBufferBeginInfo beginInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  beginInfo.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  HMB_VK_CHECK(vkBeginCommandBuffer(ownCommandBuffer_, &beginInfo));
  startFrame(ownCommandBuffer_, false);
}

void FrameRecorder::beginInto(VkCommandBuffer commandBuffer) {
  if (!commandBuffer) throw Error("beginInto() a VK_NULL_HANDLE command buffer");
  startFrame(commandBuffer, true);
  // What the command buffer's earlier commands (and earlier submissions on the queue) wrote,
  // the first pass reads.
  recordBarrier(VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT, kPassStages,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                    VK_ACCESS_TRANSFER_WRITE_BIT);
}

void FrameRecorder::startFrame(VkCommandBuffer commandBuffer, bool external) {
  HMB_VK_CHECK(vkResetDescriptorPool(context_.device(), descriptorPool_, 0));
  commandBuffer_ = commandBuffer;
  external_ = external;
  if (queryPool_) vkCmdResetQueryPool(commandBuffer_, queryPool_, 0, maxPasses_ + 1);
  passNames_.clear();
  recording_ = true;
  // The frame starts once the command buffer's earlier commands (an engine's draws) have
  // finished: a bottom-of-pipe stamp, ahead of the first pass's barrier.
  writeStamp(0);
}

void FrameRecorder::endInto() {
  if (!recording_ || !external_) throw Error("endInto() without beginInto()");
  recording_ = false;
  // The passes' writes, for every later command of the engine's.
  recordBarrier(kPassStages, kPassWrites, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
}

uint32_t FrameRecorder::beginPass(std::string_view pass) {
  if (!recording_) throw Error("pass '" + std::string(pass) + "' recorded outside begin()/submitAndWait()");
  if (passNames_.size() >= maxPasses_)
    throw Error("frame has more than " + std::to_string(maxPasses_) + " passes");
  const auto index = static_cast<uint32_t>(passNames_.size());
  passNames_.emplace_back(pass);
  return index;
}

void FrameRecorder::writeStamp(uint32_t query) {
  if (queryPool_) vkCmdWriteTimestamp(commandBuffer_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queryPool_, query);
}

void FrameRecorder::endPass(uint32_t index) {
  // The barrier right after the stamp matters on lavapipe: in a command buffer where the engine
  // drew, it takes a stamp only when it next flushes its rasterizer, which a barrier does; a
  // stamp with no barrier after it would read the time of some later pass.
  writeStamp(index + 1);
  // Everything a pass may write becomes visible to everything the next pass may do.
  recordBarrier(kPassStages, kPassWrites, kPassStages | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                    VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

void FrameRecorder::recordBarrier(VkPipelineStageFlags srcStages, VkAccessFlags srcAccess,
                                  VkPipelineStageFlags dstStages, VkAccessFlags dstAccess) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = srcAccess;
  barrier.dstAccessMask = dstAccess;
  vkCmdPipelineBarrier(commandBuffer_, srcStages, dstStages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
  ++shape_.barriers;
  if (dispatchSinceBarrier_) ++shape_.dependentChain;
  dispatchSinceBarrier_ = false;
}

void FrameRecorder::recordDispatch(bool indirect) {
  ++shape_.dispatches;
  if (indirect) ++shape_.indirectDispatches;
  dispatchSinceBarrier_ = true;
}

FrameRecorder::ShapeMark FrameRecorder::mark() const {
  return {shape_, context_.hostRoundTrips()};
}

FrameShape FrameRecorder::shapeSince(const ShapeMark& mark, HostWaitsUntil until) const {
  FrameShape shape = shape_ - mark.recorded;
  const uint64_t roundTrips = until == HostWaitsUntil::Now ? context_.hostRoundTrips()
                              : shape.submissions > 0      ? roundTripsAtLastSubmit_
                                                           : mark.hostRoundTrips;
  shape.hostWaits = static_cast<uint32_t>(roundTrips - mark.hostRoundTrips);
  return shape;
}

uint32_t FrameRecorder::bindAndBeginPass(std::string_view pass, const ComputeKernel& kernel,
                                         std::span<const Binding> bindings,
                                         std::span<const std::byte> pushConstants) {
  const auto passAndKernel = [&] { return "pass '" + std::string(pass) + "' (kernel '" + kernel.name() + "')"; };
  // Exactly one buffer at each binding number the kernel declares.
  std::vector<uint32_t> given;
  for (const Binding& b : bindings) given.push_back(b.index);
  std::sort(given.begin(), given.end());
  if (const auto twice = std::adjacent_find(given.begin(), given.end()); twice != given.end())
    throw Error(passAndKernel() + " binds binding " + std::to_string(*twice) + " twice");
  for (const uint32_t index : given)
    if (!std::binary_search(kernel.bindings().begin(), kernel.bindings().end(), index))
      throw Error(passAndKernel() + " binds binding " + std::to_string(index) + ", which the kernel does not declare");
  for (const uint32_t index : kernel.bindings())
    if (!std::binary_search(given.begin(), given.end(), index))
      throw Error(passAndKernel() + " leaves binding " + std::to_string(index) + " unbound");
  if (pushConstants.size() != kernel.pushConstantBytes())
    throw Error("pass '" + std::string(pass) + "' pushes " + std::to_string(pushConstants.size()) +
                " bytes; kernel '" + kernel.name() + "' takes " + std::to_string(kernel.pushConstantBytes()));

  VkDescriptorSet set = VK_NULL_HANDLE;
  if (!bindings.empty()) {
    const VkDescriptorSetLayout setLayout = kernel.setLayout();
    VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocInfo.descriptorPool = descriptorPool_;
    allocInfo.descriptorSetCount = 1;
    allocInfo.pSetLayouts = &setLayout;
    HMB_VK_CHECK(vkAllocateDescriptorSets(context_.device(), &allocInfo, &set));

    std::vector<VkDescriptorBufferInfo> infos(bindings.size());
    std::vector<VkDescriptorImageInfo> images(bindings.size());
    std::vector<VkBufferView> views(bindings.size());
    std::vector<VkWriteDescriptorSet> writes(bindings.size());
    for (size_t i = 0; i < bindings.size(); ++i) {
      writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[i].dstSet = set;
      writes[i].dstBinding = bindings[i].index;
      writes[i].descriptorCount = 1;
      const VkDescriptorType type = kernel.descriptorType(bindings[i].index);
      if (type == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE || type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
        if (!bindings[i].image)
          throw Error(passAndKernel() + " binds no image view at image binding " + std::to_string(bindings[i].index));
        images[i] = {VK_NULL_HANDLE, bindings[i].image, bindings[i].imageLayout};
        writes[i].descriptorType = type;
        writes[i].pImageInfo = &images[i];
        continue;
      }
      const Buffer* buffer = bindings[i].buffer;
      if (!buffer || !buffer->handle())
        throw Error(passAndKernel() + " binds an empty buffer at binding " + std::to_string(bindings[i].index));
      infos[i] = {buffer->handle(), 0, VK_WHOLE_SIZE};
      if (kernel.isTexelBinding(bindings[i].index)) {
        views[i] = buffer->texelView();
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        writes[i].pTexelBufferView = &views[i];
      } else {
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
      }
    }
    vkUpdateDescriptorSets(context_.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
  }

  const uint32_t index = beginPass(pass);
  vkCmdBindPipeline(commandBuffer_, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline());
  if (set) vkCmdBindDescriptorSets(commandBuffer_, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout(), 0, 1, &set, 0, nullptr);
  if (!pushConstants.empty())
    vkCmdPushConstants(commandBuffer_, kernel.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       static_cast<uint32_t>(pushConstants.size()), pushConstants.data());
  return index;
}

void FrameRecorder::dispatch(std::string_view pass, const ComputeKernel& kernel, std::span<const Binding> bindings,
                             std::span<const std::byte> pushConstants, glm::uvec3 groups) {
  const auto& limits = context_.limits();
  for (int axis = 0; axis < 3; ++axis)
    if (groups[axis] > limits.maxComputeWorkGroupCount[axis])
      throw Error("pass '" + std::string(pass) + "' needs " + std::to_string(groups[axis]) +
                  " work groups along axis " + std::to_string(axis) + "; the device allows " +
                  std::to_string(limits.maxComputeWorkGroupCount[axis]));
  const uint32_t index = bindAndBeginPass(pass, kernel, bindings, pushConstants);
  if (groups.x > 0 && groups.y > 0 && groups.z > 0) {
    vkCmdDispatch(commandBuffer_, groups.x, groups.y, groups.z);
    recordDispatch(false);
  }
  endPass(index);
}

void FrameRecorder::dispatchIndirect(std::string_view pass, const ComputeKernel& kernel,
                                     std::span<const Binding> bindings, std::span<const std::byte> pushConstants,
                                     const Buffer& indirect, VkDeviceSize offset) {
  if (offset % 4 != 0 || offset + sizeof(VkDispatchIndirectCommand) > indirect.size())
    throw Error("pass '" + std::string(pass) + "': indirect dispatch at byte " + std::to_string(offset) +
                " does not fit buffer '" + indirect.name() + "'");
  const uint32_t index = bindAndBeginPass(pass, kernel, bindings, pushConstants);
  vkCmdDispatchIndirect(commandBuffer_, indirect.handle(), offset);
  recordDispatch(true);
  endPass(index);
}

void FrameRecorder::fill(std::string_view pass, const Buffer& buffer, uint32_t value) {
  const uint32_t index = beginPass(pass);
  vkCmdFillBuffer(commandBuffer_, buffer.handle(), 0, VK_WHOLE_SIZE, value);
  ++shape_.transfers;
  endPass(index);
}

void FrameRecorder::copy(std::string_view pass, const Buffer& from, const Buffer& to, VkDeviceSize bytes) {
  if (bytes > from.size() || bytes > to.size())
    throw Error("copy of " + std::to_string(bytes) + " bytes past a buffer's end");
  if (bytes == 0) return;
  const uint32_t index = beginPass(pass);
  const VkBufferCopy region{0, 0, bytes};
  vkCmdCopyBuffer(commandBuffer_, from.handle(), to.handle(), 1, &region);
  ++shape_.transfers;
  endPass(index);
}

void FrameRecorder::write(std::string_view pass, const Buffer& buffer, std::span<const std::byte> bytes,
                          VkDeviceSize offset) {
  if (offset + bytes.size() > buffer.size())
    throw Error("pass '" + std::string(pass) + "' writes past the end of buffer '" + buffer.name() + "'");
  if (offset % 4 != 0 || bytes.size() % 4 != 0)
    throw Error("pass '" + std::string(pass) + "' writes a size or at an offset that is not a multiple of 4 bytes");
  if (bytes.empty()) return;
  constexpr VkDeviceSize kMaxUpdate = 65536;  // what one vkCmdUpdateBuffer may carry
  const uint32_t index = beginPass(pass);
  for (VkDeviceSize done = 0; done < bytes.size(); done += kMaxUpdate) {
    const VkDeviceSize part = std::min<VkDeviceSize>(kMaxUpdate, bytes.size() - done);
    vkCmdUpdateBuffer(commandBuffer_, buffer.handle(), offset + done, part, bytes.data() + done);
  }
  ++shape_.transfers;
  endPass(index);
}

FrameTimings FrameRecorder::submitAndWait() {
  if (!recording_ || external_) throw Error("submitAndWait() without begin()");
  recording_ = false;
  // The host reads results after the fence: make every write visible to it.
  recordBarrier(kPassStages, kPassWrites, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  HMB_VK_CHECK(vkEndCommandBuffer(commandBuffer_));
  context_.submitAndWait(commandBuffer_);
  ++shape_.submissions;
  roundTripsAtLastSubmit_ = context_.hostRoundTrips();
  return readTimings();
}

FrameTimings FrameRecorder::readTimings() const {
  if (recording_) throw Error("readTimings() while the frame is being recorded");
  FrameTimings timings;
  const auto passCount = static_cast<uint32_t>(passNames_.size());
  std::vector<uint64_t> stamps(passCount + 1);
  if (queryPool_ && passCount > 0)
    HMB_VK_CHECK(vkGetQueryPoolResults(context_.device(), queryPool_, 0, passCount + 1,
                                       stamps.size() * sizeof(uint64_t), stamps.data(), sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  const double nsPerTick = context_.info().timestampPeriodNs;
  const uint64_t mask = context_.info().timestampMask;
  auto ticksToMs = [&](uint64_t from, uint64_t to) { return double((to - from) & mask) * nsPerTick * 1e-6; };
  for (uint32_t i = 0; i < passCount; ++i) {
    PassTiming timing{passNames_[i], std::nullopt};
    if (queryPool_) timing.milliseconds = ticksToMs(stamps[i], stamps[i + 1]);
    timings.passes.push_back(std::move(timing));
  }
  if (queryPool_ && passCount > 0) timings.frameMilliseconds = ticksToMs(stamps[0], stamps[passCount]);
  return timings;
}

}  // namespace hmb::vk
