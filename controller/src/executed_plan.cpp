#include "controller/executed_plan.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iterator>

#include "planner/output_file.hpp"
#include "planner/plan_io.hpp"

namespace controller {

ExecutedPlan::~ExecutedPlan()
{
  if (spill_path_.empty()) return;
  spill_.close();
  std::remove(spill_path_.c_str());
}

void ExecutedPlan::start(const planner::Config& c0)
{
  kept_ = {c0};
  first_ = 0;
}

void ExecutedPlan::bound(size_t keep, std::function<void(const planner::Config&)> on_final, const planner::Graph* g,
                         const std::string& spill_path)
{
  if (!spill_path_.empty()) std::remove(spill_path_.c_str());  // an earlier run's
  bounded_ = true;
  keep_ = keep;
  on_final_ = std::move(on_final);
  g_ = g;
  spill_path_ = spill_path;
  if (!spill_path_.empty()) spill_.open(spill_path_, std::ios::trunc);
}

void ExecutedPlan::settle(size_t t)
{
  if (!bounded_ || t < first_ + 2 * keep_) return;  // in batches of `keep`: amortised O(1)
  const size_t drop = t - keep_ - first_;
  const auto end = kept_.begin() + static_cast<std::ptrdiff_t>(drop);
  const std::vector<planner::Config> out(std::make_move_iterator(kept_.begin()), std::make_move_iterator(end));
  for (const planner::Config& c : out)
    if (on_final_) on_final_(c);
  if (spill_.is_open() && g_) planner::write_plan_steps(spill_, *g_, out, first_);
  kept_.erase(kept_.begin(), end);
  first_ += drop;
}

void ExecutedPlan::copy_spilled(std::ostream& out)
{
  if (spill_path_.empty()) return;
  spill_.close();
  const bool wrote = !spill_.fail();
  std::ifstream in(spill_path_, std::ios::binary);
  if (!wrote || !in) throw planner::OutputError("cannot write '" + spill_path_ + "': " + std::strerror(errno));
  if (first_ > 0) out << in.rdbuf();
  in.close();
  std::remove(spill_path_.c_str());
  spill_path_.clear();
}

}  // namespace controller
