#include "xml_source.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace gridify {

XmlSource::XmlSource(const std::string& path) : path_(path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) throw planner::input_error(path, 0, "cannot open file");
  std::ostringstream ss;
  ss << in.rdbuf();
  text_ = ss.str();
  line_starts_.push_back(0);
  for (size_t k = 0; k < text_.size(); ++k)
    if (text_[k] == '\n') line_starts_.push_back(k + 1);
  // load_buffer parses a copy of text_, so node offsets (offset_debug) index text_ and
  // map to lines through line_starts_.
  pugi::xml_parse_result r = doc_.load_buffer(text_.data(), text_.size(), pugi::parse_default);
  if (!r) {
    size_t off = r.offset < 0 ? 0 : static_cast<size_t>(r.offset);
    int ln = static_cast<int>(std::upper_bound(line_starts_.begin(), line_starts_.end(), off) - line_starts_.begin());
    throw planner::input_error(path_, ln, std::string("malformed XML: ") + r.description());
  }
}

std::string XmlSource::name() const
{
  size_t s = path_.find_last_of('/');
  return s == std::string::npos ? path_ : path_.substr(s + 1);
}

int XmlSource::line(const pugi::xml_node& n) const
{
  ptrdiff_t off = n.offset_debug();
  if (off < 0) return 0;
  return static_cast<int>(std::upper_bound(line_starts_.begin(), line_starts_.end(), static_cast<size_t>(off)) -
                          line_starts_.begin());
}

planner::InputError XmlSource::error(const pugi::xml_node& n, const std::string& what) const
{
  return planner::input_error(path_, line(n), what);
}

static std::string describe(const pugi::xml_node& n)
{
  std::string d = std::string("<") + n.name();
  if (auto id = n.attribute("id")) d += std::string(" id='") + id.value() + "'";
  return d + ">";
}

std::string XmlSource::str(const pugi::xml_node& n, const char* attr) const
{
  pugi::xml_attribute a = n.attribute(attr);
  if (!a) throw error(n, describe(n) + ": missing attribute '" + attr + "'");
  return a.value();
}

// strtod, but the whole value must be a finite number (pugixml's as_double accepts garbage).
static bool parse_double(const char* s, double& out)
{
  if (!*s) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(s, &end);
  while (*end == ' ' || *end == '\t') ++end;
  return *end == '\0' && errno == 0 && std::isfinite(out);
}

double XmlSource::num(const pugi::xml_node& n, const char* attr) const
{
  std::string v = str(n, attr);
  double d = 0;
  if (!parse_double(v.c_str(), d))
    throw error(n, describe(n) + ": attribute '" + attr + "' is not a number: '" + v + "'");
  return d;
}

int XmlSource::integer(const pugi::xml_node& n, const char* attr) const
{
  double d = num(n, attr);
  if (d != std::floor(d) || std::fabs(d) > 1e9)
    throw error(n, describe(n) + ": attribute '" + attr + "' is not an integer: '" + str(n, attr) + "'");
  return static_cast<int>(d);
}

std::string XmlSource::str_or(const pugi::xml_node& n, const char* attr, const std::string& def) const
{
  return n.attribute(attr) ? str(n, attr) : def;
}

double XmlSource::num_or(const pugi::xml_node& n, const char* attr, double def) const
{
  return n.attribute(attr) ? num(n, attr) : def;
}

bool lists_agv_class(const std::string& vclasses)
{
  std::istringstream in(vclasses);
  std::string w;
  while (in >> w)
    if (w == "all" || w == "passenger") return true;
  return false;
}

}  // namespace gridify
