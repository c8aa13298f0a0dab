//! Von Mises plasticity (`MisesMat`) for every stress mode, in small and finite strain.
//!
//! One return map serves every form ([`radial_return`]): from a trial elastic strain, the
//! committed equivalent plastic strain κ and back stress β, the backward-Euler (closest-point)
//! return on the von Mises cylinder with isotropic hardening σ_y(κ) (linear, or OOFEM's
//! piecewise-linear table, solved exactly for Δκ where OOFEM makes one linear update: its
//! QUIRK) and linear kinematic hardening, and its consistent tangent. The laws built on it:
//!
//! * [`small_strain::SmallStrainMises`]: ε = ε_e + ε_p, σ = D:ε_e (OOFEM's `MisesMat`);
//! * [`finite_strain::LogStrainMises`] for `nlgeo 1`: multiplicative F = F_e·F_p with Hencky
//!   elasticity τ = D:ln V_e and the exponential map, isochoric plastic flow, objective (OOFEM has
//!   no finite-strain `MisesMat`: it applies the small-strain law to the Green–Lagrange strain,
//!   valid only for small strains);
//!
//! both as [`Law3d`]s of the full strain, which [`InMode`] puts in an element's stress mode:
//! plane strain takes ε_zz from the element (0); plane stress and bars solve the free normal stresses to zero
//! by Newton's method on their strains with the 3D law's consistent tangent and condense them
//! out of it, so the reduced tangent is the exact derivative of the reduced stress.
//!
//! Damage (`omega_crit`, `a`) scales the stress by 1 − ω(κ), with the exact (non-symmetric)
//! tangent where κ grows (OOFEM drops or misplaces the factor in some tangents: its QUIRK).

pub mod finite_strain;
pub mod small_strain;

pub use super::law::PlasticState;
use super::law::{PointLaw, Response};
use crate::model::{Damage, Hardening, Mises, StressMode};

/// Relative excess of the trial stress over the yield stress below which a point responds
/// elastically: a point the last step left on the yield surface is there only to round-off, and
/// a step that unloads it starts with the elastic tangent.
const YIELD_TOL: f64 = 1e-12;

/// Full Voigt order [xx, yy, zz, yz, xz, xy]; strains with engineering shears.
pub type V6 = [f64; 6];
pub type M6 = [[f64; 6]; 6];

impl Hardening {
    /// σ_y(κ) and dσ_y/dκ (the slope of the segment that starts at κ); an error beyond the
    /// table's last point (OOFEM stops there too).
    pub fn at(&self, kappa: f64) -> Result<(f64, f64), String> {
        if let Hardening::Table { kappa: k, .. } = self {
            let last = k[k.len() - 1];
            if k.len() > 1 && kappa > last * (1.0 + 1e-12) {
                return Err(format!(
                    "the equivalent plastic strain {kappa:.6e} is beyond the last point of h_eps \
                     ({last:.6e})"
                ));
            }
        }
        Ok(self.extended(kappa))
    }

    /// [`Hardening::at`] with the table's last segment extended beyond it (for the iterations of
    /// a return, whose trial points may pass it).
    fn extended(&self, kappa: f64) -> (f64, f64) {
        match self {
            Hardening::Linear { sig0, modulus } => (sig0 + modulus * kappa, *modulus),
            Hardening::Table {
                kappa: k,
                stress: s,
            } => {
                if k.len() == 1 {
                    return (s[0], 0.0);
                }
                let last = k.len() - 1;
                let i = k[..last].iter().rposition(|&ki| ki <= kappa).unwrap_or(0);
                let slope = (s[i + 1] - s[i]) / (k[i + 1] - k[i]);
                (s[i] + slope * (kappa - k[i]), slope)
            }
        }
    }

    /// The yield stress of the virgin material.
    pub fn initial(&self) -> f64 {
        match self {
            Hardening::Linear { sig0, .. } => *sig0,
            Hardening::Table { stress, .. } => stress[0],
        }
    }
}

impl Damage {
    /// ω(κ) = ω_c (1 − e^(−aκ)) and dω/dκ.
    pub fn at(&self, kappa: f64) -> (f64, f64) {
        let e = (-self.rate * kappa).exp();
        (self.critical * (1.0 - e), self.critical * self.rate * e)
    }
}

/// The shear and bulk moduli.
fn moduli(m: &Mises) -> (f64, f64) {
    let g = m.young / (2.0 * (1.0 + m.poisson));
    let k = m.young / (3.0 * (1.0 - 2.0 * m.poisson));
    (g, k)
}

