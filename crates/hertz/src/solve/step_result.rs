//! What a converged step hands its caller: the state, reactions, contact and material states,
//! and in dynamics the motion and the energies.

use crate::assembly::DofMap;
use crate::contact::SlotState;
use crate::solid::GpState;

use super::report::StepInfo;

/// The converged state after a step.
pub struct StepResult<'a> {
    pub step: usize,
    pub time: f64,
    pub dofs: &'a DofMap,
    /// Primary displacement vector (free, then prescribed).
    pub u: &'a [f64],
    /// Reaction per prescribed DOF (same order as `dofs.prescribed`).
    pub reactions: &'a [f64],
    pub states: &'a [Vec<GpState>],
    /// Contact state of every contact node.
    pub contact: &'a [SlotState],
    pub info: &'a StepInfo,
    /// A dynamic analysis's velocities, accelerations and energies.
    pub motion: Option<Motion<'a>>,
}

/// The motion of a dynamic step: velocity and acceleration of every primary DOF (as `u`) and the
/// energies so far.
#[derive(Clone, Copy)]
pub struct Motion<'a> {
    pub velocity: &'a [f64],
    pub acceleration: &'a [f64],
    pub energy: Energy,
}

/// Energies of a dynamic analysis at a step: the kinetic energy and the work done since the
/// start (each integrated by the trapezoidal rule over every step's increment).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energy {
    pub kinetic: f64,
    /// Work of the elements' internal forces (the strain energy of elastic bodies).
    pub internal: f64,
    /// Work of the contact forces on the bodies (the penalty's stored energy, friction's
    /// dissipation).
    pub contact: f64,
    /// Work of the damping forces (energy dissipated by Rayleigh damping).
    pub damping: f64,
    /// Work of the external loads.
    pub external: f64,
    /// Work of the support forces on prescribed motion.
    pub supports: f64,
    /// The kinetic energy at the start.
    pub initial: f64,
}

impl Energy {
    /// What the scheme created (> 0) or lost (< 0): kinetic + internal + contact + damping −
    /// external − supports − initial; zero for the trapezoidal rule on linear elastic bodies.
    pub fn balance(&self) -> f64 {
        self.kinetic + self.internal + self.contact + self.damping
            - self.external
            - self.supports
            - self.initial
    }
}

impl StepResult<'_> {
    /// Total displacement of DOF `d` of node `n`, if the node has it.
    pub fn displacement(&self, n: usize, d: u8) -> Option<f64> {
        self.dofs.code(n, d).map(|c| self.dofs.value(self.u, c))
    }
}
