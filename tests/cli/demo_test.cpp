// `make demo` end to end: scripts/demo.sh with the built binary writes its pictures, meshes and edit log,
// and its own check (the edited point set equals a fresh run on the edited input) passes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

TEST(Demo, RunsAndWritesWhatItAnnounces) {
  TempDir dir;
  const fs::path script = fs::path(SHOREMESH_SAMPLES_DIR).parent_path() / "scripts" / "demo.sh";
  const std::string cmd = "bash " + quote(script.string()) + " " + quote(SHOREMESH_BINARY) + " " +
                          quote((dir / "out").string()) + " >" + quote((dir / "log").string()) + " 2>&1";
  const int status = std::system(cmd.c_str());
  const std::string log = read_file(dir / "log");
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << log;
  EXPECT_THAT(log, ::testing::HasSubstr("identical: superior_edited.csv = shoremesh mesh superior_edited.rings"));
  EXPECT_THAT(log, ::testing::ContainsRegex("line 2: moved id 600 to .*: \\+[0-9]+ Steiner, -[0-9]+ Steiner, [0-9]+ elements changed, [0-9.e+]+ ms"));
  for (const char* f : {"superior.png", "superior_quality.png", "change_move.png", "change_add.png", "superior_edited.png",
                        "superior.msh", "superior_edited.msh", "superior_edited.geojson", "edit_log.txt"})
    EXPECT_GT(fs::file_size(dir / "out" / f), 100u) << f;
  EXPECT_THAT(read_file(dir / "out" / "edit_log.txt"), ::testing::Not(::testing::HasSubstr("error")));
}

}  // namespace
}  // namespace shoremesh::cli_test
