//! Compressible hyperelastic laws (upstream OOFEM's records, spec-upstream §4): the first
//! Piola–Kirchhoff stress P = ∂W/∂F and its tangent A = ∂P/∂F.
//!
//! Every energy here is a function φ of a few spectral traces of C = FᵀF: T_ln = tr ln C = 2 ln J,
//! T₁ = tr C, T₂ = tr C², T_(m) = tr C^m (Ogden: Σ λ_a^{2m}):
//! * Mooney–Rivlin: W = C₁(J^{−2/3} I₁ − 3) + C₂(J^{−4/3} I₂ − 3) + ½K(ln J)², I₂ = ½(T₁² − T₂)
//!   (neo-Hookean with C₂ = 0; small-strain G = 2(C₁ + C₂));
//! * Ogden: W = Σ_p μ_p/α_p (J^{−α_p/3} T_(α_p/2) − 3) + ½K(ln J)² (G = ½ Σ μ_p α_p);
//! * Simo–Pister: W = ½G(T₁ − 3) − G ln J + ½K(ln J)².
//!
//! φ's derivatives come from second-order automatic differentiation over its few arguments, the
//! traces' derivatives from [`super::spectral`] (Ogden) or in closed form (T_ln, T₁, T₂); then
//! S = 2 ∂W/∂C, P = F S and A_iJkL = δ_ik S_JL + 4 F_iI (∂²W/∂C_IJ∂C_LM) F_kM. Simo–Pister's P
//! and A are written out instead (the same to round-off, at a fraction of the cost).

use super::spectral::{eigen_symmetric, Log, Power, Scalar1, SpectralTrace, T2, T4};

/// Most arguments of φ (T_ln and up to 7 Ogden terms or T₁, T₂).
const MAXA: usize = 8;

/// A value with gradient and Hessian over φ's arguments.
#[derive(Clone, Copy)]
struct H {
    v: f64,
    g: [f64; MAXA],
    h: [[f64; MAXA]; MAXA],
}

