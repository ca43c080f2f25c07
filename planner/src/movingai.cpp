#include "planner/movingai.hpp"

#include <cstdint>
#include <fstream>
#include <sstream>

#include "planner/error.hpp"

namespace planner {
namespace {

std::ifstream open_or_throw(const std::string& path)
{
  std::ifstream in(path);
  if (!in) throw input_error(path, 0, "cannot open file");
  return in;
}

// Strips a trailing '\r' so CRLF files read like LF files.
bool next_line(std::istream& in, std::string& line, int& lineno)
{
  if (!std::getline(in, line)) return false;
  ++lineno;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  // A UTF-8 byte order mark (some Windows editors write one) failed the header check as if
  // the first line were something else.
  if (lineno == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
  return true;
}

int header_value(std::istream& in, const std::string& path, int& lineno, const std::string& key)
{
  std::string line;
  if (!next_line(in, line, lineno)) throw input_error(path, lineno + 1, "expected '" + key + " N', got end of file");
  std::istringstream ss(line);
  std::string k;
  long long v = 0;
  std::string rest;
  if (!(ss >> k >> v) || k != key || (ss >> rest) || v <= 0 || v > 100000)
    throw input_error(path, lineno, "expected '" + key + " N' with 0 < N <= 100000, got '" + line + "'");
  return static_cast<int>(v);
}

}  // namespace

Graph load_map(const std::string& path)
{
  auto in = open_or_throw(path);
  std::string line;
  int lineno = 0;
  if (!next_line(in, line, lineno) || line.rfind("type", 0) != 0)
    throw input_error(path, 1, "not a MovingAI map: first line must be 'type octile'");
  int height = header_value(in, path, lineno, "height");
  int width = header_value(in, path, lineno, "width");
  if (!next_line(in, line, lineno) || line != "map") throw input_error(path, lineno, "expected 'map'");
  // Vertex ids and cell indices are int.
  if (static_cast<long long>(width) * height > INT32_MAX)
    throw input_error(path, lineno, "map of " + std::to_string(width) + " x " + std::to_string(height) + " cells is too large");
  // Grown row by row, not sized from the header: a 45-byte file claiming 100000 x 100000
  // cells used to allocate (and zero) 1.25 GB before finding out it has no rows.
  std::vector<bool> free;
  for (int y = 0; y < height; ++y) {
    if (!next_line(in, line, lineno))
      throw input_error(path, lineno + 1, "map ends after " + std::to_string(y) + " of " + std::to_string(height) + " rows");
    if (static_cast<int>(line.size()) != width)
      throw input_error(path, lineno, "row has " + std::to_string(line.size()) + " characters, expected " + std::to_string(width));
    for (int x = 0; x < width; ++x) {
      char c = line[x];
      if (c != '.' && c != 'G' && c != 'S' && c != 'E' && c != '@' && c != 'O' && c != 'T' && c != 'W')
        throw input_error(path, lineno, std::string("unknown map character '") + c + "' at column " + std::to_string(x));
      free.push_back(c == '.' || c == 'G' || c == 'S' || c == 'E');
    }
  }
  while (next_line(in, line, lineno))
    if (line.find_first_not_of(" \t") != std::string::npos)
      throw input_error(path, lineno, "unexpected text after the last map row");
  Graph g = Graph::from_grid(width, height, free);
  g.name = path;
  return g;
}

Instance load_scen(const std::string& path, const Graph& g, int num_agents)
{
  auto in = open_or_throw(path);
  Instance ins;
  ins.source = path;
  std::string line;
  int lineno = 0;
  if (!next_line(in, line, lineno) || line.rfind("version", 0) != 0)
    throw input_error(path, 1, "not a MovingAI scenario: first line must be 'version 1'");
  auto cell = [&](int x, int y, const char* what) {
    if (x < 0 || y < 0 || x >= g.width() || y >= g.height())
      throw input_error(path, lineno, std::string(what) + " (" + std::to_string(x) + "," + std::to_string(y) + ") is off the map");
    Vertex v = g.at(x, y);
    if (v < 0)
      throw input_error(path, lineno, std::string(what) + " (" + std::to_string(x) + "," + std::to_string(y) + ") is on an obstacle");
    return v;
  };
  while ((num_agents < 0 || ins.num_agents() < num_agents) && next_line(in, line, lineno)) {
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::istringstream ss(line);
    std::string bucket, map;
    int w, h, sx, sy, gx, gy;
    double length;
    if (!(ss >> bucket >> map >> w >> h >> sx >> sy >> gx >> gy >> length))
      throw input_error(path, lineno, "expected 'bucket map width height sx sy gx gy length'");
    if (w != g.width() || h != g.height())
      throw input_error(path, lineno, "scenario is for a " + std::to_string(w) + "x" + std::to_string(h) + " map, but the map is " +
                                          std::to_string(g.width()) + "x" + std::to_string(g.height()));
    ins.starts.push_back(cell(sx, sy, "start"));
    ins.goals.push_back(cell(gx, gy, "goal"));
    ins.source_lines.push_back(lineno);
  }
  if (num_agents >= 0 && ins.num_agents() < num_agents)
    throw input_error(path, lineno, "asked for " + std::to_string(num_agents) + " agents but the scenario has only " +
                                        std::to_string(ins.num_agents()));
  if (ins.num_agents() == 0) throw input_error(path, lineno, "scenario has no agents");
  ins.check(g, true);
  return ins;
}

}  // namespace planner
