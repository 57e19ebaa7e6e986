/// dynmesh: dynamic meshing from the command line. One subcommand per job; see --help.
#include <CLI/CLI.hpp>

#include "commands.hpp"

int main(int argc, char** argv) {
    CLI::App app{"dynmesh: meshes that stay good while the shape changes"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "dynmesh 0.1.0");
    int result = 0;
    dynmesh::cli::register_flip(app, result);
    dynmesh::cli::register_worsen(app, result);
    dynmesh::cli::register_stats(app, result);
    dynmesh::cli::register_check(app, result);
    dynmesh::cli::register_sample(app, result);
    dynmesh::cli::register_experiment(app, result);
    dynmesh::cli::register_quadtree(app, result);
    dynmesh::cli::register_deform(app, result);
    CLI11_PARSE(app, argc, argv);
    return result;
}
