// shoremesh: well-spaced points and quality meshes of lakes and coastlines.
#include <CLI/CLI.hpp>

#include <iostream>

#include "commands.hpp"
#include "shoremesh/error.hpp"

int main(int argc, char** argv) {
  using namespace shoremesh::tool;
  CLI::App app{"shoremesh: size-optimal well-spaced point sets and quality meshes of lakes and coastlines\n"
               "(StableWS of Acar, Cotter, Hudson, Turkoglu, 'Dynamic Well-Spaced Point Sets', SoCG 2010)."};
  app.set_version_flag("--version", std::string("shoremesh ") + SHOREMESH_VERSION);
  app.footer("Exit codes: 0 ok, 1 bad input, 2 usage, 3 internal error.");
  app.require_subcommand(1);
  const Command mesh = add_mesh_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  try {
    if (app.got_subcommand("mesh")) return mesh();
    return kExitUsage;
  } catch (const shoremesh::InputError& e) {
    std::cerr << "shoremesh: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const shoremesh::ParameterError& e) {
    std::cerr << "shoremesh: " << e.what() << '\n';
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "shoremesh: internal error: " << e.what() << '\n';
    return kExitInternal;
  }
}
