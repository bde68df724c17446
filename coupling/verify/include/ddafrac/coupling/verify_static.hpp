#pragma once
// The static Brazilian disc compared three ways (issue 6): the DDA with bonded, unbreakable
// virtual joints (the continuum's twin), the deal.II FEM reference and, for the plain disc
// under Hondros arcs, the analytic series, all at the same load level.

#include "ddafrac/coupling/verify.hpp"

namespace ddafrac::coupling {

/// Plain disc (Hondros arcs) or flattened disc (pressure on the flats), with or without a slit.
VerificationReport verify_static(const scene::Scene& scene, const VerifyOptions& options);

}  // namespace ddafrac::coupling
