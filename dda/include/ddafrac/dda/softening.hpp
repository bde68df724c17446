#pragma once
// Linear softening of a virtual joint with fracture energy G_f (docs/design.md §5): past its
// strength a joint's springs lose stiffness as it opens further (secant damage D), so that its
// force falls linearly to zero at the opening δc = 2·G_f/σt, having dissipated G_f·l whatever
// its length l. A brittle joint instead releases what its springs hold at the strength,
// ½·σt²·l²/K, which shrinks with the blocks.

namespace ddafrac::dda {

/// μ = δc/δ0 of a joint of length l (m) whose normal springs add up to `stiffness` (N/m per m):
/// δ0 = σt·l/stiffness is the uniform opening at its tensile strength σt (Pa), δc = 2·G_f/σt the
/// opening at which the softened force is spent (G_f in J/m²). μ ≤ 1: the springs hold more than
/// G_f·l at the strength, and the joint breaks there (brittle). 0 without a tensile strength.
double softening_ductility(double fracture_energy, double tensile_strength, double stiffness, double length);

/// μ of a joint loaded in tension and shear at once (scene::ModeInteraction::Quadratic), its
/// failure ratios r1 (tension) and r2 (shear) in the mix cos²α = r1²/(r1² + r2²): the harmonic mix
/// 1/(cos²α/μ_I + sin²α/μ_II) of the two modes' ductilities. Driven in proportion to the drive
/// √(r1² + r2²), the joint then dissipates G_I = cos²α·(μ/μ_I)·G_f and G_II = sin²α·(μ/μ_II)·G_IIf
/// per unit length, which meet G_I/G_f + G_II/G_IIf = 1 (the linear energy criterion of mixed-mode
/// cohesive laws). A mode with μ = 0 (brittle) in the mix makes the joint brittle; either pure mode
/// gives its own μ.
double mixed_mode_ductility(double r1, double r2, double tensile_ductility, double shear_ductility);

/// Damage of a joint driven to x, the largest failure ratio its springs would carry undamaged
/// (x = δ/δ0 in uniform tension): 0 up to x = 1, then the secant damage of the linear branch,
/// 1 − (μ − x)/(x·(μ − 1)), reaching 1 (broken) at x = μ; with μ ≤ 1, 1 as soon as x > 1.
double softening_damage(double drive, double ductility);

}  // namespace ddafrac::dda
