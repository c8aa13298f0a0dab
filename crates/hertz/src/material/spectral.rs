//! Spectral functions of a symmetric 3×3 tensor C: T(C) = tr g(C) = Σ_a g(c_a), with its first
//! and second derivatives with respect to C, exact also where eigenvalues coincide.
//!
//! ∂T/∂C = Σ_a g′(c_a) n_a⊗n_a;  ∂²T/∂C∂C = ½ Σ_ab g⁽¹⁾(c_a, c_b) n_a⊗n_b⊗(n_a⊗n_b + n_b⊗n_a)
//! (the Daleckii–Krein formula), g⁽¹⁾(x, y) = (g′(x) − g′(y))/(x − y), and g″ for (nearly) equal
//! eigenvalues, decided with a relative tolerance (OOFEM tests exact equality: upstream QUIRK M2).

/// Symmetric 3×3 tensors and fourth-order tensors, row-major.
pub type T2 = [[f64; 3]; 3];
pub type T4 = [[[[f64; 3]; 3]; 3]; 3];

/// Eigenvalues and orthonormal eigenvectors (columns of `vecs`) of a symmetric matrix, by cyclic
/// Jacobi rotations (accurate to round-off, also for clustered eigenvalues).
pub fn eigen_symmetric(m: &T2) -> ([f64; 3], T2) {
    let mut a = *m;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        let diag = a[0][0].powi(2) + a[1][1].powi(2) + a[2][2].powi(2);
        if off <= 1e-34 * diag || off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            for k in 0..3 {
                let (vkp, vkq) = (v[k][p], v[k][q]);
                v[k][p] = c * vkp - s * vkq;
                v[k][q] = s * vkp + c * vkq;
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

/// A scalar function g with its first three derivatives' needs: g, g′, g″ at a point.
pub trait Scalar1 {
    fn g(&self, x: f64) -> f64;
    fn d1(&self, x: f64) -> f64;
    fn d2(&self, x: f64) -> f64;
}

/// g(x) = x^m (m real; x > 0).
pub struct Power(pub f64);

impl Scalar1 for Power {
    fn g(&self, x: f64) -> f64 {
        x.powf(self.0)
    }
    fn d1(&self, x: f64) -> f64 {
        self.0 * x.powf(self.0 - 1.0)
    }
    fn d2(&self, x: f64) -> f64 {
        self.0 * (self.0 - 1.0) * x.powf(self.0 - 2.0)
    }
}

/// g(x) = ln x.
pub struct Log;

impl Scalar1 for Log {
    fn g(&self, x: f64) -> f64 {
        x.ln()
    }
    fn d1(&self, x: f64) -> f64 {
        1.0 / x
    }
    fn d2(&self, x: f64) -> f64 {
        -1.0 / (x * x)
    }
}

/// tr g(C), its gradient and its Hessian, from the eigen-decomposition of C.
pub struct SpectralTrace {
    pub value: f64,
    pub grad: T2,
    pub hess: T4,
}

/// Eigenvalues closer than this (relative) count as equal in the divided difference.
const EQUAL_EIGENVALUES: f64 = 1e-6;

impl SpectralTrace {
    pub fn new(g: &dyn Scalar1, c: &[f64; 3], n: &T2) -> SpectralTrace {
        let col = |a: usize| [n[0][a], n[1][a], n[2][a]];
        let dirs = [col(0), col(1), col(2)];
        let mut value = 0.0;
        let mut grad = [[0.0; 3]; 3];
        for a in 0..3 {
            value += g.g(c[a]);
            let d = g.d1(c[a]);
            for i in 0..3 {
                for j in 0..3 {
                    grad[i][j] += d * dirs[a][i] * dirs[a][j];
                }
            }
        }
        let mut hess = [[[[0.0; 3]; 3]; 3]; 3];
        for a in 0..3 {
            for b in 0..3 {
                let (x, y) = (c[a], c[b]);
                let scale = x.abs().max(y.abs()).max(f64::MIN_POSITIVE);
                let g1 = if (x - y).abs() <= EQUAL_EIGENVALUES * scale {
                    g.d2(0.5 * (x + y))
                } else {
                    (g.d1(x) - g.d1(y)) / (x - y)
                };
                let (na, nb) = (dirs[a], dirs[b]);
                for i in 0..3 {
                    for j in 0..3 {
                        let w = 0.5 * g1 * na[i] * nb[j];
                        if w == 0.0 {
                            continue;
                        }
                        for k in 0..3 {
                            for l in 0..3 {
                                hess[i][j][k][l] += w * (na[k] * nb[l] + na[l] * nb[k]);
                            }
                        }
                    }
                }
            }
        }
        SpectralTrace { value, grad, hess }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c_of(f: &T2) -> T2 {
        let mut c = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = (0..3).map(|k| f[k][i] * f[k][j]).sum();
            }
        }
        c
    }

    fn trace(g: &dyn Scalar1, c: &T2) -> f64 {
        let (e, _) = eigen_symmetric(c);
        e.iter().map(|&x| g.g(x)).sum()
    }

    #[test]
    fn eigen_decomposition_reconstructs_the_matrix() {
        let c = c_of(&[[1.1, 0.2, -0.1], [0.05, 0.9, 0.3], [0.0, -0.2, 1.2]]);
        let (e, v) = eigen_symmetric(&c);
        for i in 0..3 {
            for j in 0..3 {
                let r: f64 = (0..3).map(|a| e[a] * v[i][a] * v[j][a]).sum();
                assert!((r - c[i][j]).abs() < 1e-14, "{r} {}", c[i][j]);
            }
        }
    }

    /// Gradient and Hessian against central differences over symmetric perturbations, for
    /// distinct, two equal and three equal eigenvalues.
    #[test]
    fn spectral_derivatives_match_finite_differences_also_at_repeated_eigenvalues() {
        let cases: [T2; 3] = [
            c_of(&[[1.1, 0.2, -0.1], [0.05, 0.9, 0.3], [0.0, -0.2, 1.2]]),
            [[1.3, 0.0, 0.0], [0.0, 1.3, 0.0], [0.0, 0.0, 0.7]],
            [[1.2, 0.0, 0.0], [0.0, 1.2, 0.0], [0.0, 0.0, 1.2]],
        ];
        for c in cases {
            for g in [&Power(0.65) as &dyn Scalar1, &Log, &Power(2.0)] {
                let (e, n) = eigen_symmetric(&c);
                let t = SpectralTrace::new(g, &e, &n);
                let h = 1e-5;
                for k in 0..3 {
                    for l in k..3 {
                        let mut dc = [[0.0; 3]; 3];
                        dc[k][l] += h;
                        dc[l][k] = dc[k][l];
                        let add = |s: f64| {
                            let mut m = c;
                            for i in 0..3 {
                                for j in 0..3 {
                                    m[i][j] += s * dc[i][j];
                                }
                            }
                            m
                        };
                        let (cp, cm) = (add(1.0), add(-1.0));
                        // Value: dT = Σ grad_ij dC_ij.
                        let fd = (trace(g, &cp) - trace(g, &cm)) / 2.0;
                        let an: f64 = (0..3)
                            .flat_map(|i| (0..3).map(move |j| (i, j)))
                            .map(|(i, j)| t.grad[i][j] * dc[i][j])
                            .sum();
                        assert!((fd - an).abs() < 1e-9, "gradient {fd} {an}");
                        // Gradient: d grad_ij = Σ hess_ijkl dC_kl.
                        let (ep, np) = eigen_symmetric(&cp);
                        let (em, nm) = eigen_symmetric(&cm);
                        let (tp, tm) = (
                            SpectralTrace::new(g, &ep, &np),
                            SpectralTrace::new(g, &em, &nm),
                        );
                        for i in 0..3 {
                            for j in 0..3 {
                                let fd = (tp.grad[i][j] - tm.grad[i][j]) / 2.0;
                                let an: f64 = (0..3)
                                    .flat_map(|a| (0..3).map(move |b| (a, b)))
                                    .map(|(a, b)| t.hess[i][j][a][b] * dc[a][b])
                                    .sum();
                                assert!((fd - an).abs() < 1e-8, "hessian {fd} {an}");
                            }
                        }
                    }
                }
            }
        }
    }
}
