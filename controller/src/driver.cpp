#include "controller/driver.hpp"

#include <algorithm>
#include <cmath>

#include "controller/sumo_error.hpp"
#include "planner/heading.hpp"

namespace controller {

namespace {
// What bounds an AGV's speed this step (before_step).
enum class Why : uint8_t { None, Held, Cruise, Follow, End, Lane };
// Distance left to the end of the agent's last running (released) move.
double left_to_drive(const std::vector<double>& dist, double done)
{
  double r = -done;
  for (double d : dist) r += d;
  return r;
}
}  // namespace

const char* DriveStats::split_name(int k)
{
  static const char* names[kSplitCount] = {
      "cruise",          "accel",          "follow",         "end_dependency", "end_rest",     "end_last",
      "lane",            "gap_stand",      "finish_wait",    "leader_arriving", "leader_waiting", "leader_rule",
      "leader_delayed",  "leader_strict",  "own_group",      "start_rule",     "turn",         "delay",
      "no_action_goal",  "no_action"};
  return names[k];
}

double stop_speed(double room, double decel, double dt)
{
  if (room <= 0) return 0;
  if (!(room < 1e9)) return INFINITY;  // nothing ahead to stop for
  // From speed v in ((n-1) decel dt, n decel dt] braking takes n steps and covers
  // dt (n v - decel dt n (n-1) / 2); from n decel dt that is b n (n+1) / 2, b = decel dt^2.
  const double b = decel * dt * dt;
  long n = std::max(1L, static_cast<long>(std::ceil((std::sqrt(1 + 8 * room / b) - 1) / 2)));
  while (n > 1 && b * (n - 1) * n / 2 >= room) --n;  // rounding at the boundaries
  while (b * n * (n + 1) / 2 < room) ++n;
  return (room / dt + decel * dt * n * (n - 1) / 2) / n;
}

double reach_speed(double room, double limit, double decel, double dt)
{
  // Braking from v in whole steps drives v, v - decel dt, ...; every step driven faster
  // than `limit` must end within `room` (the step that crosses the boundary is <= limit).
  auto fits = [&](double v) {
    double d = 0;
    for (double u = v; u > limit + 1e-12; u -= decel * dt) d += u * dt;
    return d <= room;
  };
  if (room <= 0) return limit;
  double lo = limit, hi = limit + 1.0;
  while (fits(hi)) lo = hi, hi += 2 * (hi - limit);
  for (int k = 0; k < 50; ++k) {
    const double mid = (lo + hi) / 2;
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

double Driver::lane_cap(int i) const
{
  const Agv& g = agv_[i];
  double cap = cmd_.lane_speed(g.lane);  // the lane the front is on
  double start = -g.done;                // distance from the front to the start of run[k]
  for (size_t k = 0; k < g.run.size(); ++k) {
    // During move k the front is on its target lane (a move out of a junction cell turns
    // onto it at once): already there, keep to its limit; ahead, be able to slow to it.
    const double w = cmd_.lane_speed(g.target[k].lane);
    // A front exactly at a lane's end is moved onto the next lane by SUMO: a nanometre short.
    cap = std::min(cap, start <= 1e-9 ? w : reach_speed(start - 1e-9, w, p_.decel, p_.dt));
    start += g.dist[k];
  }
  return cap;
}

Driver::Driver(Commander& cmd, executor::Adg& adg, const executor::DelayModel& delays, const DriveParams& p)
    : cmd_(cmd), adg_(adg), delays_(delays), p_(p), agv_(adg.num_agents()), waiting_start_(adg.num_agents(), 0),
      gated_(adg.num_agents(), -1)
{
  split_pending_.resize(adg.num_agents());
  noact_run_.assign(adg.num_agents(), 0);
  for (auto& c : split_pending_) c.fill(0);
  for (int i = 0; i < adg.num_agents(); ++i) agv_[i].lane = cmd_.pose(i).lane;
}

void Driver::begin(int id)
{
  const executor::Action& a = adg_.action(id);
  Agv& g = agv_[a.agent];
  g.run.push_back(id);
  gated_[a.agent] = -1;
  const gridify::SumoPose from = cmd_.pose(a.agent);
  g.dist.push_back(cmd_.begin_move(a.agent, a.from, a.to));
  g.target.push_back(cmd_.pose(a.agent));
  // A turn in place flips the lane first: that move starts on its target lane.
  const gridify::SumoPose& to = g.target.back();
  const bool turned = from.lane != to.lane && cmd_.needs_rest(a.agent, a.from, a.to);
  g.from.push_back(turned ? gridify::SumoPose{to.lane, to.pos - g.dist.back()} : from);
  st_.followed += a.handover >= 0 && adg_.action(a.handover).state != executor::State::Done &&
                  !(a.group >= 0 && adg_.action(a.handover).group == a.group);
}

bool Driver::zone_free(int i, planner::Vertex from, planner::Vertex to)
{
  if (!zone_of_) return true;
  const std::vector<std::vector<int>>& zo = *zone_of_;
  auto in = [&](planner::Vertex v, int z) { return std::find(zo[v].begin(), zo[v].end(), z) != zo[v].end(); };
  for (int z : zo[to]) {
    if (in(from, z)) continue;  // already inside: it holds the zone
    for (int j = 0; j < adg_.num_agents(); ++j) {
      if (j == i) continue;
      bool holds = in(adg_.at(j), z);
      for (int id : agv_[j].run) holds = holds || in(adg_.action(id).to, z);
      if (holds) {
        gated_[i] = z;
        return false;
      }
    }
  }
  return true;
}

bool Driver::faces(int i, int id)
{
  if (!cmd_.headings()) return true;
  Agv& g = agv_[i];
  if (g.turning) return false;
  const executor::Action& a = adg_.action(id);
  const int want = cmd_.move_heading(a.from, a.to);
  if (want == cmd_.heading(i)) return true;
  // At rest (reported by SUMO) on its cell: a quarter turn, then the next if need be.
  if (g.rest_steps > 0) {
    cmd_.begin_turn(i, planner::turn_toward(cmd_.heading(i), want), delays_.factor(i));  // slowed: slower
    g.turning = true;
  }
  return false;
}

std::vector<uint8_t> Driver::stopped() const
{
  std::vector<uint8_t> out(agv_.size(), 0);
  for (size_t i = 0; i < agv_.size(); ++i) out[i] = delays_.stopped(static_cast<int>(i));
  return out;
}

bool Driver::start_moves(int i, bool count)
{
  Agv& g = agv_[i];
  const size_t running = g.run.size();
  {
    const bool stopped = delays_.stopped(i);
    if (count) st_.delay_steps += stopped, waiting_start_[i] = false;
    if (stopped) return false;
    if (g.run.empty()) {
      const int id = adg_.next_action(i);
      if (id < 0) return false;
      // Headings: face the move first -- also while it waits for its release: the turn
      // keeps the AGV on its own cell.
      if (!faces(i, id)) {
        if (count) st_.turn_steps += g.turning;
        return false;
      }
      const bool follow = p_.follow && adg_.action(id).group < 0;  // rotations: strict
      auto ready = [&] { return follow ? adg_.released_following(id) : adg_.released(id); };
      if (!ready() && p_.switch_passages > 0 && adg_.try_switch(id, {p_.switch_passages})) ++st_.switches;
      if (!ready()) {
        if (count) ++st_.dependency_waits;
        return false;
      }
      const std::vector<int> group = adg_.group_of(id);
      bool go = true;
      for (int m : group) {
        const int j = adg_.action(m).agent;
        go = go && !delays_.stopped(j) && agv_[j].run.empty() && (j == i || faces(j, m)) &&
             (!cmd_.needs_rest(j, adg_.action(m).from, adg_.action(m).to) || agv_[j].rest_steps > 0) &&
             zone_free(j, adg_.action(m).from, adg_.action(m).to);
      }
      waiting_start_[i] = !go;
      if (!go) return false;
      ++st_.starts_from_rest;
      if (noact_run_[i] > 0) ++st_.starved_starts, st_.starved_steps += noact_run_[i];
      noact_run_[i] = 0;
      if (follow)
        adg_.start_following(id);
      else
        adg_.start(id);
      for (int m : group) begin(m);
    }
    // Continuous motion: chain the following actions already released (a prefix of the
    // agent's remaining ones), so the AGV drives through their cells and brakes only for
    // the end of the last one (or a leader's back, below). Only as far as it could need to
    // brake from full speed (plus one step's travel): that keeps cruising speed, and cells
    // further ahead stay free for the others -- a stuck AGV's replan (stuck_replan.hpp)
    // keeps every cell of its running moves.
    const double reach = p_.max_speed * p_.max_speed / (2 * p_.decel) + p_.max_speed * p_.dt;
    while (!g.run.empty() && left_to_drive(g.dist, g.done) < reach) {
      const int id = adg_.undone(i, g.run.size());
      if (id < 0) break;
      auto ready = [&] { return p_.follow ? adg_.chainable_following(id) : adg_.chainable(id); };
      if (!ready() && p_.switch_passages > 0 && adg_.try_switch(id, {p_.switch_passages})) ++st_.switches;
      if (!ready()) break;
      const executor::Action& a = adg_.action(id);
      if (cmd_.needs_rest(i, a.from, a.to)) break;
      if (!zone_free(i, a.from, a.to)) break;
      if (cmd_.headings() && cmd_.move_heading(a.from, a.to) != cmd_.heading(i)) break;  // a turn: at rest
      if (cmd_.changes_lane(i, a.from, a.to) && g.lane != cmd_.pose(i).lane) break;
      // Following: the new leader's back may pull the stopping point back (a leader chained
      // toward the cell may not be there yet) -- only as far as braking from the AGV's
      // speed still stops short of it.
      if (p_.follow) {
        const double end = left_to_drive(g.dist, g.done) + (p_.exact_chain ? cmd_.move_length(i, a.from, a.to) : 0);
        const double to = std::min(room(i), end + gap(a, end));
        if (stop_speed(to - 1e-9, p_.decel, p_.dt) < g.v - p_.decel * p_.dt) break;
      }
      if (p_.follow)
        adg_.start_chained_following(id);
      else
        adg_.start_chained(id);
      begin(id);
      ++st_.chained;
    }
  }
  return g.run.size() != running;
}

void Driver::before_step()
{
  const int n = adg_.num_agents();
  // Starts in passes: a move released by a start earlier in this step (a leader that began
  // leaving the cell) starts in the same step, not one SUMO step later per AGV of a queue.
  std::fill(gated_.begin(), gated_.end(), -1);
  for (int i = 0; i < n; ++i) start_moves(i, true);
  for (bool more = p_.same_step_starts; more;) {
    more = false;
    for (int i = 0; i < n; ++i) more = start_moves(i, false) || more;
  }
  std::vector<double> speed(n, 0.0);
  rem_.assign(n, 0.0);
  std::vector<Why> why(n, Why::None);
  for (int i = 0; i < n; ++i) {
    Agv& g = agv_[i];
    double rem = left_to_drive(g.dist, g.done);
    double v = 0;
    if (rem > 1e-12) {
      // A rotation (group) drives as one: at its slowest member's speed, and every
      // member brakes when one is stopped.
      bool held = delays_.stopped(i);
      double factor = delays_.factor(i);
      if (adg_.action(g.run.front()).group >= 0)
        for (int m : adg_.group_of(g.run.front())) {
          const int j = adg_.action(m).agent;
          held = held || delays_.stopped(j);
          factor = std::min(factor, delays_.factor(j));
        }
      const double end = rem;
      if (p_.follow) rem = std::min(rem, room(i));
      // Land a nanometre short: SUMO moves a front exactly at a lane's end onto the next
      // edge of its route, which would leave the junction cell's pose.
      const double cruise = p_.max_speed * factor, stop = stop_speed(rem - 1e-9, p_.decel, p_.dt);
      if (!held) v = std::min(cruise, stop);
      why[i] = held ? Why::Held : v >= cruise ? Why::Cruise : rem < end ? Why::Follow : Why::End;
      if (p_.lane_speeds) {
        const double cap = lane_cap(i);
        if (cap < v) v = cap, why[i] = Why::Lane;
      }
    }
    speed[i] = v;
    rem_[i] = rem;
  }
  // ... and its members arrive together: each covers the same fraction of its move as the
  // member with the longest move (moves into a junction cell are shorter than a spacing),
  // so none arrives on a cell another member's body has not yet left.
  for (int i = 0; i < n; ++i) {
    const Agv& g = agv_[i];
    if (g.run.empty() || adg_.action(g.run.front()).group < 0) continue;
    int lead = i;
    for (int m : adg_.group_of(g.run.front())) {
      const int j = adg_.action(m).agent;
      if (agv_[j].dist.front() > agv_[lead].dist.front()) lead = j;
    }
    if (lead != i) speed[i] = speed[lead] * g.dist.front() / agv_[lead].dist.front();
    if (p_.lane_speeds && lead != i)  // a member on a slower lane slows the group (scaled as above)
      speed[i] = std::min(speed[i], lane_cap(i));
  }
  for (int i = 0; i < n; ++i) {
    Agv& g = agv_[i];
    // Feasible from the speed SUMO reports: at most accel / decel in one step. The law
    // above keeps the stopping point reachable, so the lower bound never pushes an AGV
    // past it (overshoot counts it if it ever did).
    const double lo = std::max(0.0, g.v - p_.decel * p_.dt), hi = g.v + p_.accel * p_.dt;
    double v = std::clamp(speed[i], lo, std::max(lo, hi));
    if (why[i] != Why::None && why[i] != Why::Held) {
      DriveStats::Time& t = st_.time;
      ++(speed[i] > hi + 1e-12 ? t.accel : why[i] == Why::Cruise ? t.cruise : why[i] == Why::Follow ? t.follow
                                          : why[i] == Why::Lane ? t.lane : t.end);
    } else if (g.run.empty() && !delays_.stopped(i) && adg_.next_action(i) >= 0 && waiting_start_[i]) {
      ++st_.time.start_wait;
    }
    const int cat = why[i] != Why::None && why[i] != Why::Held && speed[i] > hi + 1e-12
                        ? static_cast<int>(DriveStats::kAccel)
                        : split_of(i, v, static_cast<int>(why[i]));
    ++split_pending_[i][cat];
    if (!trace_.empty()) trace_[i].push_back(static_cast<char>('a' + cat));
    noact_run_[i] = cat == DriveStats::kNoAction ? noact_run_[i] + 1 : 0;
    if (rem_[i] > 1e-12 && v * p_.dt > rem_[i] - 1e-9) v = std::max(lo, (rem_[i] - 1e-9) / p_.dt);
    if (rem_[i] <= 1e-12) v = lo;
    st_.overshoot = std::max(st_.overshoot, v * p_.dt - std::max(0.0, rem_[i]));
    // SUMO keeps a speed until it is set again; if it drove something else than our last
    // command, somebody else set it: set ours again.
    cmd_.drive(i, v, std::fabs(g.cmd - g.v) > 1e-9);
    g.cmd = v;
  }
}

int Driver::split_of(int i, double v, int why_int) const
{
  using S = DriveStats;
  const Agv& g = agv_[i];
  const Why why = static_cast<Why>(why_int);
  if (why == Why::Held) return S::kDelay;
  if (why != Why::None) {
    if (why == Why::Follow) return v <= 1e-12 && g.v <= 1e-12 ? S::kGapStand : S::kFollow;
    if (why == Why::Cruise) return S::kCruise;
    if (why == Why::Lane) return S::kLane;
    // Braking for the end of its released moves: why the next one is not chained.
    const int id = adg_.undone(i, g.run.size());
    if (id < 0) return S::kEndLast;
    const executor::Action& a = adg_.action(id);
    if (cmd_.needs_rest(i, a.from, a.to) || (cmd_.headings() && cmd_.move_heading(a.from, a.to) != cmd_.heading(i)) ||
        (cmd_.changes_lane(i, a.from, a.to) && g.lane != cmd_.pose(i).lane))
      return S::kEndRest;
    return S::kEndDep;
  }
  if (!g.run.empty()) return S::kFinishWait;  // on its target, completion waits (ADG order)
  if (delays_.stopped(i)) return S::kDelay;
  const int id = adg_.next_action(i);
  if (id < 0) return goal_of_ && goal_of_(i) == adg_.at(i) ? S::kNoActionGoal : S::kNoAction;
  if (g.turning) return S::kTurn;
  if (waiting_start_[i]) return S::kStartRule;
  const executor::Action& a = adg_.action(id);
  if (a.prev >= 0 && adg_.action(a.prev).group >= 0 && !adg_.group_done(adg_.action(a.prev).group))
    return S::kOwnGroup;
  if (a.handover < 0) return S::kLeaderStrict;  // a group member waiting for the others' dependencies
  const executor::Action& h = adg_.action(a.handover);
  if (h.state != executor::State::Pending) return S::kLeaderStrict;
  if (delays_.stopped(h.agent)) return S::kLeaderDelayed;
  if (h.prev >= 0 && adg_.action(h.prev).state != executor::State::Done) return S::kLeaderArriving;
  if (adg_.released_following(a.handover) || adg_.released(a.handover)) return S::kLeaderRule;
  return S::kLeaderWaiting;
}

double Driver::ahead(int agent, int action) const
{
  const Agv& g = agv_[agent];
  double before = 0;  // path distance from the start of run[0] to the start of `action`
  for (size_t k = 0; k < g.run.size(); ++k) {
    if (g.run[k] == action) return g.done - before;
    before += g.dist[k];
  }
  return -INFINITY;  // not running: cannot happen for a started hand-over
}

double Driver::gap(const executor::Action& a, double end) const
{
  if (a.handover < 0) return INFINITY;
  const executor::Action& h = adg_.action(a.handover);
  if (h.state == executor::State::Done || (a.group >= 0 && h.group == a.group)) return INFINITY;
  // The previous occupant of a.to is leaving it: keep the front `margin` behind its back
  // (measured as if its path went straight on through a.to: exact for a train, and at a
  // junction conservative); without the gap hand-over also short of a.to until it has
  // arrived (ADG order: its completion waits for the leader's either way, after_step).
  const double now = ahead(h.agent, a.handover) - p_.length - p_.margin;
  // Relative braking (DriveParams::sure_travel): the leader cannot stop before covering
  // its sure travel -- every command is >= v - decel dt, and an outside stop brakes no harder
  // (a body's decel is physics) -- so the follower may count on that much: trains flow at
  // full speed one cell apart instead of each braking to a stop behind a moving leader.
  // Both braking from now at the same decel, the gap shrinks at a constant rate until one
  // stops: its least is now or at the end. So only a follower already `margin` behind the
  // leader's back (end + now >= 0) may count on it; one that is not (a leader reaching v from
  // another side, its body projected straight on) waits, as without it.
  if (!p_.sure_travel || end + now < 0) return p_.gap_handover ? now : std::min(now, -1e-6);
  const double front = ahead(h.agent, a.handover) + sure_travel(h.agent);
  // ... and a leader sure to arrive (its front will reach its target) is as good as arrived:
  // a.to may be entered (to 1e-6 m: a stopping point is aimed a nanometre short, and its
  // sure travel is a sum of steps). Its completion still waits for the leader's (after_step).
  // With the gap hand-over (DriveParams::gap_handover) the body gap alone: a front at a.to
  // already puts the leader's front length + margin past it, its body off a.to's line.
  const double arrive =
      p_.gap_handover || front >= handover_dist(h.agent, a.handover) - 1e-6 ? INFINITY : -1e-6;
  return std::min(front - p_.length - p_.margin, arrive);
}

double Driver::sure_travel(int i) const
{
  // The leader braking at leader_decel >= the follower's decel: the gap only shrinks until
  // the follower stops, so the stopping points alone decide.
  const double b = std::max(p_.decel, p_.leader_decel) * p_.dt;
  double d = 0;
  for (double u = agv_[i].v - b; u > 1e-12; u -= b) d += u * p_.dt;
  return d;
}

double Driver::handover_dist(int agent, int action) const
{
  const Agv& g = agv_[agent];
  for (size_t k = 0; k < g.run.size(); ++k)
    if (g.run[k] == action) return g.dist[k];
  return INFINITY;
}

double Driver::room(int i) const
{
  const Agv& g = agv_[i];
  double room = INFINITY, end = -g.done;  // end: distance from the front to the end of run[k]
  for (size_t k = 0; k < g.run.size(); ++k) {
    end += g.dist[k];
    room = std::min(room, end + gap(adg_.action(g.run[k]), end));
  }
  return room;
}

double Driver::progress(int i, const VehiclePose& p) const
{
  const Agv& g = agv_[i];
  constexpr double tol = 1e-6;
  double before = 0;  // path distance from the start of run[0] to the start of run[k]
  for (size_t k = 0; k < g.run.size(); ++k) {
    const gridify::SumoPose &t = g.target[k], &f = g.from[k];
    if (p.lane == t.lane && p.pos <= t.pos + tol && p.pos >= t.pos - g.dist[k] - tol)
      return before + g.dist[k] - (t.pos - p.pos);
    if (p.lane == f.lane && p.pos >= f.pos - tol && p.pos <= f.pos + g.dist[k] + tol) return before + p.pos - f.pos;
    before += g.dist[k];
  }
  return NAN;
}

void Driver::after_step(const std::vector<VehiclePose>& poses)
{
  for (int i = 0; i < adg_.num_agents(); ++i) {
    Agv& g = agv_[i];
    g.lane = poses[i].lane;
    g.v = poses[i].speed;
    if (g.run.empty()) {
      g.rest_steps = g.v > 0 ? 0 : g.rest_steps + 1;
      // A turn is done once its animation has run and SUMO shows the AGV at the new
      // heading's angle (closed loop; else orient() sets it again next step).
      if (g.turning && !cmd_.turning(i)) {
        const double off = std::remainder(cmd_.angle(i) - Commander::sumo_angle(cmd_.heading(i)), 360.0);
        g.turning = std::fabs(off) > 1e-3;
      }
      continue;
    }
    // Progress as SUMO reports it, never the speed we asked for. Off every lane of its
    // moves (cannot happen while SUMO follows its route): no progress; Safety reports it.
    const double at = progress(i, poses[i]);
    if (!std::isnan(at)) g.done = std::max(0.0, at);
  }
  // Arrivals in ADG order: an action into v completes only after v's previous occupant has
  // arrived elsewhere (may_finish). A follower that reached v first (sure_travel lets it
  // enter behind a leader sure to arrive) completes once the leader has: passes until
  // nothing changes (hand-overs form a DAG, so the passes end).
  for (bool more = true; more;) {
    more = false;
    for (int i = 0; i < adg_.num_agents(); ++i) more = arrive(i, poses[i]) || more;
  }
}

bool Driver::group_arrived(int id) const
{
  // A rotation group's members finish together: one stopped mid-move (a delay) keeps the
  // others' moves running although their fronts are on their targets. Else a stuck replan
  // (Run::replan) cuts the stopped member before the group's step and a finished member
  // after it -- two AGVs on one cell in the cut plan (huge warehouse, seed 3, p = 0.01).
  if (adg_.action(id).group < 0) return true;
  for (int m : adg_.group_of(id)) {
    const executor::Action& b = adg_.action(m);
    if (m == id || b.state == executor::State::Done) continue;
    const Agv& h = agv_[b.agent];
    if (h.run.empty() || h.run.front() != m || h.done < h.dist.front() - 2e-9) return false;
  }
  return true;
}

bool Driver::arrive(int i, const VehiclePose& pose)
{
  Agv& g = agv_[i];
  bool any = false;
  {
    while (!g.run.empty() && g.done >= g.dist.front() - 2e-9 && adg_.may_finish(g.run.front()) &&
           group_arrived(g.run.front())) {
      any = true;
      g.done = std::max(0.0, g.done - g.dist.front());
      const int id = g.run.front();
      g.run.erase(g.run.begin());
      g.dist.erase(g.dist.begin());
      g.target.erase(g.target.begin());
      g.from.erase(g.from.begin());
      adg_.finish(id);
      for (int k = 0; k < DriveStats::kSplitCount; ++k) st_.split[k] += split_pending_[i][k];
      split_pending_[i].fill(0);
      if (g.run.empty()) {
        // The last target reached: the front must be on the cell.
        const gridify::SumoPose& want = cmd_.pose(i);
        const double err = pose.lane == want.lane ? std::fabs(pose.pos - want.pos) : INFINITY;
        if (err > 1e-6)
          throw ControlError("AGV " + cmd_.ids()[i] + " arrived off its cell: lane " + pose.lane + " pos " +
                             std::to_string(pose.pos) + ", expected " + want.lane + " " + std::to_string(want.pos));
        st_.max_error = std::max(st_.max_error, err);
        g.done = 0;
        g.rest_steps = 0;
      }
    }
  }
  return any;
}

const std::vector<std::vector<planner::Vertex>>& Driver::allowed() const
{
  std::vector<std::vector<planner::Vertex>>& out = allowed_;
  out.resize(agv_.size());
  for (int i = 0; i < static_cast<int>(agv_.size()); ++i) {
    out[i].clear();
    out[i].push_back(adg_.at(i));
    for (int id : agv_[i].run) out[i].push_back(adg_.action(id).to);
  }
  return out;
}

std::vector<int> Driver::groups() const
{
  std::vector<int> out(agv_.size(), -1);
  for (size_t i = 0; i < agv_.size(); ++i) {
    for (int id : agv_[i].run)
      if (adg_.action(id).group >= 0) out[i] = adg_.action(id).group;
    // Arrived first: it stays in the rotation (on its cell) until every member has arrived.
    const int last = adg_.last_done(static_cast<int>(i));
    if (out[i] < 0 && last >= 0 && adg_.action(last).group >= 0 && !adg_.group_done(adg_.action(last).group))
      out[i] = adg_.action(last).group;
  }
  return out;
}

std::string Driver::describe(int i) const
{
  std::string s = "agent " + std::to_string(i) + " at " + std::to_string(adg_.at(i)) + ", running [";
  for (int id : agv_[i].run) {
    const executor::Action& a = adg_.action(id);
    s += " #" + std::to_string(id) + " " + std::to_string(a.from) + "->" + std::to_string(a.to) + " step " +
         std::to_string(a.step) + " group " + std::to_string(a.group) + " handover " + std::to_string(a.handover);
    if (a.handover >= 0) s += adg_.action(a.handover).state == executor::State::Done ? " (done)" : " (not done)";
  }
  return s + " ]";
}

bool Driver::idle() const
{
  for (const Agv& g : agv_)
    if (!g.run.empty()) return false;
  return true;
}

}  // namespace controller