/// The isotropic elastic stiffness (strain with engineering shears).
pub fn elastic_stiffness(m: &Mises) -> M6 {
    let (g, k) = moduli(m);
    let mut d = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            d[i][j] = k - 2.0 * g / 3.0;
        }
        d[i][i] += 2.0 * g;
        d[i + 3][i + 3] = g;
    }
    d
}

/// What [`radial_return`] returns: the effective stress (before damage) and its consistent
/// tangent with respect to the trial elastic strain, the increments of κ and of the plastic
/// strain (engineering shears), the new back stress, and dΔκ/dε (zero on an elastic step).
#[derive(Debug, Clone, Copy)]
pub struct Returned {
    pub stress: V6,
    pub tangent: M6,
    pub dkappa: f64,
    pub plastic: V6,
    pub back: V6,
    pub dkappa_dstrain: V6,
}

/// The backward-Euler return on the von Mises cylinder from the trial elastic strain
/// `strain_e` (engineering shears) with committed κ and back stress `back`.
///
/// η_tr = dev σ_tr − β, q_tr = √(3/2)|η_tr|; on yield Δκ solves
/// q_tr − (3G + H_k)Δκ = σ_y(κ + Δκ), then σ = σ_tr − √6 G Δκ N (N = η_tr/|η_tr|),
/// Δε_p = √(3/2) Δκ N, Δβ = √(2/3) H_k Δκ N, and
/// D = D_e − (6G²Δκ/q_tr)(I_dev − N⊗N) − 6G²/(3G + H_k + H′) N⊗N.
pub fn radial_return(m: &Mises, strain_e: &V6, kappa: f64, back: &V6) -> Result<Returned, String> {
    let (g, _) = moduli(m);
    let de = elastic_stiffness(m);
    let mut stress = [0.0; 6];
    for i in 0..6 {
        stress[i] = (0..6).map(|j| de[i][j] * strain_e[j]).sum();
    }
    let p = (stress[0] + stress[1] + stress[2]) / 3.0;
    let mut eta = [0.0; 6];
    for i in 0..6 {
        eta[i] = stress[i] - if i < 3 { p } else { 0.0 } - back[i];
    }
    // |η| of the tensor: the shear components count twice.
    let norm = (eta[0] * eta[0]
        + eta[1] * eta[1]
        + eta[2] * eta[2]
        + 2.0 * (eta[3] * eta[3] + eta[4] * eta[4] + eta[5] * eta[5]))
        .sqrt();
    let q = (1.5f64).sqrt() * norm;
    let (yield_stress, _) = m.hardening.extended(kappa);
    if !(yield_stress > 0.0) {
        return Err(format!(
            "the yield stress has softened to {yield_stress:.4e} at κ = {kappa:.4e}"
        ));
    }
    let elastic = Returned {
        stress,
        tangent: de,
        dkappa: 0.0,
        plastic: [0.0; 6],
        back: *back,
        dkappa_dstrain: [0.0; 6],
    };
    if q - yield_stress <= YIELD_TOL * yield_stress {
        return Ok(elastic);
    }
    let hk = m.kinematic;
    let (dk, slope) = solve_consistency(m, q, kappa, 3.0 * g + hk)?;
    let n: V6 = std::array::from_fn(|i| eta[i] / norm);
    let s6 = 6f64.sqrt();
    let mut out = elastic;
    out.dkappa = dk;
    for i in 0..6 {
        out.stress[i] -= s6 * g * dk * n[i];
        // Strain increments with engineering shears: twice the tensor's shear components.
        let eng = if i < 3 { 1.0 } else { 2.0 };
        out.plastic[i] = (1.5f64).sqrt() * dk * n[i] * eng;
        out.back[i] = back[i] + (2.0f64 / 3.0).sqrt() * hk * dk * n[i];
    }
    let a = 6.0 * g * g * dk / q;
    let b = 6.0 * g * g / (3.0 * g + hk + slope);
    // I_dev mapping an engineering strain to the deviatoric stress-like tensor: δ_ij − 1/3 on
    // the normal components, ½ on the shears.
    for i in 0..6 {
        for j in 0..6 {
            let idev = match (i < 3, j < 3) {
                (true, true) => {
                    if i == j {
                        2.0 / 3.0
                    } else {
                        -1.0 / 3.0
                    }
                }
                (false, false) if i == j => 0.5,
                _ => 0.0,
            };
            out.tangent[i][j] -= a * (idev - n[i] * n[j]) + b * n[i] * n[j];
        }
        out.dkappa_dstrain[i] = s6 * g / (3.0 * g + hk + slope) * n[i];
    }
    Ok(out)
}

