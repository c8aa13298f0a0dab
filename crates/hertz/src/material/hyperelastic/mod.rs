//! Compressible hyperelastic laws (upstream OOFEM's records, spec-upstream §4), one energy per
//! file ([`mooney_rivlin`], [`ogden`], [`simo_pister`]) behind [`Energy`], and what every
//! energy shares: the second Piola–Kirchhoff stress S = 2 ∂W/∂C and the material tangent
//! D = ∂S/∂E = 4 ∂²W/∂C∂C that the element's total Lagrangian form takes (through
//! [`HyperelasticLaw`], a [`super::PointLaw`] of the Green–Lagrange strain), and P = F S with
//! A = ∂P/∂F for checks.
//!
//! An energy is a function φ of a few spectral traces of C = FᵀF: T_ln = tr ln C = 2 ln J,
//! T₁ = tr C, T₂ = tr C², T_(m) = tr C^m (Ogden: Σ λ_a^{2m}). φ's derivatives come from
//! second-order automatic differentiation over its few arguments ([`H`]), the traces'
//! derivatives from [`super::spectral`] (Ogden) or in closed form (T_ln, T₁, T₂); then
//! S = 2 Σ_a φ_a ∂T_a and D = 4 (Σ_a φ_a ∂²T_a + Σ_ab φ_ab ∂T_a ⊗ ∂T_b).
//!
//! In plane stress the strain normal to the plane is solved at each point from S₃₃ = 0 (Newton
//! from the stretch that keeps the volume) and condensed out of the tangent (upstream OOFEM
//! aborts there).

pub mod mooney_rivlin;
pub mod ogden;
pub mod simo_pister;

pub use mooney_rivlin::MooneyRivlin;
pub use ogden::Ogden;
pub use simo_pister::SimoPister;

use super::law::{PointLaw, Response};
use super::spectral::{eigen_symmetric, Log, Power, Scalar1, SpectralTrace, T2, T4};
use super::{voigt_components, VOIGT_PAIRS};
use crate::model::StressMode;

/// Most arguments of φ (T_ln and up to 7 Ogden terms or T₁, T₂).
const MAXA: usize = 8;

/// A value with gradient and Hessian over φ's arguments.
#[derive(Clone, Copy)]
pub struct H {
    pub v: f64,
    pub g: [f64; MAXA],
    pub h: [[f64; MAXA]; MAXA],
}

impl H {
    pub fn cst(v: f64) -> H {
        H {
            v,
            g: [0.0; MAXA],
            h: [[0.0; MAXA]; MAXA],
        }
    }
    pub fn var(v: f64, i: usize) -> H {
        let mut x = H::cst(v);
        x.g[i] = 1.0;
        x
    }
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, b: H) -> H {
        let mut r = self;
        r.v += b.v;
        for i in 0..MAXA {
            r.g[i] += b.g[i];
            for j in 0..MAXA {
                r.h[i][j] += b.h[i][j];
            }
        }
        r
    }
    pub fn scale(self, s: f64) -> H {
        let mut r = self;
        r.v *= s;
        for i in 0..MAXA {
            r.g[i] *= s;
            for j in 0..MAXA {
                r.h[i][j] *= s;
            }
        }
        r
    }
    #[allow(clippy::should_implement_trait)]
    pub fn mul(self, b: H) -> H {
        let mut r = H::cst(self.v * b.v);
        for i in 0..MAXA {
            r.g[i] = self.g[i] * b.v + self.v * b.g[i];
            for j in 0..MAXA {
                r.h[i][j] = self.h[i][j] * b.v
                    + self.v * b.h[i][j]
                    + self.g[i] * b.g[j]
                    + b.g[i] * self.g[j];
            }
        }
        r
    }
    pub fn exp(self) -> H {
        let e = self.v.exp();
        let mut r = H::cst(e);
        for i in 0..MAXA {
            r.g[i] = e * self.g[i];
            for j in 0..MAXA {
                r.h[i][j] = e * (self.h[i][j] + self.g[i] * self.g[j]);
            }
        }
        r
    }
}

/// A compressible hyperelastic energy W(C) as φ of spectral traces of C.
pub trait Energy: Send + Sync + std::fmt::Debug {
    /// The spectral functions whose traces φ takes, T_ln (ln) first.
    fn functions(&self) -> Vec<Box<dyn Scalar1>>;

    /// Whether they are (ln, c, c²): tr ln C, tr C and tr C², in closed form without an
    /// eigen-decomposition ([`invariant_traces`]).
    fn invariants(&self) -> bool;

