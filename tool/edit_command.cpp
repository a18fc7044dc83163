// shoremesh edit INPUT... --edits FILE|-: build once, then apply a stream of edits dynamically.
#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "edit_session.hpp"
#include "input_args.hpp"
#include "progress.hpp"
#include "shoremesh/error.hpp"

namespace shoremesh::tool {

namespace {

struct EditOptions {
  InputArgs in;
  std::string edits;
  bool json = false;
  bool lonlat_edits = false;
  EngineArgs engine;
  PreviewArgs preview;
  SizeArgs size;
};

void print(const nlohmann::json& reply, bool as_json) {
  std::cout << (as_json ? reply.dump() : reply_text(reply)) << std::endl;  // flushed: a program may be waiting
}

template <int D>
int run_edit(const EditOptions& opt, const io::InputSet& set, Progress& progress, std::istream& edits) {
  if (opt.lonlat_edits && (D != 2 || set.projection.is_none()))
    throw InputError("--lonlat-edits needs 2D lon/lat input (GPS, GeoJSON, a geographic image, --lonlat files)");
  progress.stage("StableWS and mesh of " + std::to_string(set.size()) + " points");
  const auto start = std::chrono::steady_clock::now();
  std::optional<SizeTerms> size = size_terms(opt.size, set);
  if (size && D != 2) throw ParameterError("size control (--max-size and the other size options) is for 2D meshes");
  EditSession<D> session(set, opt.engine.rho, parse_box<D>(opt.engine.box), opt.engine.keep_hull, opt.preview,
                         opt.lonlat_edits, std::move(size));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::vector<std::filesystem::path> inputs = input_paths(opt.in, set);
  for (const auto& p : size_paths(opt.size)) inputs.push_back(p);
  if (opt.edits != "-") inputs.emplace_back(opt.edits);
  session.set_inputs(std::move(inputs));
  progress.finish();
  if (!opt.json) std::cout << describe_input(set);
  print(session.build_reply(ms), opt.json);

  std::size_t failed = 0, line_no = 0;
  for (std::string line; std::getline(edits, line);) {
    ++line_no;
    const auto reply = session.run(line_no, line);
    if (!reply) continue;
    failed += !reply->value("ok", false);
    print(*reply, opt.json);
  }
  if (failed && !opt.json) std::cerr << "shoremesh: " << failed << " edit line(s) failed (exit code 1)\n";
  return failed ? kExitBadInput : kExitOk;
}

}  // namespace

Command add_edit_command(CLI::App& app) {
  auto opt = std::make_shared<EditOptions>();
  CLI::App* cmd = app.add_subcommand("edit", "Build once, then apply a stream of edits dynamically, reporting each change");
  add_input_options(cmd, opt->in);
  cmd->add_option("--edits", opt->edits,
                  "Edit lines from FILE, or '-' for standard input: add X Y [Z] | add X Y after ID (a shore point: the "
                  "new point joins its shoreline, after it) | remove ID | move ID X Y [Z] | "
                  "add-ring X1 Y1 X2 Y2 X3 Y3 ... | add-ring FILE (a ring: an island, a breakwater) | add-line X1 Y1 X2 Y2 ... (an open chain of constraint edges) | remove-ring N | "
                  "export PATH | preview PATH | preview-change PATH | stats ('#' comments)")
      ->required();
  cmd->add_flag("--json", opt->json, "Reply with one JSON object per line (for programs)");
  cmd->add_flag("--lonlat-edits", opt->lonlat_edits,
                "Edit lines give lon lat in degrees (lon/lat input only; projected like the input)");
  add_engine_options(cmd, opt->engine);
  add_size_options(cmd, opt->size);
  add_preview_options(cmd, opt->preview);
  cmd->footer(
      "Ids: input points are numbered from 0 in the order they were read (files in order); each add takes the next\n"
      "unused id and its reply says which; ids are never reused. Coordinates are the mesh's: metres for lon/lat\n"
      "input (the replies give lon/lat too; --lonlat-edits to give degrees), pixels for plain images.\n"
      "'export PATH.csv' writes the point set exactly as 'shoremesh mesh INPUT -o OUT.csv --box ...' writes it\n"
      "for the current input and the session's box.\n"
      "A bad edit line gets an error reply naming it and the session goes on; the exit code is then 1.\n"
      "\n"
      "Example:\n"
      "  printf 'move 10 1.5 2.5\\nadd 3 4\\nstats\\nexport final.csv\\n' | shoremesh edit points.csv --edits -");
  return [opt]() {
    std::ifstream file;
    if (opt->edits != "-") {
      file.open(opt->edits);
      if (!file) throw InputError("cannot read the edits", opt->edits);
    }
    std::istream& edits = opt->edits == "-" ? std::cin : file;
    Progress progress(!opt->in.quiet && Progress::stderr_is_terminal(), opt->in.files.size() + 1);
    opt->in.three_d = opt->engine.dim == 3;
    const io::InputSet set = read_user_inputs(opt->in, progress);
    const int dim = opt->engine.dim != 0 ? opt->engine.dim : set.dimension;
    return dim == 3 ? run_edit<3>(*opt, set, progress, edits) : run_edit<2>(*opt, set, progress, edits);
  };
}

}  // namespace shoremesh::tool
