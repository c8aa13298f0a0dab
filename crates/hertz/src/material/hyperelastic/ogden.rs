//! Ogden (`OgdenCompressibleMat`): W = Σ_p μ_p/α_p (J^{−α_p/3} T_(α_p/2) − 3) + ½K(ln J)²,
//! T_(m) = Σ_a λ_a^{2m} (up to 7 terms). Small-strain G = ½ Σ μ_p α_p.

use super::{Energy, H};
use crate::material::spectral::{Log, Power, Scalar1};

#[derive(Debug, Clone, PartialEq)]
pub struct Ogden {
    pub alpha: Vec<f64>,
    pub mu: Vec<f64>,
    pub k: f64,
}

impl Energy for Ogden {
    fn functions(&self) -> Vec<Box<dyn Scalar1>> {
        let mut g: Vec<Box<dyn Scalar1>> = vec![Box::new(Log)];
        for a in &self.alpha {
            g.push(Box::new(Power(0.5 * a)));
        }
        g
    }

    fn invariants(&self) -> bool {
        false
    }

    fn phi(&self, t: &[H]) -> H {
        let ln_j = t[0].scale(0.5);
        let mut w = H::cst(0.0);
        for (p, (&a, &m)) in self.alpha.iter().zip(&self.mu).enumerate() {
            let ja = t[0].scale(-a / 6.0).exp();
            w = w.add(ja.mul(t[1 + p]).add(H::cst(-3.0)).scale(m / a));
        }
        w.add(ln_j.mul(ln_j).scale(0.5 * self.k))
    }

    fn moduli(&self) -> (f64, f64) {
        (
            0.5 * self
                .alpha
                .iter()
                .zip(&self.mu)
                .map(|(a, m)| a * m)
                .sum::<f64>(),
            self.k,
        )
    }
}
