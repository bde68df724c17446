#include "ddafrac/coupling/verify.hpp"

#include <fmt/core.h>

#include <stdexcept>
#include <variant>

#include "ddafrac/coupling/verify_dynamic.hpp"
#include "ddafrac/coupling/verify_static.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

namespace {
bool is_impact(const scene::Scene& s) { return std::holds_alternative<meshes::ImpactDisc>(s.geometry); }
bool has_slit(const scene::Scene& s) {
  if (std::holds_alternative<meshes::SlitDisc>(s.geometry)) return true;
  const auto* flat = std::get_if<meshes::FlattenedDisc>(&s.geometry);
  return flat && flat->slit;
}
}  // namespace

std::vector<std::string> missing_tolerances(const scene::Scene& scene) {
  std::vector<std::string> missing;
  const scene::Verification none;
  const scene::Verification& v = scene.verification ? *scene.verification : none;
  auto need = [&](const std::optional<double>& value, const char* key) {
    if (!value) missing.push_back(std::string("verification.") + key);
  };
  if (is_impact(scene)) {
    need(v.arrival_time, "arrival_time");
    need(v.gauge_rms, "gauge_rms");
  } else {
    need(v.load, "load");
    if (!has_slit(scene)) need(v.centre_stress, "centre_stress");  // a slit takes the centre away
    need(v.field_l2, "field_l2");
  }
  return missing;
}

VerificationReport verify_scene(const scene::Scene& scene, const VerifyOptions& options) {
  const auto missing = missing_tolerances(scene);
  if (!missing.empty()) {
    std::string list;
    for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
    throw std::invalid_argument(fmt::format("{}: cannot verify without {} (add them to its [verification] table)",
                                            scene.source.empty() ? scene.name : scene.source.string(), list));
  }
  if (is_impact(scene)) return verify_dynamic(scene, options);
  if (std::holds_alternative<meshes::MshFile>(scene.geometry))
    throw std::invalid_argument(
        fmt::format("{}: verify needs a generated disc (plain, flattened, slit or impact), not a .msh file",
                    scene.source.string()));
  return verify_static(scene, options);
}

}  // namespace ddafrac::coupling
