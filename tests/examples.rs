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
            ..Default::default()
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

/// Solve an example and return its model and last contact state.
fn contact_example(
    name: &str,
) -> (
    hertz::model::Model,
    Vec<hertz::contact::SlotState>,
    Vec<f64>,
) {
    let model = hertz::input::read_model(&example(name)).unwrap().model;
    let mut out = (Vec::new(), Vec::new());
    hertz::solve::run_analysis(
        &model,
        &hertz::solve::SolveParams {
            log_steps: false,
            ..Default::default()
        },
        |r| {
            out = (r.contact.to_vec(), r.info.residual_history.clone());
            Ok(())
        },
    )
    .unwrap();
    (model, out.0, out.1)
}

/// Rigid cylinder on an elastic block (plane strain): p0 and a within 2 % of Hertz, and Newton
/// ends quadratically once the contact zone has settled.
#[test]
fn hertz_rigid_circle_p0_and_a_within_two_percent() {
    let (model, states, hist) = contact_example("hertz_rigid_circle.in");
    let c = hertz::analytic::compare_hertz(&model, &states, 0.0).unwrap();
    println!(
        "rigid circle: F {:.4} p0 {:.4} vs {:.4} ({:+.2} %), a {:.4} vs {:.4} ({:+.2} %)",
        c.force,
        c.p0,
        c.p0_ref,
        100.0 * c.p0_error(),
        c.a,
        c.a_ref,
        100.0 * c.a_error()
    );
    assert!(c.p0_error().abs() < 0.02 && c.a_error().abs() < 0.02);
    assert!(
        states.iter().filter(|s| s.active).count() >= 10,
        "the contact zone spans several elements"
    );
    // Newton: the contact branches are decided on the linearized problem, so after the first
    // step (from an open contact) the iterations converge superlinearly: one cuts the residual by
    // more than five orders of magnitude and the next reaches the round-off floor of the penalty
    // forces (p = 10⁴ E). Four iterations in all.
    println!("residual history {hist:?}");
    let n = hist.len();
    assert!((3..=5).contains(&n), "iterations: {hist:?}");
    assert!(
        hist[n - 2] < 1e-5 * hist[n - 3],
        "superlinear last iterations: {hist:?}"
    );
    assert!(hist[n - 1] < 1e-8, "converged to the floor: {hist:?}");
}

/// Elastic cylinder on an elastic block, node-to-segment between deformable bodies.
#[test]
fn hertz_elastic_cylinder_p0_and_a_within_two_percent() {
    let (model, states, _) = contact_example("hertz_cylinder.in");
    let c =
        hertz::analytic::compare_hertz(&model, &states, hertz::analytic::EXAMPLE_CYLINDER_RADIUS)
            .unwrap();
    println!(
        "elastic cylinder: F {:.4} p0 {:.4} vs {:.4} ({:+.2} %), a {:.4} vs {:.4} ({:+.2} %)",
        c.force,
        c.p0,
        c.p0_ref,
        100.0 * c.p0_error(),
        c.a,
        c.a_ref,
        100.0 * c.a_error()
    );
    assert!(c.p0_error().abs() < 0.02 && c.a_error().abs() < 0.02);
}

/// Rigid flat punch: the contact forces add up to the load, and p(x) = F/(π sqrt(a² − x²)) within
/// 5 % over the inner 80 % of the punch.
#[test]
fn flat_punch_force_balance_and_pressure_within_five_percent() {
    let (model, states, _) = contact_example("flat_punch.in");
    let (f, a) = (100.0, 1.0);
    let total = hertz::analytic::full_contact_force(&states);
    assert!((total - f).abs() < 1e-6 * f, "total contact force {total}");
    let prof = hertz::analytic::pressure_profile(&model, &states);
    let inner: Vec<_> = prof.iter().filter(|(x, _)| *x <= 0.8 * a + 1e-9).collect();
    assert!(inner.len() >= 30);
    for &&(x, p) in &inner {
        let exact = hertz::analytic::flat_punch_pressure(f, a, x);
        assert!(
            (p - exact).abs() < 0.05 * exact,
            "x = {x}: p = {p}, analytical {exact}"
        );
    }
}

/// The contact CSV has exactly the documented header and one row per contact node and step.
#[test]
fn contact_csv_has_the_documented_header_and_rows() {
    let dir = std::env::temp_dir().join(format!("hertz-csv-{}", std::process::id()));
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/oofem/contact_N2S_LM.in");
    run_file(
        &src,
        &RunOptions {
            write_outputs: true,
            out_dir: Some(dir.clone()),
            ..Default::default()
        },
    )
    .unwrap();
    let csv = std::fs::read_to_string(dir.join("contact_N2S_LM.contact.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "step,condition,node,x,y,z,gap,force,pressure,active"
    );
    assert_eq!(lines.len(), 3, "{csv}");
    let last: Vec<&str> = lines[2].split(',').collect();
    assert_eq!(&last[..3], &["2", "5", "5"]);
    let force: f64 = last[7].parse().unwrap();
    assert!((force - 8e6).abs() < 1.0, "{force}");
    assert_eq!(last[9], "1");
    std::fs::remove_dir_all(dir).ok();
}
