// The command line itself: --version, --help with an example on every command, exit codes for bad command
// lines (2) and bad inputs (1), and messages that say what is wrong and where.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

using ::testing::HasSubstr;

TEST(CommandLine, VersionAndHelpOnEveryCommand) {
  TempDir dir;
  const RunResult v = shoremesh(dir, "--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_THAT(v.out, HasSubstr("shoremesh 0."));
  const RunResult h = shoremesh(dir, "--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_THAT(h.out, HasSubstr("Exit codes: 0 ok, 1 bad input"));
  for (const char* command : {"mesh", "edit", "info", "bench"}) {
    const RunResult c = shoremesh(dir, std::string(command) + " --help");
    EXPECT_EQ(c.code, 0) << command;
    EXPECT_THAT(c.out, HasSubstr("Example")) << command;
    EXPECT_THAT(c.out, HasSubstr(std::string("shoremesh ") + command)) << command;
  }
}

struct FailureCase {
  const char* args;
  const char* says;
};

// Every case exits with `code`, and stderr starts "shoremesh: " and says what is wrong.
void expect_failures(const TempDir& dir, std::initializer_list<FailureCase> cases, int code) {
  for (const auto& c : cases) {
    const RunResult r = shoremesh(dir, c.args);
    EXPECT_EQ(r.code, code) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.says)) << c.args;
    EXPECT_THAT(r.err, ::testing::StartsWith("shoremesh: ")) << c.args;
  }
}

TEST(CommandLine, UsageErrorsExitWithTwo) {
  TempDir dir;
  write_file(dir / "p.csv", random_points(20, 10, 10, 1));
  expect_failures(dir, {
      {"", "A subcommand is required"},
      {"frobnicate", "unknown command 'frobnicate'"},
      {"mesh p.csv -o out.csv --box 0 0", "--box"},
      {"mesh p.csv -o out.csv --box 0 0 0 1", "--box takes 3 numbers"},
      {"mesh p.csv", "--output is required"},
      {"mesh p.csv -o out.csv --dim 4", "--dim"},
      {"mesh p.csv -o out.msh --format stl", "--format"},
      {"mesh p.csv -o out.csv --bogus", "--bogus"},
      {"mesh missing.csv -o out.csv", "missing.csv"},
      {"mesh p.csv -o out.csv --rho 1", "rho"},
      {"mesh p.csv -o out.csv --spacing -3", "--spacing: -3 is not above 0"},
      {"mesh p.csv -o out.csv --track-close-distance -1", "--track-close-distance: -1 is below 0"},
      {"edit p.csv", "--edits is required"},
      {"info", "input is required"},
      {"info p.csv p.csv", "input"},
  }, 2);
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

TEST(CommandLine, BadInputsExitWithOneAndNameTheLine) {
  TempDir dir;
  write_file(dir / "text.csv", "x,y\n1,2\n3,oops\n");
  write_file(dir / "dup.csv", "1,2\n3,4\n1,2\n");
  write_file(dir / "p.csv", random_points(20, 10, 10, 2));
  write_file(dir / "notes.xyz.bak", "1 2\n");
  expect_failures(dir, {
      {"mesh text.csv -o out.csv", "text.csv:3"},
      {"mesh dup.csv -o out.csv", "dup.csv:3"},
      {"mesh p.csv -o out.stl", "out.stl"},
      {"mesh p.csv -o out.csv --box 5 5 1", "p.csv:2: point 0 lies outside the given box"},
      {"mesh p.csv -o out.geojson", "GeoJSON"},
      {"mesh notes.xyz.bak -o out.csv", "unknown input format"},
      {"mesh p.csv -o out.csv --dim 3", "--dim 3 needs 3D input"},
      {"edit p.csv --edits missing.txt", "missing.txt"},
      {"mesh p.csv -o out.csv --water 300,0,0", "bad --water '300,0,0'"},
  }, 1);
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
  EXPECT_FALSE(fs::exists(dir / "out.geojson"));
}

// The progress line appears on a terminal for work over about a second, and --quiet silences it. `script`
// gives the command a terminal.
TEST(CommandLine, ProgressBarOnATerminalOnly) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "util-linux script not installed";
  TempDir dir;
  // Large enough, on one thread, that StableWS is still running when the line is first drawn (after
  // about a second; 25,000 points on two threads finished before it on an idle machine).
  write_file(dir / "big.csv", random_points(60000, 1000, 1000, 8));
  auto on_terminal = [&](const std::string& args) {
    const std::string inner = quote(SHOREMESH_BINARY) + " " + args;
    const std::string cmd = "cd " + quote(dir.path().string()) + " && script -qec " + quote(inner) + " /dev/null >" +
                            quote((dir / "tty").string()) + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << args;
    return read_file(dir / "tty");
  };
  EXPECT_THAT(on_terminal("mesh big.csv -o big.msh --threads 1"), HasSubstr("] 2/5 StableWS on 60000 points"));
  EXPECT_THAT(on_terminal("mesh --quiet big.csv -o big.msh --threads 1"), ::testing::Not(HasSubstr("StableWS on")));
}

}  // namespace
}  // namespace shoremesh::cli_test
