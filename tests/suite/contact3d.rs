//! 3D node-to-face contact through the whole program, against exact solutions.

use crate::common;

use hertz::analytic::{compare_hertz_sphere, contact_modulus};
use hertz::contact::SlotState;
use hertz::solve::{run_analysis, SolveParams};
use hertz_bench::mesh::{hex_face_on, Solid};
use hertz_bench::suite::Law;
use hertz_bench::verify::{
    neo_hookean_law, uniaxial_stress, HertzSphere, Patch, TwoBeams, BEAM_G, BEAM_H, BEAM_L, BEAM_S,
    E, HERTZ_CAP, HERTZ_R, NU, PATCH_H,
};

/// Solve `text`; the contact states and Newton iterations of every step.
fn solve(text: &str) -> (Vec<SlotState>, Vec<usize>) {
    let model = common::model_from_text(text).unwrap();
    let mut states = Vec::new();
    let mut its = Vec::new();
    run_analysis(
        &model,
        &SolveParams {
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
/// uniaxial true stress). Hexahedra with each face number on the contact side, tetrahedra
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
                slave_kind: None,
                sym,
                n: 2,
                nlgeo,
                delta: if nlgeo { 0.2 } else { 0.01 },
                steps: if nlgeo { 4 } else { 1 },
                law,
                slave_n: None,
                mortar: false,
            };
            let exact = if nlgeo {
                // The true contact pressure: the nominal stress over the lateral stretch squared.
                let (lateral, nominal) =
                    uniaxial_stress(&neo_hookean_law(), 1.0 - 0.2 / (2.0 * PATCH_H));
                -nominal / (lateral * lateral)
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

/// The factorizations a run asks for, by kind.
#[derive(Default)]
struct Factorizations(std::cell::RefCell<Vec<String>>);

impl hertz::solve::Observer for Factorizations {
    fn phase(&self, phase: &hertz::solve::Phase) {
        if let hertz::solve::Phase::Factorization { kind, .. } = phase {
            self.0.borrow_mut().push(kind.to_string());
        }
    }
}

/// The contact's candidate equations at the start (displacements and multipliers): what the
/// condensed step would hold with no limit.
fn candidate_equations(model: &hertz::model::Model) -> usize {
    let dofs = hertz::solve::number_dofs(model).unwrap();
    let contact = hertz::contact::ContactSystem::new(model).unwrap();
    let zero = vec![0.0; dofs.n_primary()];
    contact
        .candidate_equations(&hertz::assembly::NodalState::new(model, &dofs, &zero))
        .unwrap()
        .len()
        + dofs.n_lambda
}

/// A contact surface with more candidate equations than the condensed step's dense block takes
/// is condensed on the nearest points' equations instead of falling to a factorization of the
/// full tangent (the whole of a sphere's meshed face as slave nodes cost 20 times the time and
/// 10 times the memory on the 3D Hertz problem, 78k unknowns). Here the limit is lowered to
/// half the candidates of a coarse Hertz sphere whose whole cap face is the slave side: the nearest
/// points' solve gives the all-candidates solve's contact pressures to round-off, with
/// multipliers and with a penalty, and every factorization is the condensed one.
#[test]
fn a_contact_surface_beyond_the_dense_block_is_condensed_on_its_nearest_points() {
    for law in [Law::Multiplier, Law::Penalty(1e5)] {
        let text = HertzSphere {
            kind: Solid::Hex,
            sym: 0,
            h: 0.25,
            delta: 0.15,
            nlgeo: false,
            law,
            mortar: false,
        }
        .input_within(HERTZ_CAP);
        let model = common::model_from_text(&text).unwrap();
        let run = |max_condensed: usize| {
            let seen = Factorizations::default();
            let mut states = Vec::new();
            let params = SolveParams {
                max_condensed: Some(max_condensed),
                ..common::quiet()
            };
            hertz::solve::run_analysis_observed(&model, &params, &seen, |r| {
                states = r.contact.to_vec();
                Ok(())
            })
            .unwrap();
            let kinds = seen.0.into_inner();
            assert!(
                !kinds.is_empty()
                    && kinds
                        .iter()
                        .all(|k| k == "structural tangent, contact condensed"),
                "{law:?}, at most {max_condensed}: {kinds:?}"
            );
            states
        };
        // Half the candidate equations: the nearest points' set, not all of them.
        let every = candidate_equations(&model);
        let (all, near) = (run(3000), run(every / 2));
        let closed = all.iter().filter(|s| s.active).count();
        assert!(
            closed > 10 && all.len() >= 4 * closed,
            "{closed} of {}",
            all.len()
        );
        let p0 = all.iter().map(|s| s.pressure).fold(0.0, f64::max);
        for (a, b) in all.iter().zip(&near) {
            // NaN: a node with no master point in reach, in both.
            assert!(
                (a.pressure.is_nan() && b.pressure.is_nan())
                    || (a.pressure - b.pressure).abs() < 1e-9 * p0,
                "{law:?} node {}: {} vs {}",
                a.node,
                a.pressure,
                b.pressure
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
        mortar: false,
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
#[ignore = "long: runs with `cargo test --release -- --ignored` (CI runs both)"]
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

/// The end of a two-beam run: reactions (x, y) of the lower and upper clamps, the displacement
/// of both beams' free-end corners that face each other, the Newton iterations of every step,
/// and the total contact force of each condition.
struct BeamsResult {
    lower: [f64; 2],
    upper: [f64; 2],
    tips: [[f64; 2]; 2],
    iterations: Vec<usize>,
    force: [f64; 2],
}

fn two_beams(tb: &TwoBeams, swap: bool) -> BeamsResult {
    let mut text = tb.input();
    if swap {
        // The same two conditions, listed the other way round.
        let lines: Vec<&str> = text.lines().collect();
        let i = lines.iter().position(|l| l.starts_with("n2s")).unwrap();
        let mut l: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        l.swap(i, i + 1);
        text = l.join("\n") + "\n";
    }
    let model = common::model_from_text(&text).unwrap();
    let corner = |x: f64, y: f64| {
        model
            .nodes
            .iter()
            .position(|n| (n.coords[0] - x).abs() < 1e-9 && (n.coords[1] - y).abs() < 1e-9)
            .unwrap()
    };
    // The second pass's condition number.
    let second = model.contacts.iter().map(|c| c.number).max().unwrap();
    let lower_tip = corner(BEAM_L, BEAM_H);
    let upper_tip = corner(BEAM_S, BEAM_H + BEAM_G);
    let mut out = BeamsResult {
        lower: [0.0; 2],
        upper: [0.0; 2],
        tips: [[0.0; 2]; 2],
        iterations: Vec::new(),
        force: [0.0; 2],
    };
    run_analysis(
        &model,
        &SolveParams {
            max_cutbacks: 0,
            ..Default::default()
        },
        |r| {
            out.iterations.push(r.info.iterations);
            out.lower = [0.0; 2];
            out.upper = [0.0; 2];
            for (&(n, d, _), &f) in r.dofs.prescribed.iter().zip(r.reactions) {
                let side = if model.nodes[n].coords[0] < 1.0 {
                    &mut out.lower
                } else {
                    &mut out.upper
                };
                side[d as usize - 1] += f;
            }
            for (k, &n) in [lower_tip, upper_tip].iter().enumerate() {
                out.tips[k] = [r.displacement(n, 1).unwrap(), r.displacement(n, 2).unwrap()];
            }
            out.force = [0.0; 2];
            for c in r.contact {
                out.force[usize::from(c.condition == second)] += c.force;
            }
            Ok(())
        },
    )
    .unwrap();
    out
}

/// The seed's two beams bent into each other by forces at their free ends, large deformation,
/// two-pass contact (each beam's nodes on the other beam's surface: each free end's corner is
/// caught by the pass in which it is a contact node). For penalty and multipliers, on matching
/// and non-matching meshes:
/// * the clamps' reactions balance the end forces to 1e-8 (global equilibrium);
/// * master/slave symmetry: the model is point-symmetric and so is the answer (to round-off on
///   the matching mesh: the corners move by opposite amounts, and the two passes report the
///   same contact force), and listing the two conditions the other way round changes nothing
///   (1e-8);
/// * no locking: matching and non-matching meshes give the same clamp force within 0.2 %, and
///   the penalty gives the multipliers' force within 1e-4;
/// * Newton takes at most 4 iterations per step (the first steps bend the beams freely);
/// * the clamp force converges with the mesh, about as h² (printed; BENCHMARKS.md has the
///   table).
#[test]
fn two_beams_in_two_pass_contact() {
    let base = TwoBeams {
        nx: 40,
        ny: 4,
        nx_upper: None,
        force: 1.0,
        steps: 10,
        law: Law::Multiplier,
        two_pass: true,
    };
    let mut forces = Vec::new();
    for law in [Law::Multiplier, Law::Penalty(1e5)] {
        for nx_upper in [None, Some(37)] {
            let tb = TwoBeams {
                law,
                nx_upper,
                ..base
            };
            let r = two_beams(&tb, false);
            let name = format!("{law:?} upper {nx_upper:?}");
            let f = r.upper[1].abs();
            for i in 0..2 {
                assert!(
                    (r.lower[i] + r.upper[i]).abs() < 1e-8 * f,
                    "{name}: reactions {:?} {:?}",
                    r.lower,
                    r.upper
                );
            }
            assert!(
                r.iterations.iter().all(|&i| i <= 4),
                "{name}: {:?}",
                r.iterations
            );
            let asym = |r: &BeamsResult| {
                (r.tips[0][0] + r.tips[1][0])
                    .abs()
                    .max((r.tips[0][1] + r.tips[1][1]).abs())
            };
            if nx_upper.is_none() {
                assert!(asym(&r) < 1e-12, "{name}: tips {:?}", r.tips);
                // Both sides carry the interface: the passes report the same contact force
                // (the constraints dropped as repeated report the kept ones' pressure).
                assert!(
                    (r.force[0] - r.force[1]).abs() < 1e-8 * r.force[0],
                    "{name}: contact forces of the passes {:?}",
                    r.force
                );
            }
            let swapped = two_beams(&tb, true);
            assert!(
                (swapped.upper[1] - r.upper[1]).abs() < 1e-8 * f,
                "{name}: swapped {} vs {}",
                swapped.upper[1],
                r.upper[1]
            );
            let one = two_beams(
                &TwoBeams {
                    two_pass: false,
                    ..tb
                },
                false,
            );
            println!(
                "{name}: clamp force {:.6}; contact forces of the passes {:.4} {:.4}; corners off \
                 symmetry by {:.1e}; one-pass: clamp force {:.6}, corners off symmetry by {:.1e}; \
                 iterations {:?}",
                r.upper[1],
                r.force[0],
                r.force[1],
                asym(&r),
                one.upper[1],
                asym(&one),
                r.iterations
            );
            forces.push(r.upper[1]);
        }
    }
    let (matched, other) = (forces[0], forces[1]);
    assert!((other - matched).abs() < 2e-3 * matched.abs(), "{forces:?}");
    assert!(
        (forces[2] - matched).abs() < 1e-4 * matched.abs(),
        "{forces:?}"
    );
    // Mesh convergence of the clamp force (multipliers).
    let mut forces = Vec::new();
    for k in [1usize, 2, 4] {
        let tb = TwoBeams {
            nx: 20 * k,
            ny: 2 * k,
            ..base
        };
        let r = two_beams(&tb, false);
        println!("nx {} ny {}: clamp force {:.6}", tb.nx, tb.ny, r.upper[1]);
        forces.push(r.upper[1]);
    }
    assert!(
        (forces[2] - forces[1]).abs() < 0.35 * (forces[1] - forces[0]).abs(),
        "not converging as h²: {forces:?}"
    );
}

/// The elastic cylinder on a block, extruded in 3D with plane-strain constraints (every node held
/// in the depth direction): node-to-face gives the 2D node-to-segment force per unit depth, with
/// hexahedra numbered so that each of their six face numbers is on the contact surfaces. With
/// multipliers to 1e-9 (the same discrete problem); with a penalty within its error, 1e-4 (a
/// penalty acts per node, and three node rows share the depth: a different penalty per area).
#[test]
fn extruded_cylinder_matches_the_2d_section() {
    use hertz_bench::suite::cylinder_on_block;
    use hertz_bench::verify::ExtrudedCylinder;
    let h = 0.1;
    for law in [Law::Multiplier, Law::Penalty(1e6)] {
        let (states2d, _) = solve(&cylinder_on_block(h, law, false));
        let f2d: f64 = states2d.iter().map(|s| s.force).sum();
        for sym in orientations() {
            let text = ExtrudedCylinder { sym, h, ny: 2, law }.input();
            let (states, its) = solve(&text);
            let f3d: f64 = states.iter().map(|s| s.force).sum();
            println!(
                "{law:?} sym {sym}: force per depth {f3d:.8} (2D {f2d:.8}), iterations {its:?}"
            );
            let tol = if law == Law::Multiplier { 1e-9 } else { 1e-4 };
            assert!(
                (f3d - f2d).abs() < tol * f2d,
                "{law:?} sym {sym}: {f3d} vs {f2d}"
            );
            assert!(its[0] <= 3, "{its:?}");
        }
    }
}

/// The seed's wedge pressed onto a brick (one LWedge on one LSpace, small and large
/// deformation): the reactions balance (1e-8), the contact force equals the force on the wedge's
/// top, the brick's node order (each face number on top) changes nothing (1e-10), and the
/// penalty gives the multipliers' force within its own error. A block of wedges (triangular faces
/// down) on a block of bricks, nested meshes, transmits the exact uniform pressure with mortar
/// multipliers (to round-off). Node-to-face contact is 10 % off there: the slave nodes' areas do
/// not integrate the master's bilinear shape functions on triangles. (Until `Patch::slave_kind`
/// was honoured this check ran on a block of bricks.)
#[test]
fn wedge_pressed_onto_a_brick() {
    use hertz_bench::verify::WedgeOnBrick;
    for nlgeo in [false, true] {
        let mut forces = Vec::new();
        for law in [Law::Multiplier, Law::Penalty(1e6)] {
            for sym in orientations() {
                let wb = WedgeOnBrick {
                    sym,
                    delta: if nlgeo { 0.1 } else { 0.01 },
                    nlgeo,
                    steps: if nlgeo { 2 } else { 1 },
                    law,
                };
                let model = common::model_from_text(&wb.input()).unwrap();
                let top: Vec<usize> = (0..model.nodes.len())
                    .filter(|&n| (model.nodes[n].coords[2] - 1.5).abs() < 1e-12)
                    .collect();
                let mut out = (0.0, 0.0, 0.0, 0);
                run_analysis(
                    &model,
                    &SolveParams {
                        max_cutbacks: 0,
                        ..Default::default()
                    },
                    |r| {
                        let mut sum = 0.0;
                        let mut on_top = 0.0;
                        for (&(n, d, _), &f) in r.dofs.prescribed.iter().zip(r.reactions) {
                            if d == 3 {
                                sum += f;
                                if top.contains(&n) {
                                    on_top += f;
                                }
                            }
                        }
                        let contact: f64 = r.contact.iter().map(|c| c.force).sum();
                        out = (sum, on_top, contact, out.3.max(r.info.iterations));
                        Ok(())
                    },
                )
                .unwrap();
                let (sum, on_top, contact, its) = out;
                let name = format!("nlgeo {nlgeo} {law:?} sym {sym}");
                assert!(
                    sum.abs() < 1e-8 * on_top.abs(),
                    "{name}: reactions sum to {sum}"
                );
                // Small strain: the force acts along the brick's reference normal (z).
                if !nlgeo {
                    assert!(
                        (contact + on_top).abs() < 1e-8 * contact,
                        "{name}: contact {contact} vs top {on_top}"
                    );
                }
                assert!(its <= 4, "{name}: {its} iterations");
                forces.push((law, -on_top));
            }
        }
        let lm = forces[0].1;
        for &(law, f) in &forces {
            let tol = if law == Law::Multiplier { 1e-10 } else { 1e-3 };
            assert!(
                (f - lm).abs() < tol * lm,
                "nlgeo {nlgeo} {law:?}: {f} vs {lm}"
            );
        }
        println!(
            "wedge on brick, nlgeo {nlgeo}: force {lm:.6} (penalty {:.6})",
            forces[6].1
        );
        // Wedges (triangles down) on bricks, nested meshes: the exact uniform pressure.
        let p = Patch {
            kind: Solid::Hex,
            slave_kind: Some(Solid::Wedge),
            sym: 0,
            n: 2,
            nlgeo,
            delta: if nlgeo { 0.2 } else { 0.01 },
            steps: if nlgeo { 4 } else { 1 },
            law: Law::Multiplier,
            slave_n: None,
            mortar: true,
        };
        let exact = if nlgeo {
            let (lateral, nominal) = uniaxial_stress(&neo_hookean_law(), 0.8);
            -nominal / (lateral * lateral)
        } else {
            E * 0.01 / (2.0 * PATCH_H)
        };
        let (states, _) = solve(&p.input());
        let err = pressure_error(&states, exact);
        assert!(
            err < 1e-12,
            "wedges on bricks, nlgeo {nlgeo}: pressure off by {err:e}"
        );
    }
}

/// Large sliding in 2D: a block pressed onto a circular bump (R = 10) and dragged from its
/// summit down the side, 2.5 in 25 steps (ten master vertices, a tilt of 15°), large deformation,
/// penalty and multipliers. Every step converges, quadratically at the end (the last residual
/// below the square of the one before it, as far as round-off allows), in at most 3 (multipliers)
/// or 5 (penalty) iterations; the contact is frictionless, so the drag force is the press force
/// times the slope of the bump under the contact's centre, within 0.1 %.
#[test]
fn large_sliding_over_a_curved_master() {
    use hertz_bench::verify::{LargeSliding, SLIDE_R};
    let force = 20.0;
    for (law, most) in [(Law::Multiplier, 3), (Law::Penalty(1e5), 5)] {
        let ls = LargeSliding {
            nx: 32,
            travel: 2.5,
            force,
            steps: 25,
            law,
        };
        let model = common::model_from_text(&ls.input()).unwrap();
        let mut steps = 0;
        run_analysis(
            &model,
            &SolveParams {
                max_cutbacks: 0,
                ..Default::default()
            },
            |r| {
                steps += 1;
                let name = format!("{law:?} step {}", r.step);
                let h = &r.info.residual_history;
                assert!(r.info.iterations <= most, "{name}: {h:?}");
                let (a, b) = (h[h.len() - 2], h[h.len() - 1]);
                assert!(
                    b < 1e-11 || b.log10() <= 1.6 * a.log10(),
                    "{name}: not quadratic: {h:?}"
                );
                // The drag: the x reactions of the block's top.
                let drag: f64 = r
                    .dofs
                    .prescribed
                    .iter()
                    .zip(r.reactions)
                    .filter(|((n, d, _), _)| *d == 1 && model.nodes[*n].coords[1] > 0.4)
                    .map(|(_, f)| f)
                    .sum();
                let active: Vec<_> = r.contact.iter().filter(|c| c.active).collect();
                let total: f64 = active.iter().map(|c| c.force).sum();
                let xc = active.iter().map(|c| c.force * c.x[0]).sum::<f64>() / total;
                let slope = -(xc - 4.0) / (SLIDE_R * SLIDE_R - (xc - 4.0).powi(2)).sqrt();
                assert!(
                    (drag - force * slope).abs() < 1e-3 * force * slope.abs().max(0.01),
                    "{name}: drag {drag} vs {}",
                    force * slope
                );
                Ok(())
            },
        )
        .unwrap();
        assert_eq!(steps, 25);
    }
}

/// A large contact zone (2401 contact nodes, 24 000–26 000 unknowns): too many candidates for
/// the condensed contact system, so the tangent is assembled whole, and none goes to a sparse
/// LU. The penalty's general tangent, being above 20 000 unknowns, is solved by GMRES
/// preconditioned with the Cholesky of its symmetric part. Mortar's small-deformation tangent
/// is symmetric (gap rows are the force columns scaled), so its multipliers are eliminated into
/// a symmetric system for Cholesky, no GMRES (before, GMRES on the saddle point: 50 s and
/// 5.7 GB where the penalty took 4 s on a 32 × 32 patch). Node-to-face's turns general once the
/// multipliers load it (the nodal normals' linearization): GMRES, preconditioned with the
/// symmetric elimination of its symmetric counterpart. The patch test's exact pressure, to
/// round-off with multipliers and within the penalty's error, in one Newton iteration.
#[test]
fn large_contact_zone_patch_test_without_a_sparse_lu() {
    for (law, mortar, tol) in [
        (Law::Multiplier, false, 1e-12),
        (Law::Penalty(1e6), false, 1e-3),
        (Law::Multiplier, true, 1e-12),
    ] {
        let text = Patch {
            kind: Solid::Hex,
            slave_kind: None,
            sym: 0,
            n: 24,
            nlgeo: false,
            delta: 0.01,
            steps: 1,
            law,
            slave_n: None,
            mortar,
        }
        .input();
        let model = common::model_from_text(&text).unwrap();
        let mut out = (0.0, 0, 0, 0, (0, 0), true);
        run_analysis(
            &model,
            &SolveParams {
                max_cutbacks: 0,
                ..Default::default()
            },
            |r| {
                let err = pressure_error(r.contact, E * 0.01 / (2.0 * PATCH_H));
                out = (
                    err,
                    r.info.iterations,
                    r.info.solver.krylov_iterations,
                    r.dofs.n_free,
                    r.info.multipliers_eliminated,
                    r.info.solver.used_lu,
                );
                Ok(())
            },
        )
        .unwrap();
        println!(
            "large patch, {law:?}, mortar {mortar}: pressure error {:.1e}, iterations {}, \
             GMRES {}, unknowns {}, multipliers eliminated and kept {:?}",
            out.0, out.1, out.2, out.3, out.4
        );
        assert!(out.3 > hertz::solve::linear::KRYLOV_MIN_UNKNOWNS);
        assert!(out.0 < tol, "{law:?}: {out:?}");
        assert!(out.1 <= 2 && !out.5, "{law:?}: {out:?}");
        match (law, mortar) {
            (Law::Multiplier, true) => assert!(out.2 == 0 && out.4 == (2401, 0), "{out:?}"),
            (Law::Multiplier, false) => {
                assert!((1..=10).contains(&out.2) && out.4 == (2401, 0), "{out:?}")
            }
            _ => assert!((1..=10).contains(&out.2) && out.4 == (0, 0), "{out:?}"),
        }
    }
}

/// Worst relative deviation from Hertz's p(r) = p0 √(1 − r²/a²) (a and p0 from the computed force)
/// of the closed contact nodes within r < 0.8 a: on the axis, on the symmetry planes x = 0 or
/// y = 0 (off the axis), and elsewhere, as (min, max) each.
fn hertz_node_errors(states: &[SlotState]) -> [(f64, f64); 3] {
    use hertz::analytic::contact_modulus;
    let e_star = contact_modulus(E, NU, E, NU);
    let force = 4.0 * states.iter().map(|s| s.force).sum::<f64>();
    let a = (3.0 * force * HERTZ_R / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * force / (2.0 * std::f64::consts::PI * a * a);
    let mut out = [(f64::INFINITY, f64::NEG_INFINITY); 3];
    for s in states.iter().filter(|s| s.active) {
        let r = s.x[0].hypot(s.x[1]);
        if r > 0.8 * a {
            continue;
        }
        let e = s.pressure / (p0 * (1.0 - (r / a).powi(2)).sqrt()) - 1.0;
        let k = if r < 1e-9 {
            0
        } else if s.x[0].abs().min(s.x[1].abs()) < 1e-9 {
            1
        } else {
            2
        };
        out[k] = (out[k].0.min(e), out[k].1.max(e));
    }
    out
}

/// Node-to-face pressures node by node on a structured quarter model: on the axis, on the
/// symmetry planes and inside, every closed node within 0.8 a is within 3 % of Hertz, with
/// multipliers and with a penalty (1e6, 1e3 E), on bricks and on tetrahedra (each brick cut in
/// six: an unstructured-like pattern of faces).
#[test]
fn node_to_face_pressures_on_symmetry_planes_follow_hertz() {
    for kind in [Solid::Hex, Solid::Tet] {
        for law in [Law::Multiplier, Law::Penalty(1e6)] {
            let text = HertzSphere {
                kind,
                sym: 0,
                h: 0.2,
                delta: 0.15,
                nlgeo: false,
                law,
                mortar: false,
            }
            .input();
            let (states, _) = solve(&text);
            let [axis, planes, inside] = hertz_node_errors(&states);
            println!(
                "{kind:?} {law:?}: axis {:+.2} %, planes {:+.2} .. {:+.2} %, inside {:+.2} .. {:+.2} %",
                100.0 * axis.0,
                100.0 * planes.0,
                100.0 * planes.1,
                100.0 * inside.0,
                100.0 * inside.1
            );
            for (what, (lo, hi)) in [("axis", axis), ("planes", planes), ("inside", inside)] {
                assert!(
                    lo.is_finite() && lo > -0.03 && hi < 0.03,
                    "{kind:?} {law:?} {what}: {lo:+.4} .. {hi:+.4}"
                );
            }
        }
    }
}

/// A Hertz cap input (`HertzSphere::input_within`) whose push (condition 4, on the cap's top
/// nodes) becomes a force of `total` in all, reached in `steps` equal steps: the cap is then
/// held by contact alone.
fn pushed_by_force(text: &str, total: f64, steps: usize) -> String {
    let push = text
        .lines()
        .find(|l| l.starts_with("BoundaryCondition 4 "))
        .unwrap()
        .to_string();
    let set: usize = push.split_whitespace().last().unwrap().parse().unwrap();
    let count: usize = text
        .lines()
        .find(|l| l.starts_with(&format!("Set {set} nodes ")))
        .unwrap()
        .split_whitespace()
        .nth(3)
        .unwrap()
        .parse()
        .unwrap();
    let f = -total / count as f64;
    if steps == 1 {
        let load =
            format!("NodalLoad 4 loadTimeFunction 1 dofs 3 1 2 3 components 3 0 0 {f} set {set}");
        return text.replace(&push, &load);
    }
    let analysis = text.lines().nth(2).unwrap();
    let counts = text
        .lines()
        .find(|l| l.starts_with("ndofman "))
        .unwrap()
        .to_string();
    let nltf: usize = counts
        .split_whitespace()
        .skip_while(|w| *w != "nltf")
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    let ramp = nltf + 1;
    let load =
        format!("NodalLoad 4 loadTimeFunction {ramp} dofs 3 1 2 3 components 3 0 0 {f} set {set}");
    // The ramp after the other time functions: before the first set.
    let first_set = text.lines().find(|l| l.starts_with("Set ")).unwrap();
    let function = format!("PiecewiseLinFunction {ramp} npoints 2 t 2 0 {steps} f(t) 2 0 1");
    text.replace(&push, &load)
        .replacen(first_set, &format!("{function}\n{first_set}"), 1)
        .replace(
            analysis,
            &format!("StaticStructural nsteps {steps} deltat 1 rtolf 1e-8 maxiter 25"),
        )
        .replace(
            &counts,
            &counts.replace(&format!("nltf {nltf}"), &format!("nltf {}", nltf + 1)),
        )
}

/// A body held by contact alone whose contact zone grows over its steps (issue 50, item 9): the
/// tetrahedral Hertz cap pushed by a force that grows in 5 steps, the condensed block lowered so
/// that the zone outgrows the nearest points' equations and the step sets them up again, again
/// and again. Every factorization stays the condensed one (the regrown set once exceeded the
/// block and full tangents took over for the rest of the analysis), each step converges in a few
/// iterations (the held body's first step moved it by 10¹⁰ where a factorization's pivot test
/// missed that it floats: `assembly::rigid`), and the pressures are those of the run condensed on
/// every candidate; so are those of a block too small for the closed points (it grows to hold
/// them) and of full tangents throughout.
#[test]
fn a_growing_contact_zone_of_a_body_held_by_contact_alone_stays_condensed() {
    for law in [Law::Penalty(1e5), Law::Multiplier] {
        let text = HertzSphere {
            kind: Solid::Tet,
            sym: 0,
            h: 0.4,
            delta: 0.15,
            nlgeo: false,
            law,
            mortar: false,
        }
        .input_within(HERTZ_CAP);
        let model = common::model_from_text(&pushed_by_force(&text, 30.0, 5)).unwrap();
        let run = |max_condensed: usize| {
            let seen = Factorizations::default();
            let params = SolveParams {
                max_condensed: Some(max_condensed),
                condensed_contact: max_condensed > 0,
                max_cutbacks: 0,
                ..common::quiet()
            };
            let (mut states, mut its) = (Vec::new(), Vec::new());
            hertz::solve::run_analysis_observed(&model, &params, &seen, |r| {
                states = r.contact.to_vec();
                its.push(r.info.iterations);
                Ok(())
            })
            .unwrap_or_else(|e| panic!("{law:?}, at most {max_condensed}: {e}"));
            let kinds = seen.0.into_inner();
            let set_ups = kinds.len();
            assert!(
                max_condensed == 0
                    || kinds
                        .iter()
                        .all(|k| k == "structural tangent, contact condensed"),
                "{law:?}, at most {max_condensed}: {kinds:?}"
            );
            println!("{law:?}, at most {max_condensed}: iterations {its:?}, {set_ups} set-ups");
            (states, its, set_ups)
        };
        let (all, its, _) = run(3000);
        let closed = all.iter().filter(|s| s.active).count();
        assert!(closed > 10, "{law:?}: {closed} closed");
        let every = candidate_equations(&model);
        // A fifth of the candidates: the nearest points' set up at the start, then again twice.
        let (near, its_near, set_ups) = run(every / 5);
        assert!(set_ups >= 3, "{law:?}: {set_ups} set-ups");
        // A block smaller than the closed points need: it grows to hold them (it left the
        // condensed step for full tangents before).
        let (grown, its_grown, _) = run(20);
        // Full tangents: a guess that closes no point holds the cap by springs to find where
        // its motion first closes one (it had no step before, and never closed a point).
        let (full, its_full, _) = run(0);
        for i in its
            .iter()
            .chain(&its_near)
            .chain(&its_grown)
            .chain(&its_full)
        {
            assert!(
                *i <= 4,
                "{law:?}: iterations {its:?}, {its_near:?}, {its_grown:?}, {its_full:?}"
            );
        }
        let p0 = all
            .iter()
            .map(|s| s.pressure)
            .filter(|p| p.is_finite())
            .fold(0.0, f64::max);
        let others = near.iter().chain(&grown).chain(&full);
        for (a, b) in all.iter().cycle().zip(others) {
            assert!(
                (a.pressure.is_nan() && b.pressure.is_nan())
                    || (a.pressure - b.pressure).abs() < 1e-8 * p0,
                "{law:?} node {}: {} vs {}",
                a.node,
                a.pressure,
                b.pressure
            );
        }
    }
}

/// A body held by contact alone with multipliers, above the condensed step's dense block (issue
/// 30, class 1): the cap of a tetrahedral Hertz sphere, its whole bottom face the slave side,
/// pushed down by a force of 30 (not a displacement), node-to-face and mortar. Solved condensed
/// on all its candidates, condensed on its nearest points (the block lowered to 200 equations),
/// and with full tangents (no condensed step): the same contact forces on every path, and the
/// block's reactions balance the load. Reported: "the stiffness matrix is singular" at the first
/// factorization, with some 800 slave nodes.
#[test]
#[ignore = "long: 6 solves of a 3D tetrahedral contact model (about 15 s)"]
fn a_body_held_by_contact_alone_is_solved_on_every_solver_path() {
    for mortar in [false, true] {
        let text = HertzSphere {
            kind: Solid::Tet,
            sym: 0,
            h: 0.25,
            delta: 0.15,
            nlgeo: false,
            law: Law::Multiplier,
            mortar,
        }
        .input_within(HERTZ_CAP);
        let model = common::model_from_text(&pushed_by_force(&text, 30.0, 1)).unwrap();
        let run = |max_condensed: usize, condensed_contact: bool| {
            let params = SolveParams {
                max_condensed: Some(max_condensed),
                condensed_contact,
                ..common::quiet()
            };
            let mut out = (Vec::new(), 0.0);
            run_analysis(&model, &params, |r| {
                let lift: f64 = r
                    .dofs
                    .prescribed
                    .iter()
                    .zip(r.reactions)
                    .filter(|((_, d, _), _)| *d == 3)
                    .map(|(_, f)| f)
                    .sum();
                out = (r.contact.to_vec(), lift);
                Ok(())
            })
            .unwrap_or_else(|e| {
                panic!("mortar {mortar}, {max_condensed}, {condensed_contact}: {e}")
            });
            out
        };
        let (all, lift) = run(3000, true);
        assert!(
            (lift - 30.0).abs() < 1e-8,
            "mortar {mortar}: reactions {lift}"
        );
        let p0 = all
            .iter()
            .map(|s| s.pressure)
            .filter(|p| p.is_finite())
            .fold(0.0, f64::max);
        assert!(all.iter().filter(|s| s.active).count() > 10);
        for (max, condensed) in [(200, true), (3000, false)] {
            let (other, lift) = run(max, condensed);
            assert!(
                (lift - 30.0).abs() < 1e-8,
                "mortar {mortar}: reactions {lift}"
            );
            for (a, b) in all.iter().zip(&other) {
                assert!(
                    (a.pressure.is_nan() && b.pressure.is_nan())
                        || (a.pressure - b.pressure).abs() < 1e-8 * p0,
                    "mortar {mortar}, {max}, {condensed}: node {} {} vs {}",
                    a.node,
                    a.pressure,
                    b.pressure
                );
            }
        }
    }
}

/// How uniformly a patch-test run of `text` transfers its pressure: the relative spread of σ_zz
/// over every integration point, that of the active slave nodes' pressures, the first node's
/// pressure against −σ_zz, and the active nodes' count.
fn uniform_transfer(text: &str) -> (f64, f64, f64, usize) {
    let spread = |v: &[f64]| {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        (hi - lo) / hi.abs().max(lo.abs())
    };
    let model = common::model_from_text(text).unwrap();
    let (mut stress, mut pressure) = (Vec::new(), Vec::new());
    run_analysis(&model, &common::quiet(), |r| {
        stress = r.states.iter().flatten().map(|g| g.stress[2]).collect();
        pressure = r
            .contact
            .iter()
            .filter(|s| s.active)
            .map(|s| s.pressure)
            .collect();
        Ok(())
    })
    .unwrap();
    let mismatch = (pressure[0] / -stress[0] - 1.0).abs();
    (spread(&stress), spread(&pressure), mismatch, pressure.len())
}

/// Node-to-face contact between quadratic tetrahedra (QTRSpace, 6-node faces) with matching
/// meshes, mid-side nodes among the contact nodes, passes the contact patch test: a uniform
/// pressure is transferred exactly — σ_zz the same at every integration point of both blocks,
/// and every active slave node reports the same pressure (the pressure of a curved surface is
/// the L2 projection of the nodal forces, `tributary::PressureAreas::pressures`, since a uniform
/// pressure puts no force on a 6-node triangle's corners), equal to −σ_zz. Multipliers to
/// round-off in small and large deformation; a penalty to its own error, which falls tenfold
/// per decade of ε (its lumped areas, 1/19 and 16/57 of a triangle, are not the consistent 0 and
/// 1/3).
#[test]
fn node_to_face_on_quadratic_tetrahedra_passes_the_patch_test() {
    use hertz_bench::mesh::Solid;
    use hertz_bench::suite::Law;
    use hertz_bench::verify::Patch;
    for nlgeo in [false, true] {
        for (law, bound) in [
            (Law::Multiplier, 1e-10),
            (Law::Penalty(1e7), 3e-4),
            (Law::Penalty(1e8), 3e-5),
        ] {
            for sym in [0, 45] {
                let text = Patch {
                    kind: Solid::Tet,
                    slave_kind: None,
                    sym,
                    n: 2,
                    nlgeo,
                    delta: 0.01,
                    steps: 1,
                    law,
                    slave_n: Some(2),
                    mortar: false,
                }
                .input_quadratic();
                let (ds, dp, mismatch, active) = uniform_transfer(&text);
                assert_eq!(active, 25, "every slave node, mid-sides too");
                assert!(
                    ds < bound && dp < bound && (nlgeo || mismatch < bound),
                    "nlgeo {nlgeo} {law:?} sym {sym}: σ spread {ds:e}, p spread {dp:e}, p/σ {mismatch:e}"
                );
            }
        }
    }
}

/// Mortar contact between quadratic solids (QTRSpace's 6-node and QSpace's 8-node faces, small
/// and large deformation) passes the contact patch test on non-matching meshes (slave 3 × 3,
/// master 2 × 2 across): σ_zz the same at every integration point of both blocks and every slave
/// node, corners and mid-sides, carrying the same pressure as its multiplier, −σ_zz in small
/// deformation (in large the nominal pressure on the reference area, 1.6 % off the Cauchy σ).
/// The multipliers' dual basis is biorthogonal to the modified quadratic basis (positive
/// supports at the corners, where the plain basis gives 0 or −A/12), so a uniform pressure is
/// exact.
#[test]
fn mortar_on_quadratic_faces_passes_the_patch_test() {
    for (kind, nlgeo, law, bound) in [
        (Solid::Tet, false, Law::Multiplier, 1e-10),
        (Solid::Hex, false, Law::Multiplier, 1e-10),
        (Solid::Tet, false, Law::Penalty(1e8), 1e-10),
        (Solid::Hex, false, Law::Penalty(1e8), 1e-10),
        (Solid::Tet, true, Law::Multiplier, 1e-10),
        (Solid::Hex, true, Law::Multiplier, 1e-10),
    ] {
        let text = Patch {
            kind,
            slave_kind: None,
            sym: 0,
            n: 2,
            nlgeo,
            delta: 0.01,
            steps: 1,
            law,
            slave_n: Some(3),
            mortar: true,
        }
        .input_quadratic();
        let (ds, dp, mismatch, active) = uniform_transfer(&text);
        println!(
            "{kind:?} nlgeo {nlgeo} {law:?}: {active} slots, σ spread {ds:e}, p spread {dp:e}, \
             p/σ {mismatch:e}"
        );
        assert!(
            ds < bound && dp < bound && (nlgeo || mismatch < bound),
            "{kind:?} nlgeo {nlgeo} {law:?}: σ spread {ds:e}, p spread {dp:e}, p/σ {mismatch:e}"
        );
    }
}

/// Mortar multipliers on quadratic faces are eliminated, all of them, into a symmetric system
/// (no sparse LU): a multiplier biorthogonal to the modified basis also pushes the corners
/// beside its mid-side node, so the slave rows are combined by the basis transformation first
/// (`Formulation::slave_transform`). The 20-node brick patch with 8 × 8 master bricks (833
/// slave nodes, 11 113 unknowns): the exact pressure in one iteration. Kept as unknowns, the
/// mid-sides' multipliers made the 16 × 16 patch a 59 s, 6.3 GB LU where the penalty twin takes
/// 7.6 s (now 11.4 s, 1.8 GB).
#[test]
fn mortar_multipliers_on_quadratic_faces_are_eliminated() {
    let text = Patch {
        kind: Solid::Hex,
        slave_kind: None,
        sym: 0,
        n: 8,
        nlgeo: false,
        delta: 0.01,
        steps: 1,
        law: Law::Multiplier,
        slave_n: None,
        mortar: true,
    }
    .input_quadratic();
    let model = common::model_from_text(&text).unwrap();
    let mut out = (0.0, 0, (0, 0), true);
    run_analysis(&model, &common::quiet(), |r| {
        out = (
            pressure_error(r.contact, E * 0.01 / (2.0 * PATCH_H)),
            r.info.iterations,
            r.info.multipliers_eliminated,
            r.info.solver.used_lu,
        );
        Ok(())
    })
    .unwrap();
    assert!(out.0 < 1e-11 && out.1 == 1, "{out:?}");
    assert_eq!((out.2, out.3), ((833, 0), false), "{out:?}");
}

/// Two unit cubes of 4 × 4 × 4 bricks (E = 1000, ν = 0.3) across a gap of 0.01, the 25 nodes of
/// the lower one's top paired with the upper one's bottom by `condition` (node-to-node,
/// `masterset 3 slaveset 4`), the lower cube's bottom fixed, the upper one's top moved by
/// (0, 0, −0.05) (OOFEM's `NonLinearStatic`, rtolv 1e-8).
fn stacked_cubes(condition: &str) -> String {
    let n = 4usize;
    let id = |b: usize, i: usize, j: usize, k: usize| {
        1 + b * (n + 1).pow(3) + (k * (n + 1) + j) * (n + 1) + i
    };
    let mut nodes = String::new();
    let mut cells = String::new();
    for b in 0..2 {
        let z0 = if b == 0 { 0.0 } else { 1.01 };
        for k in 0..=n {
            for j in 0..=n {
                for i in 0..=n {
                    let (x, y, z) = (
                        i as f64 / n as f64,
                        j as f64 / n as f64,
                        z0 + k as f64 / n as f64,
                    );
                    nodes += &format!("node {} coords 3 {x} {y} {z}\n", id(b, i, j, k));
                }
            }
        }
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let face = |k| {
                        [
                            id(b, i, j, k),
                            id(b, i + 1, j, k),
                            id(b, i + 1, j + 1, k),
                            id(b, i, j + 1, k),
                        ]
                    };
                    let c: Vec<String> = face(k + 1)
                        .iter()
                        .chain(&face(k))
                        .map(|v| v.to_string())
                        .collect();
                    cells += &format!(
                        "LSpace {} nodes 8 {} crossSect 1 mat 1\n",
                        1 + b * n.pow(3) + (k * n + j) * n + i,
                        c.join(" ")
                    );
                }
            }
        }
    }
    let layer = |b: usize, k: usize| {
        let v: Vec<String> = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i, j)))
            .map(|(i, j)| id(b, i, j, k).to_string())
            .collect();
        format!("nodes {} {}", v.len(), v.join(" "))
    };
    format!(
        "cubes.out\nstacked cubes\nNonLinearStatic nsteps 2 controlmode 1 rtolv 1e-8 manrmsteps 1 maxiter 40\n\
         domain 3d\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 3 nic 0 nltf 2 nset 4\n{nodes}{cells}\
         SimpleCS 1\nIsoLE 1 d 0 E 1000 n 0.3 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 3 1 2 3 values 3 0 0 0 set 1\n\
         BoundaryCondition 2 loadTimeFunction 2 dofs 3 1 2 3 values 3 0 0 -0.05 set 2\n\
         {condition} 3 loadTimeFunction 1 {} masterset 3 slaveset 4\n\
         ConstantFunction 1 f(t) 1.0\nPiecewiseLinFunction 2 npoints 2 t 2 0 1 f(t) 2 0 1\n\
         Set 1 {}\nSet 2 {}\nSet 3 {} ordered_nodes\nSet 4 {} ordered_nodes\n",
        2 * (n + 1).pow(3),
        2 * n.pow(3),
        "",
        layer(0, 0),
        layer(1, n),
        layer(0, n),
        layer(1, 0),
    )
}

/// Node-to-node penalties from as soft as the elements to 10¹¹ times stiffer (E·h = 250 under a
/// node) are solved with their forces as unknowns and the penalty's compliance (issue 50 item
/// 7: with ε = 1e12 the pairs' branches chattered on gaps at the round-off of the solve and the
/// step failed after 3 halvings): each converges in 2 iterations; every closed pair's force is
/// ε times its penetration (the penalty's law, not the hard constraint) to 1e-9 (and the round-off
/// of the gap times ε), and for ε ≥ 1e8
/// the total force is the multipliers' to 1e-5.
#[test]
fn stiff_node_to_node_penalties_converge_and_keep_their_law() {
    let total = |states: &[SlotState]| states.iter().map(|s| s.force).sum::<f64>();
    let (hard, its) = solve(&stacked_cubes("n2nlagrangianmultipliercontact"));
    assert_eq!(its, [0, 2]);
    let f_hard = total(&hard);
    assert!(f_hard > 0.0 && hard.iter().filter(|s| s.active).count() == 25);
    for eps in [1e2, 1e8, 1e12, 1e14] {
        let text = stacked_cubes("n2npenaltycontact").replace(
            "loadTimeFunction 1  masterset",
            &format!("loadTimeFunction 1 penalty {eps:e} masterset"),
        );
        let (states, its) = solve(&text);
        assert_eq!(its, [0, 2], "penalty {eps:e}");
        for s in states.iter().filter(|s| s.active) {
            // The gap is a difference of coordinates near 1: its round-off, 1e-16, times ε.
            assert!(
                (s.force - eps * -s.gap).abs() <= 1e-9 * s.force + eps * 1e-15,
                "penalty {eps:e}: node {}: force {} for gap {}",
                s.node,
                s.force,
                s.gap
            );
        }
        let f = total(&states);
        println!("penalty {eps:e}: force {f} (multipliers {f_hard})");
        if eps >= 1e8 {
            assert!((f - f_hard).abs() <= 1e-5 * f_hard, "{f} vs {f_hard}");
        } else {
            assert!(f < f_hard);
        }
    }
}
