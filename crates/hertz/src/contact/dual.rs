//! First-order forward automatic differentiation: a value with its gradient with respect to up to
//! [`MAXV`] local unknowns of a contact pair. Contact kinematics (projection point, normal, gap,
//! force direction) are written once in this arithmetic; the tangent of a contact force f(q) is the
//! gradient of its components, so it is exact by construction, including the variation of the
//! projection point. An implicit quantity (a projection parameter that solves r(ξ, q) = 0) gets its
//! exact derivative from one Newton step in dual arithmetic taken from the converged value.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// Most local unknowns of one contact pair: a 2D node against a quadratic edge whose end normals
/// are averaged with the neighbouring quadratic edges (9 nodes × 2) plus a multiplier; in 3D a
/// node against a quadrilateral with moving nodal normals (27) and the two other corners of a
/// neighbouring face its friction is anchored to (6), or against an 8-node quadrilateral with
/// moving nodal normals (3 + 8 × 3 positions and 8 × 3 normals: 51).
pub const MAXV: usize = 56;

/// f with ∂f/∂q_i for i < n ≤ N: the derivative storage is a fixed array, so arithmetic never
/// allocates; small problems (a projection in two parameters) use a small N.
#[derive(Clone, Copy, Debug)]
pub struct DualN<const N: usize> {
    pub v: f64,
    pub d: [f64; N],
    pub n: usize,
}

/// The dual of the contact kinematics (up to [`MAXV`] unknowns).
pub type Dual = DualN<MAXV>;

impl<const N: usize> DualN<N> {
    pub fn constant(v: f64, n: usize) -> Self {
        debug_assert!(n <= N);
        DualN { v, d: [0.0; N], n }
    }

    /// The i-th unknown with value v.
    pub fn variable(v: f64, i: usize, n: usize) -> Self {
        let mut x = Self::constant(v, n);
        x.d[i] = 1.0;
        x
    }

    /// f(self) for a scalar function with value f and derivative f1.
    pub fn chain(self, f: f64, f1: f64) -> Self {
        let mut r = Self::constant(f, self.n);
        for i in 0..self.n {
            r.d[i] = f1 * self.d[i];
        }
        r
    }

    pub fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s)
    }

    pub fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(r, -r * r)
    }

    /// self += a·b in place (no temporaries: an accumulation's many terms).
    pub fn add_mul(&mut self, a: &Self, b: &Self) {
        let n = a.n.max(b.n);
        if n > self.n {
            self.d[self.n..n].fill(0.0);
            self.n = n;
        }
        self.v += a.v * b.v;
        for i in 0..n {
            self.d[i] += a.d[i] * b.v + a.v * b.d[i];
        }
    }

    /// The gradient as a slice.
    pub fn grad(&self) -> &[f64] {
        &self.d[..self.n]
    }
}

impl<const N: usize> Add for DualN<N> {
    type Output = Self;
    fn add(mut self, b: Self) -> Self {
        self.n = self.n.max(b.n);
        self.v += b.v;
        for i in 0..self.n {
            self.d[i] += b.d[i];
        }
        self
    }
}

impl<const N: usize> Sub for DualN<N> {
    type Output = Self;
    fn sub(mut self, b: Self) -> Self {
        self.n = self.n.max(b.n);
        self.v -= b.v;
        for i in 0..self.n {
            self.d[i] -= b.d[i];
        }
        self
    }
}

impl<const N: usize> Neg for DualN<N> {
    type Output = Self;
    fn neg(self) -> Self {
        self * -1.0
    }
}

impl<const N: usize> Mul for DualN<N> {
    type Output = Self;
    fn mul(self, b: Self) -> Self {
        let n = self.n.max(b.n);
        let mut r = Self::constant(self.v * b.v, n);
        for i in 0..n {
            r.d[i] = self.d[i] * b.v + self.v * b.d[i];
        }
        r
    }
}

impl<const N: usize> Div for DualN<N> {
    type Output = Self;
    fn div(self, b: Self) -> Self {
        let n = self.n.max(b.n);
        let q = self.v / b.v;
        let mut r = Self::constant(q, n);
        for i in 0..n {
            r.d[i] = (self.d[i] - q * b.d[i]) / b.v;
        }
        r
    }
}

impl<const N: usize> Add<f64> for DualN<N> {
    type Output = Self;
    fn add(mut self, b: f64) -> Self {
        self.v += b;
        self
    }
}

impl<const N: usize> Sub<f64> for DualN<N> {
    type Output = Self;
    fn sub(mut self, b: f64) -> Self {
        self.v -= b;
        self
    }
}

