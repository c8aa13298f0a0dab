//! The point law of every material: stress, tangent and new state from the strain and the
//! integration point's committed state. Elements call it through [`PointLaw`]; each law is a
//! file of its own ([`super::elasticity`], [`super::mises`], the energies of
//! [`super::hyperelastic`]).
//!
//! Strain and stress: in small strain ε and σ; in large deformation (total Lagrangian) the
//! Green–Lagrange strain E and the second Piola–Kirchhoff stress S, the tangent dS/dE (the
//! element adds the geometric stiffness). Reduced Voigt form of the element's stress mode,
//! engineering shear strains.
//!
//! State: a law with [`PointLaw::state_len`] > 0 keeps that many numbers per integration point.
//! Every evaluation within a step starts from the state committed when the last step (or
//! substep) converged and returns the state its strain would leave; the solver commits that
//! state once the step converges and restores the committed one when it cuts a step back
//! (see `Assembler::commit_material_state`).

/// Where a law writes its answer at one point: the caller's buffers.
pub struct Response<'a> {
    /// The stress (reduced Voigt form).
    pub stress: &'a mut [f64],
    /// Its consistent tangent (row-major, n × n).
    pub tangent: &'a mut [f64],
    /// The state the strain leaves (`state_len` numbers).
    pub state: &'a mut [f64],
    /// In plane stress, the strain normal to the plane that the law's stress leaves, where it
    /// computes one (a hyperelastic law solves for it); 0 otherwise.
    pub normal_strain: f64,
}

/// A constitutive law at one integration point.
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

    /// The stress at `strain` from the committed state `old`, its consistent tangent and the
    /// state the strain leaves, into `out`; Err with the reason where the law has no answer (a
    /// deformation that inverts the material).
    fn respond(&self, strain: &[f64], old: &[f64], out: &mut Response) -> Result<(), String>;

    /// Whether the tangent is symmetric (every law of a potential, and associative plasticity's
    /// consistent tangent): an element then computes one triangle of Bᵀ D B.
    fn symmetric_tangent(&self) -> bool {
        true
    }

    /// Whether the law's stress depends on more than the current strain (its tangent is not
    /// constant): a solver must not reuse its stiffness.
    fn is_inelastic(&self) -> bool {
        self.state_len() > 0
    }

    /// The plastic strain, κ and damage a plastic law's `state` holds (None: not plastic).
    fn plastic(&self, _state: &[f64]) -> Option<PlasticState> {
        None
    }
}

/// [`PointLaw::respond`] into separate buffers; returns the normal strain of plane stress.
pub fn respond_into(
    law: &dyn PointLaw,
    strain: &[f64],
    old: &[f64],
    (stress, tangent, state): (&mut [f64], &mut [f64], &mut [f64]),
) -> Result<f64, String> {
    let mut out = Response {
        stress,
        tangent,
        state,
        normal_strain: 0.0,
    };
    law.respond(strain, old, &mut out)?;
    Ok(out.normal_strain)
}

/// What a plastic law reports of a point's state ([`PointLaw::plastic`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PlasticState {
    /// The plastic strain (full Voigt, engineering shears; finite strain: the Hencky plastic
    /// strain ½ ln C_p).
    pub strain: [f64; 6],
    /// κ, the equivalent plastic strain.
    pub kappa: f64,
    /// ω, the damage.
    pub damage: f64,
}
