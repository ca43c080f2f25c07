#pragma once
// XmlSource: one XML file loaded with pugixml, plus the bits every reader of a SUMO file
// needs to fail cleanly: "file:line: what" messages and checked attribute access.
// Private to gridify (lives in src/): readers of .net.xml and additional files share it.
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "planner/error.hpp"

namespace gridify {

class XmlSource {
 public:
  // Loads and parses `path`; throws planner::InputError on a missing file or bad XML.
  explicit XmlSource(const std::string& path);

  const pugi::xml_document& doc() const { return doc_; }
  const std::string& path() const { return path_; }
  std::string name() const;  // the file name without directories, for messages

  // Line of a node (1-based), from pugixml's byte offset.
  int line(const pugi::xml_node& n) const;

  planner::InputError error(const pugi::xml_node& n, const std::string& what) const;

  // Checked attributes: a missing or malformed value throws an error naming the
  // element, the attribute and the line.
  std::string str(const pugi::xml_node& n, const char* attr) const;
  double num(const pugi::xml_node& n, const char* attr) const;
  int integer(const pugi::xml_node& n, const char* attr) const;
  // Optional variants: `def` when the attribute is absent (still checked when present).
  std::string str_or(const pugi::xml_node& n, const char* attr, const std::string& def) const;
  double num_or(const pugi::xml_node& n, const char* attr, double def) const;

 private:
  std::string path_;
  std::string text_;
  std::vector<size_t> line_starts_;  // byte offset of each line start
  pugi::xml_document doc_;
};

// Does a SUMO vClass list (an allow / disallow attribute: space-separated) name the AGVs'
// class -- passenger, the controller's vType's -- or "all"?
bool lists_agv_class(const std::string& vclasses);

}  // namespace gridify
