#include "planner/lacam/explored_table.hpp"

#include "planner/config.hpp"

namespace planner {

HNode* ExploredTable::find(const Vertex* c, uint64_t hash) const
{
  const size_t mask = slots_.size() - 1;
  for (size_t k = hash & mask;; k = (k + 1) & mask) {
    HNode* h = slots_[k];
    if (!h) return nullptr;
    if (h->hash == hash && config_equal(h->C, c, n_)) return h;
  }
}

void ExploredTable::insert(HNode* node)
{
  if (2 * (count_ + 1) > slots_.size()) grow();
  const size_t mask = slots_.size() - 1;
  size_t k = node->hash & mask;
  while (slots_[k]) k = (k + 1) & mask;
  slots_[k] = node;
  filled_.push_back(static_cast<uint32_t>(k));
  ++count_;
}

void ExploredTable::grow()
{
  std::vector<HNode*> old(slots_.size() * 2, nullptr);
  old.swap(slots_);
  filled_.clear();
  const size_t mask = slots_.size() - 1;
  for (HNode* h : old) {
    if (!h) continue;
    size_t k = h->hash & mask;
    while (slots_[k]) k = (k + 1) & mask;
    slots_[k] = h;
    filled_.push_back(static_cast<uint32_t>(k));
  }
}

void ExploredTable::clear()
{
  for (uint32_t k : filled_) slots_[k] = nullptr;
  filled_.clear();
  count_ = 0;
}

}  // namespace planner
