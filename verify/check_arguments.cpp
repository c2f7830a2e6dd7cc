#include "verify/check_arguments.hpp"

#include "verify/check_json.hpp"
#include "verify/check_proofs.hpp"
#include "verify/coupled_loops.hpp"
#include "verify/exact_point.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace linkbox::verify {

namespace {

// The subsystem the certificate speaks of and its proved image, which the stored image must hold.
std::optional<Box> subsystem_image(const formulate::NaturalSystem& sys, const nlohmann::json& cluster,
                                   std::vector<model::Polynomial>& eqs, newton::Certificate& cert) {
  cert = certificate_from(cluster.at("certificate"));
  if (!equations_named(cluster, "subsystem", sys.equations, eqs)) return std::nullopt;
  auto image = proved_image(eqs, cert);
  if (!image || !encloses(box_from(cluster.at("certificate").at("image")), *image)) return std::nullopt;
  return image;
}

bool unique_claimed(const nlohmann::json& cluster) {
  return cluster.at("certificate").value("unique_in_hull", false);
}

}  // namespace

std::optional<Box> recheck_exact_root(const formulate::NaturalSystem& sys, const nlohmann::json& cluster,
                                      const Box& start) {
  std::vector<model::Polynomial> eqs;
  newton::Certificate cert;
  const auto image = sys.links.empty() ? subsystem_image(sys, cluster, eqs, cert) : std::nullopt;
  const auto exact = cluster.value("exact_root", std::vector<std::string>{});
  if (!image || exact.empty() || !exact_root_in(sys.equations, exact, *image)) return std::nullopt;
  if (unique_claimed(cluster) && !unique_over(eqs, start, cert)) return std::nullopt;
  return image;
}

std::optional<Box> recheck_coupled_loops(const formulate::Formulation& f, std::uint64_t chart,
                                         const nlohmann::json& cluster, const Box& start) {
  std::vector<model::Polynomial> eqs;
  newton::Certificate cert;
  const auto image = subsystem_image(f.natural(chart), cluster, eqs, cert);
  if (!image) return std::nullopt;
  const CoupledRoom room = coupled_room(eqs, start, cert);
  if (!room.unique || (!room.cluster && unique_claimed(cluster)) ||
      !coupled_loops_root(f, chart, cert.box, room.box).proved)
    return std::nullopt;
  return image;
}

}  // namespace linkbox::verify
