//! Why a large-deformation step may fail for the material rather than the mesh or the contact:
//! `IsoLE` with `nlgeo 1` is the St. Venant–Kirchhoff law, S = λ tr(E) I + 2μ E. Its nominal
//! stress in uniaxial compression, P = E·λ(λ² − 1)/2, falls once the stretch λ is below 1/√3
//! (42 % compression), and its energy stays finite as F → 0, so an element can invert at a
//! finite energy: no contact law, penalty or step size converges past that. A block pressed
//! 50 % by a rigid plane fails in every law with it and converges with a neo-Hookean material.

use crate::assembly::Assembler;
use crate::material::spectral::eigen_symmetric;
use crate::model::{MaterialLaw, Model};

/// The stretch below which a failed step names the St. Venant–Kirchhoff law as the likely cause:
/// local compression of 30 %, on the way to the law's limit 1/√3 ≈ 0.577.
const SOFTENING_STRETCH: f64 = 0.7;

/// A sentence for a failed step's message when, at the last converged state `u`, an integration
/// point of an `IsoLE` element with `nlgeo 1` is compressed below [`SOFTENING_STRETCH`]: the
/// element, its smallest principal stretch and what to use instead.
pub fn softening_hint(model: &Model, asm: &Assembler, u: &[f64]) -> Option<String> {
    let svk = |e: usize| {
        let el = &model.elements[e];
        el.nlgeo
            && matches!(
                model.materials[el.material].law,
                MaterialLaw::LinearElastic { .. }
            )
    };
    if !(0..model.elements.len()).any(svk) {
        return None;
    }
    let states = asm.evaluate(u, false, true, None, &[]).ok()?.states?;
    let mut worst: Option<(f64, usize)> = None;
    for (e, gps) in states.iter().enumerate() {
        if !svk(e) {
            continue;
        }
        for gp in gps {
            let f = gp.f;
            let c: [[f64; 3]; 3] = std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..3).map(|k| f[k][i] * f[k][j]).sum())
            });
            let (eig, _) = eigen_symmetric(&c);
            let stretch = eig
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min)
                .max(0.0)
                .sqrt();
            if worst.is_none_or(|(s, _)| stretch < s) {
                worst = Some((stretch, e));
            }
        }
    }
    let (stretch, e) = worst.filter(|&(s, _)| s < SOFTENING_STRETCH)?;
    Some(format!(
        "element {} is IsoLE with nlgeo 1, the St. Venant–Kirchhoff law, and was compressed to a \
         principal stretch of {stretch:.3} at the last converged state: that law's stress falls \
         below a stretch of 1/√3 ≈ 0.577 and lets elements invert at a finite energy, whatever \
         the contact or the step; for large compression use a hyperelastic material \
         (MooneyRivlinCompressibleMat, OgdenCompressibleMat)",
        model.elements[e].label
    ))
}
