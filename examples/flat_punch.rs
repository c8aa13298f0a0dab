//! Rigid flat punch: runs `examples/flat_punch.in` and compares the contact pressure with the
//! half-space solution p(x) = F / (π sqrt(a² − x²)) over the inner 80 % of the punch, and the
//! total contact force with the prescribed load F.
//!
//!     cargo run --release --example flat_punch
//!
//! Exits with status 1 if the force is off or any pressure in |x| <= 0.8 a is more than 5 % off.

use hertz::analytic::{flat_punch_pressure, full_contact_force, pressure_profile};
use hertz::input::read_model;
use hertz::solve::{run_analysis, SolveParams};
use std::process::ExitCode;

/// Punch half-width and force of examples/flat_punch.in (the load record is −F/2 on a half model).
const A: f64 = 1.0;
const F: f64 = 100.0;

fn main() -> ExitCode {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "examples/flat_punch.in".into());
    let model = read_model(std::path::Path::new(&path))
        .expect("example reads")
        .model;
    let mut states = Vec::new();
    run_analysis(&model, &SolveParams::default(), |r| {
        states = r.contact.to_vec();
        Ok(())
    })
    .expect("example solves");
    let force = full_contact_force(&states);
    println!("{path}\n  total contact force {force:.6}   prescribed {F}");
    println!("       x      p(x)   analytical   error");
    let mut worst: f64 = 0.0;
    for (x, p) in pressure_profile(&model, &states) {
        if x <= 0.8 * A + 1e-9 {
            let exact = flat_punch_pressure(F, A, x);
            let err = (p - exact) / exact;
            worst = worst.max(err.abs());
            println!("  {x:6.3}  {p:8.4}  {exact:8.4}   {:+.2} %", 100.0 * err);
        }
    }
    println!(
        "  largest pressure error over |x| <= 0.8 a: {:.2} %",
        100.0 * worst
    );
    if (force - F).abs() < 1e-6 * F && worst < 0.05 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
