// Run's display hooks (run.hpp): where each AGV's state is known, it is turned into the
// FleetView's states (fleet_view.hpp holds the colours); the congestion counts and picture.
#include <filesystem>

#include "planner/budget.hpp"
#include "run.hpp"

namespace controller {

bool Run::carrying(int i) const
{
  if (!tm_) return false;
  const tasks::Task* t = tm_->task_of(i);
  return t && t->opened() && !t->finished();
}

void Run::show_lockstep(const planner::Config& cur, const planner::Config& next, bool held)
{
  const auto t0 = planner::Clock::now();
  // The tick's commands are out: movers move, unless a stopped mover holds the whole fleet
  // (then every AGV with a move waits on it). No stuck replan in lockstep.
  const int n = ins_.num_agents();
  states_.resize(n);
  for (int i = 0; i < n; ++i) {
    const bool move = next[i] != cur[i];
    states_[i] = agv_state(false, delays_->stopped(i), held && move, move && !held, carrying(i));
  }
  view_->show(states_);
  view_->add_ms(planner::ms_since(t0));
}

void Run::show_adg(const executor::Adg& adg)
{
  // Before the step, once the Driver has started what it may: the ADG says who drives (a
  // running action), who the executor holds (a pending action not released under its rule:
  // the Driver's dependency wait), and who is about to go (released but not started: a
  // group member not ready, or the step at rest before a turn -- shown as moving, not as a
  // one-step flicker).
  const auto t0 = planner::Clock::now();
  const int n = ins_.num_agents();
  const bool follow = cfg_.run.executor == "adg-follow";
  states_.resize(n);
  for (int i = 0; i < n; ++i) {
    const int id = adg.next_action(i);
    bool waiting = false, moving = false;
    if (id >= 0) {
      if (adg.action(id).state == executor::State::Running)
        moving = true;
      else if ((follow && adg.action(id).group < 0) ? adg.released_following(id) : adg.released(id))
        moving = true;
      else
        waiting = true;
    }
    // Immobile for the planner but its delay over: it drives again (the replan that makes it
    // mobile follows this step), so it shows what it does, not "stuck".
    const bool stopped = delays_->stopped(i);
    const bool stuck = stuck_ && stuck_->immobile()[i] && stopped;
    states_[i] = agv_state(stuck, stopped, waiting, moving, carrying(i));
  }
  view_->show(states_);
  view_->add_ms(planner::ms_since(t0));
}

void Run::show_goals()
{
  const auto t0 = planner::Clock::now();
  view_->goals(goals());
  view_->add_ms(planner::ms_since(t0));
}

void Run::count_tick(const planner::Config& executed, int ticks)
{
  if (!congestion_) return;
  const auto t0 = planner::Clock::now();
  congestion_->tick(executed, last_poses_, goals(), ticks);
  m_.congestion_ms += planner::ms_since(t0);
}

void Run::write_congestion()
{
  if (!congestion_) return;
  const auto t0 = planner::Clock::now();
  namespace fs = std::filesystem;
  const std::string title = "Congestion: " + fs::path(cfg_.path).filename().string() + " on " +
                            fs::path(cfg_.sumo.net).filename().string() + " (" + std::to_string(m_.agents) +
                            " AGVs, " + std::to_string(congestion_->ticks()) + " ticks, " + cfg_.run.executor + ")";
  write_congestion_png(dir_ + "/congestion.png", c_.map_, *congestion_, title);
  m_.congestion_ms += planner::ms_since(t0);
}

}  // namespace controller
