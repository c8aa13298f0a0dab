//! OOFEM's own test inputs (tests/data/oofem, copied from OOFEM's tests/sm): every
//! `#%BEGIN_CHECK%` rule must pass, and every rule of the file must have been evaluated.

use hertz::app::{run_file, RunOptions};
use hertz::output::check::parse_rules;
use std::path::PathBuf;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/oofem")
        .join(name)
}

fn check_file(name: &str) {
    let path = data(name);
    let report = run_file(&path, &RunOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(report.has_errorcheck, "{name} has an errorcheck module");
    let raw = std::fs::read_to_string(&path).unwrap();
    let n_rules = parse_rules(&raw).0.len();
    assert!(n_rules > 0);
    assert_eq!(
        report.outcomes.len(),
        n_rules,
        "{name}: every rule evaluated once"
    );
    let failures: Vec<String> = report
        .outcomes
        .iter()
        .filter(|o| !o.passed)
        .map(hertz::output::check::describe_failure)
        .collect();
    assert!(failures.is_empty(), "{name}:\n{}", failures.join("\n"));
}

#[test]
fn patch100_planestress2d_compression() {
    check_file("patch100.in");
}

#[test]
fn patch102_trplanestress2d_shear() {
    check_file("patch102.in");
}

#[test]
fn patch107_trplanestrain_confined_compression() {
    check_file("patch107.in");
}

#[test]
fn patch110_qplanestress2d_compression() {
    check_file("patch110.in");
}

#[test]
fn patch130_trplanestress2d_compression() {
    check_file("patch130.in");
}

#[test]
fn patch300_ltrspace_compression() {
    check_file("patch300.in");
}

#[test]
fn deadweight01_qplanestress2d_body_load() {
    check_file("deadweight01.in");
}

#[test]
fn deadweight03_trplanestress2d_body_load() {
    check_file("deadweight03.in");
}

#[test]
fn brick_nlgeo_1_rigid_translation_has_zero_green_lagrange_strain() {
    check_file("brick_nlgeo_1.in");
}

#[test]
fn contact_n2n_penalty_with_slave_node_and_ordered_sets() {
    check_file("contact_N2N_P.in");
}

#[test]
fn contact_n2n_lagrange_multiplier() {
    check_file("contact_N2N_LM.in");
}

#[test]
fn contact_n2s_penalty_on_large_deformation_edge() {
    check_file("contact_N2S_P.in");
}

#[test]
fn contact_n2s_lagrange_multiplier_two_steps() {
    check_file("contact_N2S_LM.in");
}
