//! 3D node-to-face contact through the whole program, against exact solutions.

mod common;

use hertz::analytic::{compare_hertz_sphere, contact_modulus};
use hertz::bench::mesh::{hex_face_on, Solid};
use hertz::bench::suite::Law;
use hertz::bench::verify3d::{
    neo_hookean_law, uniaxial_stress, HertzSphere, Patch, E, HERTZ_R, NU, PATCH_H,
};
use hertz::contact::SlotState;
use hertz::solve::{run_analysis, SolveParams};

/// Solve `text`; the contact states and Newton iterations of every step.
fn solve(text: &str) -> (Vec<SlotState>, Vec<usize>) {
    let model = common::model_from_text(text).unwrap();
    let mut states = Vec::new();
    let mut its = Vec::new();
    run_analysis(
        &model,
        &SolveParams {
            log_steps: false,
            max_cutbacks: 0,
            ..Default::default()
        },
        |r| {
            states = r.contact.to_vec();
            its.push(r.info.iterations);
            Ok(())
        },
    )
    .unwrap();
    (states, its)
}

/// Cube symmetries that put each of the six LSpace face numbers on the master's top, with both
/// handednesses among them.
fn orientations() -> Vec<usize> {
    let mut out = Vec::new();
    for face in 1..=6 {
        let sym = (0..48)
            .find(|&s| hex_face_on(s, true) == face && (s + face) % 2 == 0)
            .or_else(|| (0..48).find(|&s| hex_face_on(s, true) == face))
            .unwrap();
        out.push(sym);
    }
    out
}

/// Worst relative difference between every contact node's pressure and `exact`.
fn pressure_error(states: &[SlotState], exact: f64) -> f64 {
    assert!(!states.is_empty());
    states
        .iter()
        .map(|s| (s.pressure - exact).abs() / exact)
        .fold(0.0f64, f64::max)
}

/// Two blocks with nested non-matching meshes under uniform compression transmit the exact
/// uniform pressure: multipliers to round-off, the penalty within its own error (which falls
/// as 1/p: ten times the penalty, a tenth of the error); in small deformation (E δ / 2h) and in
/// large deformation (20 % compression of neo-Hookean blocks in 4 steps: the closed-form
/// uniaxial nominal stress). Hexahedra with each face number on the contact side, tetrahedra
/// and wedges (triangle and quadrilateral faces), in at most 5 Newton iterations per step.
#[test]
fn patch_test_transmits_the_exact_uniform_pressure() {
    let mut cases: Vec<(Solid, usize)> = orientations()
        .into_iter()
        .map(|s| (Solid::Hex, s))
        .collect();
    cases.extend([
        (Solid::Tet, 0),
        (Solid::Tet, 45),
        (Solid::Wedge, 0),
        (Solid::Wedge, 13),
    ]);
    for (kind, sym) in cases {
        for nlgeo in [false, true] {
            let patch = |law| Patch {
                kind,
                sym,
                n: 2,
                nlgeo,
                delta: if nlgeo { 0.2 } else { 0.01 },
                steps: if nlgeo { 4 } else { 1 },
                law,
            };
            let exact = if nlgeo {
                -uniaxial_stress(&neo_hookean_law(), 1.0 - 0.2 / (2.0 * PATCH_H)).1
            } else {
                E * 0.01 / (2.0 * PATCH_H)
            };
            let name = format!("{kind:?} sym {sym} nlgeo {nlgeo}");
            let mut errors = Vec::new();
            for law in [Law::Multiplier, Law::Penalty(1e6), Law::Penalty(1e5)] {
                let (states, its) = solve(&patch(law).input());
                assert!(
                    its.iter().all(|&i| i <= 5),
                    "{name} {law:?}: iterations {its:?}"
                );
                errors.push(pressure_error(&states, exact));
            }
            assert!(
                errors[0] < 1e-12,
                "{name}: multipliers off by {:e}",
                errors[0]
            );
            assert!(
                errors[1] < 1e-3 && errors[1] < 0.12 * errors[2],
                "{name}: penalty errors {:e} (p) and {:e} (p/10)",
                errors[1],
                errors[2]
            );
        }
    }
}

/// The Hertz check of one sphere-on-block run: (F, p0 error, a error).
fn hertz_sphere(kind: Solid, sym: usize, h: f64, law: Law) -> (f64, f64, f64) {
    let hs = HertzSphere {
        kind,
        sym,
        h,
        delta: 0.15,
        nlgeo: false,
        law,
    };
    let text = hs.input();
    let model = common::model_from_text(&text).unwrap();
    let (states, its) = solve(&text);
    assert!(
        its[0] <= 3,
        "{kind:?} sym {sym} {law:?}: {its:?} iterations"
    );
    let e_star = contact_modulus(E, NU, E, NU);
    let c = compare_hertz_sphere(&model, &states, HERTZ_R, e_star).expect("a contact zone");
    println!(
        "{kind:?} sym {sym} h {h} {law:?}: F {:.4}, p0 {:.4} ({:+.2} %), a {:.4} ({:+.2} %)",
        c.force,
        c.p0,
        100.0 * c.p0_error(),
        c.a,
        100.0 * c.a_error()
    );
    (c.force, c.p0_error(), c.a_error())
}

/// An elastic sphere (R = 10) pressed onto an elastic block (same E, ν), quarter model with a
/// graded mesh: p0 = 3F/(2πa²) within 3 % and a = (3FR/(4E*))^(1/3) within 5 % of Hertz for the
/// computed force F. Hexahedra with each of the six face numbers on the contact surfaces give the
/// same answer (to 1e-9); tetrahedra and wedges (triangular and quadrilateral contact faces) meet
/// the bounds on a finer mesh. Multipliers and penalty; 2 and 3 Newton iterations.
#[test]
fn hertz_sphere_on_a_block_matches_hertz_in_every_orientation() {
    let syms = orientations();
    let reference = hertz_sphere(Solid::Hex, syms[0], 0.2, Law::Multiplier);
    for &sym in &syms[1..] {
        let r = hertz_sphere(Solid::Hex, sym, 0.2, Law::Multiplier);
        assert!(
            (r.0 - reference.0).abs() < 1e-9 * reference.0,
            "sym {sym}: force {} vs {}",
            r.0,
            reference.0
        );
    }
    let mut runs = vec![
        reference,
        hertz_sphere(Solid::Hex, 0, 0.2, Law::Penalty(1e5)),
    ];
    for (kind, sym) in [(Solid::Tet, 0), (Solid::Wedge, 0), (Solid::Wedge, 13)] {
        runs.push(hertz_sphere(kind, sym, 0.15, Law::Multiplier));
    }
    for (f, ep, ea) in runs {
        assert!(
            ep.abs() < 0.03 && ea.abs() < 0.05,
            "F {f}: p0 {ep:+e}, a {ea:+e}"
        );
    }
}
