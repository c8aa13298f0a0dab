//! `MisesMat` in small strain: ε = ε_e + ε_p, σ = (1 − ω)·D:ε_e, the return of
//! [`super::radial_return`] from ε_e,tr = ε − ε_p,n. State: ε_p (6, engineering shears), κ,
//! β (6).

use super::{radial_return, Law3d, PlasticState, M6, V6};
use crate::model::Mises;

/// Positions in the state: ε_p, κ, β.
const PLASTIC: usize = 0;
const KAPPA: usize = 6;
const BACK: usize = 7;
const STATE_LEN: usize = 13;

#[derive(Debug, Clone)]
pub struct SmallStrainMises {
    pub params: Mises,
}

impl Law3d for SmallStrainMises {
    fn state_len(&self) -> usize {
        STATE_LEN
    }

    fn initial_state(&self, state: &mut [f64]) {
        state.fill(0.0);
    }

    fn respond3d(
        &self,
        strain: &V6,
        old: &[f64],
        stress: &mut V6,
        tangent: &mut M6,
        new: &mut [f64],
    ) -> Result<(), String> {
        let plastic: V6 = std::array::from_fn(|i| old[PLASTIC + i]);
        let back: V6 = std::array::from_fn(|i| old[BACK + i]);
        let kappa = old[KAPPA];
        let trial: V6 = std::array::from_fn(|i| strain[i] - plastic[i]);
        let r = radial_return(&self.params, &trial, kappa, &back)?;
        let kappa_new = kappa + r.dkappa;
        for i in 0..6 {
            new[PLASTIC + i] = plastic[i] + r.plastic[i];
            new[BACK + i] = r.back[i];
        }
        new[KAPPA] = kappa_new;
        damaged(&self.params, &r, kappa_new, stress, tangent);
        Ok(())
    }

    fn params(&self) -> &Mises {
        &self.params
    }

    fn plastic(&self, state: &[f64]) -> PlasticState {
        let kappa = state[KAPPA];
        PlasticState {
            strain: std::array::from_fn(|i| state[PLASTIC + i]),
            kappa,
            damage: self.params.damage.map_or(0.0, |d| d.at(kappa).0),
        }
    }
}

/// σ = (1 − ω(κ))·σ_eff and its tangent (1 − ω)·D_eff − ω′ σ_eff ⊗ dκ/dε (the last term only
/// where κ grows).
pub(super) fn damaged(
    m: &Mises,
    r: &super::Returned,
    kappa: f64,
    stress: &mut V6,
    tangent: &mut M6,
) {
    let (omega, domega) = m.damage.map_or((0.0, 0.0), |d| d.at(kappa));
    for i in 0..6 {
        stress[i] = (1.0 - omega) * r.stress[i];
        for j in 0..6 {
            tangent[i][j] =
                (1.0 - omega) * r.tangent[i][j] - domega * r.stress[i] * r.dkappa_dstrain[j];
        }
    }
}
