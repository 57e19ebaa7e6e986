#pragma once
/// \file One registration function per subcommand; each stores its exit code in `result`.

#include <CLI/CLI.hpp>

namespace dynmesh::cli {

void register_flip(CLI::App& root, int& result);
void register_worsen(CLI::App& root, int& result);
void register_stats(CLI::App& root, int& result);
void register_check(CLI::App& root, int& result);
void register_sample(CLI::App& root, int& result);
void register_experiment(CLI::App& root, int& result);
void register_quadtree(CLI::App& root, int& result);
void register_deform(CLI::App& root, int& result);
void register_probe(CLI::App& root, int& result);
void register_skin(CLI::App& root, int& result);

}  // namespace dynmesh::cli
