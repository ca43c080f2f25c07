// Runs you can trust (docs/faults.md): what every app does on a full disk, a signal and
// bad input -- exit code, one line on stderr naming the file or key, outputs left. Real
// apps, real SUMO (rtlacam-sumo), /dev/full as the full disk.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"
#include "temp_path.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kSrc = RTLACAM_SOURCE_DIR;

std::string slurp(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Lines of stderr that are not progress lines ("[rtlacam-sumo] tick ...", every
// run.progress_s: a loaded machine prints one even in a short run).
int lines(const std::string& s)
{
  int n = 0;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) {
    if (l.rfind("-----", 0) == 0) break;  // LeakSanitizer's "Suppressions used" table (ASan builds): not ours
    n += l.rfind("[rtlacam-sumo]", 0) != 0;
  }
  return n;
}

// A fresh output dir whose file `name` is a link to /dev/full: every write to it fails
// with ENOSPC, as on a full disk.
std::string dir_with_full(const std::string& tag, const std::string& name)
{
  const std::string dir = test::temp_dir("faults_" + tag);
  if (!name.empty()) fs::create_symlink("/dev/full", dir + "/" + name);
  return dir;
}

// A well-formed XML file, checked by a real parser (python3's expat).
bool xml_well_formed(const std::string& path)
{
  const std::string cmd = "python3 -c 'import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])' '" + path + "' 2>/dev/null";
  return std::system(cmd.c_str()) == 0;
}

bool json_valid(const std::string& path)
{
  const std::string cmd = "python3 -c 'import sys, json; json.load(open(sys.argv[1]))' '" + path + "' 2>/dev/null";
  return std::system(cmd.c_str()) == 0;
}

// A child process running `argv` (stdout/stderr to files), signalled mid-run.
struct Child {
  pid_t pid = -1;
  std::string out, err;
  explicit Child(const std::vector<std::string>& argv, const std::string& tag)
  {
    out = test::temp_path(tag + "_out.txt");
    err = test::temp_path(tag + "_err.txt");
    pid = ::fork();
    if (pid == 0) {
      if (!freopen(out.c_str(), "w", stdout) || !freopen(err.c_str(), "w", stderr)) ::_exit(126);
      std::vector<char*> a;
      for (const std::string& s : argv) a.push_back(const_cast<char*>(s.c_str()));
      a.push_back(nullptr);
      ::execv(a[0], a.data());
      ::_exit(127);
    }
  }
  // Waits (at most `s` seconds) until `pred` holds; false if the child ended first.
  template <class Pred>
  bool wait_for(Pred pred, double s)
  {
    const auto t0 = std::chrono::steady_clock::now();
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < s) {
      if (pred()) return true;
      int st = 0;
      if (::waitpid(pid, &st, WNOHANG) == pid) {
        pid = -1;
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }
  // Exit code (128 + N if a signal N killed it), after at most `s` seconds.
  int finish(double s)
  {
    const auto t0 = std::chrono::steady_clock::now();
    while (pid > 0) {
      int st = 0;
      if (::waitpid(pid, &st, WNOHANG) == pid) {
        pid = -1;
        return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st) + 1000;  // +1000: killed, not exited
      }
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > s) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
        pid = -1;
        return -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -2;
  }
  ~Child()
  {
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
};

}  // namespace

#ifdef RTLACAM_SUMO_BIN

// Every output of rtlacam-sumo on a full disk: exit 1, one line naming that file; the
// outputs that could be written are (metrics.json unless it is the one that failed).
TEST(FullDisk, EveryRtlacamSumoOutput)
{
  struct Case {
    std::string config, file;
  };
  const std::vector<Case> cases = {{"small_warehouse.yaml", "metrics.json"},
                                   {"small_warehouse.yaml", "plan.txt"},
                                   {"small_warehouse.yaml", "fcd.xml"},
                                   {"small_warehouse.yaml", "tripinfo.xml"},
                                   {"small_warehouse.yaml", "agv.add.xml"},
                                   {"small_warehouse.yaml", "congestion.png"},
                                   {"small_warehouse_lifelong.yaml", "lifelong.json"}};
  for (const Case& c : cases) {
    const std::string dir = dir_with_full(c.file, c.file);
    const test::CliResult r =
        test::run_cli(RTLACAM_SUMO_BIN, kSrc + "/config/" + c.config + " --max-ticks 30 --out " + dir);
    EXPECT_EQ(r.code, 1) << c.file << ": " << r.err;
    EXPECT_NE(r.err.find("cannot write '" + dir + "/" + c.file + "': No space left on device"), std::string::npos)
        << c.file << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    if (c.file != "metrics.json") {
      EXPECT_TRUE(json_valid(dir + "/metrics.json")) << c.file;
    }
  }
}

// SIGINT / SIGTERM mid-run (real SUMO): the run ends through its normal end -- exit
// 130 / 143, metrics.json, plan.txt and lifelong.json complete, SUMO closed so its XML
// outputs are well-formed.
void expect_clean_stop(const std::string& config, const std::vector<std::string>& extra, int sig, int code,
                       const std::string& tag)
{
  const std::string dir = test::temp_dir("faults_" + tag);
  std::vector<std::string> argv = {RTLACAM_SUMO_BIN, kSrc + "/config/" + config, "--max-ticks", "1000000", "--out", dir};
  argv.insert(argv.end(), extra.begin(), extra.end());
  Child ch(argv, tag);
  // Running for a while: SUMO has written a good part of fcd.xml.
  ASSERT_TRUE(ch.wait_for([&] { return fs::exists(dir + "/fcd.xml") && fs::file_size(dir + "/fcd.xml") > 200000; }, 60))
      << slurp(ch.err);
  ::kill(ch.pid, sig);
  EXPECT_EQ(ch.finish(60), code) << slurp(ch.err);
  const std::string err = slurp(ch.err);
  EXPECT_NE(err.find(std::string("stopped by ") + (sig == SIGINT ? "SIGINT" : "SIGTERM")), std::string::npos) << err;
  EXPECT_TRUE(json_valid(dir + "/metrics.json"));
  const std::string m = slurp(dir + "/metrics.json");
  EXPECT_NE(m.find(std::string("\"interrupted\": \"") + (sig == SIGINT ? "SIGINT" : "SIGTERM") + "\""), std::string::npos);
  EXPECT_NE(m.find("\"error\": \"\""), std::string::npos) << m;
  EXPECT_TRUE(json_valid(dir + "/lifelong.json"));
  EXPECT_GT(lines(slurp(dir + "/plan.txt")), 10);
  for (const char* f : {"fcd.xml", "tripinfo.xml", "summary.xml", "collision.xml"})
    EXPECT_TRUE(xml_well_formed(dir + "/" + f)) << f;
}

TEST(Signals, SigintLockstepLibsumo)
{
  expect_clean_stop("small_warehouse_lifelong.yaml", {}, SIGINT, 130, "sigint");
}

TEST(Signals, SigtermAdgLibsumo)
{
  expect_clean_stop("small_warehouse_lifelong_agv.yaml", {}, SIGTERM, 143, "sigterm");
}

TEST(Signals, SigintTraci)
{
  expect_clean_stop("small_warehouse_lifelong.yaml", {"--backend", "traci"}, SIGINT, 130, "sigint_traci");
}

// A scratch config; "@/" in `yaml` stands for the source tree (paths in a config are
// relative to the config's own folder).
std::string write_config(const std::string& name, std::string yaml)
{
  for (size_t at; (at = yaml.find("@/")) != std::string::npos;) yaml.replace(at, 2, kSrc + "/");
  const std::string path = test::temp_path(name);
  std::ofstream(path) << yaml;
  return path;
}

// Bad input: exit 2 before SUMO starts, one line naming the key; never a crash.
TEST(BadInput, RtlacamSumoConfigs)
{
  const std::string net = "sumo:\n  net: @/sumo_scenarios/small.net.xml\n";
  struct Case {
    std::string yaml, expect;
  };
  const std::vector<Case> cases = {
      {net + "fleet: {count: 3}\nrun: {tick_s: 1e300}\n", "run.tick_s: must be <= 3600 s"},
      {net + "fleet: {count: 3}\nrun: {tick_s: 2000}\n", "run.tick_s: at most 10000 SUMO steps per tick"},
      {net + "fleet: {count: 3}\nrun:\n  tick_s: 1.0\n  tick_s: 2.0\n", "run.tick_s: duplicate key (line 6; first on line 5)"},
      {net + "  extra_args: [--end, '100']\nfleet: {count: 3}\n", "sumo.extra_args[0]: '--end' is set by the controller: use run.max_ticks"},
      {net + "  extra_args: ['--step-length=0.1']\nfleet: {count: 3}\n", "'--step-length' is set by the controller: use sumo.step_length"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string path = write_config("bad" + std::to_string(i) + ".yaml", cases[i].yaml);
    const test::CliResult r = test::run_cli(RTLACAM_SUMO_BIN, path + " --out " + test::temp_dir("bad"));
    EXPECT_EQ(r.code, 2) << cases[i].yaml << r.err;
    EXPECT_NE(r.err.find(cases[i].expect), std::string::npos) << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
  }
}

// An instance the search proves unsolvable (two AGVs that must pass each other in a
// corridor): exit 4 at once, "unsolvable", not max_ticks of waiting.
TEST(BadInput, UnsolvableProvenEndsAtOnce)
{
  const std::string path = write_config("line.yaml",
                                        "sumo:\n  net: @/tests/data/controller/line.net.xml\n"
                                        "fleet: {count: 2, starts: [a, b]}\ntasks: {goals: [b, a]}\n"
                                        "planner: {budget_ms: 0, expansions: 100}\nrun: {max_ticks: 100000, progress_s: 0}\n");
  const std::string dir = test::temp_dir("unsolvable");
  const test::CliResult r = test::run_cli(RTLACAM_SUMO_BIN, path + " --out " + dir);
  EXPECT_EQ(r.code, 4) << r.out << r.err;
  EXPECT_NE(r.out.find("unsolvable"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("unsolvable"), std::string::npos) << r.err;
  const std::string m = slurp(dir + "/metrics.json");
  EXPECT_NE(m.find("\"unsolvable\": true"), std::string::npos);
  const size_t at = m.find("\"ticks\": ");
  ASSERT_NE(at, std::string::npos) << m;
  EXPECT_LE(std::stol(m.substr(at + 9)), 2) << m;  // proven within the first ticks, not after 100000
}

// rtlacam-sumo on a net in tests/data/gridify/ that it refuses: exit 2 before SUMO starts,
// one line "<config>: sumo.net: <net>: <where>..." that contains `why`.
void expect_bad_net(const std::string& net, const std::string& where, const std::string& why)
{
  const std::string path = write_config(net + ".yaml", "sumo:\n  net: @/tests/data/gridify/" + net +
                                                           ".net.xml\nfleet: {count: 2}\nrun: {max_ticks: 50, progress_s: 0}\n");
  const test::CliResult r = test::run_cli(RTLACAM_SUMO_BIN, path + " --out " + test::temp_dir(net));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(path + ": sumo.net: " + kSrc + "/tests/data/gridify/" + net + ".net.xml: " + where),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
}

// A net SUMO cannot drive (a dead-end aisle without a turnaround: an AGV there would reach
// its route's end and be removed) is bad input, found before SUMO starts (was exit 3).
TEST(BadInput, ADeadEndNetIsBadInput)
{
  expect_bad_net("noturnarounds", "edge '", "' has no SUMO connection onwards (a dead end without a turnaround");
}

// A net where a turn the planner may take has no SUMO connection (netconvert
// --no-left-connections): only a jump could drive it, so it is bad input before SUMO starts.
TEST(BadInput, ANetNeedingJumpsIsBadInput)
{
  expect_bad_net("no_left_turns", "junction '", "an AGV would have to jump");
}

// A goal on a component gridify dropped: the error says gridify dropped it.
TEST(BadInput, GoalOnADroppedComponentNamesTheDrop)
{
  const std::string path = write_config("dropped.yaml",
                                        "sumo:\n  net: @/tests/data/gridify/disconnected.net.xml\n"
                                        "fleet: {count: 1, starts: [a]}\ntasks: {goals: [f]}\n");
  const test::CliResult r = test::run_cli(RTLACAM_SUMO_BIN, path + " --out " + test::temp_dir("dropped"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("tasks.goals[0]: 'f' is neither a cell id, a station nor a junction of the graph (gridify "
                       "dropped it: component e, f: 4 cell(s) not connected to the largest component"),
            std::string::npos)
      << r.err;
}

#endif  // RTLACAM_SUMO_BIN

#ifdef RTLACAM_LIFELONG_BIN
const std::string kProblem = kSrc + "/tests/data/tasks/lorr/2024/random.domain/RANDOM-01.json";

TEST(FullDisk, RtlacamLifelongOut)
{
  const test::CliResult r = test::run_cli(RTLACAM_LIFELONG_BIN, "--problem " + kProblem + " --steps 20 --budget-ms 1 --quiet --out /dev/full");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot write '/dev/full': No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
}

TEST(BadInput, RtlacamLifelongNegativeBudget)
{
  for (const char* b : {"-1", "nan", "inf"}) {
    const test::CliResult r = test::run_cli(RTLACAM_LIFELONG_BIN, "--problem " + kProblem + " --budget-ms " + b);
    EXPECT_EQ(r.code, 2) << b << r.err;
    EXPECT_NE(r.err.find("--budget-ms"), std::string::npos) << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
  }
}

TEST(Signals, RtlacamLifelongWritesItsLog)
{
  const std::string log = test::temp_path("lifelong_sig.json");
  Child ch({RTLACAM_LIFELONG_BIN, "--problem", kProblem, "--steps", "100000000", "--budget-ms", "1", "--out", log,
            "--progress-s", "0.05"},
           "lifelong_sig");
  // A progress line: the run is stepping.
  ASSERT_TRUE(ch.wait_for([&] { return slurp(ch.err).find("errands") != std::string::npos; }, 60)) << slurp(ch.err);
  ::kill(ch.pid, SIGTERM);
  EXPECT_EQ(ch.finish(60), 143) << slurp(ch.err);
  EXPECT_NE(slurp(ch.err).find("stopped by SIGTERM"), std::string::npos) << slurp(ch.err);
  EXPECT_TRUE(json_valid(log));
  EXPECT_NE(slurp(log).find("\"interrupted\":\"SIGTERM\""), std::string::npos);
}
#endif

#ifdef RTLACAM_BENCH_BIN
TEST(FullDisk, RtlacamBenchOut)
{
  const test::CliResult r = test::run_cli(
      RTLACAM_BENCH_BIN, "--map " + kSrc + "/tests/data/planner/random-32-32-20.map --scen " + kSrc +
                             "/tests/data/planner/random-32-32-20-random-1.scen -N 10 --json --out /dev/full");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot write '/dev/full': No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
}

TEST(BadInput, RtlacamBenchNegativeCutoff)
{
  const test::CliResult r = test::run_cli(
      RTLACAM_BENCH_BIN, "--map " + kSrc + "/tests/data/planner/random-32-32-20.map --scen " + kSrc +
                             "/tests/data/planner/random-32-32-20-random-1.scen -N 10 --cutoff-ms -1");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--cutoff-ms"), std::string::npos) << r.err;
}
#endif

#ifdef RTLACAM_GRIDIFY_BIN
TEST(FullDisk, RtlacamGridifyWriters)
{
  for (const char* opt : {"--map", "--svg", "--json"}) {
    const test::CliResult r =
        test::run_cli(RTLACAM_GRIDIFY_BIN, kSrc + "/sumo_scenarios/small.net.xml -q " + opt + " /dev/full");
    EXPECT_EQ(r.code, 1) << opt << r.err;
    EXPECT_NE(r.err.find("cannot write '/dev/full': No space left on device"), std::string::npos) << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
  }
}
#endif