/// Δκ with q_tr − c·Δκ = σ_y(κ + Δκ) (c = 3G + H_k), and the hardening slope there: Newton's
/// method, bracketed (a piecewise-linear σ_y makes it exact in as many steps as segments cross).
fn solve_consistency(m: &Mises, q: f64, kappa: f64, c: f64) -> Result<(f64, f64), String> {
    let residual = |dk: f64| {
        let (sy, h) = m.hardening.extended(kappa + dk);
        (q - c * dk - sy, h)
    };
    let (mut lo, mut hi) = (0.0f64, q / c);
    let mut dk = 0.0;
    for _ in 0..100 {
        let (r, h) = residual(dk);
        if c + h <= 0.0 {
            return Err(format!(
                "the hardening slope {h:.4e} softens faster than the elastic response can follow \
                 (3G + hk + H must stay positive)"
            ));
        }
        if r.abs() <= 1e-15 * q || hi - lo <= 1e-16 * hi.max(f64::MIN_POSITIVE) {
            return Ok((dk, h));
        }
        if r > 0.0 {
            lo = dk;
        } else {
            hi = dk;
        }
        let next = dk + r / (c + h);
        dk = if next > lo && next < hi {
            next
        } else {
            0.5 * (lo + hi)
        };
    }
    Err("the plastic return did not converge".into())
}

/// A law of the full strain (small strain ε or Green–Lagrange E, engineering shears), as
/// [`InMode`] puts it in a stress mode.
pub trait Law3d: Send + Sync + std::fmt::Debug {
    fn state_len(&self) -> usize;
    fn initial_state(&self, state: &mut [f64]);
    /// The stress (σ or S), its tangent and the state the strain leaves.
    fn respond3d(
        &self,
        strain: &V6,
        old: &[f64],
        stress: &mut V6,
        tangent: &mut M6,
        new: &mut [f64],
    ) -> Result<(), String>;
    /// Symmetric but where damage grows.
    fn symmetric_tangent(&self) -> bool {
        self.params().damage.is_none()
    }
    fn plastic(&self, state: &[f64]) -> PlasticState;
    fn params(&self) -> &Mises;
}

/// A state's κ within the hardening's range: the returns extend a table beyond its last point
/// (the iterates of a plane-stress or uniaxial condition may pass it); a converged state there
/// is an error, as in OOFEM.
fn check_range(m: &Mises, kappa: f64) -> Result<(), String> {
    m.hardening.at(kappa).map(|_| ())
}

/// A [`Law3d`] in an element's stress mode.
#[derive(Debug)]
pub struct InMode<L> {
    pub law: L,
    pub mode: StressMode,
}

impl<L: Law3d> InMode<L> {
    /// The strain components the mode leaves free (their stresses zero): plane stress ε_zz,
    /// bars ε_yy and ε_zz.
    fn free(&self) -> &'static [usize] {
        match self.mode {
            StressMode::PlaneStress => &[2],
            StressMode::Uniaxial => &[1, 2],
            _ => &[],
        }
    }

    /// The free strains (`strain[f]` for f in `free`) where their stresses vanish, by Newton's
    /// method from the strains in `strain` (the elastic estimate), halving a step that does not
    /// lower the residual; `stress`, `tangent` and `new` then hold the law's answer there.
    fn solve_free(
        &self,
        strain: &mut V6,
        old: &[f64],
        stress: &mut V6,
        tangent: &mut M6,
        new: &mut [f64],
    ) -> Result<(), String> {
        let free = self.free();
        let norm = |s: &V6| free.iter().map(|&f| s[f] * s[f]).sum::<f64>().sqrt();
        let largest = |v: &V6| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        self.law.respond3d(strain, old, stress, tangent, new)?;
        for _ in 0..60 {
            // The stresses' round-off is that of the trial stress, D times the strain.
            let stiffness = free.iter().fold(0.0f64, |a, &f| a.max(tangent[f][f].abs()));
            let floor = 1e-12 * largest(stress).max(stiffness * largest(strain));
            let r = norm(stress);
            if r <= floor {
                return Ok(());
            }
            let step = newton_step(free, stress, tangent)?;
            if step.iter().all(|d| d.abs() <= 1e-15 * largest(strain)) {
                return Ok(());
            }
            let start = *strain;
            let mut t = 1.0;
            loop {
                for (k, &f) in free.iter().enumerate() {
                    strain[f] = start[f] + t * step[k];
                }
                self.law.respond3d(strain, old, stress, tangent, new)?;
                if norm(stress) < r || t < 1e-3 {
                    break;
                }
                t *= 0.5;
            }
        }
        Err(format!(
            "the {} condition did not converge",
            if free.len() == 1 {
                "plane-stress"
            } else {
                "uniaxial-stress"
            }
        ))
    }
}

