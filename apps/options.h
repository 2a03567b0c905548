// Command-line option groups shared by subcommands: form factors and solvers. Each group
// fills a library settings struct; the flags and defaults are stated once, here.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "radiosity/radiosity_pipeline.h"

namespace radkit::app {

struct FormFactorOptions {
  FormFactorSettings settings;
  std::string enforce;  ///< "" or "reciprocity"
  std::string storage = "double";
  std::string memoryBudget = "8GiB";
  /// Validates and converts the text options into `settings`; throws CLI::ValidationError.
  void finish();
};

struct SolverOptions {
  std::string solvers = "gauss-seidel";
  SolverSettings stopping;
  std::string norm = "relative";
  std::vector<SolverChoice> choices;  ///< filled by finish()
  void finish();
};

void addFormFactorOptions(CLI::App& command, FormFactorOptions& options);
void addSolverOptions(CLI::App& command, SolverOptions& options, const std::string& defaultSolvers);

/// "8GiB", "512MiB", "2e9" -> bytes; throws CLI::ValidationError on anything else.
std::size_t parseBytes(const std::string& text);

}  // namespace radkit::app
