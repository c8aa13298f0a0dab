//! `MisesMat` for bars: rate-independent plasticity with the von Mises (in 1D: |σ|) yield
//! condition and linear isotropic hardening, σ_y(κ) = σ₀ + H·κ, κ the accumulated plastic strain
//! (OOFEM's `MisesMat` with `sig0` and `H`, without damage). Backward-Euler return map: the trial
//! stress σ* = E(ε − ε_p); if |σ*| > σ_y(κ), Δκ = (|σ*| − σ_y(κ)) / (E + H), ε_p += Δκ·sign σ*,
//! σ = σ* − E·Δκ·sign σ*, and the consistent tangent E·H/(E + H). State: (ε_p, κ).

use super::law::PointLaw;

/// Relative excess over the yield stress below which a point counts as elastic.
const YIELD_TOL: f64 = 1e-12;

/// Uniaxial von Mises plasticity with linear isotropic hardening.
#[derive(Debug, Clone, Copy)]
pub struct UniaxialMises {
    pub young: f64,
    /// Initial yield stress σ₀.
    pub yield_stress: f64,
    /// Hardening modulus H (0: perfectly plastic).
    pub hardening: f64,
}

impl PointLaw for UniaxialMises {
    fn components(&self) -> usize {
        1
    }

    fn state_len(&self) -> usize {
        2
    }

    fn respond(
        &self,
        strain: &[f64],
        old: &[f64],
        out: &mut super::law::Response,
    ) -> Result<(), String> {
        let (stress, tangent, new) = (&mut *out.stress, &mut *out.tangent, &mut *out.state);
        let (e, h) = (self.young, self.hardening);
        let (plastic, kappa) = (old[0], old[1]);
        let trial = e * (strain[0] - plastic);
        let limit = self.yield_stress + h * kappa;
        let excess = trial.abs() - limit;
        // A point the last step left on the yield surface is there only to round-off: within
        // it, it responds elastically (so a step that unloads it starts with the elastic
        // tangent, not the hardening one).
        if excess <= YIELD_TOL * limit {
            stress[0] = trial;
            tangent[0] = e;
            new[..2].copy_from_slice(&old[..2]);
        } else {
            let dk = excess / (e + h);
            let sign = trial.signum();
            stress[0] = trial - e * dk * sign;
            tangent[0] = e * h / (e + h);
            new[0] = plastic + dk * sign;
            new[1] = kappa + dk;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::law::respond_into;

    /// The tangent is the derivative of the stress at fixed old state, elastic and plastic.
    #[test]
    fn tangent_is_the_derivative_of_the_return_map() {
        let m = UniaxialMises {
            young: 200.0,
            yield_stress: 1.0,
            hardening: 20.0,
        };
        let old = [0.002, 0.003];
        for eps in [0.004, 0.01, -0.02] {
            let (mut s, mut t, mut n) = ([0.0f64], [0.0f64], [0.0; 2]);
            respond_into(&m, &[eps], &old, (&mut s, &mut t, &mut n)).unwrap();
            let h = 1e-7;
            let (mut sp, mut sm, mut tt, mut nn) = ([0.0], [0.0], [0.0], [0.0; 2]);
            respond_into(&m, &[eps + h], &old, (&mut sp, &mut tt, &mut nn)).unwrap();
            respond_into(&m, &[eps - h], &old, (&mut sm, &mut tt, &mut nn)).unwrap();
            let fd = (sp[0] - sm[0]) / (2.0 * h);
            assert!(
                (fd - t[0]).abs() < 1e-6 * t[0].abs(),
                "ε {eps}: {fd} vs {}",
                t[0]
            );
            // On the yield surface after a plastic step, inside it after an elastic one.
            let limit = m.yield_stress + m.hardening * n[1];
            assert!(
                s[0].abs() <= limit * (1.0 + 1e-12),
                "ε {eps}: |σ| {} > {limit}",
                s[0]
            );
        }
    }
}
