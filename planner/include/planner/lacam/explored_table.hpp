#pragma once
// ExploredTable: configuration -> HNode, the "Explored" set of LaCAM. Open addressing with
// linear probing over HNode pointers; the key is the node's own configuration, so nothing
// is copied on insert.
#include <cstdint>
#include <vector>

#include "planner/lacam/hnode.hpp"

namespace planner {

class ExploredTable {
 public:
  explicit ExploredTable(int num_agents = 0) : n_(num_agents) {}
  void set_num_agents(int n) { n_ = n; }

  HNode* find(const Vertex* c, uint64_t hash) const;
  void insert(HNode* node);  // node->hash must be set; the configuration must be new
  void clear();
  size_t size() const { return count_; }
  size_t bytes_reserved() const { return slots_.capacity() * sizeof(HNode*) + filled_.capacity() * sizeof(uint32_t); }

 private:
  void grow();
  int n_;
  std::vector<HNode*> slots_ = std::vector<HNode*>(1024, nullptr);
  std::vector<uint32_t> filled_;  // occupied slot indices, so clear() is O(size)
  size_t count_ = 0;
};

}  // namespace planner
