#include "planner/dist_table.hpp"

namespace planner {

DistTable::DistTable(const Graph& g, size_t max_tables) : g_(g), cache_(std::make_shared<DistCache>(g, max_tables)) {}

DistTable::DistTable(const Graph& g, std::shared_ptr<DistCache> cache)
    : g_(g), cache_(cache ? std::move(cache) : std::make_shared<DistCache>(g))
{
}

DistTable::~DistTable() { unpin_all(); }

void DistTable::unpin_all()
{
  for (DistCache::Table* t : agent_table_) cache_->unpin(t);
}

void DistTable::share(std::shared_ptr<DistCache> cache)
{
  Config goals;
  for (DistCache::Table* t : agent_table_) goals.push_back(t->goal);
  unpin_all();
  agent_table_.clear();
  cache_ = std::move(cache);
  if (!goals.empty()) set_goals(goals);
}

void DistTable::set_goals(const Config& goals)
{
  if (goals.size() == agent_table_.size()) {
    // A lifelong epoch: a few goals changed; the others keep their pinned tables (no lookup
    // of every agent's table at every epoch start).
    bool changed = false;
    for (size_t i = 0; i < goals.size(); ++i) {
      if (agent_table_[i]->goal == goals[i]) continue;
      DistCache::Table* t = cache_->table(goals[i]);
      cache_->pin(t);
      cache_->unpin(agent_table_[i]);
      agent_table_[i] = t;
      changed = true;
    }
    if (changed) cache_->trim();
    return;
  }
  // Pin the new tables before unpinning the old, so tables kept across the change stay.
  std::vector<DistCache::Table*> next(goals.size());
  for (size_t i = 0; i < goals.size(); ++i) cache_->pin(next[i] = cache_->table(goals[i]));
  unpin_all();
  agent_table_ = std::move(next);
  cache_->trim();
}

}  // namespace planner
