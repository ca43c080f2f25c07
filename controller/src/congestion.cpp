#include "controller/congestion.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "planner/output_file.hpp"

namespace controller {

void Congestion::tick(const planner::Config& at, const std::vector<VehiclePose>& poses, const planner::Config& goals,
                      int ticks)
{
  for (size_t i = 0; i < at.size(); ++i) {
    occupancy_[at[i]] += ticks;
    // Stood still: SUMO's pose unchanged over the whole tick (exact: scheme S and the
    // Driver land fronts exactly on cells); a turn in place changes the lane, so it moved.
    const bool stood = i < last_.size() && i < poses.size() && poses[i].lane == last_[i].lane &&
                       std::fabs(poses[i].pos - last_[i].pos) < 1e-9;
    if (stood && at[i] != goals[i]) waiting_[at[i]] += ticks;
  }
  last_ = poses;
  ticks_ += ticks;
}

namespace {

constexpr int kTitleH = 44, kPanelTitleH = 26, kScaleH = 62, kMargin = 14;

// The net's box and the scale that fits it into a panel's map area (y up in SUMO, down here).
struct Frame {
  double min_x = 0, max_y = 0, scale = 1, ox = 0, oy = 0;
};

Frame frame(const gridify::CellMap& map)
{
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const gridify::Cell& c : map.cells) {
    x0 = std::min(x0, c.x), x1 = std::max(x1, c.x);
    y0 = std::min(y0, c.y), y1 = std::max(y1, c.y);
  }
  if (map.cells.empty()) x0 = x1 = y0 = y1 = 0;
  const double pad = map.cell_length;  // half a cell each side, so edge cells are whole
  const double aw = kCongestionWidth / 2.0 - 2 * kMargin, ah = kCongestionHeight - kTitleH - kPanelTitleH - kScaleH;
  Frame f;
  f.scale = std::min(aw / (x1 - x0 + pad), ah / (y1 - y0 + pad));
  f.min_x = x0 - pad / 2;
  f.max_y = y1 + pad / 2;
  f.ox = kMargin + (aw - (x1 - x0 + pad) * f.scale) / 2;
  f.oy = kTitleH + kPanelTitleH + (ah - (y1 - y0 + pad) * f.scale) / 2;
  return f;
}

Pixel place(const Frame& f, int panel, double x, double y)
{
  return {panel * kCongestionWidth / 2.0 + f.ox + (x - f.min_x) * f.scale, f.oy + (f.max_y - y) * f.scale};
}

// Sequential scale (ColorBrewer YlOrRd, extended): light yellow = few, dark red = most.
void ramp(double t, double rgb[3])
{
  static const double stops[5][3] = {{255, 255, 178}, {254, 204, 92}, {253, 141, 60}, {227, 26, 28}, {128, 0, 38}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int k = std::min(3, static_cast<int>(t));
  const double u = t - k;
  for (int c = 0; c < 3; ++c) rgb[c] = ((1 - u) * stops[k][c] + u * stops[k + 1][c]) / 255;
}

const double kNever[3] = {0.88, 0.88, 0.88};  // a cell no AGV ever counted on

void text(cairo_t* cr, double x, double y, double size, const std::string& s, bool bold = false, bool centre = false)
{
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, centre ? x - e.width / 2 - e.x_bearing : x, y);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_show_text(cr, s.c_str());
}

void panel(cairo_t* cr, const gridify::CellMap& map, const Frame& f, int p, const std::vector<long long>& v,
           const std::string& name)
{
  const double x0 = p * kCongestionWidth / 2.0;
  text(cr, x0 + kCongestionWidth / 4.0, kTitleH + 18, 15, name, true, true);
  // The net: every adjacency as a thin line, so empty aisles still show.
  cairo_set_source_rgb(cr, 0.75, 0.75, 0.75);
  cairo_set_line_width(cr, std::max(0.5, 0.08 * f.scale));
  for (planner::Vertex u = 0; u < map.graph.size(); ++u)
    for (planner::Vertex w : map.graph.neighbors(u)) {
      if (w < u) continue;
      const Pixel a = place(f, p, map.cells[u].x, map.cells[u].y), b = place(f, p, map.cells[w].x, map.cells[w].y);
      cairo_move_to(cr, a.x, a.y);
      cairo_line_to(cr, b.x, b.y);
    }
  cairo_stroke(cr);
  const long long top = std::max(1LL, *std::max_element(v.begin(), v.end()));
  const double side = std::max(1.5, 0.8 * map.cell_length * f.scale);
  for (size_t c = 0; c < map.cells.size(); ++c) {
    double rgb[3] = {kNever[0], kNever[1], kNever[2]};
    if (v[c] > 0) ramp(static_cast<double>(v[c]) / top, rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    const Pixel m = place(f, p, map.cells[c].x, map.cells[c].y);
    cairo_rectangle(cr, m.x - side / 2, m.y - side / 2, side, side);
    cairo_fill(cr);
  }
  // The scale: a "never" swatch, then the ramp from 1 to the maximum.
  const double y = kCongestionHeight - kScaleH + 14, w = kCongestionWidth / 2.0 - 2 * kMargin - 130;
  cairo_set_source_rgb(cr, kNever[0], kNever[1], kNever[2]);
  cairo_rectangle(cr, x0 + kMargin, y, 16, 16);
  cairo_fill(cr);
  text(cr, x0 + kMargin + 20, y + 13, 12, "0");
  const double rx = x0 + kMargin + 50;
  cairo_pattern_t* g = cairo_pattern_create_linear(rx, 0, rx + w, 0);
  for (int k = 0; k <= 16; ++k) {
    double rgb[3];
    ramp(k / 16.0, rgb);
    cairo_pattern_add_color_stop_rgb(g, k / 16.0, rgb[0], rgb[1], rgb[2]);
  }
  cairo_set_source(cr, g);
  cairo_rectangle(cr, rx, y, w, 16);
  cairo_fill(cr);
  cairo_pattern_destroy(g);
  char buf[64];
  text(cr, rx, y + 32, 12, "1", false, true);
  std::snprintf(buf, sizeof buf, "%lld", (top + 1) / 2);
  text(cr, rx + w / 2, y + 32, 12, buf, false, true);
  std::snprintf(buf, sizeof buf, "%lld", top);
  text(cr, rx + w, y + 32, 12, buf, false, true);
  text(cr, rx + w + 14, y + 13, 12, "AGV-ticks");
}

cairo_status_t append(void* out, const unsigned char* data, unsigned int n)
{
  static_cast<std::string*>(out)->append(reinterpret_cast<const char*>(data), n);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

Pixel congestion_pixel(const gridify::CellMap& map, int panel, planner::Vertex v)
{
  return place(frame(map), panel, map.cells[v].x, map.cells[v].y);
}

void write_congestion_png(const std::string& path, const gridify::CellMap& map, const Congestion& c,
                          const std::string& title)
{
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> s(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, kCongestionWidth, kCongestionHeight), cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(s.get()), cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  text(cr.get(), kCongestionWidth / 2.0, 28, 18, title, true, true);
  const Frame f = frame(map);
  panel(cr.get(), map, f, 0, c.occupancy(), "occupancy: AGV-ticks on the cell");
  panel(cr.get(), map, f, 1, c.waiting(), "waiting: AGV-ticks standing, not on its goal");
  cairo_surface_flush(s.get());
  std::string png;
  const cairo_status_t st = cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS
                                ? cairo_status(cr.get())
                                : cairo_surface_write_to_png_stream(s.get(), append, &png);
  if (st != CAIRO_STATUS_SUCCESS)
    throw planner::OutputError("cannot write '" + path + "': cairo: " + cairo_status_to_string(st));
  planner::write_file(path, png);
}

}  // namespace controller
