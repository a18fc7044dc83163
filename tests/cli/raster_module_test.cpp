// The raster module (docs/raster_module.md): a run that reads and writes no raster loads none of GDAL,
// OpenImageIO and OpenCV; a run that does loads libshoremesh_raster.so from beside the tool; a module that
// cannot be loaded stops the run naming it and the loader's reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cli_test_util.hpp"

namespace shoremesh::cli_test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// Runs `env ENV shoremesh ARGS` in `dir` (ENV: env's options and assignments), with glibc's loader log of
// the tool in dir/ld.<pid>; the log's text comes back in `loaded`.
struct LoggedRun {
  RunResult result;
  std::string loaded;
};
LoggedRun run_logged(const TempDir& dir, const std::string& env, const std::string& args) {
  const fs::path out = dir / ".stdout", err = dir / ".stderr";
  const std::string cmd = "cd " + quote(dir.path().string()) + " && env " + env + " LD_DEBUG=libs LD_DEBUG_OUTPUT=" +
                          quote((dir / "ld").string()) + " " + quote(SHOREMESH_BINARY) + " " + args + " </dev/null >" +
                          quote(out.string()) + " 2>" + quote(err.string());
  const int status = std::system(cmd.c_str());
  LoggedRun r;
  r.result.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.result.out = read_file(out);
  r.result.err = read_file(err);
  for (const auto& entry : fs::directory_iterator(dir.path()))
    if (entry.path().filename().string().rfind("ld.", 0) == 0) r.loaded += read_file(entry.path());
  return r;
}

// A lake of 0.1 degrees with an island, lon/lat: projected with PROJ's scale measured, no raster anywhere.
const char* kLonLatRings =
    "-87.0,47.0\n-86.9,47.0\n-86.9,47.1\n-87.0,47.1\n-87.0,47.0\n\n"
    "-86.96,47.04\n-86.96,47.06\n-86.94,47.06\n-86.94,47.04\n-86.96,47.04\n";

TEST(RasterModule, RingFileRunLoadsNoRasterLibrary) {
  TempDir dir;
  write_file(dir / "lake.csv", kLonLatRings);
  // A module path that cannot load: the run must not need it.
  const LoggedRun r = run_logged(dir, "SHOREMESH_RASTER_MODULE=" + quote((dir / "absent.so").string()),
                                 "mesh lake.csv --lonlat -o lake.msh");
  ASSERT_EQ(r.result.code, 0) << r.result.err;
  EXPECT_TRUE(fs::exists(dir / "lake.msh"));
  ASSERT_THAT(r.loaded, HasSubstr("libproj"));  // the log is there (and PROJ is linked)
  for (const char* library : {"libgdal", "libOpenImageIO", "libopencv", "libshoremesh_raster"})
    EXPECT_THAT(r.loaded, Not(HasSubstr(library))) << library;
}

TEST(RasterModule, ImageRunLoadsTheModuleBesideTheTool) {
  TempDir dir;
  const LoggedRun r = run_logged(dir, "-u SHOREMESH_RASTER_MODULE",
                                 "info " + quote(superior_mask()) + " --largest-water --spacing 8000");
  ASSERT_EQ(r.result.code, 0) << r.result.err;
  EXPECT_THAT(r.result.out, HasSubstr("rings"));
  const std::string module = (fs::path(SHOREMESH_BINARY).parent_path() / "libshoremesh_raster.so").string();
  EXPECT_THAT(r.loaded, HasSubstr(module));
  EXPECT_THAT(r.loaded, HasSubstr("libgdal"));
}

TEST(RasterModule, MissingModuleNamesItAndTheReason) {
  TempDir dir;
  const std::string absent = (dir / "absent" / "libshoremesh_raster.so").string();
  const LoggedRun r = run_logged(dir, "SHOREMESH_RASTER_MODULE=" + quote(absent),
                                 "mesh " + quote(superior_mask()) + " --largest-water --spacing 8000 -o x.msh");
  EXPECT_EQ(r.result.code, 3);
  EXPECT_THAT(r.result.err, HasSubstr("the raster module libshoremesh_raster.so"));
  EXPECT_THAT(r.result.err, HasSubstr(absent + ": cannot open shared object file"));
  EXPECT_FALSE(fs::exists(dir / "x.msh"));
}

TEST(RasterModule, ALibraryThatIsNotTheModuleIsRefused) {
  TempDir dir;
  // The C library is a shared object every process has loaded, without the module's entry.
  const LoggedRun probe = run_logged(dir, "", "--version");
  std::string libc;
  for (const std::string& line : lines_of(probe.loaded))
    if (const auto at = line.find("calling init: "); at != std::string::npos && line.ends_with("/libc.so.6"))
      libc = line.substr(at + 14);
  ASSERT_FALSE(libc.empty()) << probe.loaded;
  const LoggedRun r = run_logged(dir, "SHOREMESH_RASTER_MODULE=" + quote(libc),
                                 "mesh --dem " + quote(samples("salish/salish_sea_topobathy.tif")) + " -o x.14");
  EXPECT_EQ(r.result.code, 3);
  EXPECT_THAT(r.result.err, HasSubstr(libc + ": not shoremesh's raster module"));
}

}  // namespace
}  // namespace shoremesh::cli_test
