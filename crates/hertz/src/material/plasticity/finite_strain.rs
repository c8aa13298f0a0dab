//! `MisesMat` in finite strain (`nlgeo 1`): multiplicative plasticity F = F_e·F_p with Hencky
//! elasticity, the Kirchhoff stress τ = (1 − ω)·D:ε_e of the logarithmic elastic strain
//! ε_e = ½ ln b_e, and the exponential-map return (Simo 1992; de Souza Neto, Perić & Owen,
//! box 14.3): in the logarithmic strains the return is [`super::radial_return`]'s, so plastic
//! flow is isochoric and the law reduces to the small-strain one for small strains.
//!
//! Written in the reference configuration, as the element asks (S and dS/dE from the
//! Green–Lagrange strain E): the state is C_p⁻¹ (with κ). With C_p⁻¹ = L·Lᵀ (Cholesky) and
//! b̃ = Lᵀ·C·L, which has the eigenvalues of the trial b_e = F·C_p⁻¹·Fᵀ and is its rotation,
//! ε_tr = ½ ln b̃, S = L·b̃⁻¹·τ̃·Lᵀ and the new C_p⁻¹ = L·b̃⁻¹·exp(2ε_e)·Lᵀ, τ̃ the return's
//! stress in b̃'s frame. Rotations never enter: the law is objective by construction. The
//! tangent is the exact derivative of that chain: the derivative of the matrix logarithm by
//! the Daleckii–Krein formula (divided differences of ln, exact also for equal eigenvalues),
//! the return's consistent tangent, and the products'.

use super::small_strain::damaged;
use super::{radial_return, Law3d, PlasticState, M6, V6};
use crate::material::spectral::{eigen_symmetric, T2};
use crate::material::VOIGT_PAIRS;
use crate::model::Mises;

/// Positions in the state: C_p⁻¹ (xx, yy, zz, yz, xz, xy), κ.
const CP_INV: usize = 0;
const KAPPA: usize = 6;
const STATE_LEN: usize = 7;

#[derive(Debug, Clone)]
pub struct LogStrainMises {
    pub params: Mises,
}

/// A symmetric tensor from its Voigt components; `eng`: the shears are engineering ones.
fn tensor(v: &V6, eng: bool) -> T2 {
    let mut t = [[0.0; 3]; 3];
    for (k, &(i, j)) in VOIGT_PAIRS.iter().enumerate() {
        let x = if i != j && eng { 0.5 * v[k] } else { v[k] };
        t[i][j] = x;
        t[j][i] = x;
    }
    t
}

/// The Voigt components of a (symmetrized) tensor; `eng`: doubled shears.
fn voigt(t: &T2, eng: bool) -> V6 {
    std::array::from_fn(|k| {
        let (i, j) = VOIGT_PAIRS[k];
        let x = 0.5 * (t[i][j] + t[j][i]);
        if i != j && eng {
            2.0 * x
        } else {
            x
        }
    })
}

fn mul(a: &T2, b: &T2) -> T2 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose(a: &T2) -> T2 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// Q·diag(d)·Qᵀ.
fn spectral(q: &T2, d: &[f64; 3]) -> T2 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|a| q[i][a] * d[a] * q[j][a]).sum()))
}

