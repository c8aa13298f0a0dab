//! Backtracking of Newton steps where a material yields.

/// The backtracking of a Newton step where a material yields: its steps across the kinks of
/// plastic loading and unloading (with contact nodes opening and closing over a plastic zone)
/// can cycle. From the second step on, a step is halved (up to [`MAX_HALVINGS`] times, each an
/// iteration) while the residual along it, r·Δu, keeps more than [`SLOPE_KEPT`] of its size at
/// the step's start (Crisfield's line-search test; the residual's norm may rise once on
/// Newton's way to quadratic convergence, so it is no test). Measured on
/// examples/indentation.in (perfectly plastic): the deepest step cycled for 40 iterations and
/// was cut in two (53 in all); with this, 9 and no cut-back; a plastic patch keeps its 6.
#[derive(Default)]
pub(super) struct Backtrack {
    /// r·Δu where the step Δu started, halved with the step.
    slope: f64,
    halvings: usize,
}

const MAX_HALVINGS: usize = 4;
const SLOPE_KEPT: f64 = 0.8;

impl Backtrack {
    /// A new step `du` from the residual `rhs`.
    pub(super) fn start(&mut self, rhs: &[f64], du: &[f64]) {
        self.slope = rhs.iter().zip(du).map(|(r, d)| r * d).sum();
        self.halvings = 0;
    }

    /// Whether the step `du` that led to `u` (free DOFs), whose residual is `rhs`, is to be
    /// halved: if so, `u` and `du` are moved back to its half.
    pub(super) fn halves(&mut self, rhs: &[f64], u: &mut [f64], du: &mut [f64]) -> bool {
        let slope: f64 = rhs.iter().zip(du.iter()).map(|(r, d)| r * d).sum();
        if !(slope.abs() > SLOPE_KEPT * self.slope.abs()) || self.halvings == MAX_HALVINGS {
            return false;
        }
        self.halvings += 1;
        self.slope *= 0.5;
        for (x, d) in u.iter_mut().zip(du.iter_mut()) {
            *d *= 0.5;
            *x -= *d;
        }
        true
    }
}
