#pragma once
// The shoremesh command line: each command registers its options on the CLI11 app and returns the
// function that runs it. main() catches errors once and maps them to exit codes.
#include <CLI/CLI.hpp>

#include <functional>

namespace shoremesh::tool {

// Exit codes (documented in --help and the README).
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInternal = 3;

using Command = std::function<int()>;

Command add_mesh_command(CLI::App& app);   // mesh_command.cpp
Command add_edit_command(CLI::App& app);   // edit_command.cpp
Command add_info_command(CLI::App& app);   // info_command.cpp
Command add_bench_command(CLI::App& app);  // bench_command.cpp
Command add_terrain_command(CLI::App& app);  // terrain_command.cpp
Command add_serve_command(CLI::App& app);  // serve_command.cpp

}  // namespace shoremesh::tool