    /// φ of the traces.
    fn phi(&self, t: &[H]) -> H;

    /// Small-strain shear and bulk moduli (G, K): the tangent at C = I.
    fn moduli(&self) -> (f64, f64);

    /// S and D at C in closed form into `s` and `d`, where the law has one (faster than the
    /// general path, the same to round-off): whether it has.
    fn closed_form(&self, _c: &T2, _s: &mut T2, _d: &mut T4) -> bool {
        false
    }
}

/// The invariant functions (ln, c, c²) of Mooney–Rivlin and Simo–Pister.
pub(crate) fn invariant_functions() -> Vec<Box<dyn Scalar1>> {
    vec![Box::new(Log), Box::new(Power(1.0)), Box::new(Power(2.0))]
}

/// The strain energy W at C.
pub fn energy_at(energy: &dyn Energy, c: &T2) -> f64 {
    let (e, _) = eigen_symmetric(c);
    let t: Vec<H> = energy
        .functions()
        .iter()
        .map(|g| H::cst(e.iter().map(|&x| g.g(x)).sum()))
        .collect();
    energy.phi(&t).v
}

/// S = 2 ∂W/∂C and D = ∂S/∂E = 4 ∂²W/∂C∂C at C; Err(det C) where det C ≤ 0.
pub fn material_response(energy: &dyn Energy, c: &T2) -> Result<(T2, T4), f64> {
    let mut s = [[0.0; 3]; 3];
    let mut d = [[[[0.0; 3]; 3]; 3]; 3];
    material_response_into(energy, c, &mut s, &mut d)?;
    Ok((s, d))
}

/// [`material_response`] into `s` and `d`.
fn material_response_into(energy: &dyn Energy, c: &T2, s: &mut T2, d: &mut T4) -> Result<(), f64> {
    let det = crate::fem::geometry::det3(c);
    if !(det > 0.0) {
        return Err(det);
    }
    if energy.closed_form(c, s, d) {
        return Ok(());
    }
    let traces: Vec<SpectralTrace> = if energy.invariants() {
        invariant_traces(c)
    } else {
        let (e, n) = eigen_symmetric(c);
        energy
            .functions()
            .iter()
            .map(|g| SpectralTrace::new(g.as_ref(), &e, &n))
            .collect()
    };
    let args: Vec<H> = traces
        .iter()
        .enumerate()
        .map(|(i, t)| H::var(t.value, i))
        .collect();
    let phi = energy.phi(&args);
    let na = traces.len();
    // ∂W/∂C = Σ_a φ_a ∂T_a, ∂²W/∂C∂C = Σ_a φ_a ∂²T_a + Σ_b (Σ_a φ_ab ∂T_a) ⊗ ∂T_b.
    *s = [[0.0; 3]; 3];
    let mut mixed = [[[0.0; 3]; 3]; MAXA];
    for a in 0..na {
        for i in 0..3 {
            for j in 0..3 {
                s[i][j] += 2.0 * phi.g[a] * traces[a].grad[i][j];
                for (b, m) in mixed.iter_mut().enumerate().take(na) {
                    m[i][j] += phi.h[a][b] * traces[a].grad[i][j];
                }
            }
        }
    }
    for i in 0..3 {
        for j in 0..3 {
            for k in 0..3 {
                for l in 0..3 {
                    let mut v = 0.0;
                    for b in 0..na {
                        v += phi.g[b] * traces[b].hess[i][j][k][l]
                            + mixed[b][i][j] * traces[b].grad[k][l];
                    }
                    d[i][j][k][l] = 4.0 * v;
                }
            }
        }
    }
    Ok(())
}

/// The first Piola–Kirchhoff stress P = F S and its tangent A_iJkL = δ_ik S_JL +
/// F_iI D_IJLM F_kM at F; Err(det F) where det F ≤ 0.
pub fn pk1(energy: &dyn Energy, f: &T2) -> Result<(T2, T4), f64> {
    let det = crate::fem::geometry::det3(f);
    if !(det > 0.0) {
        return Err(det);
    }
    let (s, d) = material_response(energy, &right_cauchy_green(f))?;
    let mut p = [[0.0; 3]; 3];
    for i in 0..3 {
        for jj in 0..3 {
            p[i][jj] = (0..3).map(|ii| f[i][ii] * s[ii][jj]).sum();
        }
    }
    // Σ_I F_iI D[I][J][L][M] → [i][J][L][M].
    let mut fd = [[[[0.0; 3]; 3]; 3]; 3];
    for i in 0..3 {
        for jj in 0..3 {
            for ll in 0..3 {
                for mm in 0..3 {
                    fd[i][jj][ll][mm] = (0..3).map(|ii| f[i][ii] * d[ii][jj][ll][mm]).sum();
                }
            }
        }
    }
    let mut a = [[[[0.0; 3]; 3]; 3]; 3];
    for i in 0..3 {
        for jj in 0..3 {
            for k in 0..3 {
                for ll in 0..3 {
                    let mut v = (0..3).map(|mm| fd[i][jj][ll][mm] * f[k][mm]).sum::<f64>();
                    if i == k {
                        v += s[jj][ll];
                    }
                    a[i][jj][k][ll] = v;
                }
            }
        }
    }
    Ok((p, a))
}