impl H {
    fn cst(v: f64) -> H {
        H {
            v,
            g: [0.0; MAXA],
            h: [[0.0; MAXA]; MAXA],
        }
    }
    fn var(v: f64, i: usize) -> H {
        let mut x = H::cst(v);
        x.g[i] = 1.0;
        x
    }
    fn add(self, b: H) -> H {
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
    fn scale(self, s: f64) -> H {
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
    fn mul(self, b: H) -> H {
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
    fn exp(self) -> H {
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

/// A compressible hyperelastic law.
#[derive(Debug, Clone, PartialEq)]
pub enum Hyperelastic {
    MooneyRivlin {
        c1: f64,
        c2: f64,
        k: f64,
    },
    Ogden {
        alpha: Vec<f64>,
        mu: Vec<f64>,
        k: f64,
    },
    SimoPister {
        g: f64,
        k: f64,
    },
}

impl Hyperelastic {
    /// Small-strain shear and bulk moduli (G, K): the tangent at F = I. Simo–Pister's `k`
    /// multiplies ½(ln J)² without an isochoric split, so it is Lamé's λ there and the bulk
    /// modulus is k + 2G/3 (upstream's note E = 9KG/(3K + G) with K = k is only approximate).
    pub fn moduli(&self) -> (f64, f64) {
        match self {
            Hyperelastic::MooneyRivlin { c1, c2, k } => (2.0 * (c1 + c2), *k),
            Hyperelastic::Ogden { alpha, mu, k } => (
                0.5 * alpha.iter().zip(mu).map(|(a, m)| a * m).sum::<f64>(),
                *k,
            ),
            Hyperelastic::SimoPister { g, k } => (*g, k + 2.0 * g / 3.0),
        }
    }

    /// The spectral functions the energy is written in, and φ of their traces (first argument
    /// always T_ln).
    fn traces(&self) -> Vec<Box<dyn Scalar1>> {
        let mut g: Vec<Box<dyn Scalar1>> = vec![Box::new(Log)];
        match self {
            Hyperelastic::MooneyRivlin { .. } | Hyperelastic::SimoPister { .. } => {
                g.push(Box::new(Power(1.0)));
                g.push(Box::new(Power(2.0)));
            }
            Hyperelastic::Ogden { alpha, .. } => {
                for a in alpha {
                    g.push(Box::new(Power(0.5 * a)));
                }
            }
        }
        g
    }

    fn phi(&self, t: &[H]) -> H {
        let ln_j = t[0].scale(0.5);
        let (kk, iso) = match self {
            Hyperelastic::MooneyRivlin { c1, c2, k } => {
                let i1 = t[1];
                let i2 = t[1].mul(t[1]).add(t[2].scale(-1.0)).scale(0.5);
                let j23 = t[0].scale(-1.0 / 3.0).exp();
                let j43 = t[0].scale(-2.0 / 3.0).exp();
                let w = j23
                    .mul(i1)
                    .add(H::cst(-3.0))
                    .scale(*c1)
                    .add(j43.mul(i2).add(H::cst(-3.0)).scale(*c2));
                (*k, w)
            }
            Hyperelastic::Ogden { alpha, mu, k } => {
                let mut w = H::cst(0.0);
                for (p, (&a, &m)) in alpha.iter().zip(mu).enumerate() {
                    let ja = t[0].scale(-a / 6.0).exp();
                    w = w.add(ja.mul(t[1 + p]).add(H::cst(-3.0)).scale(m / a));
                }
                (*k, w)
            }
            Hyperelastic::SimoPister { g, k } => {
                let w = t[1].add(H::cst(-3.0)).scale(0.5 * g).add(ln_j.scale(-g));
                (*k, w)
            }
        };
        iso.add(ln_j.mul(ln_j).scale(0.5 * kk))
    }

    /// The strain energy W at F (for checks).
    pub fn energy(&self, f: &T2) -> f64 {
        let c = right_cauchy_green(f);
        let (e, _) = eigen_symmetric(&c);
        let t: Vec<H> = self
            .traces()
            .iter()
            .map(|g| H::cst(e.iter().map(|&x| g.g(x)).sum()))
            .collect();
        self.phi(&t).v
    }

    /// First Piola–Kirchhoff stress P and tangent A = ∂P/∂F at F; Err when det F ≤ 0.
    pub fn pk1(&self, f: &T2) -> Result<(T2, T4), f64> {
        let det = crate::fem::geometry::det3(f);
        if !(det > 0.0) {
            return Err(det);
        }
        if let Hyperelastic::SimoPister { g, k } = *self {
            return Ok(simo_pister(g, k, f, det));
        }
        let c = right_cauchy_green(f);
        // (Simo–Pister has returned above; its traces are Mooney–Rivlin's.)
        let traces: Vec<SpectralTrace> = match self {
            Hyperelastic::MooneyRivlin { .. } | Hyperelastic::SimoPister { .. } => {
                invariant_traces(&c)
            }
            Hyperelastic::Ogden { .. } => {
                let (e, n) = eigen_symmetric(&c);
                self.traces()
                    .iter()
                    .map(|g| SpectralTrace::new(g.as_ref(), &e, &n))
                    .collect()
            }
        };
        let args: Vec<H> = traces
            .iter()
            .enumerate()
            .map(|(i, t)| H::var(t.value, i))
            .collect();
        let phi = self.phi(&args);
        let na = traces.len();
        // ∂W/∂C = Σ_a φ_a ∂T_a, ∂²W/∂C∂C = Σ_a φ_a ∂²T_a + Σ_b (Σ_a φ_ab ∂T_a) ⊗ ∂T_b.
        let mut dw = [[0.0; 3]; 3];
        let mut mixed = [[[0.0; 3]; 3]; MAXA];
        for a in 0..na {
            for i in 0..3 {
                for j in 0..3 {
                    dw[i][j] += phi.g[a] * traces[a].grad[i][j];
                    for (b, m) in mixed.iter_mut().enumerate().take(na) {
                        m[i][j] += phi.h[a][b] * traces[a].grad[i][j];
                    }
                }
            }
        }
        let mut ddw = [[[[0.0; 3]; 3]; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    for l in 0..3 {
                        let mut v = 0.0;
                        for b in 0..na {
                            v += phi.g[b] * traces[b].hess[i][j][k][l]
                                + mixed[b][i][j] * traces[b].grad[k][l];
                        }
                        ddw[i][j][k][l] = v;
                    }
                }
            }
        }
        let mut s = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                s[i][j] = 2.0 * dw[i][j];
            }
        }
        let mut p = [[0.0; 3]; 3];
        for i in 0..3 {
            for jj in 0..3 {
                p[i][jj] = (0..3).map(|ii| f[i][ii] * s[ii][jj]).sum();
            }
        }
        // A_iJkL = δ_ik S_JL + 4 Σ_IM F_iI W_CC[I][J][L][M] F_kM.
        let mut fw = [[[[0.0; 3]; 3]; 3]; 3]; // Σ_I F_iI W[I][J][L][M] → [i][J][L][M]
        for i in 0..3 {
            for jj in 0..3 {
                for ll in 0..3 {
                    for mm in 0..3 {
                        fw[i][jj][ll][mm] = (0..3).map(|ii| f[i][ii] * ddw[ii][jj][ll][mm]).sum();
                    }
                }
            }
        }
        let mut a = [[[[0.0; 3]; 3]; 3]; 3];
        for i in 0..3 {
            for jj in 0..3 {
                for k in 0..3 {
                    for ll in 0..3 {
                        let mut v =
                            4.0 * (0..3).map(|mm| fw[i][jj][ll][mm] * f[k][mm]).sum::<f64>();
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
}

/// Simo–Pister's P and A in closed form (the general path's to round-off, without its
/// fourth-order products): with F⁻ᵀ and ln J,
///   P = G F + (k ln J − G) F⁻ᵀ,
///   A_iJkL = G δ_ik δ_JL + (G − k ln J) F⁻ᵀ_iL F⁻ᵀ_kJ + k F⁻ᵀ_iJ F⁻ᵀ_kL.
fn simo_pister(g: f64, k: f64, f: &T2, det: f64) -> (T2, T4) {
    let inv = crate::fem::geometry::inverse3(f, det);
    let fit: T2 = std::array::from_fn(|i| std::array::from_fn(|j| inv[j][i]));
    let ln_j = det.ln();
    let mut p = [[0.0; 3]; 3];
    let mut a = [[[[0.0; 3]; 3]; 3]; 3];
    for i in 0..3 {
        for jj in 0..3 {
            p[i][jj] = g * f[i][jj] + (k * ln_j - g) * fit[i][jj];
            for kk in 0..3 {
                for ll in 0..3 {
                    let mut v =
                        (g - k * ln_j) * fit[i][ll] * fit[kk][jj] + k * fit[i][jj] * fit[kk][ll];
                    if i == kk && jj == ll {
                        v += g;
                    }
                    a[i][jj][kk][ll] = v;
                }
            }
        }
    }
    (p, a)
}

/// The traces of `traces()` for Mooney–Rivlin and Simo–Pister, tr ln C = ln det C, tr C and
/// tr C², in closed form (the same values as [`SpectralTrace`] without the eigen-decomposition
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

    fn laws() -> Vec<Hyperelastic> {
        vec![
            Hyperelastic::MooneyRivlin {
                c1: 1.0,
                c2: 0.5,
                k: 10.0,
            },
            Hyperelastic::Ogden {
                alpha: vec![1.3, -2.0],
                mu: vec![0.8, -0.4],
                k: 10.0,
            },
            Hyperelastic::SimoPister { g: 1.0, k: 10.0 },
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
            let (p, _) = law.pk1(&f).unwrap();
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
                let (p, a) = law.pk1(&f).unwrap();
                let h = 1e-6;
                for k in 0..3 {
                    for l in 0..3 {
                        let (mut fp, mut fm) = (f, f);
                        fp[k][l] += h;
                        fm[k][l] -= h;
                        let dw = (law.energy(&fp) - law.energy(&fm)) / (2.0 * h);
                        assert!(
                            (dw - p[k][l]).abs() < 1e-7,
                            "{law:?}: P[{k}][{l}] {} vs {dw}",
                            p[k][l]
                        );
                        let (pp, _) = law.pk1(&fp).unwrap();
                        let (pm, _) = law.pk1(&fm).unwrap();
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
        let law = Hyperelastic::SimoPister { g: 1.0, k: 1.0 };
        for f in deformations() {
            let cc = right_cauchy_green(&f);
            let (e, n) = eigen_symmetric(&cc);
            let closed = invariant_traces(&cc);
            for (g, t) in law.traces().iter().zip(&closed) {
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
            let (_, a) = law.pk1(&id).unwrap();
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
            let (p, _) = law.pk1(&f).unwrap();
            for row in p {
                for v in row {
                    assert!(v.abs() < 1e-13, "{law:?}: {p:?}");
                }
            }
        }
    }
}
