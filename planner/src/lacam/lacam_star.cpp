// LaCAM* refinement of Lacam (the "LaCAM* refinement" section of lacam.hpp): neighbour
// links, costs, the Dijkstra-style rewrite, the search after the first solution, and the
// re-basing of g when RT-LaCAM reroots.
#include <algorithm>
#include <string>

#include "planner/lacam/lacam.hpp"

namespace planner {

int32_t Lacam::edge_cost(const Vertex* a, const Vertex* b) const
{
  int32_t c = 0;
  for (int i = 0; i < n_; ++i) c += !(a[i] == goals_[i] && b[i] == goals_[i]);
  return c;
}

int32_t Lacam::heuristic(const Vertex* C)
{
  int32_t h = 0;
  for (int i = 0; i < n_; ++i) h += dist_.get(i, C[i]);
  return h;
}

void Lacam::link(HNode* a, HNode* b)
{
  for (const Neighbor* e = a->neighbors; e; e = e->next)
    if (e->to == b) return;
  Neighbor* e = links_.alloc(2);
  e[0] = Neighbor{b, a->neighbors, -1};
  a->neighbors = &e[0];
  e[1] = Neighbor{a, b->neighbors, -1};
  b->neighbors = &e[1];
}

int32_t Lacam::cost(HNode* from, Neighbor* e)
{
  if (e->cost < 0) e->cost = edge_cost(from->C, e->to->C);
  return e->cost;
}

size_t Lacam::bytes_reserved() const
{
  return nodes_.bytes_reserved() + constraints_.bytes_reserved() + configs_.bytes_reserved() +
         orders_.bytes_reserved() + priorities_.bytes_reserved() + links_.bytes_reserved() +
         all_.capacity() * sizeof(HNode*) + open_.capacity() * sizeof(HNode*) + explored_.bytes_reserved();
}

void Lacam::start_refining()
{
  for (HNode* h : all_) h->h = heuristic(h->C);
  rebase(root_, nullptr, true);
  refining_ = true;
}

void Lacam::push_if_promising(HNode* h)
{
  if (h->g + h->h < goal_->g + goal_->h) open_.push_back(h);
}

// One LaCAM* iteration after the first solution (lacam3's loop body with H_goal set).
Status Lacam::refine_expand()
{
  if ((expansions_ & 63) == 0 && bytes_reserved() > opt_.refine_max_mb * (size_t{1} << 20)) {
    refining_ = false;
    refine_capped_ = true;
    return status_;
  }
  const bool all_goals = config_equal(goal_->C, goals_.data(), n_);
  const bool lns = opt_.lns && lns_failures_ < 1000 && all_goals;
  // Engineering LaCAM* guidance (lacam_guide.cpp): SUO until done, then dives.
  const bool guide = all_goals && !goal_test_ &&
                     (dive_ ||
                      (opt_.scatter && !scatter_stopped_ && (!scatter_started_ || !scatter_.done() || scatter_.passes() > passes_dived_)) ||
                      (opt_.dive && dive_failures_ < 1000));
  // SUO's first pass and its dive take every refinement iteration (they matter most), then
  // the guide gets a third of them (half without LNS); the rest as before.
  const bool urgent = opt_.scatter && !first_dive_done_;
  if (guide && (urgent || (guide_iterations_++ % (lns ? 3 : 2)) == 0 || (open_.empty() && !lns))) {
    guide_step();
    return status_;
  }
  if (lns && (open_.empty() || (refine_iterations_++ & 1) == 0)) {
    ++expansions_;
    if (lns_step()) lns_failures_ = 0;
    else ++lns_failures_;
    // An expansion costs O(N) (one PIBT call); an LNS step O(T x N) and more: charge it in
    // expansion-equivalents, so that a budget in expansions bounds the work too.
    units_ = std::max<uint64_t>(1, lns_.work() / static_cast<uint64_t>(std::max(n_, 1)));
    return status_;
  }
  if (open_.empty()) {  // nothing cheaper is reachable by LaCAM*
    refining_ = false;
    return status_;
  }
  ++expansions_;
  HNode* H = open_.back();
  if (H->g >= goal_->g) {  // cannot lead to a cheaper goal
    open_.pop_back();
    return status_;
  }
  if (is_goal(H)) {  // a goal test may accept several configurations
    goal_ = H;
    open_.pop_back();
    return status_;
  }
  Constraint* L = H->pop();
  if (!L) {
    open_.pop_back();
    return status_;
  }
  grow_lowlevel(H, L);
  if (!pibt_.generate(H->C, H->order, L, scratch_.data(), rng_)) return status_;
  const uint64_t hash = config_hash(scratch_.data(), n_);
  if (HNode* known = explored_.find(scratch_.data(), hash)) {
    link(H, known);
    rewrite(H, known);
    push_if_promising(rng_.uniform() < opt_.restart_rate ? root_ : known);
  } else {
    HNode* h = new_node(scratch_.data(), H, hash);
    h->g = H->g + edge_cost(H->C, h->C);
    h->h = heuristic(h->C);
    link(H, h);
    explored_.insert(h);
    push_if_promising(h);
  }
  return status_;
}

bool Lacam::lns_step()
{
  std::vector<Config> p = path(goal_);
  if (!lns_.step(p, goals_, opt_.lns_agents, rng_, deadline_)) return false;
  insert_path(p);
  return true;
}

// The configurations of a valid path from the root become nodes (new ones as children of
// their predecessor) and links; each link is rewired like a revisit, so the goal's g drops
// to the path's cost (or less).
HNode* Lacam::insert_path(const std::vector<Config>& p)
{
  HNode* prev = root_;
  for (size_t t = 1; t < p.size(); ++t) prev = step_to(prev, p[t].data());
  return prev;
}

// Label-correcting Dijkstra from a new link's two ends: a node whose g drops takes the
// relaxing node as parent, and the drop propagates along the links. Costs are positive off
// the goal configuration, so parents stay a tree and the root (g = 0) is never re-parented.
void Lacam::rewrite(HNode* a, HNode* b)
{
  queue_.clear();
  queue_.push_back(a);
  queue_.push_back(b);
  for (size_t k = 0; k < queue_.size(); ++k) {
    HNode* from = queue_[k];
    for (Neighbor* e = from->neighbors; e; e = e->next) {
      HNode* to = e->to;
      const int64_t g = from->g + cost(from, e);
      if (g >= to->g) continue;
      to->g = g;
      to->parent = from;
      queue_.push_back(to);
      if (to->g + to->h < goal_->g + goal_->h) open_.push_back(to);
    }
  }
}

// Recomputes g over the tree below new_root (the whole tree), walking from a node x to its
// tree children (links y with y->parent == x). Along an edge that kept its direction the
// cost is g_old(y) - g_old(x); the reversed edge new_root -> old_root, or every edge when
// `explicit_costs`, is costed explicitly.
void Lacam::rebase(HNode* new_root, HNode* old_root, bool explicit_costs)
{
  walk_.clear();
  walk_.emplace_back(new_root, new_root->g);
  new_root->g = 0;
  while (!walk_.empty()) {
    const auto [x, x_old] = walk_.back();
    walk_.pop_back();
    for (Neighbor* e = x->neighbors; e; e = e->next) {
      HNode* y = e->to;
      if (y->parent != x) continue;
      const int64_t y_old = y->g;
      const bool reversed = x == new_root && y == old_root;
      y->g = x->g + (explicit_costs || reversed ? cost(x, e) : y_old - x_old);
      walk_.emplace_back(y, y_old);
    }
  }
}

bool Lacam::check_costs(std::string* why) const
{
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (!refining_) return fail("costs are kept only while refining");
  if (root_->g != 0) return fail("root g is " + std::to_string(root_->g));
  for (const HNode* s : all_) {
    int64_t sum = 0;
    for (const HNode* h = s; h->parent; h = h->parent) sum += edge_cost(h->parent->C, h->C);
    if (sum != s->g)
      return fail("node " + std::to_string(s->id) + ": g " + std::to_string(s->g) + ", tree path cost " +
                  std::to_string(sum));
  }
  return true;
}

}  // namespace planner