/// A hyperelastic energy as the point law of an element's stress mode: S and dS/dE of the
/// Green–Lagrange strain in reduced Voigt form.
#[derive(Debug)]
pub struct HyperelasticLaw {
    energy: Box<dyn Energy>,
    mode: StressMode,
}

impl HyperelasticLaw {
    pub fn new(energy: Box<dyn Energy>, mode: StressMode) -> HyperelasticLaw {
        HyperelasticLaw { energy, mode }
    }

    /// S and D at the Green–Lagrange strain `e` (a tensor) into `s` and `d`, the element's
    /// message where the material inverts.
    fn at(&self, e: &T2, s: &mut T2, d: &mut T4) -> Result<(), String> {
        let c: T2 = std::array::from_fn(|i| {
            std::array::from_fn(|j| 2.0 * e[i][j] + if i == j { 1.0 } else { 0.0 })
        });
        material_response_into(self.energy.as_ref(), &c, s, d)
            .map_err(|det| format!("element inverted (det C = {det:.3e})"))
    }

    /// Plane stress: the normal strain E₃₃ where S₃₃ = 0 at the in-plane strain of `e`, by
    /// Newton's method from the stretch that keeps the volume, with steps halved to keep the
    /// stretch real; `e` then holds it, and `s` and `d` S and D there.
    fn plane_stress(&self, e: &mut T2, s: &mut T2, d: &mut T4) -> Result<(), String> {
        let c2 = (2.0 * e[0][0] + 1.0) * (2.0 * e[1][1] + 1.0) - 4.0 * e[0][1] * e[1][0];
        if !(c2 > 0.0) {
            return Err(format!("element inverted (in-plane det C = {c2:.3e})"));
        }
        e[2][2] = 0.5 * (1.0 / c2.sqrt() - 1.0);
        let mut scale = 0.0f64;
        for _ in 0..60 {
            self.at(e, s, d)?;
            scale = scale.max(s.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())));
            let r = s[2][2];
            if r.abs() <= 1e-14 * scale.max(f64::MIN_POSITIVE) {
                return Ok(());
            }
            let mut step = -r / d[2][2][2][2];
            while 2.0 * (e[2][2] + step) + 1.0 <= 0.0 {
                step *= 0.5;
            }
            e[2][2] += step;
            if step.abs() <= 1e-15 * (1.0 + 2.0 * e[2][2]) {
                return self.at(e, s, d);
            }
        }
        Err("plane stress: the out-of-plane stretch did not converge".into())
    }
}

impl PointLaw for HyperelasticLaw {
    fn components(&self) -> usize {
        voigt_components(self.mode).len()
    }

    fn respond(&self, strain: &[f64], _old: &[f64], out: &mut Response) -> Result<(), String> {
        let comps = voigt_components(self.mode);
        let mut e = [[0.0; 3]; 3];
        for (k, &c) in comps.iter().enumerate() {
            let (i, j) = VOIGT_PAIRS[c];
            let v = if i == j { strain[k] } else { 0.5 * strain[k] };
            e[i][j] = v;
            e[j][i] = v;
        }
        let plane_stress = self.mode == StressMode::PlaneStress;
        let mut s = [[0.0; 3]; 3];
        let mut d = [[[[0.0; 3]; 3]; 3]; 3];
        if plane_stress {
            self.plane_stress(&mut e, &mut s, &mut d)?;
        } else {
            self.at(&e, &mut s, &mut d)?;
        }
        if plane_stress {
            // E₃₃ follows the in-plane strain through S₃₃ = 0: dE₃₃ = −D₃₃kl dE_kl / D₃₃₃₃, so
            // the in-plane tangent is D_ijkl − D_ij33 D_33kl / D₃₃₃₃.
            let d33 = d[2][2][2][2];
            let col: T2 = std::array::from_fn(|i| std::array::from_fn(|j| d[i][j][2][2]));
            let row: T2 = std::array::from_fn(|k| std::array::from_fn(|l| d[2][2][k][l]));
            for i in 0..3 {
                for j in 0..3 {
                    for k in 0..3 {
                        for l in 0..3 {
                            d[i][j][k][l] -= col[i][j] * row[k][l] / d33;
                        }
                    }
                }
            }
            out.normal_strain = e[2][2];
        }
        let n = comps.len();
        for (a, &ca) in comps.iter().enumerate() {
            let (i, j) = VOIGT_PAIRS[ca];
            out.stress[a] = s[i][j];
            for (b, &cb) in comps.iter().enumerate() {
                let (k, l) = VOIGT_PAIRS[cb];
                out.tangent[a * n + b] = d[i][j][k][l];
            }
        }
        Ok(())
    }
}

