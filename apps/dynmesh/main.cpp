/// dynmesh: dynamic meshing from the command line. One subcommand per job; see --help.
#include <CLI/CLI.hpp>

#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/io/output_set.hpp"
#include "dynmesh/version.hpp"

int main(int argc, char** argv) {
    namespace cli = dynmesh::cli;
    CLI::App app{"dynmesh: meshes that stay good while the shape changes"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("dynmesh ") + dynmesh::kVersion);
    app.footer(cli::exit_code_help());
    dynmesh::install_output_cleanup_on_signals();  // a killed run leaves no temporary
    int result = 0;
    cli::register_flip(app, result);
    cli::register_worsen(app, result);
    cli::register_stats(app, result);
    cli::register_check(app, result);
    cli::register_sample(app, result);
    cli::register_experiment(app, result);
    cli::register_quadtree(app, result);
    cli::register_deform(app, result);
    cli::register_probe(app, result);
    cli::register_skin(app, result);
    // "dynmesh frob": name the unknown subcommand instead of CLI11's "a subcommand is required".
    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands({}))
            known = known || sub->check_name(argv[1]);
        if (!known) {
            std::cerr << "dynmesh: usage error: unknown subcommand '" << argv[1]
                      << "' (see dynmesh --help)" << std::endl;
            return cli::kExitUsage;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line, the usage exit code of the contract.
        std::string msg = e.what();
        for (char& c : msg)
            if (c == '\n') c = ' ';
        std::cerr << "dynmesh: usage error: " << msg << " (see dynmesh --help)" << std::endl;
        return cli::kExitUsage;
    }
    return result;
}
