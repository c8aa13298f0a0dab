//! hertz's integration tests, one binary (one link step) with a module per area. `cargo test
//! --release` runs the everyday suite; the long group (ironing histories, 3D series, the largest
//! finite-difference checks) is marked `#[ignore = "long: ..."]` and runs with `-- --ignored`.
//! One area: `cargo test --release --test suite friction::`.

mod common;

mod axisymmetry;
mod cli;
mod condensed;
mod contact3d;
mod contact_geometry;
mod contact_suite;
mod contact_tangent;
mod dynamics;
mod elements;
mod examples;
mod friction;
mod gmsh;
mod hairpin;
mod hyperelastic;
mod indentation;
pub(crate) mod locking;
mod mortar;
mod newton;
mod oofem_suite;
#[cfg(feature = "petsc")]
mod petsc;
mod plasticity;
mod plot;
mod pressure;
mod robustness;
mod self_contact;
mod translation;
mod upstream;