/// The traces of [`invariant_functions`], tr ln C = ln det C, tr C and tr C², in closed form (the same values as [`SpectralTrace`] without the eigen-decomposition
/// and its powers, which took 30 % of a large-deformation run): their gradients C⁻¹, I and 2C,
/// their Hessians −½(C⁻¹_ik C⁻¹_jl + C⁻¹_il C⁻¹_jk), 0 and δ_ik δ_jl + δ_il δ_jk.
fn invariant_traces(c: &T2) -> Vec<SpectralTrace> {
    let det = crate::fem::geometry::det3(c);
    let ci = crate::fem::geometry::inverse3(c, det);
    let mut log = SpectralTrace {
        value: det.ln(),
        grad: ci,
        hess: [[[[0.0; 3]; 3]; 3]; 3],
    };
    let mut linear = SpectralTrace {
        value: c[0][0] + c[1][1] + c[2][2],
        grad: [[0.0; 3]; 3],
        hess: [[[[0.0; 3]; 3]; 3]; 3],
    };
    let mut square = SpectralTrace {
        value: (0..3)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .map(|(i, j)| c[i][j] * c[i][j])
            .sum(),
        grad: [[0.0; 3]; 3],
        hess: [[[[0.0; 3]; 3]; 3]; 3],
    };
    let delta = |i: usize, j: usize| if i == j { 1.0 } else { 0.0 };
    for i in 0..3 {
        linear.grad[i][i] = 1.0;
        for j in 0..3 {
            square.grad[i][j] = 2.0 * c[i][j];
            for k in 0..3 {
                for l in 0..3 {
                    log.hess[i][j][k][l] = -0.5 * (ci[i][k] * ci[j][l] + ci[i][l] * ci[j][k]);
                    square.hess[i][j][k][l] = delta(i, k) * delta(j, l) + delta(i, l) * delta(j, k);
                }
            }
        }
    }
    vec![log, linear, square]
}

