// planner::write_file / check_xml_output (output_file.hpp): every failure of a write is an
// OutputError naming the file and the reason; stop_signal.hpp's request flag.
#include "planner/output_file.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <csignal>

#include <fstream>
#include <sstream>
#include <string>

#include "planner/stop_signal.hpp"
#include "temp_path.hpp"

namespace {

std::string slurp(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string error_of(const std::function<void()>& f)
{
  try {
    f();
  } catch (const planner::OutputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(WriteFile, WritesEveryByte)
{
  const std::string p = test::temp_path("w.txt");
  std::string big(300000, 'x');  // several buffer fills
  big += "end\n";
  planner::write_file(p, big);
  EXPECT_EQ(slurp(p), big);
  planner::write_file(p, [](std::ostream& o) { o << "short\n"; });
  EXPECT_EQ(slurp(p), "short\n");  // truncated, not appended
}

TEST(WriteFile, FullDiskNamesTheFile)
{
  // /dev/full takes the open and fails every write with ENOSPC; a small write would sit in
  // an ofstream's buffer and be dropped at its destructor without a word.
  EXPECT_EQ(error_of([] { planner::write_file("/dev/full", "{}\n"); }), "cannot write '/dev/full': No space left on device");
  EXPECT_EQ(error_of([] { planner::write_file("/dev/full", std::string(200000, 'x')); }),
            "cannot write '/dev/full': No space left on device");
}

TEST(WriteFile, MissingFolderNamesTheFile)
{
  EXPECT_EQ(error_of([] { planner::write_file("/nonexistent/dir/x.json", "{}"); }),
            "cannot write '/nonexistent/dir/x.json': No such file or directory");
}

TEST(WriteFile, AnExceptionInTheFillPropagates)
{
  const std::string p = test::temp_path("throw.txt");
  EXPECT_THROW(planner::write_file(p, [](std::ostream&) { throw std::runtime_error("x"); }), std::runtime_error);
}

TEST(CheckXmlOutput, CompleteTruncatedAndDevices)
{
  const std::string p = test::temp_path("o.xml");
  std::ofstream(p) << "<fcd-export>\n  <timestep time=\"0\"/>\n</fcd-export>\n";
  EXPECT_EQ(error_of([&] { planner::check_xml_output(p, "fcd-export"); }), "(no error)");
  std::ofstream(p) << "<fcd-export>\n  <timestep time=\"0\"/>\n  <timest";  // a full disk cut it here
  EXPECT_EQ(error_of([&] { planner::check_xml_output(p, "fcd-export"); }),
            "cannot write '" + p + "': incomplete (no closing </fcd-export>; full disk?)");
  EXPECT_EQ(error_of([] { planner::check_xml_output("/dev/full", "fcd-export"); }),
            "cannot write '/dev/full': No space left on device");
  EXPECT_EQ(error_of([] { planner::check_xml_output("/dev/null", "fcd-export"); }), "(no error)");
}

TEST(StopSignal, HandlerRecordsTheFirstSignalOnly)
{
  planner::reset_stop_signal();
  planner::install_stop_handlers();
  EXPECT_EQ(planner::stop_signal(), 0);
  ::raise(SIGTERM);  // recorded, the process lives on
  EXPECT_EQ(planner::stop_signal(), SIGTERM);
  EXPECT_STREQ(planner::signal_name(planner::stop_signal()), "SIGTERM");
  planner::reset_stop_signal();
  EXPECT_EQ(planner::stop_signal(), 0);
  // The handler reset itself: a second SIGTERM would kill (not raised here).
  struct sigaction sa {};
  sigaction(SIGTERM, nullptr, &sa);
  EXPECT_EQ(sa.sa_handler, SIG_DFL);
  // ... and set the watchdog: a process that cannot get to its end path (blocked on a frozen
  // SUMO) is ended kStopGraceS later. Cancelled here, the test process lives on.
  const unsigned left = ::alarm(0);
  EXPECT_GT(left, planner::kStopGraceS - 5);
  EXPECT_LE(left, planner::kStopGraceS);
}

TEST(StopSignal, ASignalIgnoredAtStartStaysIgnored)
{
  std::signal(SIGINT, SIG_IGN);  // as nohup or `cmd &` in a script leave it
  planner::reset_stop_signal();
  planner::install_stop_handlers();
  struct sigaction sa {};
  sigaction(SIGINT, nullptr, &sa);
  EXPECT_EQ(sa.sa_handler, SIG_IGN);
  ::raise(SIGINT);
  EXPECT_EQ(planner::stop_signal(), 0);
  sigaction(SIGTERM, nullptr, &sa);
  EXPECT_NE(sa.sa_handler, SIG_IGN);  // SIGTERM was not ignored: handled
}
