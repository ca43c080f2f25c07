#pragma once
// Checked writes: the one way every app and library writes a result file. A write that
// fails anywhere (open, any byte, the close: a full disk, /dev/full, no permission) is an
// OutputError "cannot write 'PATH': <reason>" -- exit 1 in every app -- never a silent
// truncated file. std::ofstream alone buffers the last bytes and drops the close error.
#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>

namespace planner {

struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Opens `path` (truncating), lets `fill` write to the stream, flushes and closes; throws
// OutputError naming the file and the system's reason on the first failure.
void write_file(const std::string& path, const std::function<void(std::ostream&)>& fill);

// Same, for a string.
void write_file(const std::string& path, const std::string& content);

// For a file someone else wrote (SUMO's XML outputs): a regular file must end with
// `</root>` (an element SUMO writes only at its close; a full disk truncates before it);
// anything else (a device such as /dev/full) must accept one more byte. Throws OutputError.
void check_xml_output(const std::string& path, const std::string& root);

}  // namespace planner
