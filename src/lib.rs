//! hertz: a finite-element program for solid mechanics with contact that reads OOFEM input files.

pub mod app;
pub mod bench;
pub mod error;
pub mod fem;
pub mod input;
pub mod model;
pub mod output;
pub mod solid;
pub mod solve;
