#pragma once
/// @file
/// The progress checker of the planning layer: progress is a shrinking of the path left to the
/// goal; too little of it within a time window is a stall (the robot loops round an obstacle,
/// pushes against one, or is boxed in), and the planner then replans and recovers.

namespace floornav {

class ProgressChecker {
 public:
  /// A stall is less than `distance` m of progress within `window` s.
  ProgressChecker(double window = 8.0, double distance = 0.1)
      : window_(window), distance_(distance) {}

  /// Starts a new window at time `t` with `remaining` m left.
  void reset(double t, double remaining) {
    anchor_time_ = t;
    best_ = remaining;
  }
  /// One step: true when the window has run out without progress (then call reset).
  bool stalled(double t, double remaining) {
    if (remaining <= best_ - distance_) {
      reset(t, remaining);
      return false;
    }
    return t - anchor_time_ >= window_;
  }
  /// When the current window started (the last progress).
  double anchor_time() const { return anchor_time_; }
  double best() const { return best_; }

 private:
  double window_;
  double distance_;
  double anchor_time_{0.0};
  double best_{0.0};
};

}  // namespace floornav
