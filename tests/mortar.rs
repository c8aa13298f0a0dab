//! Mortar segment-to-segment contact: the contact patch test across non-matching meshes (a
//! uniform pressure transferred exactly, where node-to-segment contact is not and refinement does
//! not help), and the exactness of its tangent.

mod common;

use hertz::solve::run_analysis;

/// The pressure on the top of `common::mortar_blocks`.
const P: f64 = 10.0;

/// The worst deviation of σ_yy from −P over every integration point, relative to P, and of the
/// slave nodes' contact pressures.
fn patch_errors(text: &str) -> (f64, f64) {
    let model = common::model_from_text(text).unwrap();
    let (mut stress, mut pressure) = (f64::NAN, f64::NAN);
    run_analysis(&model, &common::quiet(), |r| {
        stress = r
            .states
            .iter()
            .flatten()
            .map(|g| (g.stress[1] + P).abs() / P)
            .fold(0.0, f64::max);
        pressure = r
            .contact
            .iter()
            .filter(|s| s.pressure.is_finite() && s.active)
            .map(|s| (s.pressure - P).abs() / P)
            .fold(0.0, f64::max);
        Ok(())
    })
    .unwrap();
    (stress, pressure)
}

/// Mortar passes the patch test to round-off on non-matching meshes, with multipliers and with a
/// penalty (uniform penetration P/ε), whichever side is finer, on straight and quadratic edges;
/// node-to-segment contact misses it by percent and does not improve with refinement.
#[test]
fn mortar_passes_the_contact_patch_test_on_non_matching_meshes() {
    for (n_low, n_up) in [(5, 3), (3, 5), (10, 7), (20, 13)] {
        for law in [
            "s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 1 segmentset 1 2",
            "s2spenaltycontact 4 loadTimeFunction 1 penalty 1e6 slavesegment 1 segmentset 1 2",
            // No penalty: one from the mesh.
            "s2spenaltycontact 4 loadTimeFunction 1 slavesegment 1 segmentset 1 2",
        ] {
            let (s, p) = patch_errors(&common::mortar_blocks(n_low, n_up, 0, law));
            println!(
                "{n_low}/{n_up} {}: stress {s:.1e}, pressure {p:.1e}",
                &law[..18]
            );
            assert!(s < 1e-10 && p < 1e-10, "{n_low}/{n_up} {law}: {s:e} {p:e}");
        }
        for law in [
            "s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 1 segmentset 1 2",
            "s2spenaltycontact 4 loadTimeFunction 1 penalty 1e6 slavesegment 1 segmentset 1 2",
        ] {
            let (s, p) = patch_errors(&common::mortar_blocks_q8(n_low, n_up, 0, law));
            println!(
                "{n_low}/{n_up} quadratic {}: stress {s:.1e}, pressure {p:.1e}",
                &law[..18]
            );
            assert!(
                s < 1e-10 && p < 1e-10,
                "quadratic {n_low}/{n_up} {law}: {s:e} {p:e}"
            );
        }
        let (s, _) = patch_errors(&common::mortar_blocks(
            n_low,
            n_up,
            0,
            "n2slagrangianmultipliercontact 4 loadTimeFunction 1 slaveset 4 segmentset 1 2",
        ));
        println!("{n_low}/{n_up} node-to-segment: stress {s:.1e}");
        assert!(s > 1e-2, "node-to-segment fails the patch test: {s:e}");
    }
}

/// Hertz with mortar contact (multipliers), a rigid cylinder (examples/hertz_mortar.in) and an
/// elastic one (examples/hertz_cylinder_mortar.in) on a block: p0 and a within 1 % of the
/// closed form, the nodal pressures decreasing monotonically from the centre (no node-to-node
/// oscillation) and within 2 % of p0 of the Hertz profile at every node inside 0.8 a. (a is the
/// ellipse fitted to the nodes inside 0.8 a: a mortar pressure is a weighted average over the
/// node's edges, so the rim's nodes straddle the edge of contact.)
#[test]
fn hertz_with_mortar_contact_meets_hertz() {
    for (file, radius) in [("hertz_mortar.in", 0.0), ("hertz_cylinder_mortar.in", 20.0)] {
        hertz_case(file, radius);
    }
}

/// One Hertz example with mortar contact (see the test above); `radius` of an elastic cylinder.
fn hertz_case(file: &str, radius: f64) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(file);
    let (model, states, residuals) = common::solve_contact(&path);
    let c = hertz::analytic::compare_hertz(&model, &states, radius).unwrap();
    let profile = hertz::analytic::pressure_profile(&model, &states);
    let inner: Vec<(f64, f64)> = profile
        .iter()
        .copied()
        .filter(|&(x, _)| x < 0.8 * c.a_ref)
        .collect();
    let a = hertz::analytic::fit_ellipse(&inner).unwrap();
    let a_error = a / c.a_ref - 1.0;
    let worst = profile
        .iter()
        .filter(|&&(x, _)| x < 0.8 * c.a_ref)
        .map(|&(x, p)| (p - c.p0_ref * (1.0 - (x / c.a_ref).powi(2)).sqrt()).abs() / c.p0_ref)
        .fold(0.0, f64::max);
    println!(
        "{file}: F {:.4}, p0 {:+.2} %, a {:+.2} %, profile within {:.2} % of p0, {} iterations",
        c.force,
        100.0 * c.p0_error(),
        100.0 * a_error,
        100.0 * worst,
        residuals.len() - 1
    );
    assert!(c.p0_error().abs() < 0.01 && a_error.abs() < 0.01);
    assert!(worst < 0.02, "{worst}");
    assert!(
        profile.windows(2).all(|w| w[1].1 < w[0].1),
        "monotonic pressure: {profile:?}"
    );
    assert!(residuals.len() - 1 <= 5);
}
