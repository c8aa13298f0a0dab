//! Mooney–Rivlin (`MooneyRivlinCompressibleMat`): W = C₁(J^{−2/3} I₁ − 3) + C₂(J^{−4/3} I₂ − 3)
//! + ½K(ln J)², I₂ = ½(T₁² − T₂); neo-Hookean with C₂ = 0. Small-strain G = 2(C₁ + C₂).

use super::{invariant_functions, Energy, H};
use crate::material::spectral::Scalar1;

#[derive(Debug, Clone, PartialEq)]
pub struct MooneyRivlin {
    pub c1: f64,
    pub c2: f64,
    pub k: f64,
}

impl Energy for MooneyRivlin {
    fn functions(&self) -> Vec<Box<dyn Scalar1>> {
        invariant_functions()
    }

    fn invariants(&self) -> bool {
        true
    }

    fn phi(&self, t: &[H]) -> H {
        let ln_j = t[0].scale(0.5);
        let i1 = t[1];
        let i2 = t[1].mul(t[1]).add(t[2].scale(-1.0)).scale(0.5);
        let j23 = t[0].scale(-1.0 / 3.0).exp();
        let j43 = t[0].scale(-2.0 / 3.0).exp();
        j23.mul(i1)
            .add(H::cst(-3.0))
            .scale(self.c1)
            .add(j43.mul(i2).add(H::cst(-3.0)).scale(self.c2))
            .add(ln_j.mul(ln_j).scale(0.5 * self.k))
    }

    fn moduli(&self) -> (f64, f64) {
        (2.0 * (self.c1 + self.c2), self.k)
    }
}
