//! Examples are verifications: each runs and meets its analytical reference.

use hertz::app::{run_file, RunOptions};
use hertz::output::check::RuleKind;
use std::path::PathBuf;

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

/// Cantilever, tip shear P: Timoshenko deflection P L³/(3EI) + P L/(κ G A) within 1 %.
#[test]
fn cantilever_tip_deflection_matches_timoshenko_within_one_percent() {
    let (l, h, e, nu, p) = (10.0f64, 1.0f64, 1000.0, 0.3, 1.0);
    let i = h.powi(3) / 12.0;
    let g = e / (2.0 * (1.0 + nu));
    let exact = -(p * l.powi(3) / (3.0 * e * i) + p * l / (5.0 / 6.0 * g * h));
    let dir = std::env::temp_dir().join(format!("hertz-ex-{}", std::process::id()));
    let report = run_file(
        &example("cantilever.in"),
        &RunOptions {
            write_outputs: true,
            out_dir: Some(dir.clone()),
            log_steps: false,
        },
    )
    .expect("cantilever solves");
    assert_eq!(report.n_failed(), 0);
    let tip = report
        .outcomes
        .iter()
        .find(|o| {
            matches!(
                o.rule.kind,
                RuleKind::Node {
                    node: 325,
                    dof: 2,
                    ..
                }
            )
        })
        .and_then(|o| o.computed)
        .expect("tip rule evaluated");
    let err = (tip - exact).abs() / exact.abs();
    println!(
        "cantilever tip deflection: computed {tip:.6}, Timoshenko {exact:.6}, error {:.3} %",
        100.0 * err
    );
    assert!(err < 0.01, "error {err}");
    for f in ["cantilever.out", "cantilever.1.vtu", "cantilever.pvd"] {
        assert!(dir.join(f).is_file(), "{f} written");
    }
    std::fs::remove_dir_all(dir).ok();
}
