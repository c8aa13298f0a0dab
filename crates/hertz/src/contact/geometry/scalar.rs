//! The number type contact geometry is written in: plain `f64` for the search, [`DualN`] for the
//! kinematics whose derivatives make the tangent.

use crate::contact::dual::DualN;
use std::ops::{Add, Div, Mul, Neg, Sub};

pub trait Scalar:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
{
    /// A constant of the same kind (for duals: with as many unknowns as `self`).
    fn cst(&self, v: f64) -> Self;
    fn val(&self) -> f64;
    fn sqrt(self) -> Self;
}

impl Scalar for f64 {
    fn cst(&self, v: f64) -> f64 {
        v
    }
    fn val(&self) -> f64 {
        *self
    }
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
}

impl<const N: usize> Scalar for DualN<N> {
    fn cst(&self, v: f64) -> Self {
        DualN::constant(v, self.n)
    }
    fn val(&self) -> f64 {
        self.v
    }
    fn sqrt(self) -> Self {
        DualN::sqrt(self)
    }
}
