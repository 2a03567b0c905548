// radkit brdf: the energy a single-scattering microfacet BRDF loses, for the lab. One JSON
// object with the directional albedo E(μ) (F = 1) and E_avg, or with --table a CSV of E
// over a grid of μ and α.
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "bsdf/microfacet.h"

namespace radkit::app {

namespace {

/// Quadrature strata per axis for E(μ) (midpoint rule on the visible-normal warp).
constexpr int kStrata = 128;
/// μ nodes of the E(μ) table behind E_avg and the compensation lobe.
constexpr int kTableNodes = 64;

struct BrdfCommand {
  std::string model = "cook-torrance", masking = "height-correlated";
  double alpha = 0.5, mu = 1;
  bool compensated = false, table = false;
};

void checkUnitInterval(const char* name, double v) {
  if (!(v > 0 && v <= 1))
    throw CLI::ValidationError(name, std::to_string(v) + " is outside (0, 1]");
}

/// E with F = 1: single scattering, plus ∫ f_ms μi dωi = 1 − E_table(μ) when compensated.
double albedo(const GgxDistribution& d, MaskingShadowing g, double mu, bool compensated,
              const MicrofacetAlbedoTable* t) {
  const double e = directionalAlbedo(d, g, mu, kStrata);
  return compensated ? e + (1 - t->albedo(mu)) : e;
}

/// E_avg of the compensated BRDF, 2 ∫ E μ dμ by the midpoint rule on 32 nodes.
double averageAlbedo(const GgxDistribution& d, MaskingShadowing g, const MicrofacetAlbedoTable& t) {
  const int n = 32;
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double mu = (k + 0.5) / n;
    sum += albedo(d, g, mu, true, &t) * mu;
  }
  return 2 * sum / n;
}

void runBrdf(const BrdfCommand& cmd) {
  if (cmd.model != "cook-torrance")
    throw CLI::ValidationError("--model", "unknown model \"" + cmd.model +
                                              "\": only cook-torrance has an energy loss to show");
  const MaskingShadowing g = parseMaskingShadowing(cmd.masking);
  if (cmd.table) {
    std::printf("alpha,mu,E%s\n", cmd.compensated ? ",E_compensated" : "");
    for (int a = 1; a <= 10; ++a) {
      const GgxDistribution d(0.1 * a);
      const MicrofacetAlbedoTable t(d, g, kTableNodes);
      for (int m = 1; m <= 20; ++m) {
        const double mu = 0.05 * m, e = directionalAlbedo(d, g, mu, kStrata);
        if (cmd.compensated)
          std::printf("%.2f,%.2f,%.6f,%.6f\n", 0.1 * a, mu, e, e + 1 - t.albedo(mu));
        else
          std::printf("%.2f,%.2f,%.6f\n", 0.1 * a, mu, e);
      }
    }
    return;
  }
  checkUnitInterval("--alpha", cmd.alpha);
  checkUnitInterval("--mu", cmd.mu);
  const GgxDistribution d(cmd.alpha);
  const MicrofacetAlbedoTable t(d, g, kTableNodes);
  nlohmann::json j{
      {"model", cmd.model},
      {"G", maskingShadowingName(g)},
      {"alpha", cmd.alpha},
      {"mu", cmd.mu},
      {"compensated", cmd.compensated},
      {"E", albedo(d, g, cmd.mu, cmd.compensated, &t)},
      {"E_single_scattering", directionalAlbedo(d, g, cmd.mu, kStrata)},
      {"E_avg", cmd.compensated ? averageAlbedo(d, g, t) : t.average()},
      {"E_avg_single_scattering", t.average()},
      {"energy_lost", cmd.compensated ? 0.0 : 1 - directionalAlbedo(d, g, cmd.mu, kStrata)}};
  std::cout << j.dump(2) << std::endl;
}

}  // namespace

void addBrdfCommand(CLI::App& app) {
  auto cmd = std::make_shared<BrdfCommand>();
  CLI::App* sub = app.add_subcommand("brdf",
                                     "Directional albedo E(mu) and E_avg of a microfacet BRDF (F = "
                                     "1): the energy single scattering loses");
  sub->add_option("--model", cmd->model, "BRDF model (cook-torrance)")->capture_default_str();
  sub->add_option("--alpha", cmd->alpha, "GGX alpha = roughness², in (0, 1]")
      ->capture_default_str();
  sub->add_option("--mu", cmd->mu, "cos theta of the outgoing direction, in (0, 1]")
      ->capture_default_str();
  sub->add_option("--g", cmd->masking,
                  "Shadowing-masking: height-correlated, separable, schlick, cook-torrance")
      ->capture_default_str();
  sub->add_flag("--compensated", cmd->compensated, "Add the Kulla-Conty multiple-scattering lobe");
  sub->add_flag("--table", cmd->table, "Print E over alpha = 0.1..1 and mu = 0.05..1 as CSV");
  sub->callback([cmd] { runBrdf(*cmd); });
}

}  // namespace radkit::app
