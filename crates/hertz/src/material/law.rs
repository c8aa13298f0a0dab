//! The point law of small-strain materials: stress, tangent and new state from the strain and the
//! integration point's committed state. Elements call it through [`PointLaw`]; each law is a file
//! of its own ([`super::elasticity`], [`super::mises`]).
//!
//! State: a law with [`PointLaw::state_len`] > 0 keeps that many numbers per integration point.
//! Every evaluation within a step starts from the state committed when the last step (or
//! substep) converged and returns the state its strain would leave; the solver commits that
//! state once the step converges and restores the committed one when it cuts a step back
//! (see `Assembler::commit_material_state`).

/// A small-strain constitutive law at one integration point.
pub trait PointLaw: Send + Sync + std::fmt::Debug {
    /// Strain and stress components: the reduced Voigt form of the element's stress mode.
    fn components(&self) -> usize;

    /// State variables per integration point (0: an elastic law).
    fn state_len(&self) -> usize {
        0
    }

    /// The state of a point that has not yet deformed.
    fn initial_state(&self, state: &mut [f64]) {
        state.fill(0.0);
    }

    /// σ(ε; `old`) into `stress`, the consistent tangent dσ/dε (row-major, n × n) into
    /// `tangent`, and the state the strain leaves into `new` (`old`, `new`: `state_len` numbers).
    fn respond(
        &self,
        strain: &[f64],
        old: &[f64],
        stress: &mut [f64],
        tangent: &mut [f64],
        new: &mut [f64],
    );

    /// Whether the law's stress depends on more than the current strain (its tangent is not
    /// constant): a solver must not reuse its stiffness.
    fn is_inelastic(&self) -> bool {
        self.state_len() > 0
    }
}
