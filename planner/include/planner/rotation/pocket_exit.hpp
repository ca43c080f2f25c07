#pragma once
// PocketExit: the pocket exit rule for the rotation solvers that rank cells (pibt-rot, and
// wppl through its rollouts): while a robot stands in a dead-end pocket (the task layer's
// labels, RealtimePlanner::set_pockets) with its goal outside it, nobody moves deeper into
// that pocket (to a cell farther from its mouth), the leaver included.
//
// Why: a station at the end of a one-wide stub. Robots bound for it follow the holder in and
// face the station; the holder's next goal is outside. A cell robot backs out in one move, a
// robot with a heading needs a half turn first (three actions to leave), and the line behind
// it (the stub, then the crowd on the cross aisle at its mouth) must do the same in the same
// steps, so the holder never gets out: large_warehouse_lifelong (200 AGVs, 3-cell station
// stubs), grid twin, pibt-rot+arrows 194 errands in the first 1000 steps, 30 in the last
// (session 37, docs/twin_bench.md). With the rule the next robots wait at the mouth, where a
// quarter turn takes them out of the holder's way, if the holder plans first: the robots
// at the mouth are older (its priority restarted with its new goal), and with the exit rule
// alone they never yield (pibt-rot: 0.0204 errands/step, a deadlock). So a leaver whose way
// out is taken plans first (first()). epibt applies the same marks and blocks() to its
// operations (EpibtOptions::pocket_exit, session 36; its leavers_first ranks every leaving()
// robot first, session 37).
#include <vector>

#include "planner/config.hpp"
#include "planner/graph.hpp"

namespace planner {

class PocketExit {
 public:
  // `pocket`: per vertex its pocket's label, -1 outside (empty: no pockets, the rule is off).
  void set(const Graph& g, std::vector<Vertex> pocket);
  // Marks the pockets that hold a robot whose goal is outside them (call once per step).
  void mark(const Config& current, const Config& goals);
  // Is the move from `from` to `to` deeper into a marked pocket?
  bool blocks(Vertex from, Vertex to) const
  {
    if (leaving_.empty() || from == to) return false;
    const Vertex p = pocket_[to];
    return p >= 0 && leaving_[p] && depth_[to] > (pocket_[from] == p ? depth_[from] : 0);
  }
  bool any() const { return !leaving_list_.empty(); }
  // Leavers first: must a robot at `at` with goal `goal` leave a pocket at least two cells
  // deep whose way out is taken (another robot in it, or one on a cell at its mouth, at the
  // last mark())? Such a robot plans first (RotationPibt; epibt ranks every leaver first).
  // Why only those: on MR23-I-08 (random map, 800 robots, many dead ends around task cells)
  // every leaver first cost pibt-rot 29 % (1.481 -> 1.057 errands/step); one-cell pockets
  // are the dead-end boost's already, and a leaver with a free way needs no help.
  bool first(Vertex at, Vertex goal) const
  {
    if (!leaving(at, goal)) return false;
    const Vertex p = pocket_[at];
    return maxd_[p] >= 2 && crowded_[p];
  }
  // Must a robot at `at` with goal `goal` leave its pocket?
  bool leaving(Vertex at, Vertex goal) const { return !pocket_.empty() && pocket_[at] >= 0 && pocket_[goal] != pocket_[at]; }

 private:
  std::vector<Vertex> pocket_;   // vertex -> pocket label, -1
  std::vector<int> depth_;       // pocket cell -> moves from its mouth (1 next to it); 0 outside
  std::vector<char> leaving_;    // label -> a robot in it has its goal outside (this step)
  std::vector<Vertex> leaving_list_;
  std::vector<int> maxd_;        // label -> its deepest cell's depth
  std::vector<std::pair<Vertex, Vertex>> mouths_;  // (label, an outside cell next to the pocket)
  std::vector<int> count_;       // label -> robots in the pocket (last mark(), marked pockets only)
  std::vector<char> crowded_;    // label -> count_ >= 2 or a mouth cell taken (last mark())
};

}  // namespace planner
