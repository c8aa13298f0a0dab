//! hertz: a finite-element program for solid mechanics with contact that reads OOFEM input files.
//!
//! # Scope
//! Static problems on trusses, 2D plane stress/strain and 3D solids (bricks, tetrahedra, wedges)
//! in small strain or total-Lagrangian large deformation, read from the OOFEM text format, solved
//! by Newton–Raphson on a sparse direct solver, and checked by the `#%BEGIN_CHECK%` rules the
//! files carry; materials with a state per integration point (von Mises plasticity of bars).
//! Not in scope: dynamics, plasticity of continua, shells and beams, arc-length control.
//!
//! # Layers
//! [`fem`] knows reference elements only (shape functions, quadrature, Jacobians); [`solid`]
//! evaluates element kernels point-wise (internal force, tangent, integration-point states);
//! [`contact`] evaluates contact conditions point-wise (geometry, search, kinematics, laws);
//! [`assembly`] numbers DOFs and assembles element and contact contributions on a fixed sparse
//! pattern; [`solve`] factorizes, runs Newton and drives the load steps; [`input`] turns the text
//! into a checked [`model::Model`]; [`output`] writes results and evaluates rules.
//!
//! # The math in brief
//! Each step solves r(u) = F_int(u) − F_ext(t) = 0 on the free DOFs, with prescribed values
//! u_p = ū·f(t). The total-Lagrangian kernel uses F = I + ∂u/∂X, E = ½(FᵀF − I), S = D:E and
//! F_int,a = ∫ F·S·∇N_a dV; its tangent adds the geometric term ∫ ∇N_a·S·∇N_b dV·I. Contact adds
//! internal forces p·w·g·B (penalty) or λ·B with the constraint g = 0 (multipliers) per contact
//! point, g the gap and B the force direction over the point's unknowns (for mortar contact g is
//! a slave node's weighted mean gap), and with friction a friction force λ_T with Alart and
//! Curnier's complementarity function of the slip from an anchor, with exact (unsymmetric)
//! tangents; a frictional penalty condition has its forces λ, λ_T as unknowns too, with the
//! penalty's compliance in their rows (g + λ/ε = 0, and g_T = λ_T/ε_T while it sticks).
//!
//! # Example
//! ```
//! use hertz::app::{run_file, RunOptions};
//! let report = run_file(std::path::Path::new("../../examples/cantilever.in"), &RunOptions::default())?;
//! assert_eq!(report.n_failed(), 0);
//! # Ok::<(), hertz::error::Error>(())
//! ```

// Numerical kernels index several arrays with one loop variable; iterator chains would hide the math.
#![allow(clippy::needless_range_loop)]
// `!(x > 0.0)` is deliberate where NaN must count as failure.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod analytic;
pub mod app;
pub mod assembly;
pub mod contact;
pub mod error;
pub mod fem;
pub mod input;
pub mod material;
pub mod mesh;
pub mod model;
pub mod output;
pub mod solid;
pub mod solve;
#[cfg(test)]
mod testing;
