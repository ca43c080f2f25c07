#include "tasks/lifelong_log.hpp"

#include "tasks/task_pool.hpp"

namespace tasks {

nlohmann::json lifelong_log(const RunInfo& info, const LifelongResult& r)
{
  nlohmann::json j;
  j["actionModel"] = lorr_name(r.action_model);
  j["problem"] = info.problem;
  j["solver"] = info.solver;
  j["mode"] = info.mode;
  j["assigner"] = info.mode == "pool" ? info.assigner : "none";
  j["budgetMs"] = info.budget_ms;
  j["seed"] = info.seed;
  j["teamSize"] = info.team_size;
  j["makespan"] = r.steps;
  j["numTaskFinished"] = r.tasks_finished;
  j["numErrandFinished"] = r.errands_finished;
  const double steps = r.steps > 0 ? static_cast<double>(r.steps) : 1.0;
  j["taskThroughput"] = static_cast<double>(r.tasks_finished) / steps;
  j["errandThroughput"] = static_cast<double>(r.errands_finished) / steps;
  const PlannerTimes pt = summarize(r.planner_ms);
  j["plannerTimeStats"] = {{"mean", pt.mean}, {"p50", pt.p50}, {"p99", pt.p99}, {"max", pt.max}};
  const PlannerTimes es = summarize(r.epoch_start_ms);
  j["epochStartStats"] = {{"mean", es.mean}, {"p50", es.p50}, {"p99", es.p99}, {"max", es.max}};
  const PlannerTimes pc = summarize(r.precompute_ms);
  j["precomputeStats"] = {{"mean", pc.mean}, {"p50", pc.p50}, {"p99", pc.p99}, {"max", pc.max}};
  j["stepsOverBudget"] = r.steps_over_budget;
  const PlannerTimes cpu = summarize(r.planner_cpu_ms);
  j["plannerCpuTimeStats"] = {{"mean", cpu.mean}, {"p50", cpu.p50}, {"p99", cpu.p99}, {"max", cpu.max}};
  j["stepsOverBudgetCpu"] = r.steps_over_budget_cpu;
  const PlannerTimes ecpu = summarize(r.epoch_start_cpu_ms);
  j["epochStartCpuStats"] = {{"mean", ecpu.mean}, {"p50", ecpu.p50}, {"p99", ecpu.p99}, {"max", ecpu.max}};
  j["msPerExpansion"] = r.ms_per_expansion;
  j["msPerFirstExpansion"] = r.ms_per_first_expansion;
  j["searchesSkipped"] = r.searches_skipped;
  j["distTables"] = {{"end", r.dist_tables},
                     {"max", r.dist_tables_max},
                     {"maxMB", r.dist_mb_max},
                     {"queryPops", r.dist_counters.query_pops},
                     {"queryPopsMaxStep", r.query_pops_max},
                     {"precomputePops", r.dist_counters.precompute_pops},
                     {"estimates", r.dist_counters.estimates}};
  nlohmann::json times = nlohmann::json::array();
  for (double ms : r.planner_ms) times.push_back(ms / 1000.0);  // LoRR: seconds
  j["plannerTimes"] = std::move(times);
  j["setupMs"] = r.setup_ms;
  j["taskLayerMs"] = r.task_ms;
  j["wallMs"] = r.wall_ms;
  j["epochs"] = r.epochs;
  // The task layer's counts (lifelong_epochs.hpp), named as in the SUMO controller's
  // metrics.json "lifelong" (errandTicks and stallTicks: add_task_fields).
  j["maxErrandTicks"] = r.counts.max_goal_ticks;
  j["queues"] = {{"maxHeading", r.counts.max_heading}, {"queuedTicks", r.counts.queued_ticks}, {"clearings", r.counts.clearings}, {"jamClearings", r.counts.jam_clearings},
                {"clearingSteps", r.counts.clearing_steps}, {"longestClearing", r.counts.longest_clearing}};
  j["parking"] = {{"idleAtEnd", r.counts.idle}, {"parkedAtEnd", r.counts.parked},
                  {"idleTicks", r.counts.idle_ticks}, {"parkedTicks", r.counts.parked_ticks}};
  if (r.action_model == ActionModel::Rotation) j["windowFullSteps"] = r.window_full;
  j["expansions"] = r.expansions;
  j["numPlannerErrors"] = r.planner_errors;
  if (!r.first_error.empty()) j["firstPlannerError"] = r.first_error;
  nlohmann::json ev = nlohmann::json::array();
  for (const Event& e : r.events) ev.push_back({e.t, e.agent, e.task, e.errand + 1});
  j["events"] = std::move(ev);
  return j;
}

void add_stuck_fields(nlohmann::json& j, const LifelongResult& r)
{
  j["unreachableGoals"] = r.unreachable_goals;
  j["unsolvableEpoch"] = r.unsolvable_epoch;
}

std::string stuck_warning(const LifelongResult& r)
{
  std::string w;
  if (r.unreachable_goals > 0)
    w = std::to_string(r.unreachable_goals) + " agent(s) at the end cannot reach their goal (errand in another component)";
  if (r.unsolvable_epoch)
    w += std::string(w.empty() ? "" : "; ") + "the planner proved the last epoch's goals unsolvable (the agents cannot all reach them)";
  return w.empty() ? w : "warning: " + w + " (" + std::to_string(r.tasks_finished) + " tasks finished)";
}

void add_task_fields(nlohmann::json& j, const TaskManager& tasks)
{
  // The free-flow bound (free_flow.hpp) and the share of it the run reached.
  // Over every errand handed out: the finished ones and those open at the end (free_flow.hpp:
  // finished ones alone are biased to the short); the finished-only figure beside it.
  if (const FreeFlowBound* ff = tasks.free_flow()) {
    const planner::Config open = tasks.open_errands();
    const double bound = ff->errands_per_step(open);
    j["freeFlowBound"] = bound;
    j["freeFlowBoundFinishedOnly"] = ff->errands_per_step();
    j["freeFlowStepsPerErrand"] = ff->steps_per_errand(open);
    if (j.contains("errandThroughput") && bound > 0)
      j["errandThroughputOverFreeFlow"] = j["errandThroughput"].get<double>() / bound;
  }
  // Errand times and stalls (errand_stalls.hpp): K = stallTicks.max.
  if (tasks.stalls()) {
    const ErrandStalls::Summary st = tasks.stall_summary();
    j["errandTicks"] = {{"max", st.max_open}, {"p99", st.p99_open}, {"errands", st.errands}};
    j["stallTicks"] = {{"max", st.max_stall}, {"p99", st.p99_stall}};
  }
  // Batteries (battery.hpp): the same fields as the SUMO controller's metrics.json "battery".
  if (const Battery* b = tasks.battery())
    j["battery"] = {{"capacity_wh", b->options().capacity_wh},
                    {"charging", b->options().charging},
                    {"critical", b->options().critical},
                    {"reserve_margin", b->options().reserve_margin},
                    {"charging_errands", b->errands()},
                    {"dropped_mid_task", tasks.dropped_for_charge()},
                    {"ran_empty", b->ran_empty()},
                    {"charging_share", b->agent_ticks() > 0 ? static_cast<double>(b->charging_ticks()) / b->agent_ticks() : 0.0},
                    {"min_charge", b->min_charge()}};
  if (const auto* pool = dynamic_cast<const TaskPool*>(&tasks)) {
    j["reassign"] = pool->reassigns();
    j["numReassignments"] = pool->reassignments();
  }
}

}  // namespace tasks
