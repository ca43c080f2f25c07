#include "tasks/lorr_files.hpp"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <unordered_map>

#include "planner/error.hpp"

namespace tasks {
namespace {

using planner::input_error;
using planner::Vertex;

struct LineReader {
  std::ifstream in;
  std::string path;
  int lineno = 0;

  explicit LineReader(const std::string& p) : in(p), path(p)
  {
    if (!in) throw input_error(path, 0, "cannot open file");
  }
  bool next(std::string& line)
  {
    if (!std::getline(in, line)) return false;
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (lineno == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);  // a UTF-8 byte order mark
    return true;
  }
};

std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

bool parse_int(const std::string& s, long long& v)
{
  const std::string t = trim(s);
  if (t.empty()) return false;
  errno = 0;
  char* end = nullptr;
  v = std::strtoll(t.c_str(), &end, 10);
  return errno == 0 && end == t.c_str() + t.size();
}

// Skips '#' comments, reads the count line.
long long read_count(LineReader& r, const char* what)
{
  std::string line;
  while (r.next(line)) {
    if (!line.empty() && line[0] == '#') continue;
    long long n = 0;
    if (!parse_int(line, n) || n < 0) throw input_error(r.path, r.lineno, std::string("expected the number of ") + what + ", got '" + line + "'");
    return n;
  }
  throw input_error(r.path, r.lineno + 1, std::string("expected the number of ") + what + ", got end of file");
}

}  // namespace

Vertex lorr_cell(const planner::Graph& g, long long id, const std::string& path, int line)
{
  const long long cells = static_cast<long long>(g.width()) * g.height();
  if (id < 0 || id >= cells)
    throw input_error(path, line, "cell id " + std::to_string(id) + " is off the map (" + std::to_string(g.width()) + " x " +
                                      std::to_string(g.height()) + ", ids 0.." + std::to_string(cells - 1) + ")");
  const int x = static_cast<int>(id % g.width()), y = static_cast<int>(id / g.width());
  const Vertex v = g.at(x, y);
  if (v < 0)
    throw input_error(path, line, "cell id " + std::to_string(id) + " (row " + std::to_string(y) + ", column " +
                                      std::to_string(x) + ") is an obstacle");
  return v;
}

planner::Config load_lorr_agents(const std::string& path, const planner::Graph& g, int team_size)
{
  LineReader r(path);
  const long long declared = read_count(r, "agents");
  if (team_size >= 0 && team_size > declared)
    throw input_error(path, r.lineno, "teamSize " + std::to_string(team_size) + " but the file declares only " +
                                          std::to_string(declared) + " agents");
  const long long n = team_size >= 0 ? team_size : declared;
  planner::Config starts;
  std::unordered_map<Vertex, int> line_of;
  std::string line;
  while (static_cast<long long>(starts.size()) < n) {
    if (!r.next(line))
      throw input_error(path, r.lineno, "declares " + std::to_string(declared) + " agents but has only " + std::to_string(starts.size()));
    long long id = 0;
    if (!parse_int(line, id)) throw input_error(path, r.lineno, "expected a cell id, got '" + line + "'");
    const Vertex v = lorr_cell(g, id, path, r.lineno);
    auto [it, fresh] = line_of.emplace(v, r.lineno);
    if (!fresh)
      throw input_error(path, r.lineno, "cell id " + std::to_string(id) + " is already the start of the agent on line " +
                                            std::to_string(it->second));
    starts.push_back(v);
  }
  return starts;
}

TaskFile load_lorr_tasks(const std::string& path, const planner::Graph& g)
{
  LineReader r(path);
  const long long declared = read_count(r, "tasks");
  if (declared <= 0) throw input_error(path, r.lineno, "the file declares no tasks");
  TaskFile f;
  f.path = path;
  std::string line;
  while (f.size() < declared) {
    if (!r.next(line))
      throw input_error(path, r.lineno, "declares " + std::to_string(declared) + " tasks but has only " + std::to_string(f.size()));
    std::vector<Vertex> errands;
    size_t b = 0;
    while (true) {
      const size_t e = line.find(',', b);
      const std::string field = line.substr(b, e == std::string::npos ? std::string::npos : e - b);
      long long id = 0;
      if (!parse_int(field, id)) throw input_error(path, r.lineno, "expected comma-separated cell ids, got '" + line + "'");
      errands.push_back(lorr_cell(g, id, path, r.lineno));
      if (e == std::string::npos) break;
      b = e + 1;
    }
    f.tasks.push_back(std::move(errands));
    f.lines.push_back(r.lineno);
  }
  return f;
}

}  // namespace tasks
