#include "gridify/rules_file.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "xml_source.hpp"

namespace gridify {

namespace {

// Does this closingReroute close its edge for the AGVs (vClass passenger, the default of
// the controller's vType)? SUMO's default for a closing without allow/disallow: closed for
// all but "authority".
bool closes_for_agvs(const XmlSource& src, const pugi::xml_node& c)
{
  if (c.attribute("disallow")) return lists_agv_class(src.str(c, "disallow"));
  if (c.attribute("allow")) return !lists_agv_class(src.str(c, "allow"));
  return true;
}

std::vector<planner::Point> parse_shape(const XmlSource& src, const pugi::xml_node& n)
{
  std::vector<planner::Point> pts;
  std::istringstream in(src.str(n, "shape"));
  std::string pair;
  while (in >> pair) {
    const size_t comma = pair.find(',');
    planner::Point p;
    try {
      size_t used = 0;
      p.x = std::stod(pair.substr(0, comma), &used);
      if (comma == std::string::npos || used != comma) throw std::invalid_argument("x");
      const std::string ys = pair.substr(comma + 1);
      p.y = std::stod(ys, &used);
      if (used != ys.size() && ys[used] != ',') throw std::invalid_argument("y");  // x,y[,z]
    } catch (const std::exception&) {
      throw src.error(n, "<poly id='" + src.str_or(n, "id", "") + "'>: shape: '" + pair + "' is not x,y");
    }
    pts.push_back(p);
  }
  return pts;
}

}  // namespace

SumoRules read_sumo_rules(const std::string& path)
{
  XmlSource src(path);
  SumoRules rules;
  pugi::xml_node root = src.doc().document_element();
  if (!root) return rules;
  for (pugi::xml_node n : root.children()) {
    const std::string element = n.name();
    if (element == "rerouter") {
      const std::string id = src.str(n, "id");
      for (pugi::xml_node iv : n.children("interval")) {
        SumoClosure c;
        c.source = src.name() + ":" + std::to_string(src.line(iv)) + ": rerouter '" + id + "'";
        c.begin = src.num_or(iv, "begin", 0.0);
        c.end = src.num_or(iv, "end", std::numeric_limits<double>::infinity());
        if (!(c.begin >= 0) || std::isnan(c.end))
          throw src.error(iv, "<rerouter id='" + id + "'> interval: begin must be >= 0");
        if (c.end < c.begin)
          throw src.error(iv, "<rerouter id='" + id + "'> interval: end " + src.str(iv, "end") + " < begin " +
                                  src.str_or(iv, "begin", "0"));
        for (pugi::xml_node cr : iv.children("closingReroute"))
          if (closes_for_agvs(src, cr)) c.edges.push_back(src.str(cr, "id"));
        for (pugi::xml_node cr : iv.children("closingLaneReroute"))
          if (closes_for_agvs(src, cr)) c.lanes.push_back(src.str(cr, "id"));
        if (!c.edges.empty() || !c.lanes.empty()) rules.closures.push_back(std::move(c));
      }
    } else if (element == "poly" && src.str_or(n, "type", "") == kZoneType) {
      SumoZone z;
      z.id = src.str(n, "id");
      z.source = src.name() + ":" + std::to_string(src.line(n)) + ": poly '" + z.id + "'";
      z.shape = parse_shape(src, n);
      if (z.shape.size() < 3)
        throw src.error(n, "<poly id='" + z.id + "' type='" + kZoneType + "'>: a zone needs a shape of >= 3 points");
      rules.zones.push_back(std::move(z));
    }
  }
  return rules;
}

bool inside(const std::vector<planner::Point>& poly, double x, double y)
{
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const planner::Point& a = poly[i];
    const planner::Point& b = poly[j];
    if ((a.y > y) != (b.y > y) && x < (b.x - a.x) * (y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

}  // namespace gridify
