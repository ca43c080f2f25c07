#include "gridify/svg_writer.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "planner/error.hpp"
#include "planner/output_file.hpp"

namespace gridify {

namespace {

// Fixed colours for the usual kinds; others cycle through a palette.
std::string kind_colour(const std::string& kind, std::map<std::string, std::string>& used)
{
  static const std::map<std::string, std::string> fixed = {
      {"pickup", "#2ca02c"}, {"drop", "#d62728"}, {"parking", "#9467bd"}, {"charging", "#ff7f0e"}, {"stop", "#17becf"}};
  static const char* palette[] = {"#8c564b", "#e377c2", "#bcbd22", "#1f77b4", "#7f7f7f"};
  auto it = used.find(kind);
  if (it != used.end()) return it->second;
  auto f = fixed.find(kind);
  std::string c = f != fixed.end() ? f->second : palette[used.size() % 5];
  used[kind] = c;
  return c;
}

std::string esc(const std::string& s)
{
  std::string o;
  for (char ch : s) {
    if (ch == '<') o += "&lt;";
    else if (ch == '>') o += "&gt;";
    else if (ch == '&') o += "&amp;";
    else if (ch == '"') o += "&quot;";
    else o += ch;
  }
  return o;
}

}  // namespace

std::string to_svg(const CellMap& m, const SvgOptions& opt)
{
  double minx = std::numeric_limits<double>::infinity(), miny = minx, maxx = -minx, maxy = -minx;
  auto grow = [&](double x, double y) {
    minx = std::min(minx, x), maxx = std::max(maxx, x), miny = std::min(miny, y), maxy = std::max(maxy, y);
  };
  for (const Cell& c : m.cells) grow(c.x, c.y);
  for (const Dropped& d : m.dropped)
    for (auto& [p, q] : d.segments) grow(p.x, p.y), grow(q.x, q.y);
  if (!std::isfinite(minx)) minx = miny = maxx = maxy = 0;
  const double c = m.cell_length;
  const double extent = std::max({maxx - minx, maxy - miny, c});
  const double s = opt.pixels_per_metre > 0 ? opt.pixels_per_metre : std::clamp(1000.0 / extent, 2.0, 60.0);
  const double margin = 2 * c * s + 10, header = 44;
  const double W = (maxx - minx) * s + 2 * margin, H = (maxy - miny) * s + 2 * margin + header;
  auto X = [&](double x) { return (x - minx) * s + margin; };
  auto Y = [&](double y) { return (maxy - y) * s + margin + header; };  // SUMO's y points up

  std::ostringstream o;
  o.precision(6);
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W << ' '
    << H << "\" font-family=\"sans-serif\">\n";
  o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";

  // Aisles (bands), then dropped parts.
  o << "<g stroke=\"#d9d9d9\" stroke-width=\"" << 0.8 * c * s << "\" stroke-linecap=\"square\">\n";
  for (const Aisle& a : m.aisles) {
    const Cell* p = a.cells.front() >= 0 ? &m.cells[a.cells.front()] : &m.cells[a.cells[1]];
    const Cell* q = a.cells.back() >= 0 ? &m.cells[a.cells.back()] : &m.cells[a.cells[a.cells.size() - 2]];
    o << "<line x1=\"" << X(p->x) << "\" y1=\"" << Y(p->y) << "\" x2=\"" << X(q->x) << "\" y2=\"" << Y(q->y) << "\"/>\n";
  }
  o << "</g>\n<g stroke=\"#e41a1c\" stroke-width=\"" << std::max(1.5, 0.12 * c * s) << "\" stroke-dasharray=\""
    << std::max(3.0, 0.3 * c * s) << "\" fill=\"none\">\n";
  const double dj = std::max(4.0, 0.6 * c * s);
  for (const Dropped& d : m.dropped)
    for (auto& [p, q] : d.segments) {
      std::string title = "<title>" + esc(d.kind + " " + d.id + ": " + d.reason) + "</title>";
      if (p.x == q.x && p.y == q.y)  // a dropped junction
        o << "<rect x=\"" << X(p.x) - dj / 2 << "\" y=\"" << Y(p.y) - dj / 2 << "\" width=\"" << dj << "\" height=\"" << dj
          << "\" stroke-dasharray=\"none\">" << title << "</rect>\n";
      else
        o << "<line x1=\"" << X(p.x) << "\" y1=\"" << Y(p.y) << "\" x2=\"" << X(q.x) << "\" y2=\"" << Y(q.y) << "\">" << title
          << "</line>\n";
    }
  o << "</g>\n";

  // Graph edges.
  o << "<g stroke=\"#333333\" stroke-width=\"" << std::max(0.8, 0.06 * c * s) << "\">\n";
  for (planner::Vertex v = 0; v < m.graph.size(); ++v)
    for (planner::Vertex u : m.graph.neighbors(v))
      if (v < u || !m.graph.adjacent(u, v))  // two-way edges once, one-way arcs always
        o << "<line x1=\"" << X(m.cells[v].x) << "\" y1=\"" << Y(m.cells[v].y) << "\" x2=\"" << X(m.cells[u].x)
          << "\" y2=\"" << Y(m.cells[u].y) << "\"/>\n";
  o << "</g>\n";

  // Cells.
  const double r = std::max(1.2, 0.14 * c * s), js = std::max(3.0, 0.5 * c * s);
  o << "<g>\n";
  for (planner::Vertex v = 0; v < m.graph.size(); ++v) {
    const Cell& cell = m.cells[v];
    if (cell.kind == CellKind::Junction)
      o << "<rect x=\"" << X(cell.x) - js / 2 << "\" y=\"" << Y(cell.y) - js / 2 << "\" width=\"" << js << "\" height=\""
        << js << "\" fill=\"#3b6fb6\"><title>" << v << " junction " << esc(cell.junction) << "</title></rect>\n";
    else
      o << "<circle cx=\"" << X(cell.x) << "\" cy=\"" << Y(cell.y) << "\" r=\"" << r << "\" fill=\"#222222\"><title>" << v
        << " " << esc(cell.poses[0].lane) << " " << cell.poses[0].pos << "</title></circle>\n";
  }
  o << "</g>\n";

  // Stations.
  std::map<std::string, std::string> colours;
  const double font = std::clamp(0.45 * c * s, 7.0, 14.0);
  o << "<g font-size=\"" << font << "\">\n";
  for (const Station& st : m.stations) {
    const Cell& cell = m.cells[st.cell];
    o << "<circle cx=\"" << X(cell.x) << "\" cy=\"" << Y(cell.y) << "\" r=\"" << std::max(3.0, 0.35 * c * s)
      << "\" fill=\"" << kind_colour(st.kind, colours) << "\" stroke=\"black\" stroke-width=\"0.8\"><title>"
      << esc(st.kind + " " + st.id) << "</title></circle>\n";
    if (opt.labels)
      o << "<text x=\"" << X(cell.x) + 0.4 * c * s << "\" y=\"" << Y(cell.y) - 0.4 * c * s << "\">" << esc(st.id)
        << "</text>\n";
  }
  if (opt.labels)
    for (const Cell& cell : m.cells)
      if (cell.kind == CellKind::Junction)
        o << "<text x=\"" << X(cell.x) + 0.3 * c * s << "\" y=\"" << Y(cell.y) + font + 0.3 * c * s
          << "\" fill=\"#3b6fb6\">" << esc(cell.junction) << "</text>\n";
  o << "</g>\n";

  // Header: what this is and the counts, plus the station legend.
  std::string name = m.net_path.substr(m.net_path.find_last_of('/') + 1);
  o << "<text x=\"10\" y=\"18\" font-size=\"14\">" << esc(name) << ": " << m.cells.size() << " cells ("
    << m.num_junction_cells() << " junction), " << m.graph.num_edges() << " edges, " << m.aisles.size()
    << " aisles, cell " << c << " m, dropped " << m.dropped.size() << "</text>\n";
  double lx = 10;
  for (auto& [kind, col] : colours) {
    o << "<circle cx=\"" << lx + 5 << "\" cy=\"33\" r=\"5\" fill=\"" << col << "\"/><text x=\"" << lx + 14
      << "\" y=\"37\" font-size=\"12\">" << esc(kind) << "</text>\n";
    lx += 24 + 7.0 * kind.size();
  }
  if (!m.dropped.empty())
    o << "<line x1=\"" << lx << "\" y1=\"33\" x2=\"" << lx + 20
      << "\" y2=\"33\" stroke=\"#e41a1c\" stroke-width=\"2\" stroke-dasharray=\"4\"/><text x=\"" << lx + 24
      << "\" y=\"37\" font-size=\"12\">dropped</text>\n";
  o << "</svg>\n";
  return o.str();
}

void write_svg(const CellMap& m, const std::string& path, const SvgOptions& opt)
{
  planner::write_file(path, to_svg(m, opt));
}

}  // namespace gridify
