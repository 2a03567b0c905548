// radkit: the command line. Each subcommand parses, calls the libraries and writes files.
#include <CLI/CLI.hpp>

#include <iostream>
#include <new>

#include "apps/common.h"
#include "util/errors.h"
#include "util/threads.h"

namespace {
/// `--threads N` on every command that runs something (commands that own a --threads, like
/// `bench solver`, keep theirs). It acts while parsing, before the command's callback runs.
void addThreadsOption(CLI::App& command) {
  for (CLI::App* sub : command.get_subcommands({})) addThreadsOption(*sub);
  if (!command.get_subcommands({}).empty() || command.get_parent() == nullptr) return;
  if (command.get_option_no_throw("--threads") != nullptr) return;
  command
      .add_option_function<int>(
          "--threads", [](const int& n) { radkit::limitThreads(n); },
          "Threads for every parallel loop (default: all cores); 1 runs serially")
      ->check(CLI::Range(1, 1024))
      ->trigger_on_parse();
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"radkit: radiosity and global-illumination toolkit"};
  app.set_version_flag("--version", std::string("radkit ") + RADKIT_VERSION);
  app.require_subcommand(1);
  radkit::app::addMeshCommand(app);
  radkit::app::addPipelineCommands(app);
  radkit::app::addBenchCommands(app);
  radkit::app::addViewCommand(app);
  radkit::app::addStudyCommand(app);
  radkit::app::addRenderCommand(app);
  radkit::app::addBrdfCommand(app);
  radkit::app::addPhotonsCommand(app);
  radkit::app::addTerrainCommand(app);
  radkit::app::addSkyCommand(app);
  radkit::app::addCloudsCommand(app);
  radkit::app::addPillarsCommand(app);
  addThreadsOption(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints help, the version or the usage error; its codes (105, 106, ...) differ by
    // kind of usage error, but every error exits 1 (docs/run.md), help and --version 0.
    return app.exit(e) == 0 ? 0 : 1;
  } catch (const std::bad_alloc&) {
    // The fix names only the size options the command that ran has.
    std::string options;
    for (const CLI::App* sub : app.get_subcommands())
      for (const CLI::App* leaf = sub; leaf;) {
        for (const char* name : {"--patches", "--max-area", "--memory-budget", "--photons",
                                 "--samples", "--spp", "--size", "--width", "--height"})
          if (leaf->get_option_no_throw(name) != nullptr &&
              options.find(std::string(name) + ",") == std::string::npos)
            options += std::string(name) + ", ";
        const auto subs = leaf->get_subcommands();
        leaf = subs.empty() ? nullptr : subs.front();
      }
    std::cerr << "radkit: error: out of memory. Fix: "
              << (options.empty()
                      ? std::string("use a smaller input")
                      : "use smaller values of " + options.substr(0, options.size() - 2))
              << ".\n";
    return 1;
  } catch (const radkit::InputError& e) {
    std::cerr << "radkit: error: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "radkit: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
