//! The contact robustness suite (`hertz::bench::suite`, `hertz bench --suite`): every everyday
//! setup converges with at most 25 Newton iterations per step and no step cut-back, with penalty
//! and with multipliers, and the penalty answer equals its multiplier twin within the penalty's
//! own error (estimated from a run with a tenth of the penalty, Richardson's rule).

use hertz::bench::suite::{self, setups, twin_mismatch, Law};

#[test]
fn every_setup_converges_quickly_and_penalty_matches_multipliers() {
    let all = setups();
    assert!(all.len() >= 30, "{} setups", all.len());
    let classes: std::collections::BTreeSet<&str> = all.iter().map(|s| s.class).collect();
    for class in [
        "flush",
        "vertex-centred",
        "sliding",
        "quadratic edges",
        "unloading",
        "large penalty",
        "touching start, force control",
        "starting penetration",
        "large deformation",
        "elastic cylinder",
        "node-to-node",
    ] {
        assert!(classes.contains(class), "class {class} covered");
    }
    let mut failures = Vec::new();
    for s in &all {
        let t = match s.run_twins() {
            Ok(t) => t,
            Err(e) => {
                failures.push(format!("{}: {e}", s.name));
                continue;
            }
        };
        for (law, o) in [("penalty", &t.penalty), ("multipliers", &t.multipliers)] {
            let worst = o.iterations.iter().max().copied().unwrap_or(0);
            if worst > 25 || o.substeps.iter().any(|&n| n > 1) {
                failures.push(format!(
                    "{} ({law}): iterations {:?}, substeps {:?}",
                    s.name, o.iterations, o.substeps
                ));
            }
        }
        let (ru, rf) = twin_mismatch(s.penalty, &t.penalty, &t.penalty10, &t.multipliers);
        if !(ru <= 1.0 && rf <= 1.0) {
            failures.push(format!(
                "{}: penalty vs multipliers {ru:.2} (displacement), {rf:.2} (force) times the penalty error",
                s.name
            ));
        }
        // Penalty forces converge to the multipliers' as 1/p: the penalty run is off by about
        // 10/9 of its distance to the p/10 run (more than a third of it, unless at round-off).
        let last = t.multipliers.force.len() - 1;
        let (fp, ft, fm) = (
            t.penalty.force[last],
            t.penalty10.force[last],
            t.multipliers.force[last],
        );
        if (ft - fp).abs() > 1e-6 * fm.abs() && (fp - fm).abs() < 0.3 * (ft - fp).abs() / 9.0 {
            failures.push(format!(
                "{}: the penalty error does not scale as 1/p ({fp} / {ft} / {fm})",
                s.name
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The elastic cylinder with `nlgeo 1` converges, and its contact force is within 1 % of the
/// small-strain force (the strains are below 1 %).
#[test]
fn elastic_cylinder_in_large_deformation_matches_small_strain_within_one_percent() {
    for law in [Law::Penalty(suite::PENALTY), Law::Multiplier] {
        let small = suite::run(&suite::cylinder_on_block(0.05, law, false)).unwrap();
        let large = suite::run(&suite::cylinder_on_block(0.05, law, true)).unwrap();
        let (fs, fl) = (small.force[0], large.force[0]);
        assert!(fs > 1.0, "{law:?}: force {fs}");
        assert!(
            ((fl - fs) / fs).abs() < 0.01,
            "{law:?}: small strain {fs}, large deformation {fl}"
        );
        assert!(large.iterations[0] <= 6, "{law:?}: {:?}", large.iterations);
    }
}
