#pragma once
/// @file
/// A general hybrid automaton (section 5.3.3): discrete modes q, each with a flow x' = f_q(x);
/// edges q -> q' with a guard G_{q,q'} and a reset R_{q,q'} that may write the automaton's memory.
///
/// Step order (HybridAutomaton::step), once per control period:
///   1. evaluate the guards of the current mode's edges, in the order they were added (priority);
///      an edge is considered only once the mode has been held for its `min_dwell`;
///   2. take at most one transition: apply its reset to the memory, change mode, log it;
///   3. the caller then asks for the new mode's flow (HybridAutomaton::flow).
/// Guards are sampled at the control period: a guard that is true at a sample fires there.
/// Hysteresis ("fat guards") is expressed by giving the leaving guard a different threshold from
/// the entering one. Failure: the step never throws; a bad structure is refused by the Builder.
///
/// Chatter (Zeno, Fig 5.9) is detected explicitly: `chatter_switches` transitions within
/// `chatter_window` seconds raise a chatter episode in the state.

#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace floornav {

/// One mode change, for the transition log.
struct Transition {
  double time{0.0};  ///< seconds
  int from{-1};
  int to{-1};
  int edge{-1};  ///< index of the edge whose guard fired
};

/// Counts switches in a sliding time window (Zeno detection).
struct ChatterMonitor {
  static constexpr int kCapacity = 32;
  std::array<double, kCapacity> times{};
  int count{0};           ///< switches stored (<= kCapacity)
  int head{0};            ///< next write position
  int episodes{0};        ///< chatter episodes seen
  double first_time{-1};  ///< time the first episode was detected, -1 if none
  bool active{false};     ///< in an episode now

  /// Records a switch at `t`; returns true when this switch starts a new chatter episode.
  bool record(double t, int switches, double window) {
    times[static_cast<std::size_t>(head)] = t;
    head = (head + 1) % kCapacity;
    if (count < kCapacity) ++count;
    const int n = std::min(switches, kCapacity);
    if (count < n) return false;
    const int oldest = (head - n + kCapacity) % kCapacity;
    const bool chatter = t - times[static_cast<std::size_t>(oldest)] <= window;
    const bool starts = chatter && !active;
    active = chatter;
    if (starts) {
      ++episodes;
      if (first_time < 0) first_time = t;
    }
    return starts;
  }
};

template <class Input, class Memory, class Output>
class HybridAutomaton {
 public:
  using Flow = std::function<Output(const Input&, const Memory&)>;
  using Guard = std::function<bool(const Input&, const Memory&)>;
  using Reset = std::function<void(const Input&, Memory&)>;

  struct Mode {
    std::string name;
    Flow flow;
    bool terminal{false};  ///< no edge leaves it (STOP)
  };
  struct Edge {
    int from{-1};
    int to{-1};
    std::string guard_name;
    Guard guard;
    Reset reset;  ///< may be empty
    double min_dwell{0.0};
  };

  /// Everything that changes while the automaton runs; copyable, so runs can be replayed.
  struct State {
    int mode{0};
    double time_in_mode{0.0};
    Memory memory{};
    ChatterMonitor chatter{};
    int switches{0};
  };

  /// Builds and validates the structure, then freezes it.
  class Builder {
   public:
    int add_mode(std::string name, Flow flow, bool terminal = false) {
      modes_.push_back({std::move(name), std::move(flow), terminal});
      return static_cast<int>(modes_.size()) - 1;
    }
    /// An edge; edges of one mode are tried in the order they are added.
    void add_edge(int from, int to, std::string guard_name, Guard guard, Reset reset = {},
                  double min_dwell = 0.0) {
      edges_.push_back(
          {from, to, std::move(guard_name), std::move(guard), std::move(reset), min_dwell});
    }
    /// The same edge from every non-terminal mode other than `to` (e.g. any -> STOP).
    void add_edge_from_every_mode(int to, const std::string& guard_name, const Guard& guard,
                                  const Reset& reset = {}) {
      for (int m = 0; m < static_cast<int>(modes_.size()); ++m)
        if (m != to && !modes_[static_cast<std::size_t>(m)].terminal)
          add_edge(m, to, guard_name, guard, reset);
    }
    void set_initial(int mode) { initial_ = mode; }
    void set_chatter_rule(int switches, double window) {
      chatter_switches_ = switches;
      chatter_window_ = window;
    }

