//! Examples are verifications: each runs and meets its analytical reference.

use crate::common;

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

/// Solve an example and return its model, last contact state and residual history.
fn contact_example(
    name: &str,
) -> (
    hertz::model::Model,
    Vec<hertz::contact::SlotState>,
    Vec<f64>,
) {
    common::solve_contact(&example(name))
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
        "step,condition,node,x,y,z,gap,force,pressure,active,friction,slip"
    );
    assert_eq!(lines.len(), 3, "{csv}");
    let last: Vec<&str> = lines[2].split(',').collect();
    assert_eq!(&last[..3], &["2", "5", "5"]);
    let force: f64 = last[7].parse().unwrap();
    assert!((force - 8e6).abs() < 1.0, "{force}");
    assert_eq!(last[9], "1");
    std::fs::remove_dir_all(dir).ok();
}

/// The committed verification examples are exactly what `hertz bench --examples DIR` writes.
#[test]
fn verification_examples_are_the_generated_ones() {
    for ex in hertz_bench::examples::all() {
        let committed = std::fs::read_to_string(example(ex.file)).expect("example committed");
        assert!(
            committed == ex.text(),
            "examples/{} differs from `hertz bench --examples`: regenerate it",
            ex.file
        );
    }
}

/// Solve an example file, calling `each` with the model and every converged step.
fn run_example(
    name: &str,
    mut each: impl FnMut(&hertz::model::Model, &hertz::solve::StepResult) -> usize,
) -> Vec<usize> {
    let model = hertz::input::read_model(&example(name)).unwrap().model;
    let mut its = Vec::new();
    hertz::solve::run_analysis(
        &model,
        &hertz::solve::SolveParams {
            max_cutbacks: 0,
            ..Default::default()
        },
        |r| {
            its.push(each(&model, r));
            Ok(())
        },
    )
    .unwrap();
    its
}

/// The sum of the reactions in direction `dof` of the prescribed DOFs whose node passes `pick`.
fn reaction(
    model: &hertz::model::Model,
    r: &hertz::solve::StepResult,
    dof: u8,
    pick: impl Fn([f64; 3]) -> bool,
) -> f64 {
    r.dofs
        .prescribed
        .iter()
        .zip(r.reactions)
        .filter(|((n, d, _), _)| *d == dof && pick(model.nodes[*n].coords))
        .map(|(_, f)| f)
        .sum()
}

/// examples/patch3d.in: every contact node's pressure is the closed-form uniaxial true stress of
/// the neo-Hookean law at 20 % compression (the nominal one over the lateral stretch squared), to
/// round-off, in ≤ 3 iterations.
#[test]
fn patch3d_example_transmits_the_exact_pressure() {
    use hertz_bench::verify::{neo_hookean_law, uniaxial_stress, PATCH_H};
    let stretch = 1.0 - hertz_bench::examples::PATCH_DELTA / (2.0 * PATCH_H);
    let (lateral, nominal) = uniaxial_stress(&neo_hookean_law(), stretch);
    let exact = -nominal / (lateral * lateral);
    let mut worst = 0.0f64;
    let its = run_example("patch3d.in", |_, r| {
        if r.step == 4 {
            for s in r.contact {
                worst = worst.max((s.pressure - exact).abs() / exact);
            }
        }
        r.info.iterations
    });
    println!("patch3d: P {exact:.10}, worst node off by {worst:.1e}, iterations {its:?}");
    assert_eq!(its.len(), 4);
    assert!(worst < 1e-12, "pressure off by {worst:e}");
    assert!(its.iter().all(|&i| i <= 3), "{its:?}");
}

/// Run a Hertz sphere example: its comparison with Hertz for the computed force.
fn hertz_sphere_example(file: &str) -> hertz::analytic::HertzComparison {
    use hertz::analytic::{compare_hertz_sphere, contact_modulus};
    use hertz_bench::verify::{E, HERTZ_R, NU};
    let mut c = None;
    run_example(file, |model, r| {
        c = compare_hertz_sphere(model, r.contact, HERTZ_R, contact_modulus(E, NU, E, NU));
        r.info.iterations
    });
    let c = c.expect("a contact zone");
    println!(
        "{file}: F {:.4}, p0 {:+.2} %, a {:+.2} %",
        c.force,
        100.0 * c.p0_error(),
        100.0 * c.a_error()
    );
    c
}

/// examples/hertz_sphere.in: p0 within 3 % and a within 5 % of Hertz for the computed force.
#[test]
fn hertz_sphere_example_matches_hertz() {
    let c = hertz_sphere_example("hertz_sphere.in");
    assert!(c.p0_error().abs() < 0.03 && c.a_error().abs() < 0.05);
}

/// examples/hertz_sphere_mortar.in: p0 and a within 2 % of Hertz for the computed force.
#[test]
fn hertz_sphere_mortar_example_matches_hertz() {
    let c = hertz_sphere_example("hertz_sphere_mortar.in");
    assert!(c.p0_error().abs() < 0.02 && c.a_error().abs() < 0.02);
}

/// examples/two_beams.in: the clamps balance the end forces to 1e-8 and the upper clamp's force
/// is the header's −0.626077.
#[test]
fn two_beams_example_balances_and_gives_the_tabulated_force() {
    use hertz_bench::verify::{BEAM_L, BEAM_S};
    let mut out = (0.0, 0.0);
    run_example("two_beams.in", |model, r| {
        let lower = reaction(model, r, 2, |p| p[0] < 1.0);
        let upper = reaction(model, r, 2, |p| p[0] > BEAM_S + BEAM_L - 1e-9);
        out = (lower, upper);
        r.info.iterations
    });
    let f = hertz_bench::examples::BEAMS_FORCE;
    println!("two beams: clamp forces {:.8} {:.8}", out.0, out.1);
    // Each end force f; the lower clamp holds −f minus the contact, the upper +f plus it.
    assert!((out.0 + out.1).abs() < 1e-8 * f, "{out:?}");
    assert!((out.1 + 0.626077).abs() < 1e-6, "{out:?}");
}

