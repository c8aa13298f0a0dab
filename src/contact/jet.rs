//! Second-order forward automatic differentiation ("hyper-dual" numbers): a value with its
//! gradient and Hessian with respect to up to `MAXV` local unknowns. Contact gaps are written once
//! in this arithmetic, so their first and second derivatives — the contact residual and tangent —
//! are exact by construction.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// Most local unknowns of one contact pair (3D node + 3-node segment + reference node = 12).
pub const MAXV: usize = 12;

/// f with ∂f/∂q_i and ∂²f/∂q_i∂q_j for i, j < n.
#[derive(Clone, Copy, Debug)]
pub struct Jet {
    pub v: f64,
    pub g: [f64; MAXV],
    pub h: [[f64; MAXV]; MAXV],
    pub n: usize,
}

impl Jet {
    pub fn constant(v: f64, n: usize) -> Jet {
        Jet {
            v,
            g: [0.0; MAXV],
            h: [[0.0; MAXV]; MAXV],
            n,
        }
    }

    /// The i-th unknown with value v.
    pub fn variable(v: f64, i: usize, n: usize) -> Jet {
        let mut j = Jet::constant(v, n);
        j.g[i] = 1.0;
        j
    }

    /// f(self) for a scalar function with derivatives f1 = f', f2 = f''.
    pub fn chain(self, f: f64, f1: f64, f2: f64) -> Jet {
        let n = self.n;
        let mut r = Jet::constant(f, n);
        for i in 0..n {
            r.g[i] = f1 * self.g[i];
            for j in 0..n {
                r.h[i][j] = f1 * self.h[i][j] + f2 * self.g[i] * self.g[j];
            }
        }
        r
    }

    pub fn sqrt(self) -> Jet {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s, -0.25 / (s * self.v))
    }

    pub fn recip(self) -> Jet {
        let r = 1.0 / self.v;
        self.chain(r, -r * r, 2.0 * r * r * r)
    }

    pub fn powi(self, k: i32) -> Jet {
        if k == 0 {
            return Jet::constant(1.0, self.n);
        }
        let kf = k as f64;
        self.chain(
            self.v.powi(k),
            kf * self.v.powi(k - 1),
            kf * (kf - 1.0) * self.v.powi(k - 2),
        )
    }

    fn n2(a: &Jet, b: &Jet) -> usize {
        a.n.max(b.n)
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(self, b: Jet) -> Jet {
        let n = Jet::n2(&self, &b);
        let mut r = Jet::constant(self.v + b.v, n);
        for i in 0..n {
            r.g[i] = self.g[i] + b.g[i];
            for j in 0..n {
                r.h[i][j] = self.h[i][j] + b.h[i][j];
            }
        }
        r
    }
}

impl Sub for Jet {
    type Output = Jet;
    fn sub(self, b: Jet) -> Jet {
        self + (-b)
    }
}

impl Neg for Jet {
    type Output = Jet;
    fn neg(self) -> Jet {
        self * -1.0
    }
}

impl Mul for Jet {
    type Output = Jet;
    fn mul(self, b: Jet) -> Jet {
        let n = Jet::n2(&self, &b);
        let mut r = Jet::constant(self.v * b.v, n);
        for i in 0..n {
            r.g[i] = self.g[i] * b.v + self.v * b.g[i];
            for j in 0..n {
                r.h[i][j] = self.h[i][j] * b.v
                    + self.v * b.h[i][j]
                    + self.g[i] * b.g[j]
                    + b.g[i] * self.g[j];
            }
        }
        r
    }
}

impl Div for Jet {
    type Output = Jet;
    #[allow(clippy::suspicious_arithmetic_impl)] // a / b = a · (1/b)
    fn div(self, b: Jet) -> Jet {
        self * b.recip()
    }
}

impl Add<f64> for Jet {
    type Output = Jet;
    fn add(mut self, b: f64) -> Jet {
        self.v += b;
        self
    }
}

impl Sub<f64> for Jet {
    type Output = Jet;
    fn sub(mut self, b: f64) -> Jet {
        self.v -= b;
        self
    }
}

impl Mul<f64> for Jet {
    type Output = Jet;
    fn mul(mut self, b: f64) -> Jet {
        self.v *= b;
        for i in 0..self.n {
            self.g[i] *= b;
            for j in 0..self.n {
                self.h[i][j] *= b;
            }
        }
        self
    }
}

/// The unknowns `vals` as jets: q_i = vals[i] with ∂q_i/∂q_j = δ_ij.
pub fn seed(vals: &[f64]) -> Vec<Jet> {
    vals.iter()
        .enumerate()
        .map(|(i, &v)| Jet::variable(v, i, vals.len()))
        .collect()
}

/// Dot product of two small vectors of jets.
pub fn dot(a: &[Jet], b: &[Jet]) -> Jet {
    let mut s = a[0] * b[0];
    for i in 1..a.len() {
        s = s + a[i] * b[i];
    }
    s
}

/// Dot product with a constant vector.
pub fn dot_const(a: &[Jet], b: &[f64]) -> Jet {
    let mut s = a[0] * b[0];
    for i in 1..a.len() {
        s = s + a[i] * b[i];
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jet_derivatives_match_closed_form() {
        // f(x, y) = sqrt(x² + y²) / (x y + 1) at (0.7, 1.3)
        let (x0, y0) = (0.7, 1.3);
        let x = Jet::variable(x0, 0, 2);
        let y = Jet::variable(y0, 1, 2);
        let f = (x * x + y * y).sqrt() / (x * y + 1.0);
        let fv = |x: f64, y: f64| (x * x + y * y).sqrt() / (x * y + 1.0);
        assert!((f.v - fv(x0, y0)).abs() < 1e-15);
        let h = 1e-6;
        let gx = (fv(x0 + h, y0) - fv(x0 - h, y0)) / (2.0 * h);
        let gy = (fv(x0, y0 + h) - fv(x0, y0 - h)) / (2.0 * h);
        assert!((f.g[0] - gx).abs() < 1e-8 && (f.g[1] - gy).abs() < 1e-8);
        let h = 1e-4;
        let hxy = (fv(x0 + h, y0 + h) - fv(x0 + h, y0 - h) - fv(x0 - h, y0 + h)
            + fv(x0 - h, y0 - h))
            / (4.0 * h * h);
        let hxx = (fv(x0 + h, y0) - 2.0 * fv(x0, y0) + fv(x0 - h, y0)) / (h * h);
        assert!(
            (f.h[0][1] - hxy).abs() < 1e-6 && (f.h[1][0] - hxy).abs() < 1e-6,
            "{} {hxy}",
            f.h[0][1]
        );
        assert!((f.h[0][0] - hxx).abs() < 1e-6, "{} {hxx}", f.h[0][0]);
    }
}
