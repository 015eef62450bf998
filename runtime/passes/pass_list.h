// A stage's passes, declared once in the order a frame records them. Each declaration names its
// pass (the plan's and the timings' name), says why a frame leaves it out (asked when the frame
// is planned; empty: it runs) and how it records. The stage's plan() and record() both walk the
// list, so what a frame plans and what it records cannot drift apart. A declaration dispatches a
// kernel of the manifest (kernels/manifest.h), built the first time a frame records it, or
// records without one of its own (fills, a pass object's recording); a group stands for a pass
// object that plans several named passes itself and records, given the frame's plan, those the
// plan runs. A pass recorded in several steps between others declares each step under its name:
// the plan takes the first step's reason, and each step records when the plan runs the pass and
// the step's own reason, asked again with the recording's inputs, is empty (docs/architecture.md).
#pragma once

#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hmblur/frame_plan.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

// What a declared dispatch records with: its name and its kernel.
struct DeclaredPass {
  std::string_view name;
  const vk::ComputeKernel& kernel;
};

// Inputs: what the stage's passes read this frame (a struct of pointers: default-constructed,
// it stands for a frame whose inputs the plan does not need).
template <class Inputs>
class PassList {
 public:
  using SkipReason = std::function<std::string(const Inputs&)>;
  using Dispatch = std::function<void(vk::FrameRecorder&, const DeclaredPass&, const Inputs&)>;
  using Record = std::function<void(vk::FrameRecorder&, const Inputs&)>;
  using Plan = std::function<void(FramePlan&, const Inputs&)>;
  using RecordPlanned = std::function<void(vk::FrameRecorder&, const FramePlan&, const Inputs&)>;

  explicit PassList(const vk::Context& context) : context_(&context) {}

  // A pass that dispatches `kernel` (kernels::kernel("stage/name")).
  PassList& dispatch(std::string name, const kernels::KernelFacts& kernel, Dispatch record, SkipReason skipped = {}) {
    return add({std::move(name), std::move(skipped), {}, {}, &kernel, std::move(record), nullptr, {}});
  }
  // A pass recorded without a kernel of its own.
  PassList& pass(std::string name, Record record, SkipReason skipped = {}) {
    return add({std::move(name), std::move(skipped), std::move(record), {}, nullptr, {}, nullptr, {}});
  }
  // A pass object that plans its own passes: `record` is given the frame's plan and records those
  // of its passes the plan runs.
  PassList& group(Plan plan, RecordPlanned record) {
    return add({{}, {}, {}, std::move(plan), nullptr, {}, nullptr, std::move(record)});
  }
  // Another list's passes, planned and recorded in its place (`passes` outlives this list).
  PassList& include(const PassList& passes) {
    return group([&passes](FramePlan& plan, const Inputs& inputs) { passes.plan(plan, inputs); },
                 [&passes](vk::FrameRecorder& frame, const FramePlan& plan, const Inputs& inputs) {
                   passes.record(frame, plan, inputs);
                 });
  }

  void plan(FramePlan& plan, const Inputs& inputs = {}) const {
    std::vector<std::string_view> planned;
    for (const Declared& d : declared_) {
      if (d.plan) {
        d.plan(plan, inputs);
      } else if (std::find(planned.begin(), planned.end(), d.name) == planned.end()) {
        plan.runUnless(d.name, skipReason(d, inputs));
        planned.push_back(d.name);
      }
    }
  }

  // Records every pass the list's own plan for `inputs` runs: for a stage recorded on its own,
  // outside a frame that planned it.
  void recordAll(vk::FrameRecorder& frame, const Inputs& inputs) const {
    FramePlan own;
    plan(own, inputs);
    record(frame, own, inputs);
  }

  // Records, in order, the declared passes `plan` runs.
  void record(vk::FrameRecorder& frame, const FramePlan& plan, const Inputs& inputs) const {
    for (const Declared& d : declared_) {
      if (!runs(d, plan, inputs)) continue;
      if (d.plan) {
        d.recordPlanned(frame, plan, inputs);
        continue;
      }
      if (!d.kernel) {
        d.record(frame, inputs);
        continue;
      }
      if (!d.built) d.built = std::make_unique<vk::ComputeKernel>(*context_, *d.kernel);
      d.dispatch(frame, DeclaredPass{d.name, *d.built}, inputs);
    }
  }

 private:
  struct Declared {
    std::string name;
    SkipReason skipped;
    Record record;
    Plan plan;
    const kernels::KernelFacts* kernel;
    Dispatch dispatch;
    mutable std::unique_ptr<vk::ComputeKernel> built;
    RecordPlanned recordPlanned;  // a group's
    bool step = false;            // one of several declarations of its pass
  };

  PassList& add(Declared declared) {
    for (Declared& other : declared_)
      if (!declared.name.empty() && other.name == declared.name) other.step = declared.step = true;
    declared_.push_back(std::move(declared));
    return *this;
  }

  static std::string skipReason(const Declared& d, const Inputs& inputs) {
    return d.skipped ? d.skipped(inputs) : std::string();
  }

  static bool runs(const Declared& d, const FramePlan& plan, const Inputs& inputs) {
    if (d.plan) return true;  // the group records what the plan runs of its own
    return plan.runs(d.name) && (!d.step || skipReason(d, inputs).empty());
  }

  const vk::Context* context_;
  std::vector<Declared> declared_;
};

}  // namespace hmb::passes
