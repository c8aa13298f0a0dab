//! Newton driver: quadratic convergence of full Newton on a geometrically nonlinear problem,
//! step cut-back when an iteration limit is hit, and a clear error when cutting cannot help.

mod common;

use hertz::solve::run_analysis;
use std::path::PathBuf;

/// Solve tests/data/cantilever_nlgeo.in with the given maxiter; returns (tip v, substeps, history).
fn solve(maxiter: usize) -> hertz::error::Result<(f64, usize, Vec<f64>)> {
    let src = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/cantilever_nlgeo.in"),
    )
    .unwrap();
    let model = common::model_from_text(&src.replace("MAXITER", &maxiter.to_string()))?;
    let tip = model.nodes.iter().position(|n| n.label == 63).unwrap();
    let mut out = (0.0, 0, Vec::new());
    run_analysis(&model, &common::quiet(), |r| {
        out = (
            r.displacement(tip, 2).unwrap(),
            r.info.substeps,
            r.info.residual_history.clone(),
        );
        Ok(())
    })?;
    Ok(out)
}

#[test]
fn full_newton_converges_quadratically_on_large_deflection() {
    let (v, substeps, hist) = solve(50).unwrap();
    assert_eq!(substeps, 1);
    // Large deflection: beam theory would give P L³/(3EI) = 3.2; the nonlinear answer is smaller.
    assert!(v < -1.0 && v > -3.2, "tip deflection {v}");
    println!("residual history {hist:?}");
    // Quadratic convergence over the last iterations: r_{k+1} <= C r_k² with a modest C.
    let n = hist.len();
    assert!(n >= 4);
    let (a, b, c) = (hist[n - 3], hist[n - 2], hist[n - 1]);
    assert!(
        a < 1e-2,
        "the last iterations start close to the solution: {a:e}"
    );
    assert!(
        b <= 10.0 * a * a && c <= 10.0 * b * b,
        "quadratic: {a:e} {b:e} {c:e}"
    );
}

#[test]
fn iteration_limit_cuts_the_step_and_reaches_the_same_equilibrium() {
    let (v_ref, _, _) = solve(50).unwrap();
    let (v, substeps, _) = solve(5).unwrap();
    assert!(substeps > 1, "the step was cut ({substeps} substeps)");
    assert!((v - v_ref).abs() < 1e-6 * v_ref.abs(), "{v} vs {v_ref}");
}

#[test]
fn hopeless_step_fails_with_a_solver_error() {
    let err = solve(3).unwrap_err();
    assert_eq!(err.exit_code(), 3);
    let msg = err.to_string();
    assert!(
        msg.contains("did not converge within 3 iterations even after 5 step halvings"),
        "{msg}"
    );
}
