#![allow(clippy::needless_range_loop)]
//! Every contact tangent is the Jacobian of its residual: central finite differences of the local
//! contact residual, for every law (penalty, multiplier active and inactive) and every partner
//! (node; straight and quadratic edges in small and large deformation, in the middle of an edge,
//! on a vertex whose normal is averaged with the neighbouring edge, past the open end of the
//! master where the force is weighted down and the multipliers hold the gap or the ramp's end;
//! circle, cavity, sphere, polynomial above and below,
//! plane, with and without a moving reference node; a prescribed normal). Partners are held fixed
//! while the contact point moves with the unknowns, as in the linearization. Friction is checked
//! with multipliers and with a penalty (solved in the multipliers' form, with its compliance), the
//! tangent over the multipliers too. A penalty point's tangent with a held force (the solver's
//! `SlotLinearization::hold_force`) is checked against the residual ε·g·v written as ε·v ⊗ ∇g − λ·∂v.

use crate::common;

use common::{face_input, face_input_of, label_of_slave, strip, LM, PEN};

use hertz::assembly::NodalState;
use hertz::contact::{ContactSystem, Search};
use hertz::fem::shape::HEXA8_CORNERS;
use hertz_bench::mesh::Solid;

struct Case {
    name: String,
    text: String,
    /// (node label, displacement) applied before evaluating.
    disp: Vec<(usize, [f64; 3])>,
    lambda: f64,
    /// Expected number of active contact nodes.
    active: usize,
}

/// Largest relative difference between the assembled local tangents and central differences of
/// the local residuals at `u`, over all contributions; and the evaluated states.
fn fd_error(
    model: &hertz::model::Model,
    contact: &ContactSystem,
    dofs: &hertz::assembly::DofMap,
    u: &[f64],
) -> (f64, Vec<hertz::contact::SlotState>, usize) {
    fd_error_with_history(model, contact, dofs, u, None)
}

/// The tangent's worst relative error against central differences along `directions` (over
/// all the unknowns): per point, K v over its unknowns against (f(u + hv) − f(u − hv))/2h, two
/// evaluations a direction instead of two per unknown of every point (large-deformation mortar on
/// quadratic faces evaluates slowly). Returns the error, the states at `u` and the points checked.
fn directional_fd_error(
    model: &hertz::model::Model,
    contact: &ContactSystem,
    dofs: &hertz::assembly::DofMap,
    u: &[f64],
    directions: &[Vec<f64>],
) -> (f64, Vec<hertz::contact::SlotState>, usize) {
    let (points, states) = contact
        .evaluate(&NodalState::new(model, dofs, u), Search::Fresh)
        .unwrap();
    let contribs: Vec<_> = points.iter().map(|p| p.contribution()).collect();
    let at = |u: &[f64]| {
        let points = contact
            .evaluate(&NodalState::new(model, dofs, u), Search::Frozen(&states))
            .unwrap()
            .0;
        points
            .iter()
            .map(|p| p.contribution().fe)
            .collect::<Vec<_>>()
    };
    let h = 1e-6;
    let mut worst = 0.0f64;
    for v in directions {
        let shifted =
            |sign: f64| -> Vec<f64> { u.iter().zip(v).map(|(a, b)| a + sign * h * b).collect() };
        let (fp, fm) = (at(&shifted(1.0)), at(&shifted(-1.0)));
        for (k, c) in contribs.iter().enumerate() {
            let m = c.codes.len();
            let scale = c.ke.iter().fold(1e-12f64, |a, v| a.max(v.abs()));
            for i in 0..m {
                let kv: f64 = (0..m).map(|j| c.ke[i * m + j] * v[c.codes[j]]).sum();
                let fd = (fp[k][i] - fm[k][i]) / (2.0 * h);
                worst = worst.max((fd - kv).abs() / scale);
            }
        }
    }
    let checked = contribs.iter().filter(|c| !c.fe.is_empty()).count();
    (worst, states, checked)
}

/// [`fd_error`] with a friction history (the converged states of a last step at u = 0).
fn fd_error_with_history(
    model: &hertz::model::Model,
    contact: &ContactSystem,
    dofs: &hertz::assembly::DofMap,
    u: &[f64],
    history: Option<&[hertz::contact::SlotState]>,
) -> (f64, Vec<hertz::contact::SlotState>, usize) {
    let (points, states) = contact
        .evaluate_with_history(&NodalState::new(model, dofs, u), Search::Fresh, history)
        .unwrap();
    let contribs: Vec<_> = points.iter().map(|p| p.contribution()).collect();
    let point = |u: &[f64], k: usize| {
        contact
            .evaluate_with_history(
                &NodalState::new(model, dofs, u),
                Search::Frozen(&states),
                history,
            )
            .unwrap()
            .0
            .swap_remove(k)
    };
    let h = 1e-6;
    let mut worst = 0.0f64;
    let mut checked = 0;
    for (k, c) in contribs.iter().enumerate() {
        if c.fe.is_empty() {
            continue;
        }
        let m = c.codes.len();
        let scale = c.ke.iter().fold(1e-12f64, |a, v| a.max(v.abs()));
        let held = held_force_check(&points[k]);
        for j in 0..m {
            let code = c.codes[j];
            assert!(code < dofs.n_primary(), "plain DOFs in these cases");
            let (mut up, mut um) = (u.to_vec(), u.to_vec());
            up[code] += h;
            um[code] -= h;
            let (pp, pm) = (point(&up, k), point(&um, k));
            let (fp, fm) = (pp.contribution().fe, pm.contribution().fe);
            for i in 0..m {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                worst = worst.max((fd - c.ke[i * m + j]).abs() / scale);
            }
            if let Some((ke, penalty, force)) = &held {
                // R = ε·g·v: the tangent with the held force λ is ε·v ⊗ ∇g − λ·∂v.
                let (r0, rp, rm) = (&points[k].closed_fe, &pp.closed_fe, &pm.closed_fe);
                let g0 = points[k].gap;
                for i in 0..m {
                    let du = (rp[i] / (penalty * pp.gap) - rm[i] / (penalty * pm.gap)) / (2.0 * h);
                    let expected = r0[i] / g0 * points[k].gap_grad[j] - force * du;
                    worst = worst.max((expected - ke[i * m + j]).abs() / scale);
                }
            }
        }
        checked += 1;
    }
    (worst, states, checked)
}

