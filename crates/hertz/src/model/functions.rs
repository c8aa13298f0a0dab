//! Time functions (spec §1.15).

/// A load-time function f(t).
#[derive(Debug, Clone)]
pub enum TimeFunction {
    Constant(f64),
    PiecewiseLinear { t: Vec<f64>, f: Vec<f64> },
    Peak { t: f64, value: f64 },
}

impl TimeFunction {
    /// f(t). Before the first point of a piecewise-linear function OOFEM returns the first *date*
    /// (QUIRK, spec §1.15); hertz returns the first *value* (constant extrapolation), which is the
    /// only reading that makes sense; the reader warns when a step time falls there.
    pub fn eval(&self, time: f64) -> f64 {
        match self {
            TimeFunction::Constant(v) => *v,
            TimeFunction::Peak { t, value } => {
                if (time - t).abs() < 1e-6 {
                    *value
                } else {
                    0.0
                }
            }
            TimeFunction::PiecewiseLinear { t, f } => {
                if time <= t[0] {
                    return f[0];
                }
                for i in 1..t.len() {
                    if (time - t[i]).abs() < 1e-12 {
                        return f[i];
                    }
                    if time < t[i] {
                        let s = (time - t[i - 1]) / (t[i] - t[i - 1]);
                        return f[i - 1] + s * (f[i] - f[i - 1]);
                    }
                }
                *f.last().unwrap()
            }
        }
    }

    /// First abscissa of a piecewise-linear function, if any.
    pub fn first_time(&self) -> Option<f64> {
        match self {
            TimeFunction::PiecewiseLinear { t, .. } => t.first().copied(),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn piecewise_linear_interpolates_and_clamps() {
        let f = TimeFunction::PiecewiseLinear {
            t: vec![-1.0, 0.0, 500.0],
            f: vec![0.0, 1.0, 501.0],
        };
        assert_eq!(f.eval(3.0), 4.0);
        assert_eq!(f.eval(0.0), 1.0);
        assert_eq!(f.eval(600.0), 501.0);
        assert_eq!(f.eval(-5.0), 0.0);
    }
}
