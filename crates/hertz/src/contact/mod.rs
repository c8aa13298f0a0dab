//! Contact conditions (spec §2) as state-dependent internal forces with exact tangents.
//!
//! A condition is a [`Formulation`]: it says which nodes need DOFs, how many multipliers it adds
//! and which equations its contributions can touch, and evaluates itself at the current state into
//! local contributions (one per slot) for the assembler. Every formulation has the same
//! inside: [`geometry`] (surfaces, projection, normals), [`search`] (which partner a node meets),
//! kinematics in [`dual`] arithmetic (gap, weight, force direction and their derivatives) and a
//! [`law`] (penalty or multipliers, and Coulomb friction, whose forces are multipliers under
//! either: with a penalty, its compliance 1/ε in their rows) that turns them into a residual and
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
//!
//! # Words
//!
//! * **contact node**: a node whose contact is checked (OOFEM's slave node).
//! * **slot**: what the solver sees of one contact node of one condition: one normal gap (for
//!   mortar the node's weighted gap over its support), one normal force (a penalty's, or a
//!   multiplier), its friction, its [`SlotState`] after an evaluation and its
//!   [`SlotLinearization`] (unknowns, residual and tangent of its closed branch, branch rule).
//!   Slots are numbered condition by condition in the order of their contact nodes.
//! * **contact point**: the point of the master a contact node's gap is measured to (its
//!   projection along the smoothed normal), whose variation the tangent includes.
//! * **partner**: the master edge, face or rigid shape a slot is paired with ([`Partner`]).
//! * **branch**: closed (the law's force acts) or open (no force) of a slot; the
//!   [`BranchRule`] decides it.
//! * **compliance**: 1/ε of a penalty solved with its forces as unknowns (0 for multipliers).
//! * **anchor**: the master's material point a sticking slot is held to ([`Anchor`]).

pub mod dual;
pub mod geometry;
pub mod law;
pub mod mortar;
pub mod n2n;
pub mod n2s;
pub mod search;
pub mod slot;
pub mod tributary;

pub mod formulation;
mod initial;
mod repeated;
pub mod system;

pub use formulation::{interface_weights, Anchor, Formulation, Partner, Search, SlotState};
pub use initial::{initial_warnings, pressure_warning};
pub use slot::{BranchRule, SlotLinearization};
pub use system::{crossing_message, ContactSystem};