fn displaced(model: &hertz::model::Model, dofs: &hertz::assembly::DofMap, case: &Case) -> Vec<f64> {
    let mut u = vec![0.0; dofs.n_primary()];
    for &(label, d) in &case.disp {
        let n = model
            .nodes
            .iter()
            .position(|x| x.label == label)
            .unwrap_or_else(|| panic!("{}: node {label}", case.name));
        for k in 0..3 {
            if let Some(c) = dofs.code(n, k as u8 + 1) {
                u[c] = d[k];
            }
        }
    }
    for i in dofs.n_free - dofs.n_lambda..dofs.n_free {
        u[i] = case.lambda;
    }
    u
}

fn check(case: &Case) {
    let model =
        common::model_from_text(&case.text).unwrap_or_else(|e| panic!("{}: {e}", case.name));
    let mut contact = ContactSystem::new(&model).unwrap();
    let dofs = hertz::solve::number_dofs(&model).unwrap();
    contact.set_pressure_limit(f64::INFINITY);
    let u = displaced(&model, &dofs, case);
    let (err, states, checked) = fd_error(&model, &contact, &dofs, &u);
    let n_active = states.iter().filter(|s| s.active).count();
    assert_eq!(
        n_active, case.active,
        "{}: active contact nodes ({states:?})",
        case.name
    );
    assert!(checked > 0, "{}: no contribution checked", case.name);
    assert!(
        err < 1e-6,
        "{}: tangent off by {err:e} (relative)",
        case.name
    );
}

/// Displacements by node label.
type Disp = Vec<(usize, [f64; 3])>;

/// An edge case: a strip of `nm` master elements, the contact node at `pos` displaced by `ds`,
/// master nodes displaced by `dm`.
struct EdgeCase {
    name: &'static str,
    nm: usize,
    pos: (f64, f64),
    ds: [f64; 3],
    dm: Disp,
}

fn edge_cases() -> Vec<EdgeCase> {
    vec![
        // In the middle of an edge, nodes of the edge moved.
        EdgeCase {
            name: "mid-edge",
            nm: 1,
            pos: (0.3, 1.05),
            ds: [0.04, -0.11, 0.0],
            dm: vec![(3, [0.02, -0.01, 0.0]), (4, [-0.01, 0.03, 0.0])],
        },
        // Near the vertex shared by two edges (normal averaged over both; neighbours move).
        EdgeCase {
            name: "vertex",
            nm: 3,
            pos: (1.02, 1.05),
            ds: [-0.03, -0.09, 0.0],
            dm: vec![
                (5, [0.01, -0.02, 0.0]),
                (6, [0.0, 0.03, 0.0]),
                (7, [0.02, 0.01, 0.0]),
                (8, [-0.01, -0.015, 0.0]),
            ],
        },
        // Just past the open end of the master: the force is weighted down (0 < w < 1) (an
        // isolated node: the ramp is 1 % of the end edge long, here 0.01). The node is 0.002
        // past the end, e = 0.002 − 0.01 = −0.008 past the ramp's end, and about 0.02 deep (the
        // end node moved up): the multipliers hold max(g, e) = e, the ramp's end.
        EdgeCase {
            name: "open-end",
            nm: 2,
            pos: (2.0, 1.0),
            ds: [0.002, -0.01, 0.0],
            dm: vec![(5, [0.01, -0.02, 0.0]), (6, [0.0, 0.01, 0.0])],
        },
        // The same about 0.004 deep: the multipliers hold g.
        EdgeCase {
            name: "open-end, shallow",
            nm: 2,
            pos: (2.0, 1.0),
            ds: [0.002, -0.002, 0.0],
            dm: vec![(5, [0.01, -0.02, 0.0]), (6, [0.0, 0.01, 0.0])],
        },
    ]
}

#[test]
fn n2s_tangents_are_jacobians_of_residuals_on_straight_and_quadratic_edges() {
    for kind in ["q4", "q8"] {
        for nlgeo in [0u8, 1] {
            for c in edge_cases() {
                for (law, lambda, label) in [(PEN, 0.0, "pen"), (LM, 7.0, "lm")] {
                    let text = strip(kind, nlgeo, c.nm, c.pos, None, law);
                    let mut disp = c.dm.clone();
                    disp.push((label_of_slave(&text), c.ds));
                    check(&Case {
                        name: format!("{}-{kind}-nlgeo{nlgeo}-{label}", c.name),
                        text,
                        disp,
                        lambda,
                        active: 1,
                    });
                }
            }
        }
    }
}

/// A frictional case: the history is the state at u = 0, the tangent checked at the displaced
/// state (multipliers, the normal and the friction force's components, at `lambda`), where the
/// point must stick or slip as `stick` says.
/// For a penalty point that is closed with its geometric part and weight 1: its closed tangent
/// with half its force held (`SlotLinearization::hold_force`), the penalty and the held force.
fn held_force_check(p: &hertz::contact::SlotLinearization) -> Option<(Vec<f64>, f64, f64)> {
    let geo = p.geometric.as_ref()?;
    if geo.force == 0.0 || geo.weight != 1.0 || p.gap >= 0.0 {
        return None;
    }
    let mut q = p.clone();
    let force = 0.5 * geo.force;
    q.hold_force(force);
    Some((q.closed_ke, geo.penalty, force))
}

