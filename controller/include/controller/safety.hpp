#pragma once
// Safety: the check after every SUMO step that does not trust the executor (nor SUMO's
// collision output, which sees neither opposite lanes nor junctions without internal
// lanes). From the front positions SUMO reports:
//   - every AGV is on a cell or between two adjacent cells of the aisle it drives on, and
//     those cells are ones it may use now (the cell it stands on for the executor and the
//     targets of the moves it executes);
//   - no two AGVs stand on one cell; with `exclusive` (adg executor) no cell is even claimed
//     by two (standing on it, or driving on a segment that ends at it): the ADG promises
//     that, lockstep does not (a follower enters the cell its leader is leaving). The one
//     exception the ADG makes on purpose: the members of a rotation group (a->b->c->a in
//     one step, executor/adg.hpp) start and drive together, each entering the cell the next
//     one is leaving, so two members of one unfinished group may share a cell claim
//     (`group[i]`: the rotation group agent i takes part in, -1 if none; the body check
//     below still keeps them apart on a lane);
//   - following mode (run.executor adg-follow, set_following): cells may be shared by a
//     leader and its follower, so instead of whole-cell claims the bodies are checked around
//     every cell v: each AGV at v, driving toward it or away from it is put on one line
//     through v (front at minus its distance to v, or plus its distance past v) and no two
//     bodies [front - length, front] on that line may intersect -- exact for a train, at a
//     junction stricter than the geometry; and one driving toward v from u and one leaving
//     v are not a head-on pass (the leaver not heading to u). Rotation-group members are
//     exempt as above;
//   - no two bodies [front - length, front] intersect on one lane. (Not across the two
//     lanes of an aisle: they lie side by side, and with the front on the cell centre two
//     AGVs facing each other on adjacent cells have overlapping projections; the cell
//     claims above catch a head-on pass.)
// Each violation is a ControlError naming the AGVs, the lane and the time.
#include <string>
#include <unordered_map>
#include <vector>

#include "controller/sumo_backend.hpp"
#include "gridify/cell_map.hpp"

namespace controller {

struct Claim {
  planner::Vertex a = -1, b = -1;  // on cell a (b == -1) or between cells a and b
};

class Safety {
 public:
  Safety(const gridify::CellMap& map, double length);

  // Where a front at (lane, pos) is in cell terms; a == -1 if the lane is not an aisle lane.
  Claim locate(const std::string& lane, double pos) const;

  // allowed[i]: the cells agent i may claim now. Throws ControlError on a violation.
  void check(const std::vector<VehiclePose>& poses, const std::vector<std::vector<planner::Vertex>>& allowed,
             const std::vector<std::string>& ids, double t, bool exclusive,
             const std::vector<int>& group = {});

  // adg-follow: body-based checks around cells instead of exclusive cell claims.
  void set_following(bool on) { following_ = on; }

  long long checks() const { return checks_; }
  // The two agents of the last cell overlap reported (-1, -1 if none): for diagnostics.
  std::pair<int, int> last_overlap() const { return last_overlap_; }

 private:
  Claim locate(const std::pair<const std::string, std::pair<int, bool>>& lane, double pos) const;
  // Following mode: an AGV's relation to one cell (see above).
  struct Near {
    planner::Vertex cell;
    bool entering;         // driving toward `cell`; else at it or leaving it
    double dist;           // entering: front's distance to cell; else front's distance past it
    planner::Vertex other; // entering: the cell it comes from; leaving: where it goes (-1: at)
    int agent;
  };
  void check_following(const std::vector<VehiclePose>& poses, const std::vector<std::string>& ids,
                       const std::string& when, const std::vector<int>& group);
  struct Body {
    int lane;
    double back, front;
    int agent;
  };

  const gridify::CellMap& map_;
  std::vector<Body> bodies_;
  std::vector<Near> near_;
  bool following_ = false;
  std::vector<std::unordered_map<std::string, std::pair<int, bool>>::const_iterator> lane_cache_;
  double length_;
  std::vector<int> owner_;         // cell -> agent claiming it, valid where stamp_ == epoch_
  std::vector<unsigned> stamp_;
  unsigned epoch_ = 0;
  long long checks_ = 0;
  std::pair<int, int> last_overlap_{-1, -1};
};

}  // namespace controller