/// examples/wedge_on_brick.in: the reactions balance and the contact force is the force on the
/// wedge's top.
#[test]
fn wedge_on_brick_example_balances() {
    let mut out = (0.0, 0.0, 0.0);
    run_example("wedge_on_brick.in", |model, r| {
        let all = reaction(model, r, 3, |_| true);
        let top = reaction(model, r, 3, |p| (p[2] - 1.5).abs() < 1e-12);
        out = (all, top, r.contact.iter().map(|c| c.force).sum());
        r.info.iterations
    });
    println!("wedge on brick: reactions {out:?}");
    assert!(out.0.abs() < 1e-8 * out.1.abs() && out.1 < 0.0);
    assert!((out.2 + out.1).abs() < 1e-8 * out.2);
}

/// examples/cylinder3d.in gives cylinder2d.in's force per unit depth to 1e-9.
#[test]
fn extruded_cylinder_example_matches_its_section() {
    let force = |name| {
        let mut f = 0.0;
        run_example(name, |_, r| {
            f = r.contact.iter().map(|c| c.force).sum();
            r.info.iterations
        });
        f
    };
    let (f2, f3) = (force("cylinder2d.in"), force("cylinder3d.in"));
    println!("cylinder: 2D {f2:.10}, 3D per depth {f3:.10}");
    assert!((f3 - f2).abs() < 1e-9 * f2, "{f3} vs {f2}");
}

/// examples/large_sliding.in: 25 steps of at most 3 iterations; the last drag force is the press
/// force times the slope under the contact's centre within 0.1 %.
#[test]
fn large_sliding_example_drags_by_the_slope() {
    use hertz_bench::verify::SLIDE_R;
    let force = hertz_bench::examples::SLIDING_FORCE;
    let mut last = (0.0, 0.0);
    let its = run_example("large_sliding.in", |model, r| {
        let drag = reaction(model, r, 1, |p| p[1] > 0.4);
        let active: Vec<_> = r.contact.iter().filter(|c| c.active).collect();
        let total: f64 = active.iter().map(|c| c.force).sum();
        let xc = active.iter().map(|c| c.force * c.x[0]).sum::<f64>() / total;
        let slope = -(xc - 4.0) / (SLIDE_R * SLIDE_R - (xc - 4.0).powi(2)).sqrt();
        last = (drag, force * slope);
        r.info.iterations
    });
    println!(
        "large sliding: drag {:.6} vs {:.6}, iterations {its:?}",
        last.0, last.1
    );
    assert_eq!(its.len(), 25);
    assert!(its.iter().all(|&i| i <= 3), "{its:?}");
    assert!((last.0 - last.1).abs() < 1e-3 * last.1.abs(), "{last:?}");
}

/// `--vtu binary` and the default text VTU hold the same doubles, bit for bit (the text holds
/// shortest round-trip digits), NaN gaps included, for a contact run with every array.
#[test]
fn binary_and_ascii_vtu_hold_the_same_values() {
    let dir = std::env::temp_dir().join(format!("hertz-vtu-formats-{}", std::process::id()));
    let mut arrays = Vec::new();
    for (sub, vtu_format) in [
        ("ascii", hertz::output::vtu::VtuFormat::Ascii),
        ("binary", hertz::output::vtu::VtuFormat::Binary),
    ] {
        let vtu = common::run_writing_vtu(
            &example("hertz_rigid_circle.in"),
            Some(dir.join(sub)),
            vtu_format,
        );
        let text = std::fs::read(&vtu).unwrap();
        let appended = text.windows(12).any(|w| w == b"AppendedData");
        assert_eq!(appended, sub == "binary", "{sub}: appended data block");
        arrays.push(common::read_vtu(&vtu));
    }
    let (ascii, binary) = (&arrays[0], &arrays[1]);
    assert_eq!(
        ascii.keys().collect::<Vec<_>>(),
        binary.keys().collect::<Vec<_>>()
    );
    for (name, a) in ascii {
        let bits = |v: &Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(a), bits(&binary[name]), "array {name}");
    }
    assert!(ascii["contact_gap"].iter().any(|g| g.is_nan()));
    assert!(ascii["contact_pressure"].iter().any(|&p| p != 0.0));
    std::fs::remove_dir_all(dir).ok();
}

/// Without `penalty`, node-to-segment contact takes one from the mesh (10³ times the stiffness
/// E·A/h under each node): the rigid-cylinder Hertz example still meets Hertz within 2 % in a
/// handful of iterations.
#[test]
fn penalty_from_the_mesh_meets_hertz() {
    let text = std::fs::read_to_string(example("hertz_rigid_circle.in"))
        .unwrap()
        .replace(" penalty 1e+07 ", " ");
    assert!(!text.contains("penalty 1e+07"));
    let path = std::env::temp_dir().join(format!("hertz-auto-penalty-{}.in", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let (model, states, hist) = common::solve_contact(&path);
    std::fs::remove_file(&path).ok();
    let c = hertz::analytic::compare_hertz(&model, &states, 0.0).unwrap();
    println!(
        "penalty from the mesh: p0 {:+.2} %, a {:+.2} %, {} iterations",
        100.0 * c.p0_error(),
        100.0 * c.a_error(),
        hist.len() - 1
    );
    assert!(c.p0_error().abs() < 0.02 && c.a_error().abs() < 0.02);
    assert!(hist.len() - 1 <= 5);
}