impl<const N: usize> Mul<f64> for DualN<N> {
    type Output = Self;
    fn mul(mut self, b: f64) -> Self {
        self.v *= b;
        for i in 0..self.n {
            self.d[i] *= b;
        }
        self
    }
}

/// A value with its gradient over any number of unknowns: the form in which a contact point's
/// kinematics reach its law. A dual evaluation gives one directly ([`Jet::from`]); kinematics
/// whose unknowns exceed [`MAXV`] are evaluated in duals over a few intermediate quantities and
/// chained to the local unknowns (see [`Jet::chain`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Jet {
    pub v: f64,
    pub d: Vec<f64>,
}

impl From<Dual> for Jet {
    fn from(x: Dual) -> Jet {
        Jet {
            v: x.v,
            d: x.grad().to_vec(),
        }
    }
}

impl Jet {
    pub fn constant(v: f64, m: usize) -> Jet {
        Jet { v, d: vec![0.0; m] }
    }

    /// The jet over `m` unknowns of a dual over intermediate variables z: d/dq = Σ_k ∂x/∂z_k ·
    /// ∂z_k/∂q, where `dz[k]` lists the nonzero (unknown, ∂z_k/∂q) of z_k.
    pub fn chain(x: &Dual, dz: &[Vec<(usize, f64)>], m: usize) -> Jet {
        let mut d = vec![0.0; m];
        for (k, entries) in dz.iter().enumerate() {
            let a = x.d[k];
            if a != 0.0 {
                for &(j, v) in entries {
                    d[j] += a * v;
                }
            }
        }
        Jet { v: x.v, d }
    }

    /// self += a · b, in place; nothing to do where b is zero (its value and gradient: a
    /// mortar moment's force direction at an unknown the face does not hold).
    pub fn add_product(&mut self, a: &Jet, b: &Jet) {
        if b.v == 0.0 && b.d.iter().all(|&x| x == 0.0) {
            return;
        }
        self.v += a.v * b.v;
        for ((s, x), y) in self.d.iter_mut().zip(&a.d).zip(&b.d) {
            *s += x * b.v + a.v * y;
        }
    }

    /// self · other.
    pub fn product(&self, other: &Jet) -> Jet {
        Jet {
            v: self.v * other.v,
            d: self
                .d
                .iter()
                .zip(&other.d)
                .map(|(a, b)| a * other.v + self.v * b)
                .collect(),
        }
    }
}

/// A small vector of duals (a position, a normal) of dimension ≤ 3.
pub type DVec = [Dual; 3];

/// The unknowns `vals` as duals: q_i = `vals[i]` with ∂q_i/∂q_j = δ_ij, in a space of `n` unknowns.
pub fn seed(vals: &[f64], n: usize) -> Vec<Dual> {
    vals.iter()
        .enumerate()
        .map(|(i, &v)| Dual::variable(v, i, n))
        .collect()
}

/// A constant vector as duals.
pub fn constant_vec(x: &[f64], n: usize) -> DVec {
    let mut r = [Dual::constant(0.0, n); 3];
    for (ri, &xi) in r.iter_mut().zip(x) {
        *ri = Dual::constant(xi, n);
    }
    r
}

/// a·b over the first `dim` components.
pub fn dot(a: &DVec, b: &DVec, dim: usize) -> Dual {
    let mut s = a[0] * b[0];
    for i in 1..dim {
        s = s + a[i] * b[i];
    }
    s
}

/// a − b.
pub fn sub(a: &DVec, b: &DVec, dim: usize) -> DVec {
    let mut r = *a;
    for i in 0..dim {
        r[i] = a[i] - b[i];
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dual_derivatives_match_central_differences() {
        // f(x, y) = sqrt(x² + y²) / (x y + 1) at (0.7, 1.3)
        let (x0, y0) = (0.7, 1.3);
        let x = Dual::variable(x0, 0, 2);
        let y = Dual::variable(y0, 1, 2);
        let f = (x * x + y * y).sqrt() / (x * y + 1.0) - x.recip() * 0.5;
        let fv = |x: f64, y: f64| (x * x + y * y).sqrt() / (x * y + 1.0) - 0.5 / x;
        assert!((f.v - fv(x0, y0)).abs() < 1e-15);
        let h = 1e-6;
        let gx = (fv(x0 + h, y0) - fv(x0 - h, y0)) / (2.0 * h);
        let gy = (fv(x0, y0 + h) - fv(x0, y0 - h)) / (2.0 * h);
        assert!((f.d[0] - gx).abs() < 1e-8, "{} {gx}", f.d[0]);
        assert!((f.d[1] - gy).abs() < 1e-8, "{} {gy}", f.d[1]);
    }
}
