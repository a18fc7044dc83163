// shoremesh: well-spaced points and quality meshes of lakes and coastlines.
#include <CLI/CLI.hpp>

#include <iostream>
#include <map>
#include <string>

#include "commands.hpp"
#include "shoremesh/error.hpp"

int main(int argc, char** argv) {
  using namespace shoremesh::tool;
  CLI::App app{"shoremesh: size-optimal well-spaced point sets and quality meshes of lakes and coastlines\n"
               "(StableWS of Acar, Cotter, Hudson, Turkoglu, 'Dynamic Well-Spaced Point Sets', SoCG 2010)."};
  app.set_version_flag("--version", std::string("shoremesh ") + SHOREMESH_VERSION);
  app.footer(
      "Exit codes: 0 ok, 1 bad input (a file, an edit line), 2 usage (the command line), 3 internal error.\n"
      "'shoremesh COMMAND --help' shows each command's options and an example.");
  app.require_subcommand(1);
  const std::map<std::string, Command> commands = {{"mesh", add_mesh_command(app)},
                                                   {"edit", add_edit_command(app)},
                                                   {"info", add_info_command(app)},
                                                   {"bench", add_bench_command(app)},
                                                   {"terrain", add_terrain_command(app)},
                                                   {"serve", add_serve_command(app)}};

  if (argc > 1 && argv[1][0] != '-' && !commands.contains(argv[1])) {
    std::cerr << "shoremesh: unknown command '" << argv[1] << "' (mesh, edit, info, bench, terrain, serve; see shoremesh --help)\n";
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::cerr << "shoremesh: " << e.what() << "\n(see shoremesh"
              << (argc > 1 && commands.contains(argv[1]) ? std::string(" ") + argv[1] : std::string()) << " --help)\n";
    return kExitUsage;
  }
  try {
    for (const auto& [name, run] : commands)
      if (app.got_subcommand(name)) return run();
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