    /// Throws std::logic_error for: no modes, an edge naming an unknown mode, an edge leaving a
    /// terminal mode, a mode without a flow, an unreachable mode, or no terminal mode.
    HybridAutomaton build() const {
      const int n = static_cast<int>(modes_.size());
      if (n == 0) throw std::logic_error("hybrid automaton: no modes");
      if (initial_ < 0 || initial_ >= n)
        throw std::logic_error("hybrid automaton: no initial mode");
      bool has_terminal = false;
      for (const Mode& m : modes_) {
        if (!m.flow) throw std::logic_error("hybrid automaton: mode '" + m.name + "' has no flow");
        has_terminal = has_terminal || m.terminal;
      }
      if (!has_terminal) throw std::logic_error("hybrid automaton: no terminal (STOP) mode");
      for (const Edge& e : edges_) {
        if (e.from < 0 || e.from >= n || e.to < 0 || e.to >= n)
          throw std::logic_error("hybrid automaton: edge '" + e.guard_name + "' names no mode");
        if (modes_[static_cast<std::size_t>(e.from)].terminal)
          throw std::logic_error("hybrid automaton: edge '" + e.guard_name +
                                 "' leaves a terminal mode");
        if (!e.guard) throw std::logic_error("hybrid automaton: edge without a guard");
      }
      std::vector<bool> seen(static_cast<std::size_t>(n), false);
      std::vector<int> stack{initial_};
      seen[static_cast<std::size_t>(initial_)] = true;
      while (!stack.empty()) {
        const int m = stack.back();
        stack.pop_back();
        for (const Edge& e : edges_)
          if (e.from == m && !seen[static_cast<std::size_t>(e.to)]) {
            seen[static_cast<std::size_t>(e.to)] = true;
            stack.push_back(e.to);
          }
      }
      for (int m = 0; m < n; ++m)
        if (!seen[static_cast<std::size_t>(m)])
          throw std::logic_error("hybrid automaton: mode '" +
                                 modes_[static_cast<std::size_t>(m)].name + "' is unreachable");
      HybridAutomaton a;
      a.modes_ = modes_;
      a.edges_ = edges_;
      a.initial_ = initial_;
      a.chatter_switches_ = chatter_switches_;
      a.chatter_window_ = chatter_window_;
      a.edges_by_mode_.resize(static_cast<std::size_t>(n));
      for (int i = 0; i < static_cast<int>(edges_.size()); ++i)
        a.edges_by_mode_[static_cast<std::size_t>(edges_[static_cast<std::size_t>(i)].from)]
            .push_back(i);
      return a;
    }

   private:
    std::vector<Mode> modes_;
    std::vector<Edge> edges_;
    int initial_{0};
    int chatter_switches_{8};
    double chatter_window_{1.0};
  };

  /// A fresh state in the initial mode with the given memory.
  State initial_state(Memory memory = {}) const {
    State s;
    s.mode = initial_;
    s.memory = std::move(memory);
    return s;
  }

  /// Steps 1-2 of the step order: at most one guarded transition at time `t`, after the mode was
  /// held for `dt` more seconds. Returns the transition taken, if any.
  std::optional<Transition> step(const Input& in, State& s, double t, double dt) const {
    s.time_in_mode += dt;
    for (int i : edges_by_mode_[static_cast<std::size_t>(s.mode)]) {
      const Edge& e = edges_[static_cast<std::size_t>(i)];
      if (s.time_in_mode + 1e-12 < e.min_dwell) continue;
      if (!e.guard(in, s.memory)) continue;
      if (e.reset) e.reset(in, s.memory);
      const Transition tr{t, s.mode, e.to, i};
      s.mode = e.to;
      s.time_in_mode = 0.0;
      ++s.switches;
      s.chatter.record(t, chatter_switches_, chatter_window_);
      return tr;
    }
    return std::nullopt;
  }

  /// Step 3: the current mode's flow.
  Output flow(const Input& in, const State& s) const {
    return modes_[static_cast<std::size_t>(s.mode)].flow(in, s.memory);
  }

  bool is_terminal(const State& s) const {
    return modes_[static_cast<std::size_t>(s.mode)].terminal;
  }
  const std::vector<Mode>& modes() const { return modes_; }
  const std::vector<Edge>& edges() const { return edges_; }
  int mode_count() const { return static_cast<int>(modes_.size()); }
  /// Index of the mode called `name`, or -1.
  int find_mode(const std::string& name) const {
    for (int i = 0; i < mode_count(); ++i)
      if (modes_[static_cast<std::size_t>(i)].name == name) return i;
    return -1;
  }

 private:
  HybridAutomaton() = default;
  std::vector<Mode> modes_;
  std::vector<Edge> edges_;
  std::vector<std::vector<int>> edges_by_mode_;
  int initial_{0};
  int chatter_switches_{8};
  double chatter_window_{1.0};
};

}  // namespace floornav
