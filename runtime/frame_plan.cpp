#include "hmblur/frame_plan.h"

#include <algorithm>

#include "hmblur/error.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb {
namespace {

auto runningNamed(std::string_view name) {
  return [name](const PlannedPass& p) { return p.run && p.name == name; };
}

}  // namespace

void FramePlan::run(std::string name) {
  if (runs(name)) throw Error("pass '" + name + "' planned twice");
  passes_.push_back({std::move(name), true, {}, std::nullopt, {}, {}});
}

void FramePlan::runWithin(std::string name, std::string within) {
  run(std::move(name));
  passes_.back().within = std::move(within);
}

void FramePlan::skip(std::string name, std::string reason) {
  passes_.push_back({std::move(name), false, std::move(reason), std::nullopt, {}, {}});
}

void FramePlan::runUnless(std::string name, const std::string& skipReason) {
  if (skipReason.empty())
    run(std::move(name));
  else
    skip(std::move(name), skipReason);
}

bool FramePlan::runs(std::string_view name) const {
  return std::any_of(passes_.begin(), passes_.end(), runningNamed(name));
}

PlannedPass* FramePlan::runningPass(std::string_view name) {
  auto it = std::find_if(passes_.begin(), passes_.end(), runningNamed(name));
  return it == passes_.end() ? nullptr : &*it;
}

void FramePlan::attachTimings(const vk::FrameTimings& timings) {
  for (const vk::PassTiming& timing : timings.passes) {
    PlannedPass* pass = runningPass(timing.name);
    if (!pass) throw Error("pass '" + timing.name + "' was recorded but not planned");
    if (timing.milliseconds) pass->milliseconds = pass->milliseconds.value_or(0.0) + *timing.milliseconds;
  }
}

void FramePlan::noteNoWork(std::string_view name, std::string reason) {
  PlannedPass* pass = runningPass(name);
  if (!pass) throw Error("pass '" + std::string(name) + "' did not run");
  pass->noWork = std::move(reason);
}

}  // namespace hmb
