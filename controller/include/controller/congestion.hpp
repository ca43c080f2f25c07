#pragma once
// Congestion: where the fleet stood over a run, counted per cell at the end of every tick,
// and its picture (output.congestion: congestion.png beside metrics.json):
//   occupancy  AGV-ticks on the cell (the cell the executor has the AGV on);
//   waiting    AGV-ticks an AGV stood on the cell (its SUMO pose unchanged over the tick)
//              while the cell was not its goal -- the queues, not the parked AGVs.
// The picture draws both over the net at the cells' x/y (gridify keeps them), one panel
// each, with a colour scale and a title naming the config and the net. Written with cairo
// and planner::write_file (a full disk is one OutputError line).
#include <string>
#include <vector>

#include "controller/sumo_backend.hpp"
#include "gridify/cell_map.hpp"
#include "planner/config.hpp"

namespace controller {

class Congestion {
 public:
  explicit Congestion(int cells) : occupancy_(cells, 0), waiting_(cells, 0) {}

  // End of a tick: each AGV's executed cell, its SUMO pose after the tick, its goal during
  // it; `ticks` > 1: a lockstep step stretched over that many ticks (a slowed mover).
  void tick(const planner::Config& at, const std::vector<VehiclePose>& poses, const planner::Config& goals,
            int ticks = 1);

  const std::vector<long long>& occupancy() const { return occupancy_; }
  const std::vector<long long>& waiting() const { return waiting_; }
  long long ticks() const { return ticks_; }

 private:
  std::vector<long long> occupancy_, waiting_;
  std::vector<VehiclePose> last_;  // poses after the previous tick
  long long ticks_ = 0;
};

// The picture's size in pixels: two panels side by side (occupancy left, waiting right).
constexpr int kCongestionWidth = 1200, kCongestionHeight = 640;

struct Pixel {
  double x = 0, y = 0;
};
// Where the centre of cell v is drawn in panel 0 (occupancy) or 1 (waiting).
Pixel congestion_pixel(const gridify::CellMap& map, int panel, planner::Vertex v);

// Draws the counts over the net as a PNG at `path`; `title` heads it. Throws
// planner::OutputError naming the file when it cannot be written.
void write_congestion_png(const std::string& path, const gridify::CellMap& map, const Congestion& c,
                          const std::string& title);

}  // namespace controller
