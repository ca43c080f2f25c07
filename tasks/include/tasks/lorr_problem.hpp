#pragma once
// LorrProblem: a League of Robot Runners problem JSON (2023 and 2024 rounds).
//   2023: mapFile, agentFile, teamSize, taskFile, numTasksReveal (int), taskAssignmentStrategy
//   2024: the same plus "version", numTasksReveal is a multiplier of teamSize (1.5)
// File names are relative to the problem file. The step count comes from
// simulation_time.json beside the problem or one directory up (keys "I-04" for
// MR23-I-04.json, "RANDOM-01" for RANDOM-01.json); -1 if there is none.
#include <string>

namespace tasks {

struct LorrProblem {
  std::string path;        // the problem JSON
  std::string name;        // file stem, e.g. "MR23-I-04"
  std::string map_file, agent_file, task_file;  // resolved paths
  int team_size = 0;
  double num_tasks_reveal = 1;
  int year = 2023;         // 2024 when "version" is present
  std::string strategy;    // taskAssignmentStrategy ("" when absent)
  long simulation_time = -1;

  // Default task mode: roundrobin for 2023 roundrobin problems, pool otherwise.
  std::string default_mode() const { return strategy == "roundrobin" ? "roundrobin" : "pool"; }
  // Revealed tasks in pool mode: numTasksReveal x teamSize (2024), at least one per agent.
  int pool_size() const;
};

// Throws planner::InputError ("path: what") on unreadable files and missing/bad fields.
LorrProblem load_lorr_problem(const std::string& path);

}  // namespace tasks
