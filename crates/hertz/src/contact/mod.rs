//! Contact conditions (spec §2) as state-dependent internal forces with exact tangents.
//!
//! A condition is a [`Formulation`]: it says which nodes need DOFs, how many multipliers it adds
//! and which equations its contributions can touch, and evaluates itself at the current state into
//! local contributions (one per contact point) for the assembler. Every formulation has the same
//! inside: [`geometry`] (surfaces, projection, normals), [`search`] (which partner a node meets),
//! kinematics in [`dual`] arithmetic (gap, weight, force direction and their derivatives) and a
//! [`law`] (penalty or multiplier, and Coulomb friction: a return map on penalty points, friction
//! multipliers on node-to-segment multiplier points) that turns them into a residual and
//! tangent. Formulations: [`n2n`] (node-to-node), [`n2s`] (node-to-segment),
//! [`mortar`] (segment-to-segment, 2D edges and 3D faces). The friction history is the anchors
//! of the converged contact states ([`Anchor`]): the solver restores them with the states when
//! it cuts a step.
//!
//! OOFEM defects fixed here (spec §2.10): normals point out of the master body whatever the node
//! order; the gap is measured to the contact point; the tangent is the exact derivative, including
//! the variation of the contact point; the active set is a complementarity rule, not the sign of
//! the gap with frozen multipliers; contact forces are internal forces, never accumulated between
//! steps; prescribed normals are normalized; node numbers are labels; rigid segments have their
//! body on a side fixed by definition.

pub mod dual;
pub mod geometry;
pub mod law;
pub mod mortar;
pub mod n2n;
pub mod n2s;
pub mod point;
pub mod search;
pub mod tributary;

pub mod formulation;
mod initial;
pub mod system;

pub use crate::model::queries::{master_young, model_size, stiffest_young};
pub use formulation::*;
pub use initial::initial_warnings;
pub use point::{BranchRule, ContactPoint};
pub use system::{crossing_message, ContactSystem};