/// The Newton step −D_ff⁻¹ σ_f of the free strains (one or two).
fn newton_step(free: &[usize], stress: &V6, d: &M6) -> Result<[f64; 2], String> {
    match free {
        [a] => Ok([-stress[*a] / d[*a][*a], 0.0]),
        [a, b] => {
            let det = d[*a][*a] * d[*b][*b] - d[*a][*b] * d[*b][*a];
            if det == 0.0 {
                return Err("singular tangent in the uniaxial-stress condition".into());
            }
            Ok([
                -(d[*b][*b] * stress[*a] - d[*a][*b] * stress[*b]) / det,
                -(-d[*b][*a] * stress[*a] + d[*a][*a] * stress[*b]) / det,
            ])
        }
        _ => Ok([0.0; 2]),
    }
}

impl<L: Law3d> PointLaw for InMode<L> {
    fn components(&self) -> usize {
        super::voigt_components(self.mode).len()
    }

    fn state_len(&self) -> usize {
        self.law.state_len()
    }

    fn initial_state(&self, state: &mut [f64]) {
        self.law.initial_state(state);
    }

    fn respond(&self, strain: &[f64], old: &[f64], out: &mut Response) -> Result<(), String> {
        let comps = super::voigt_components(self.mode);
        let mut full = [0.0; 6];
        for (k, &c) in comps.iter().enumerate() {
            full[c] = strain[k];
        }
        let (mut stress, mut d) = ([0.0; 6], [[0.0; 6]; 6]);
        let free = self.free();
        if free.is_empty() {
            self.law
                .respond3d(&full, old, &mut stress, &mut d, out.state)?;
        } else {
            // The elastic estimate of the free strains (ν of the elastic stiffness).
            self.law
                .respond3d(&full, old, &mut stress, &mut d, out.state)?;
            let step = newton_step(free, &stress, &d)?;
            for (k, &f) in free.iter().enumerate() {
                full[f] += step[k];
            }
            self.solve_free(&mut full, old, &mut stress, &mut d, out.state)?;
            condense(free, &mut d);
            if self.mode == StressMode::PlaneStress {
                out.normal_strain = full[2];
            }
        }
        check_range(self.law.params(), self.law.plastic(out.state).kappa)?;
        let n = comps.len();
        for (a, &ca) in comps.iter().enumerate() {
            out.stress[a] = stress[ca];
            for (b, &cb) in comps.iter().enumerate() {
                out.tangent[a * n + b] = d[ca][cb];
            }
        }
        Ok(())
    }

    fn symmetric_tangent(&self) -> bool {
        self.law.symmetric_tangent()
    }

    fn plastic(&self, state: &[f64]) -> Option<PlasticState> {
        Some(self.law.plastic(state))
    }
}

/// D ← D − D_·f D_ff⁻¹ D_f· : the tangent of the other stresses with the free strains following
/// through σ_f = 0.
fn condense(free: &[usize], d: &mut M6) {
    let inv: [[f64; 2]; 2] = match free {
        [a] => [[1.0 / d[*a][*a], 0.0], [0.0, 0.0]],
        [a, b] => {
            let det = d[*a][*a] * d[*b][*b] - d[*a][*b] * d[*b][*a];
            [
                [d[*b][*b] / det, -d[*a][*b] / det],
                [-d[*b][*a] / det, d[*a][*a] / det],
            ]
        }
        _ => return,
    };
    let orig = *d;
    for i in 0..6 {
        for j in 0..6 {
            let mut c = 0.0;
            for (p, &fp) in free.iter().enumerate() {
                for (q, &fq) in free.iter().enumerate() {
                    c += orig[i][fp] * inv[p][q] * orig[fq][j];
                }
            }
            d[i][j] -= c;
        }
    }
}

/// The law of a `MisesMat` for elements in `mode`; `nlgeo` takes the finite-strain form.
pub fn mises_law(m: &Mises, mode: StressMode, nlgeo: bool) -> super::Law {
    if nlgeo && mode != StressMode::Uniaxial {
        std::sync::Arc::new(InMode {
            law: finite_strain::LogStrainMises { params: m.clone() },
            mode,
        })
    } else {
        std::sync::Arc::new(InMode {
            law: small_strain::SmallStrainMises { params: m.clone() },
            mode,
        })
    }
}

#[cfg(test)]
mod tests;
