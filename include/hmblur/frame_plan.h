// Which passes a frame runs, which it leaves out and why, and what each one cost. Decided
// before recording from the scene and the settings; the report prints it as it is.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hmb::vk {
struct FrameTimings;
}

namespace hmb {

struct PlannedPass {
  std::string name;
  bool run = true;
  std::string reason;                  // why it is skipped (empty for a pass that runs)
  std::optional<double> milliseconds;  // device time, once measured
  // A pass that ran but found no work on the device (an indirect dispatch of no groups: what
  // it would have read was decided on the device during the frame), and why.
  std::string noWork;
  // A code path inside other passes rather than a dispatch of its own: those passes, whose
  // times include it (empty for a pass of its own).
  std::string within;
};

class FramePlan {
 public:
  void run(std::string name);
  void skip(std::string name, std::string reason);
  // Runs the pass when skipReason is empty, else skips it for that reason.
  void runUnless(std::string name, const std::string& skipReason);
  // A code path that runs inside the passes named by `within` (comma separated).
  void runWithin(std::string name, std::string within);
  bool runs(std::string_view name) const;
  const std::vector<PlannedPass>& passes() const { return passes_; }

  // Copies measured times onto the passes of the same name (a pass dispatched more than once
  // accumulates its dispatches).
  void attachTimings(const vk::FrameTimings& timings);
  // After the frame: the pass ran with nothing to do, for this reason (it must have run).
  void noteNoWork(std::string_view name, std::string reason);

 private:
  PlannedPass* runningPass(std::string_view name);  // the planned pass of that name that runs, or null

  std::vector<PlannedPass> passes_;
};

}  // namespace hmb