/// C = FᵀF.
pub fn right_cauchy_green(f: &T2) -> T2 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| f[k][i] * f[k][j]).sum();
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn laws() -> Vec<Box<dyn Energy>> {
        vec![
            Box::new(MooneyRivlin {
                c1: 1.0,
                c2: 0.5,
                k: 10.0,
            }),
            Box::new(Ogden {
                alpha: vec![1.3, -2.0],
                mu: vec![0.8, -0.4],
                k: 10.0,
            }),
            Box::new(SimoPister { g: 1.0, k: 10.0 }),
        ]
    }

    /// Upstream OOFEM's reference values (spec-upstream §4.5, λ = 1.2, confined stretch
    /// F = diag(λ, 1, 1)): P11, P22.
    #[test]
    fn confined_uniaxial_stretch_gives_oofems_stresses() {
        let expected = [
            (2.143974, 1.448439),
            (1.705866, 1.711304),
            (1.886013, 1.823216),
        ];
        let f = [[1.2, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        for (law, (p11, p22)) in laws().iter().zip(expected) {
            let (p, _) = pk1(law.as_ref(), &f).unwrap();
            assert!((p[0][0] - p11).abs() < 5e-6, "{law:?}: P11 {}", p[0][0]);
            assert!((p[1][1] - p22).abs() < 5e-6, "{law:?}: P22 {}", p[1][1]);
            assert!((p[2][2] - p22).abs() < 5e-6);
            assert!(p[0][1].abs() + p[1][0].abs() < 1e-14);
        }
    }

    /// A general deformation gradient, and a rotated stretch R · diag(1.2, 0.9, 0.9) with two
    /// equal principal stretches.
    fn deformations() -> [T2; 2] {
        let (c, s) = (0.6f64.cos(), 0.6f64.sin());
        [
            [[1.1, 0.2, -0.1], [0.05, 0.9, 0.3], [0.0, -0.2, 1.2]],
            [
                [1.2 * c, -0.9 * s, 0.0],
                [1.2 * s, 0.9 * c, 0.0],
                [0.0, 0.0, 0.9],
            ],
        ]
    }

    /// P is the derivative of W, and A the derivative of P (central differences), at the
    /// [`deformations`].
    #[test]
    fn stress_and_tangent_are_derivatives_of_energy_and_stress() {
        for law in laws() {
            for f in deformations() {
                let (p, a) = pk1(law.as_ref(), &f).unwrap();
                let h = 1e-6;
                for k in 0..3 {
                    for l in 0..3 {
                        let (mut fp, mut fm) = (f, f);
                        fp[k][l] += h;
                        fm[k][l] -= h;
                        let w = |f: &T2| energy_at(law.as_ref(), &right_cauchy_green(f));
                        let dw = (w(&fp) - w(&fm)) / (2.0 * h);
                        assert!(
                            (dw - p[k][l]).abs() < 1e-7,
                            "{law:?}: P[{k}][{l}] {} vs {dw}",
                            p[k][l]
                        );
                        let (pp, _) = pk1(law.as_ref(), &fp).unwrap();
                        let (pm, _) = pk1(law.as_ref(), &fm).unwrap();
                        for i in 0..3 {
                            for j in 0..3 {
                                let fd = (pp[i][j] - pm[i][j]) / (2.0 * h);
                                assert!(
                                    (fd - a[i][j][k][l]).abs() < 1e-6,
                                    "{law:?}: A[{i}][{j}][{k}][{l}] {} vs {fd}",
                                    a[i][j][k][l]
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// The closed-form traces of Mooney–Rivlin and Simo–Pister are the spectral ones: values,
    /// gradients and Hessians to round-off, at a general C and at one with a double eigenvalue.
    #[test]
    fn invariant_traces_are_the_spectral_ones() {
        let law = SimoPister { g: 1.0, k: 1.0 };
        for f in deformations() {
            let cc = right_cauchy_green(&f);
            let (e, n) = eigen_symmetric(&cc);
            let closed = invariant_traces(&cc);
            for (g, t) in law.functions().iter().zip(&closed) {
                let sp = SpectralTrace::new(g.as_ref(), &e, &n);
                assert!(
                    (sp.value - t.value).abs() < 1e-13,
                    "{} vs {}",
                    sp.value,
                    t.value
                );
                for i in 0..3 {
                    for j in 0..3 {
                        assert!((sp.grad[i][j] - t.grad[i][j]).abs() < 1e-12);
                        for k in 0..3 {
                            for l in 0..3 {
                                let (a, b) = (sp.hess[i][j][k][l], t.hess[i][j][k][l]);
                                // The spectral divided differences of equal eigenvalues are
                                // good to about 1e-6 relative (EQUAL_EIGENVALUES).
                                assert!((a - b).abs() < 1e-5, "[{i}{j}{k}{l}] {a} vs {b}");
                            }
                        }
                    }
                }
            }
        }
    }

    /// The small-strain moduli are the tangent at F = I: A = λ δij δkl + G (δik δjl + δil δjk)
    /// with λ = K − 2G/3.
    #[test]
    fn small_strain_moduli_are_the_tangent_at_the_identity() {
        let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        for law in laws() {
            let (g, k) = law.moduli();
            let lambda = k - 2.0 * g / 3.0;
            let (_, a) = pk1(law.as_ref(), &id).unwrap();
            let d = |i: usize, j: usize| if i == j { 1.0 } else { 0.0 };
            for i in 0..3 {
                for j in 0..3 {
                    for m in 0..3 {
                        for n in 0..3 {
                            let want = lambda * d(i, j) * d(m, n)
                                + g * (d(i, m) * d(j, n) + d(i, n) * d(j, m));
                            assert!(
                                (a[i][j][m][n] - want).abs() < 1e-12,
                                "{law:?}: A[{i}][{j}][{m}][{n}] {} vs {want}",
                                a[i][j][m][n]
                            );
                        }
                    }
                }
            }
        }
    }

    /// A rigid rotation is stress-free.
    #[test]
    fn rigid_rotation_is_stress_free() {
        let (c, s) = (1.1f64.cos(), 1.1f64.sin());
        let f = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
        for law in laws() {
            let (p, _) = pk1(law.as_ref(), &f).unwrap();
            for row in p {
                for v in row {
                    assert!(v.abs() < 1e-13, "{law:?}: {p:?}");
                }
            }
        }
    }
}
