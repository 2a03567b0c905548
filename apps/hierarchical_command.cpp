#include "apps/hierarchical_command.h"

#include <cstdio>

#include "apps/common.h"

namespace radkit::app {

void addHierarchicalOptions(CLI::App& run, HierarchicalOptions& o) {
  o.methodOption =
      run.add_option("--method", o.method,
                     "dense: F for every patch pair; hierarchical: links between clusters and "
                     "elements refined to --epsilon (docs/hierarchical.md)")
          ->check(CLI::IsMember({"dense", "hierarchical"}))
          ->capture_default_str();
  run.add_option(
         "--epsilon", o.settings.epsilon,
         "Hierarchical: largest error a link may carry, as a fraction of the emitted power (of a "
         "tenth of the light leaving the surfaces where that exceeds ten times the emission)")
      ->capture_default_str();
  run.add_option("--min-area", o.settings.minArea,
                 "Hierarchical: smallest element (scene units²); 0: " +
                     fmt("%g", kDefaultMinAreaFraction) + " of the scene's area")
      ->capture_default_str();
  run.add_option("--hr-rays", o.settings.raysPerLink, "Hierarchical: visibility rays per link")
      ->capture_default_str();
  run.add_option("--hr-rounds", o.settings.rounds,
                 "Hierarchical: refine-and-solve rounds, from epsilon·4^(rounds−1) down to epsilon")
      ->capture_default_str();
  run.add_option("--gather", o.gather, "Hierarchical: gather ordering, jacobi or gauss-seidel")
      ->capture_default_str();
  run.add_option("--check-links", o.checkLinks,
                 "Hierarchical: check N links drawn at random against a Monte Carlo reference "
                 "(4096 point pairs each): links_check.csv, report.json link_check")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  run.add_option("--link-colour", o.linkColour, "Hierarchical: colour links.png by F or by power")
      ->check(CLI::IsMember({"F", "power"}))
      ->capture_default_str();
  run.add_option("--daylight-per", o.daylightPer,
                 "Hierarchical, with a sky: daylight estimated on every leaf element (elements "
                 "split along sun shadow edges) or once per input face")
      ->check(CLI::IsMember({"element", "face"}))
      ->capture_default_str();
}

void finishHierarchicalOptions(HierarchicalOptions& o) {
  o.settings.order = parseGatherOrder(o.gather);
  o.settings.elementDaylight = o.daylightPer == "element";
}

}  // namespace radkit::app