fn check_friction(
    name: String,
    text: String,
    disp: Vec<(usize, [f64; 3])>,
    lambda: f64,
    stick: bool,
) {
    let model = common::model_from_text(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut contact = ContactSystem::new(&model).unwrap();
    let dofs = hertz::solve::number_dofs(&model).unwrap();
    contact.set_pressure_limit(f64::INFINITY);
    let u0 = vec![0.0; dofs.n_primary()];
    let history = contact
        .evaluate(
            &hertz::assembly::NodalState::new(&model, &dofs, &u0),
            Search::Fresh,
        )
        .unwrap()
        .1;
    assert!(
        history.iter().all(|s| s.anchor.is_some()),
        "{name}: anchors"
    );
    let case = Case {
        name: name.clone(),
        text,
        disp,
        lambda,
        active: 1,
    };
    let u = displaced(&model, &dofs, &case);
    let (err, states, checked) = fd_error_with_history(&model, &contact, &dofs, &u, Some(&history));
    let closed = states
        .iter()
        .find(|s| s.active)
        .unwrap_or_else(|| panic!("{name}: a closed point"));
    let (s, force) = closed
        .friction
        .unwrap_or_else(|| panic!("{name}: friction"));
    assert_eq!(s, stick, "{name}: stick");
    assert!(force > 0.0, "{name}: friction force");
    assert!(checked > 0 && err < 1e-6, "{name}: tangent off by {err:e}");
}

/// The frictional tangent (unsymmetric: stick, and slip with the force along the slip) is the
/// Jacobian of the residual, against straight and quadratic edges in small and large
/// deformation and against rigid segments (fixed and moving with a node). The history is the
/// state at u = 0 (the anchor where the node first touched); at the displaced state the node has
/// slid along the master and pressed into it (μ = 5: stick, μ = 0.05: slip). With the penalty
/// law, and with multipliers (the normal force and the friction force's components at 1000:
/// the tangent over the multipliers too).
#[test]
fn friction_tangents_are_jacobians_of_residuals_in_stick_and_slip() {
    for (base, lambda) in [(PEN, 1000.0), (LM, 1000.0)] {
        for (mu, stick) in [(5.0, true), (0.05, false)] {
            let law = format!("{base} friction {mu}");
            for kind in ["q4", "q8"] {
                for nlgeo in [0u8, 1] {
                    for c in edge_cases().into_iter().take(2) {
                        let text = strip(kind, nlgeo, c.nm, c.pos, None, &law);
                        let mut disp = c.dm.clone();
                        disp.push((label_of_slave(&text), c.ds));
                        check_friction(
                            format!("{}-{kind}-nlgeo{nlgeo}-mu{mu}-{}", c.name, &base[..4]),
                            text,
                            disp,
                            lambda,
                            stick,
                        );
                    }
                }
            }
            for seg in [
                "circlecontactsegment 1 centerpoint 2 0.3 0.2 radius 0.9 node 900",
                "planecontactsegment 1 point 2 0 1.0 normal 2 0.2 1 node 900",
                "polynomialcontactsegment 1 coeffs 3 0.4 -0.1 1.0",
            ] {
                let text = strip("q4", 0, 1, (0.3, 1.05), Some(seg), &law);
                let mut disp = vec![(label_of_slave(&text), [0.05, -0.12, 0.0])];
                if seg.contains("node 900") {
                    disp.push((900, [0.01, 0.03, 0.0]));
                }
                let name = format!("{seg}-mu{mu}-{}", &base[..4]);
                check_friction(name, text, disp, lambda, stick);
            }
        }
    }
}

/// Friction against faces (hexahedra, tetrahedra, wedges; small and large deformation): stick
/// and slip, the anchor where the node first met the surface, in the middle of a face and where
/// the node moves to the neighbouring face (the anchor's corners are unknowns too). Penalty and
/// multipliers (at 1000).
#[test]
#[ignore = "long: runs with `cargo test --release -- --ignored` (CI runs both)"]
fn friction_tangents_against_faces_are_jacobians_of_residuals() {
    let laws = [
        (
            "n2spenaltycontact 1 loadTimeFunction 1 penalty 1000",
            1000.0,
        ),
        (
            "n2slagrangianmultipliercontact 1 loadTimeFunction 1",
            1000.0,
        ),
    ];
    for (base, lambda) in laws {
        for (mu, stick) in [(5.0, true), (0.05, false)] {
            let law = format!("{base} friction {mu}");
            for kind in [Solid::Hex, Solid::Tet, Solid::Wedge] {
                for nlgeo in [0u8, 1] {
                    for (name, pos, ds) in [
                        ("mid-face", [0.3, 0.4, 1.1], [0.05, -0.03, -0.2]),
                        ("vertex", [0.97, 0.98, 1.1], [0.06, 0.05, -0.15]),
                    ] {
                        let (text, node) = face_input(kind, 0, nlgeo, pos, &law);
                        let disp = vec![
                            (node, ds),
                            (14, [0.01, -0.02, 0.03]),
                            (10, [0.0, 0.01, -0.02]),
                        ];
                        check_friction(
                            format!("{name}-{kind:?}-nlgeo{nlgeo}-mu{mu}-{}", &base[..4]),
                            text,
                            disp,
                            lambda,
                            stick,
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn n2s_tangent_with_a_prescribed_normal_is_jacobian_of_residual() {
    for nlgeo in [0u8, 1] {
        for law in [PEN, LM] {
            let text = strip(
                "q4",
                nlgeo,
                2,
                (0.8, 1.02),
                None,
                &format!("{law} normal 2 0.2 1"),
            );
            let disp = vec![
                (label_of_slave(&text), [0.03, -0.1, 0.0]),
                (4, [0.01, 0.02, 0.0]),
            ];
            check(&Case {
                name: format!("normal-nlgeo{nlgeo}"),
                text,
                disp,
                lambda: 3.0,
                active: 1,
            });
        }
    }
}

#[test]
fn n2s_multiplier_inactive_row_holds_lambda_at_zero() {
    let text = strip("q4", 0, 1, (0.3, 1.05), None, LM);
    check(&Case {
        name: "lm-off".into(),
        text,
        disp: vec![],
        lambda: 0.0,
        active: 0,
    });
}

#[test]
fn rigid_segment_tangents_are_jacobians_of_residuals() {
    // (name, segment, displacement of the contact node): the node starts at (0.3, 1.05)..(0.9, 2.05).
    let cases: [(&str, &str, [f64; 3]); 7] = [
        (
            "circle",
            "circlecontactsegment 1 centerpoint 2 0.3 0.2 radius 0.9",
            [0.05, -0.12, 0.0],
        ),
        (
            "circle-node",
            "circlecontactsegment 1 centerpoint 2 0.3 0.2 radius 0.9 node 900",
            [0.05, -0.12, 0.0],
        ),
        (
            "cavity",
            "circlecontactsegment 1 centerpoint 2 0.3 0.6 radius 0.4 cavity",
            [0.05, 0.02, 0.0],
        ),
        (
            "poly-below",
            "polynomialcontactsegment 1 coeffs 3 0.4 -0.1 1.0",
            [0.05, -0.12, 0.0],
        ),
        (
            "poly-above",
            "polynomialcontactsegment 1 coeffs 3 0.4 -0.1 0.9 bodyabove",
            [0.05, 0.02, 0.0],
        ),
        (
            "plane",
            "planecontactsegment 1 point 2 0 1.0 normal 2 0.2 1",
            [0.05, -0.15, 0.0],
        ),
        (
            "plane-node",
            "planecontactsegment 1 point 2 0 1.0 normal 2 0.2 1 node 900",
            [0.05, -0.15, 0.0],
        ),
    ];
    for (name, seg, d) in cases {
        for (law, lambda) in [(PEN, 0.0), (LM, 5.0)] {
            let text = strip("q4", 0, 1, (0.3, 1.05), Some(seg), law);
            let mut disp = vec![(label_of_slave(&text), d)];
            if seg.contains("node 900") {
                disp.push((900, [0.01, 0.03, 0.0]));
            }
            check(&Case {
                name: name.to_string(),
                text,
                disp,
                lambda,
                active: 1,
            });
        }
    }
}

/// A 3D input with one unit brick (nodes 1..8), node 9 at `node9` and the given extra records.
fn brick_input(ncontactseg: usize, nset: usize, node9: &str, records: &str) -> String {
    let mut text = format!(
        "fd3.out\nfd\nNonLinearStatic nsteps 1 controlmode 1\ndomain 3d\nOutputManager\n\
         ndofman 9 nelem 1 ncrosssect 1 nmat 1 nbc 1 nic 0 nltf 1 nset {nset} ncontactseg {ncontactseg}\n"
    );
    for (i, p) in HEXA8_CORNERS.iter().enumerate() {
        text += &format!("node {} coords 3 {} {} {}\n", i + 1, p[0], p[1], p[2]);
    }
    text + &format!("node 9 coords 3 {node9}\nLSpace 1 nodes 8 1 2 3 4 5 6 7 8\n{records}")
}

#[test]
fn sphere_tangent_in_3d_is_jacobian_of_residual() {
    for cond in [
        "n2spenaltycontact 1 loadTimeFunction 1 penalty 1000 nodeset 2 2 3 segmentset 1 1",
        "n2slagrangianmultipliercontact 1 loadTimeFunction 1 nodeset 2 2 3 segmentset 1 1",
    ] {
        let text = brick_input(
            1,
            1,
            "0.4 0.5 2.5",
            &format!(
                "circlecontactsegment 1 centerpoint 3 0.4 0.5 2.5 radius 1.6 node 9\n\
                 SimpleCS 1 material 1 set 1\nIsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n{cond}\n\
                 ConstantFunction 1 f(t) 1\nSet 1 allelements\n"
            ),
        );
        let disp = vec![
            (2, [0.02, 0.01, 0.1]),
            (3, [-0.01, 0.0, 0.08]),
            (9, [0.0, 0.02, -0.03]),
        ];
        check(&Case {
            name: "sphere".into(),
            text,
            disp,
            lambda: 2.0,
            active: 2,
        });
    }
}

#[test]
fn n2n_tangents_in_2d_and_3d_are_jacobians_of_residuals() {
    for cond in [
        "n2npenaltycontact 1 loadTimeFunction 1 penalty 1000 masterset 2 slaveset 3",
        "n2nlagrangianmultipliercontact 1 loadTimeFunction 1 masterset 2 slaveset 3",
        "n2npenaltycontact 1 loadTimeFunction 1 penalty 1000 masterset 2 slaveset 3 normal 3 0.1 0.2 1",
    ] {
        let text = brick_input(
            0,
            3,
            "0.1 1.2 1.3",
            &format!(
                "SimpleCS 1 material 1 set 1\nIsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n{cond}\n\
                 ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 nodes 1 2\nSet 3 nodes 1 9\n"
            ),
        );
        let disp = vec![(9, [-0.05, -0.3, -0.45]), (2, [0.02, 0.01, 0.03])];
        check(&Case {
            name: "n2n-3d".into(),
            text,
            disp,
            lambda: 2.0,
            active: 1,
        });
    }
}

/// Port of the spec's finite-difference check (spec §2.9, fd_check_n2s_tangent.py): edge
/// x1 = (1, 1.02), x2 = (0, 0.98), node xs = (0.7, 0.95), p = 1, deformed normal. For a single
/// straight edge the force direction is the gradient of the gap, and hertz's tangent equals
/// Wriggers' consistent form K = p NvNvᵀ + (p g/l)(Bv Tvᵀ + Tv Bvᵀ) − (p g²/l²) Bv Bvᵀ; OOFEM's
/// (mixed term with the wrong sign) differs from it by the published 0.116.
#[test]
fn n2s_penalty_tangent_matches_the_consistent_closed_form_of_the_spec() {
    let text =
        "fd.out\nfd\nNonLinearStatic nsteps 1 controlmode 1\ndomain PlaneStrain\nOutputManager\n\
        ndofman 5 nelem 1 ncrosssect 1 nmat 1 nbc 1 nic 0 nltf 1 nset 2 ncontactseg 1\n\
        node 1 coords 2 1 1.02\nnode 2 coords 2 0 0.98\nnode 3 coords 2 0 0\nnode 4 coords 2 1 0\n\
        node 5 coords 2 0.7 0.95\nQuad1PlaneStrain 1 nodes 4 1 2 3 4 nlgeo 1\n\
        linear2delementedgecontactsegment 1 edgeset 2\nSimpleCS 1 thick 1 material 1 set 1\n\
        IsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n\
        n2spenaltycontact 1 loadTimeFunction 1 penalty 1 nodeset 1 5 segmentset 1 1\n\
        ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 elementboundaries 2 1 1\n";
    let model = common::model_from_text(text).unwrap();
    let mut contact = ContactSystem::new(&model).unwrap();
    contact.set_pressure_limit(f64::INFINITY);
    let dofs = hertz::solve::number_dofs(&model).unwrap();
    let u = vec![0.0; dofs.n_primary()];
    let (points, states) = contact
        .evaluate(
            &hertz::assembly::NodalState::new(&model, &dofs, &u),
            Search::Fresh,
        )
        .unwrap();
    let c = &points[0].contribution();
    assert_eq!(c.codes.len(), 6, "node 5, then edge nodes 1 and 2");
    let k_hertz = |i: usize, j: usize| c.ke[i * 6 + j];
    let p = 1.0;
    let (xs, x1, x2): ([f64; 2], [f64; 2], [f64; 2]) = ([0.7, 0.95], [1.0, 1.02], [0.0, 0.98]);
    let t = [x2[0] - x1[0], x2[1] - x1[1]];
    let l = (t[0] * t[0] + t[1] * t[1]).sqrt();
    let e = [t[0] / l, t[1] / l];
    let n = [t[1] / l, -t[0] / l];
    let xi = 2.0 * (e[0] * (xs[0] - x1[0]) + e[1] * (xs[1] - x1[1])) / l - 1.0;
    let (n1, n2) = ((1.0 - xi) / 2.0, (1.0 + xi) / 2.0);
    let gap = (xs[0] - x1[0]) * n[0] + (xs[1] - x1[1]) * n[1];
    assert!(
        (gap - states[0].gap).abs() < 1e-15,
        "gap {gap} vs {}",
        states[0].gap
    );
    assert!((gap + 0.058).abs() < 1e-3);
    let nv = [n[0], n[1], -n1 * n[0], -n1 * n[1], -n2 * n[0], -n2 * n[1]];
    let tv = [e[0], e[1], -n1 * e[0], -n1 * e[1], -n2 * e[0], -n2 * e[1]];
    let bv = [0.0, 0.0, n[0], n[1], -n[0], -n[1]];
    let k_fixed = |i: usize, j: usize| {
        p * nv[i] * nv[j] + p * gap / l * (bv[i] * tv[j] + tv[i] * bv[j])
            - p * gap * gap / (l * l) * bv[i] * bv[j]
    };
    let k_oofem = |i: usize, j: usize| {
        p * nv[i] * nv[j]
            - p * gap / l * (bv[i] * tv[j] + tv[i] * bv[j])
            - p * gap * gap / (l * l) * bv[i] * bv[j]
    };
    let (mut d_fixed, mut d_oofem) = (0.0f64, 0.0f64);
    for i in 0..6 {
        for j in 0..6 {
            d_fixed = d_fixed.max((k_hertz(i, j) - k_fixed(i, j)).abs());
            d_oofem = d_oofem.max((k_hertz(i, j) - k_oofem(i, j)).abs());
        }
    }
    assert!(d_fixed < 1e-12, "consistent closed form: {d_fixed:e}");
    assert!(
        (d_oofem - 0.116).abs() < 2e-3,
        "OOFEM's form is off by {d_oofem}"
    );
}

/// Node against the faces of hexahedra, tetrahedra and wedges in several node orders: in the
/// middle of a face, near the vertex where faces meet (normals averaged, in large deformation
/// over the faces around it), past an open edge of the master (force weighted down); small and
/// large deformation; penalty and multipliers; with a prescribed normal. Also against the curved
/// 6- and 8-node faces of quadratic tetrahedra and bricks (the mid-side nodes off the chords).
#[test]
fn face_tangents_are_jacobians_of_residuals() {
    let positions: [(&str, [f64; 3], [f64; 3]); 3] = [
        ("mid-face", [0.3, 0.4, 1.1], [0.02, -0.03, -0.2]),
        ("vertex", [1.003, 0.98, 1.1], [0.01, 0.005, -0.15]),
        ("past-edge", [2.05, 0.7, 1.1], [0.0, 0.01, -0.2]),
    ];
    let penalty = "n2spenaltycontact 1 loadTimeFunction 1 penalty 1000";
    let multiplier = "n2slagrangianmultipliercontact 1 loadTimeFunction 1";
    for (kind, quadratic, syms) in [
        (Solid::Hex, false, &[0, 13, 22, 45][..]),
        (Solid::Tet, false, &[0, 45]),
        (Solid::Wedge, false, &[0, 13]),
        (Solid::Hex, true, &[22]),
        (Solid::Tet, true, &[45]),
    ] {
        for &sym in syms {
            for nlgeo in [0u8, 1] {
                for (name, pos, ds) in positions {
                    for (law, lambda, extra) in [
                        (penalty, 0.0, ""),
                        (multiplier, 3.0, ""),
                        (penalty, 0.0, " normal 3 0.1 -0.2 1"),
                    ] {
                        let (text, node) = face_input_of(
                            kind,
                            quadratic,
                            sym,
                            nlgeo,
                            pos,
                            &format!("{law}{extra}"),
                        );
                        check(&Case {
                            name: format!(
                                "{name}-{kind:?}{}-sym{sym}-nlgeo{nlgeo}{extra}",
                                if quadratic { "-quadratic" } else { "" }
                            ),
                            text,
                            disp: vec![
                                (node, ds),
                                (14, [0.01, -0.02, 0.03]),
                                (10, [0.0, 0.01, -0.02]),
                            ],
                            lambda,
                            active: 1,
                        });
                    }
                }
            }
        }
    }
}

/// The 2D mortar cases of condition `law` (a record with `slavesegment`): name, input, the
/// displacements and the expected active slots. Non-matching blocks of straight edges (3/2) and
/// of curved quadratic ones (the mid-side nodes moved off the chords), and the upper block
/// against a rigid circle moving with a node (999), each upper block sunk and sheared so that
/// the overlaps move, the lower block's top nodes moved a little.
fn mortar2d_cases(nlgeo: u8, law: &str) -> Vec<(String, String, Disp, usize)> {
    let shear = |n: usize, dy: f64, y: f64| [0.013 + 0.02 * y, dy + 0.003 * (n as f64).sin(), 0.0];
    let mut cases = Vec::new();
    // The upper block: nodes after the lower one's 12; the lower block's top nodes 9..12.
    let text = common::mortar_blocks(3, 2, nlgeo, law);
    let model = common::model_from_text(&text).unwrap();
    let mut disp: Disp = (13..=21)
        .map(|n| (n, shear(n, -0.01, model.nodes[n - 1].coords[1])))
        .collect();
    disp.extend((9..=12).map(|n| (n, [0.004 * (n as f64).cos(), 0.002, 0.0])));
    cases.push(("straight".to_string(), text, disp, 3));
    let text = common::mortar_blocks(3, 2, nlgeo, law)
        .replace(
            "linear2delementedgecontactsegment 2 edgeset 2",
            "circlecontactsegment 2 centerpoint 2 1.0 -3.0 radius 3.0 node 999",
        )
        .replace("ndofman 21 ", "ndofman 22 ")
        .replace(
            "\nnode 1 coords",
            "\nnode 999 coords 2 1.0 -3.0\nnode 1 coords",
        );
    let model = common::model_from_text(&text).unwrap();
    let mut disp: Disp = (13..=21)
        .map(|n| {
            let y = model.nodes.iter().find(|x| x.label == n).unwrap().coords[1];
            (n, shear(n, -0.05, y))
        })
        .collect();
    disp.push((999, [0.01, 0.02, 0.0]));
    cases.push(("circle".to_string(), text, disp, 1));
    // Quadratic edges (3 and 2 elements of 8 nodes: the lower block's top row is nodes 23..29,
    // the upper block is 30..50, its bottom row 30..34).
    let text = common::mortar_blocks_q8(3, 2, nlgeo, law);
    let model = common::model_from_text(&text).unwrap();
    let mut disp: Disp = (30..=50)
        .map(|n| (n, shear(n, -0.01, model.nodes[n - 1].coords[1])))
        .collect();
    disp.extend((23..=29).map(|n| (n, [0.004 * (n as f64).cos(), 0.002 * (n as f64).sin(), 0.0])));
    cases.push(("q8".to_string(), text, disp, 5));
    cases
}

/// The 3D mortar case: the patch of `kind` (1 and 2 elements across) with condition `law`, the
/// slave block sunk and sheared so that the overlaps move, the master's top nodes moved out of
/// plane.
fn mortar3d_case(
    kind: hertz_bench::mesh::Solid,
    nlgeo: bool,
    law: hertz_bench::suite::Law,
) -> (String, Disp) {
    let text = mortar3d_patch(kind, nlgeo, law).input();
    let disp = sunk_and_sheared(&text);
    (text, disp)
}

/// The mortar tangent is the Jacobian of its residual, in small deformation (reference
/// segmentation and normals, the gap following the nodes) and in large deformation (everything
/// current: segmentation limits, normals, lengths), for penalty and multipliers, on non-matching
/// meshes of straight and of curved quadratic edges and against a rigid circle moving with a node,
/// with both blocks displaced and sheared so that the overlaps move ([`mortar2d_cases`]).
#[test]
fn mortar_tangents_are_jacobians_of_residuals() {
    check_mortar2d("mortar", |text| text);
}

/// Every case of [`mortar2d_cases`], small and large deformation, penalty and multipliers, its
/// input passed through `adapt`, checked against finite differences under the name `prefix`.
fn check_mortar2d(prefix: &str, adapt: fn(String) -> String) {
    for nlgeo in [0u8, 1] {
        for (law, lambda) in [
            (
                "s2spenaltycontact 4 loadTimeFunction 1 penalty 1e4 slavesegment 1 segmentset 1 2",
                0.0,
            ),
            (
                "s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 1 segmentset 1 2",
                3.0,
            ),
        ] {
            for (name, text, disp, active) in mortar2d_cases(nlgeo, law) {
                check(&Case {
                    name: format!("{prefix}-{name}-nlgeo{nlgeo}-{}", &law[..4]),
                    text: adapt(text),
                    disp,
                    lambda,
                    active,
                });
            }
        }
    }
}

/// An input's nodes and circle centre moved by 1 along x (for an axisymmetric model: off the
/// axis).
fn off_the_axis(text: &str) -> String {
    let shift = |l: &str, key: &str| -> Option<String> {
        let i = l.find(key)? + key.len();
        let rest = &l[i..];
        let x: f64 = rest.split_whitespace().next()?.parse().ok()?;
        let after = rest.trim_start().split_once(' ').map_or("", |x| x.1);
        Some(format!("{}{} {after}", &l[..i], x + 1.0))
    };
    text.lines()
        .map(|l| {
            shift(l, "coords 2 ")
                .or_else(|| shift(l, "centerpoint 2 "))
                .unwrap_or_else(|| l.to_string())
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The same in axisymmetry (the blocks on `L4Axisymm` and `Q4Axisymm`, moved to radii 1 to 3):
/// every integral carries the slave point's radius, current in large deformation, and the
/// tangent stays the Jacobian of the residual.
#[test]
fn axisymmetric_mortar_tangents_are_jacobians_of_residuals() {
    check_mortar2d("axisymmetric-mortar", |text| {
        let text = off_the_axis(
            &text
                .replace("\nQPlaneStress2d ", "\nQ4Axisymm ")
                .replace("\nPlaneStress2d ", "\nL4Axisymm "),
        );
        assert!(text.contains("Axisymm") && text.contains("coords 2 1 "));
        text
    });
}

/// The multiplier law's production tangent — no `set_pressure_limit` — is the Jacobian of its
/// residual at any pressure: with multipliers at 100 times the stiffest E, the 2D mortar cases
/// in large deformation, where the geometric part λ ∂B is not zero ([`mortar2d_cases`]: straight
/// and quadratic edges, a rigid circle moving with a node). The penalty laws drop the geometric
/// part there (`geometric_tangent_is_dropped_only_beyond_a_pressure_of_e`,
/// tests/suite/contact_geometry.rs).
#[test]
fn multiplier_tangent_keeps_its_geometric_part_beyond_a_pressure_of_e() {
    let law = "s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 1 segmentset 1 2";
    for (name, text, disp, active) in mortar2d_cases(1, law) {
        let model = common::model_from_text(&text).unwrap();
        let young = model
            .materials
            .iter()
            .map(|m| m.young())
            .fold(0.0, f64::max);
        let contact = ContactSystem::new(&model).unwrap();
        let dofs = hertz::solve::number_dofs(&model).unwrap();
        let case = Case {
            name: name.clone(),
            text,
            disp,
            lambda: 100.0 * young,
            active,
        };
        let u = displaced(&model, &dofs, &case);
        let (err, states, checked) = fd_error(&model, &contact, &dofs, &u);
        // λ this large also holds points with a small opening closed (λ − c·g > 0).
        assert!(
            states.iter().filter(|s| s.active).count() >= active,
            "{name}"
        );
        assert!(checked > 0 && err < 1e-6, "{name}: tangent off by {err:e}");
    }
}

/// The 3D mortar tangent is the Jacobian of its residual, in small deformation (reference
/// segmentation, the gap following the nodes) and in large deformation (the clipping, the plane,
/// the normals and the weights at the current state), for penalty and multipliers, on
/// non-matching quadrilateral (hexahedra), triangular (tetrahedra) and mixed (wedges) faces
/// ([`mortar3d_case`]).
#[test]
#[ignore = "long: runs with `cargo test --release -- --ignored` (CI runs both)"]
fn mortar_tangents_in_3d_are_jacobians_of_residuals() {
    use hertz_bench::mesh::Solid;
    use hertz_bench::suite::Law;
    for kind in [Solid::Hex, Solid::Tet, Solid::Wedge] {
        for nlgeo in [false, true] {
            for (law, lambda) in [(Law::Penalty(1e4), 0.0), (Law::Multiplier, 3.0)] {
                let (text, disp) = mortar3d_case(kind, nlgeo, law);
                let name = format!("mortar3d {kind:?} nlgeo {nlgeo} {law:?}");
                check_mortar3d(&name, &text, disp, lambda, Differences::EveryUnknown);
            }
        }
    }
}

/// [`mortar3d_case`] in quadratic elements (QTRSpace, QSpace).
fn mortar3d_quadratic_case(
    kind: hertz_bench::mesh::Solid,
    nlgeo: bool,
    law: hertz_bench::suite::Law,
) -> (String, Disp) {
    let text = mortar3d_patch(kind, nlgeo, law).input_quadratic();
    let disp = sunk_and_sheared(&text);
    (text, disp)
}

/// The patch of the 3D mortar cases: slave 2 × 2 across on a master 1 × 1.
fn mortar3d_patch(
    kind: hertz_bench::mesh::Solid,
    nlgeo: bool,
    law: hertz_bench::suite::Law,
) -> hertz_bench::verify::Patch {
    hertz_bench::verify::Patch {
        kind,
        slave_kind: None,
        sym: 0,
        n: 1,
        nlgeo,
        delta: 0.01,
        steps: 1,
        law,
        slave_n: Some(2),
        mortar: true,
    }
}

/// The displacements of a 3D mortar case: the slave block's nodes (those of the elements above
/// z = 0) sunk and sheared, the master's top nodes moved out of plane.
fn sunk_and_sheared(text: &str) -> Disp {
    let model = common::model_from_text(text).unwrap();
    let mut slave = std::collections::BTreeSet::new();
    for e in &model.elements {
        let z: f64 = e.nodes.iter().map(|&n| model.nodes[n].coords[2]).sum();
        if z > 0.0 {
            slave.extend(e.nodes.iter().copied());
        }
    }
    model
        .nodes
        .iter()
        .enumerate()
        .filter_map(|(i, n)| {
            let [x, y, z] = n.coords;
            let k = n.label as f64;
            if slave.contains(&i) {
                Some((
                    n.label,
                    [0.013 + 0.02 * z, -0.007 + 0.01 * z, -0.01 + 0.003 * k.sin()],
                ))
            } else if z.abs() < 1e-9 {
                Some((n.label, [0.004 * k.cos(), 0.002 * x, 0.003 * (k + y).sin()]))
            } else {
                None
            }
        })
        .collect()
}

/// The mortar tangent on quadratic faces is the Jacobian of its residual, in small deformation
/// (the reference segmentation through flat sub-faces, the curved surfaces' normals) and in
/// large (the current one, every quantity differentiated through the sub-faces' vertices): the
/// patch in 10-node tetrahedra and 20-node bricks (slave 2 × 2 across on a master 1 × 1), the
/// slave block sunk and sheared, the master's top nodes moved out of plane, penalty and
/// multipliers; checked along four directions over all unknowns ([`directional_fd_error`]).
/// Dropping the derivative of the curved area element makes it 5e-2.
#[test]
fn mortar_tangents_on_quadratic_faces_are_jacobians_of_residuals() {
    use hertz_bench::mesh::Solid;
    use hertz_bench::suite::Law;
    for (kind, nlgeo) in [Solid::Hex, Solid::Tet]
        .into_iter()
        .flat_map(|k| [(k, false), (k, true)])
    {
        for (law, lambda) in [(Law::Penalty(1e4), 0.0), (Law::Multiplier, 3.0)] {
            let (text, disp) = mortar3d_quadratic_case(kind, nlgeo, law);
            let name = format!("quadratic mortar3d {kind:?} nlgeo {nlgeo} {law:?}");
            check_mortar3d(&name, &text, disp, lambda, Differences::Directions(4));
        }
    }
}

/// The 3D mortar tangent against rigid shapes is the Jacobian of its residual: the patch's slave
/// block ([`mortar3d_case`], sunk and sheared) on a rigid sphere moving with a node and on a
/// tilted plane, hexahedra, tetrahedra and wedges, small and large deformation, penalty and
/// multipliers.
#[test]
fn mortar_tangents_against_rigid_shapes_in_3d_are_jacobians_of_residuals() {
    use hertz_bench::mesh::Solid;
    use hertz_bench::suite::Law;
    for kind in [Solid::Hex, Solid::Tet, Solid::Wedge] {
        for nlgeo in [false, true] {
            for (law, lambda) in [(Law::Penalty(1e4), 0.0), (Law::Multiplier, 3.0)] {
                let (text, disp) = mortar3d_case(kind, nlgeo, law);
                let name = format!("{kind:?} nlgeo {nlgeo} {law:?}");
                let (sphere, on_sphere) = on_rigid_sphere(&text, disp.clone());
                check_mortar3d(
                    &format!("mortar3d sphere {name}"),
                    &sphere,
                    on_sphere,
                    lambda,
                    Differences::EveryUnknown,
                );
                let plane = common::with_rigid_master(
                    &text,
                    "planecontactsegment 1 point 3 0.5 0.5 0.08 normal 3 0.1 -0.05 1",
                    [0.0; 3],
                );
                let name = format!("mortar3d plane {name}");
                check_mortar3d(&name, &plane, disp, lambda, Differences::EveryUnknown);
            }
        }
    }
}

/// A 3D mortar case ([`mortar3d_case`]) with its master faces replaced by a rigid sphere moving
/// with node 999 (itself displaced), which the sunk slave block penetrates everywhere.
fn on_rigid_sphere(text: &str, mut disp: Disp) -> (String, Disp) {
    let sphere = "circlecontactsegment 1 centerpoint 3 0.5 0.5 -3.0 radius 3.0 node 999";
    disp.push((999, [0.01, -0.02, 0.1]));
    (
        common::with_rigid_master(text, sphere, [0.5, 0.5, -3.0]),
        disp,
    )
}

/// How [`check_mortar3d`] differences the residual.
enum Differences {
    /// Two evaluations per unknown of every point ([`fd_error`]).
    EveryUnknown,
    /// Two evaluations per pseudo-random direction over all unknowns, multipliers too
    /// ([`directional_fd_error`]: large-deformation mortar on quadratic faces evaluates slowly).
    Directions(usize),
}

/// The FD check of a 3D mortar case displaced by `disp`, multipliers at `lambda`: every slave
/// node active and checked (at least the 9 of a linear case), the tangent within 1e-6 of the
/// differences.
fn check_mortar3d(name: &str, text: &str, disp: Disp, lambda: f64, differences: Differences) {
    let model = common::model_from_text(text).unwrap();
    let mut contact = ContactSystem::new(&model).unwrap();
    let dofs = hertz::solve::number_dofs(&model).unwrap();
    contact.set_pressure_limit(f64::INFINITY);
    let u = displaced(
        &model,
        &dofs,
        &Case {
            name: name.to_string(),
            text: String::new(),
            disp,
            lambda,
            active: 0,
        },
    );
    let (err, states, checked) = match differences {
        Differences::EveryUnknown => fd_error(&model, &contact, &dofs, &u),
        Differences::Directions(n) => {
            let directions: Vec<Vec<f64>> = (1..=n)
                .map(|d| {
                    (0..u.len())
                        .map(|i| ((i * 7 + d * 13) as f64).sin())
                        .collect()
                })
                .collect();
            directional_fd_error(&model, &contact, &dofs, &u, &directions)
        }
    };
    let active = states.iter().filter(|s| s.active).count();
    println!("{name}: {err:.1e} over {checked} points, {active} active");
    assert!(
        active >= 9 && active == states.len() && checked == states.len(),
        "{name}: {active} active, {checked} checked of {}",
        states.len()
    );
    assert!(err < 1e-6, "{name}: tangent off by {err:e} (relative)");
}

/// Mortar friction's tangent (unsymmetric) is the Jacobian of its residual in stick (μ = 5) and
/// slip (μ = 0.01), small and large deformation (the shares of the current segmentation
/// differentiated too), on the cases of the frictionless mortar tests: 2D straight
/// and quadratic edges and a rigid circle moving with a node, 3D hexahedra, tetrahedra and
/// wedges against faces and against a rigid sphere moving with a node, 10-node tetrahedra and
/// 20-node bricks on their curved faces (small deformation); the history is the state
/// at u = 0. Penalty (solved in multiplier form) and multipliers, the pressures and the friction
/// tractions' components at 1000: the tangent over the multipliers too.
#[test]
#[ignore = "long: runs with `cargo test --release -- --ignored` (CI runs both)"]
fn mortar_friction_tangents_are_jacobians_in_stick_and_slip() {
    use hertz_bench::mesh::Solid;
    use hertz_bench::suite::Law;
    let laws = [
        (
            "s2spenaltycontact 4 loadTimeFunction 1 penalty 1e4 slavesegment 1 segmentset 1 2",
            Law::Penalty(1e4),
            1000.0,
        ),
        (
            "s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 1 segmentset 1 2",
            Law::Multiplier,
            1000.0,
        ),
    ];
    for (law, law3d, lambda) in laws {
        let mut cases: Vec<(String, String, Disp)> = Vec::new();
        for nlgeo in [0u8, 1] {
            cases.extend(
                mortar2d_cases(nlgeo, law)
                    .into_iter()
                    .map(|(name, text, disp, _)| (format!("{name} nlgeo {nlgeo}"), text, disp)),
            );
        }
        for (kind, nlgeo) in [Solid::Hex, Solid::Tet, Solid::Wedge]
            .into_iter()
            .flat_map(|k| [(k, false), (k, true)])
        {
            let (text, disp) = mortar3d_case(kind, nlgeo, law3d);
            let kind = format!("{kind:?} nlgeo {}", u8::from(nlgeo));
            // Against faces, and against a rigid sphere moving with a node.
            let (sphere, on_sphere) = on_rigid_sphere(&text, disp.clone());
            cases.push((kind.clone(), text, disp));
            cases.push((format!("{kind} sphere"), sphere, on_sphere));
        }
        // Quadratic faces in small deformation (the shares of the modified basis' dual).
        for kind in [Solid::Hex, Solid::Tet] {
            let (text, disp) = mortar3d_quadratic_case(kind, false, law3d);
            cases.push((format!("quadratic {kind:?} nlgeo 0"), text, disp));
        }
        for (name, text, disp) in cases {
            for (mu, stick) in [(5.0, true), (0.01, false)] {
                let name = format!("mortar friction {name} mu {mu} {}", &law[..4]);
                let text = text.replace("slavesegment", &format!("friction {mu} slavesegment"));
                let model =
                    common::model_from_text(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
                let mut contact = ContactSystem::new(&model).unwrap();
                let dofs = hertz::solve::number_dofs(&model).unwrap();
                contact.set_pressure_limit(f64::INFINITY);
                let u0 = vec![0.0; dofs.n_primary()];
                let history = contact
                    .evaluate(
                        &hertz::assembly::NodalState::new(&model, &dofs, &u0),
                        Search::Fresh,
                    )
                    .unwrap()
                    .1;
                let case = Case {
                    name: name.clone(),
                    text: String::new(),
                    disp: disp.clone(),
                    lambda,
                    active: 0,
                };
                let u = displaced(&model, &dofs, &case);
                let (err, states, checked) =
                    fd_error_with_history(&model, &contact, &dofs, &u, Some(&history));
                let closed: Vec<_> = states.iter().filter_map(|s| s.friction).collect();
                let (sticking, force) = (
                    closed.iter().filter(|f| f.0).count(),
                    closed.iter().map(|f| f.1).sum::<f64>(),
                );
                println!(
                    "{name}: {err:.1e} over {checked} points, {} closed, {sticking} stick",
                    closed.len()
                );
                assert!(!closed.is_empty() && force > 0.0, "{name}: friction");
                assert_eq!(sticking == closed.len(), stick, "{name}: {sticking} stick");
                assert!(err < 1e-6, "{name}: tangent off by {err:e} (relative)");
            }
        }
    }
}