/// The lower Cholesky factor of a symmetric positive definite tensor.
fn cholesky(a: &T2) -> Option<T2> {
    let mut l = [[0.0; 3]; 3];
    for j in 0..3 {
        let d = a[j][j] - (0..j).map(|k| l[j][k] * l[j][k]).sum::<f64>();
        if !(d > 0.0) {
            return None;
        }
        l[j][j] = d.sqrt();
        for i in j + 1..3 {
            l[i][j] = (a[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>()) / l[j][j];
        }
    }
    Some(l)
}

/// (ln a − ln b)/(a − b), and 1/a where a = b (a series near it).
fn log_divided(a: f64, b: f64) -> f64 {
    let x = a / b - 1.0;
    if x.abs() < 1e-4 {
        (1.0 - x / 2.0 + x * x / 3.0 - x * x * x / 4.0 + x.powi(4) / 5.0) / b
    } else {
        (a.ln() - b.ln()) / (a - b)
    }
}

impl Law3d for LogStrainMises {
    fn state_len(&self) -> usize {
        STATE_LEN
    }

    fn initial_state(&self, state: &mut [f64]) {
        state.fill(0.0);
        state[CP_INV..CP_INV + 3].fill(1.0);
    }

    fn respond3d(
        &self,
        strain: &V6,
        old: &[f64],
        stress: &mut V6,
        tangent: &mut M6,
        new: &mut [f64],
    ) -> Result<(), String> {
        let mut c = tensor(strain, true);
        for (i, row) in c.iter_mut().enumerate() {
            for x in row.iter_mut() {
                *x *= 2.0;
            }
            row[i] += 1.0;
        }
        let cp_inv = tensor(&std::array::from_fn(|i| old[CP_INV + i]), false);
        let l = cholesky(&cp_inv).ok_or("the plastic deformation C_p is not positive definite")?;
        let lt = transpose(&l);
        let bt = mul(&lt, &mul(&c, &l));
        let (lam, q) = eigen_symmetric(&bt);
        if lam.iter().any(|&x| !(x > 0.0)) {
            return Err(format!(
                "element inverted (elastic stretch eigenvalue {:.3e})",
                lam.iter().cloned().fold(f64::INFINITY, f64::min)
            ));
        }
        let eps_tr = spectral(&q, &lam.map(|x| 0.5 * x.ln()));
        let kappa = old[KAPPA];
        // Kinematic hardening is refused with `nlgeo 1` (input): no back stress here.
        let r = radial_return(&self.params, &voigt(&eps_tr, true), kappa, &[0.0; 6])?;
        let kappa_new = kappa + r.dkappa;
        let (mut tau, mut dtau) = ([0.0; 6], [[0.0; 6]; 6]);
        damaged(&self.params, &r, kappa_new, &mut tau, &mut dtau);
        let tau_t = tensor(&tau, false);
        let bt_inv = spectral(&q, &lam.map(|x| 1.0 / x));
        let s = mul(&l, &mul(&mul(&bt_inv, &tau_t), &lt));
        *stress = voigt(&s, false);
        // The new C_p⁻¹ = L·b̃⁻¹·exp(2ε_e)·Lᵀ, ε_e coaxial with b̃.
        let eps_e = tensor(
            &std::array::from_fn(|i| voigt(&eps_tr, true)[i] - r.plastic[i]),
            true,
        );
        let in_frame = mul(&transpose(&q), &mul(&eps_e, &q));
        let d: [f64; 3] = std::array::from_fn(|a| (2.0 * in_frame[a][a]).exp() / lam[a]);
        let cp_new = mul(&l, &mul(&spectral(&q, &d), &lt));
        new[CP_INV..CP_INV + 6].copy_from_slice(&voigt(&cp_new, false));
        new[KAPPA] = kappa_new;
        // dS/dE, column by column.
        let g: [[f64; 3]; 3] =
            std::array::from_fn(|a| std::array::from_fn(|b| log_divided(lam[a], lam[b])));
        for k in 0..6 {
            let mut unit = [0.0; 6];
            unit[k] = 1.0;
            // dC = 2 dE: 2 on a normal component, 1 on both entries of a shear (γ = 2E_ij).
            let mut dc = tensor(&unit, true);
            for row in dc.iter_mut() {
                for x in row.iter_mut() {
                    *x *= 2.0;
                }
            }
            let dbt = mul(&lt, &mul(&dc, &l));
            let m = mul(&transpose(&q), &mul(&dbt, &q));
            let deps_frame: T2 =
                std::array::from_fn(|a| std::array::from_fn(|b| 0.5 * m[a][b] * g[a][b]));
            let deps = mul(&q, &mul(&deps_frame, &transpose(&q)));
            let de = voigt(&deps, true);
            let dtau_v: V6 = std::array::from_fn(|i| (0..6).map(|j| dtau[i][j] * de[j]).sum());
            let dtau_t = tensor(&dtau_v, false);
            let dbt_inv = mul(&bt_inv, &mul(&dbt, &bt_inv));
            let mut x = mul(&bt_inv, &dtau_t);
            let y = mul(&dbt_inv, &tau_t);
            for i in 0..3 {
                for j in 0..3 {
                    x[i][j] -= y[i][j];
                }
            }
            let ds = voigt(&mul(&l, &mul(&x, &lt)), false);
            for i in 0..6 {
                tangent[i][k] = ds[i];
            }
        }
        Ok(())
    }

    fn params(&self) -> &Mises {
        &self.params
    }

    /// The Hencky plastic strain ½ ln C_p = −½ ln C_p⁻¹.
    fn plastic(&self, state: &[f64]) -> PlasticState {
        let cp_inv = tensor(&std::array::from_fn(|i| state[CP_INV + i]), false);
        let (lam, q) = eigen_symmetric(&cp_inv);
        let kappa = state[KAPPA];
        PlasticState {
            strain: voigt(&spectral(&q, &lam.map(|x| -0.5 * x.ln())), true),
            kappa,
            damage: self.params.damage.map_or(0.0, |d| d.at(kappa).0),
        }
    }
}
