//! Hertz contact in plane strain: runs `examples/hertz_rigid_circle.in` (rigid cylinder) or
//! `examples/hertz_cylinder.in` (elastic cylinder on an elastic block), then compares the
//! maximum pressure p0 and the half-width a with Hertz's solution for the computed force F:
//!   a = sqrt(4 F R/(π E*)),  p0 = sqrt(F E*/(π R)),  1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2.
//!
//!     cargo run --release --example hertz -- examples/hertz_rigid_circle.in
//!     cargo run --release --example hertz -- examples/hertz_cylinder.in
//!
//! Exits with status 1 if p0 or a is more than 2 % off.

use hertz::analytic::{compare_hertz, EXAMPLE_CYLINDER_RADIUS};
use hertz::input::read_model;
use hertz::solve::{run_analysis, SolveParams};
use std::process::ExitCode;

fn main() -> ExitCode {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "examples/hertz_rigid_circle.in".into());
    let model = match read_model(std::path::Path::new(&path)) {
        Ok(r) => r.model,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let mut states = Vec::new();
    if let Err(e) = run_analysis(&model, &SolveParams::default(), |r| {
        states = r.contact.to_vec();
        Ok(())
    }) {
        eprintln!("error: {e}");
        return ExitCode::from(3);
    }
    let Some(c) = compare_hertz(&model, &states, EXAMPLE_CYLINDER_RADIUS) else {
        eprintln!("error: no contact zone of several nodes");
        return ExitCode::from(1);
    };
    let (force, p0, p0_ref, a, a_ref) = (c.force, c.p0, c.p0_ref, c.a, c.a_ref);
    let (ep, ea) = (c.p0_error(), c.a_error());
    println!("{path}");
    println!("  contact force F        {force:.6}");
    println!(
        "  max pressure p0        {p0:.6}   Hertz {p0_ref:.6}   error {:+.2} %",
        100.0 * ep
    );
    println!(
        "  half-width a           {a:.6}   Hertz {a_ref:.6}   error {:+.2} %",
        100.0 * ea
    );
    if ep.abs() < 0.02 && ea.abs() < 0.02 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
