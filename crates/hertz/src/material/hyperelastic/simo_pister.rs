//! Simo–Pister (`SimoPisterMat`): W = ½G(T₁ − 3) − G ln J + ½k(ln J)². Its `k` multiplies
//! ½(ln J)² without an isochoric split, so it is Lamé's λ at small strain and the bulk modulus
//! is k + 2G/3 (upstream's note E = 9KG/(3K + G) with K = k is only approximate).

use super::{invariant_functions, Energy, H};
use crate::material::spectral::{Scalar1, T2, T4};

#[derive(Debug, Clone, PartialEq)]
pub struct SimoPister {
    pub g: f64,
    pub k: f64,
}

impl Energy for SimoPister {
    fn functions(&self) -> Vec<Box<dyn Scalar1>> {
        invariant_functions()
    }

    fn invariants(&self) -> bool {
        true
    }

    fn phi(&self, t: &[H]) -> H {
        let ln_j = t[0].scale(0.5);
        t[1].add(H::cst(-3.0))
            .scale(0.5 * self.g)
            .add(ln_j.scale(-self.g))
            .add(ln_j.mul(ln_j).scale(0.5 * self.k))
    }

    fn moduli(&self) -> (f64, f64) {
        (self.g, self.k + 2.0 * self.g / 3.0)
    }

    /// With C⁻¹ and ln J:
    ///   S = G (I − C⁻¹) + k ln J C⁻¹,
    ///   D_IJKL = k C⁻¹_IJ C⁻¹_KL + (G − k ln J)(C⁻¹_IK C⁻¹_JL + C⁻¹_IL C⁻¹_JK).
    fn closed_form(&self, c: &T2, s: &mut T2, d: &mut T4) -> bool {
        let (g, k) = (self.g, self.k);
        let det = crate::fem::geometry::det3(c);
        let ci = crate::fem::geometry::inverse3(c, det);
        let ln_j = 0.5 * det.ln();
        for i in 0..3 {
            for j in 0..3 {
                s[i][j] = (k * ln_j - g) * ci[i][j] + if i == j { g } else { 0.0 };
                for kk in 0..3 {
                    for l in 0..3 {
                        d[i][j][kk][l] = k * ci[i][j] * ci[kk][l]
                            + (g - k * ln_j) * (ci[i][kk] * ci[j][l] + ci[i][l] * ci[j][kk]);
                    }
                }
            }
        }
        true
    }
}
