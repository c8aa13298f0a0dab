#![allow(clippy::needless_range_loop)]
//! Every contact tangent is the Jacobian of its residual: central finite differences of the local
//! contact residual, for every law (penalty, multiplier active and inactive) and every partner
//! (node, straight and quadratic edge in small and large deformation, circle, sphere, polynomial,
//! plane, with and without a moving reference node). Search results (partner and contact point)
//! are held fixed, as in the linearization.

mod common;

use hertz::contact::ContactSystem;
use hertz::fem::shape::HEXA8_CORNERS;

struct Case {
    name: &'static str,
    text: String,
    /// (node label, displacement) applied before evaluating.
    disp: Vec<(usize, [f64; 3])>,
    lambda: f64,
    /// Expected number of active contact nodes.
    active: usize,
}

fn check(case: &Case) {
    let model =
        common::model_from_text(&case.text).unwrap_or_else(|e| panic!("{}: {e}", case.name));
    let dofs = hertz::solve::number_dofs(&model).unwrap();
    let mut contact = ContactSystem::new(&model, dofs.n_free - dofs.n_lambda).unwrap();
    contact.set_curvature_limit(f64::INFINITY);
    let mut u = vec![0.0; dofs.n_primary()];
    for &(label, d) in &case.disp {
        let Some(n) = model.nodes.iter().position(|x| x.label == label) else {
            continue;
        };
        for k in 0..3 {
            if let Some(c) = dofs.code(n, k as u8 + 1) {
                u[c] = d[k];
            }
        }
    }
    for i in dofs.n_free - dofs.n_lambda..dofs.n_free {
        u[i] = case.lambda;
    }
    let (contribs, states) = contact.evaluate(&model, &dofs, &u).unwrap();
    let n_active = states.iter().filter(|s| s.active).count();
    assert_eq!(
        n_active, case.active,
        "{}: active contact nodes ({states:?})",
        case.name
    );
    let h = 1e-6;
    let mut checked = 0;
    for (k, c) in contribs.iter().enumerate() {
        if c.fe.is_empty() {
            continue;
        }
        let m = c.codes.len();
        let scale = c.ke.iter().fold(1e-12f64, |a, v| a.max(v.abs()));
        for j in 0..m {
            let code = c.codes[j];
            assert!(code < dofs.n_primary(), "plain DOFs in these cases");
            let (mut up, mut um) = (u.clone(), u.clone());
            up[code] += h;
            um[code] -= h;
            let fp = &contact
                .evaluate_with(&model, &dofs, &up, Some(&states))
                .unwrap()
                .0[k];
            let fm = &contact
                .evaluate_with(&model, &dofs, &um, Some(&states))
                .unwrap()
                .0[k];
            for i in 0..m {
                let fd = (fp.fe[i] - fm.fe[i]) / (2.0 * h);
                let err = (fd - c.ke[i * m + j]).abs() / scale;
                assert!(
                    err < 1e-6,
                    "{}: K[{i}][{j}] = {} but dr/du = {fd} (relative error {err:e})",
                    case.name,
                    c.ke[i * m + j]
                );
            }
        }
        checked += 1;
    }
    assert!(checked > 0, "{}: no contribution checked", case.name);
}

/// Two quads: the lower one's top edge (element 1, edge 3) is the master segment; node 5 of the
/// upper one is the contact node.
fn two_quads(
    kind: &str,
    nlgeo: u8,
    segment: &str,
    condition: &str,
    extra_nodes: &str,
    nextra: usize,
) -> String {
    let (e1, n1) = if kind == "q8" {
        ("QPlaneStress2d 1 nodes 8 3 4 1 2 9 10 11 12", 12)
    } else {
        ("Quad1PlaneStrain 1 nodes 4 3 4 1 2", 8)
    };
    let q8 = if kind == "q8" {
        "node 9 coords 2 0.5 1.02\nnode 10 coords 2 0 0.5\nnode 11 coords 2 0.5 0\nnode 12 coords 2 1 0.5\n"
    } else {
        ""
    };
    format!(
        "fd.out\nfd\nNonLinearStatic nsteps 1 controlmode 1\ndomain {}\nOutputManager\n\
         ndofman {} nelem 2 ncrosssect 1 nmat 1 nbc 1 nic 0 nltf 1 nset 3 ncontactseg 1\n\
         node 1 coords 2 0 0\nnode 2 coords 2 1 0\nnode 3 coords 2 1 1\nnode 4 coords 2 0 1\n\
         node 5 coords 2 0.3 1.05\nnode 6 coords 2 1.3 1.05\nnode 7 coords 2 1.3 2.05\nnode 8 coords 2 0.3 2.05\n{q8}{extra_nodes}\
         {e1} nlgeo {nlgeo}\nQuad1PlaneStrain 2 nodes 4 5 6 7 8\n{segment}\n\
         SimpleCS 1 thick 1 material 1 set 1\nIsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n{condition}\n\
         ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 elementboundaries 2 1 1\nSet 3 nodes 1 5\n",
        if kind == "q8" { "2dPlaneStress" } else { "PlaneStrain" },
        n1 + nextra
    )
}

const EDGE: &str = "linear2delementedgecontactsegment 1 edgeset 2";
const PEN: &str = "n2spenaltycontact 1 loadTimeFunction 1 penalty 1000 nodeset 1 5 segmentset 1 1";
const LM: &str = "n2slagrangianmultipliercontact 1 loadTimeFunction 1 nodeset 1 5 segmentset 1 1";

fn edge_disp() -> Vec<(usize, [f64; 3])> {
    vec![
        (5, [0.04, -0.11, 0.0]),
        (3, [0.02, -0.01, 0.0]),
        (4, [-0.01, 0.03, 0.0]),
        (9, [0.01, 0.015, 0.0]),
    ]
}

#[test]
fn n2s_penalty_tangent_is_jacobian_of_residual_on_straight_edges() {
    for nlgeo in [0, 1] {
        check(&Case {
            name: "edge-pen",
            text: two_quads("q4", nlgeo, EDGE, PEN, "", 0),
            disp: edge_disp(),
            lambda: 0.0,
            active: 1,
        });
    }
}

#[test]
fn n2s_penalty_tangent_is_jacobian_of_residual_on_quadratic_edges() {
    for nlgeo in [0, 1] {
        check(&Case {
            name: "q8-pen",
            text: two_quads("q8", nlgeo, EDGE, PEN, "", 0),
            disp: edge_disp(),
            lambda: 0.0,
            active: 1,
        });
    }
}

#[test]
fn n2s_multiplier_tangent_is_jacobian_of_residual_active_and_inactive() {
    for kind in ["q4", "q8"] {
        for nlgeo in [0, 1] {
            let text = two_quads(kind, nlgeo, EDGE, LM, "", 0);
            check(&Case {
                name: "edge-lm",
                text: text.clone(),
                disp: edge_disp(),
                lambda: 7.0,
                active: 1,
            });
            // Separated and without force: inactive, the row enforces λ = 0.
            check(&Case {
                name: "edge-lm-off",
                text,
                disp: vec![],
                lambda: 0.0,
                active: 0,
            });
        }
    }
}

#[test]
fn n2n_tangents_are_jacobians_of_residuals() {
    for cond in [
        "n2npenaltycontact 1 loadTimeFunction 1 penalty 1000 masterset 4 slaveset 3",
        "n2nlagrangianmultipliercontact 1 loadTimeFunction 1 masterset 4 slaveset 3",
        "n2npenaltycontact 1 loadTimeFunction 1 penalty 1000 masterset 4 slaveset 3 normal 2 0.1 1",
    ] {
        let text =
            two_quads("q4", 0, EDGE, cond, "", 0).replace("nset 3", "nset 4") + "Set 4 nodes 1 4\n";
        let text = text
            .replace("ncontactseg 1", "ncontactseg 0")
            .replace(&format!("{EDGE}\n"), "");
        check(&Case {
            name: "n2n",
            text,
            disp: vec![(5, [-0.3, -0.2, 0.0]), (4, [0.01, 0.02, 0.0])],
            lambda: 3.0,
            active: 1,
        });
    }
}

#[test]
fn rigid_segment_tangents_are_jacobians_of_residuals() {
    let cases = [
        (
            "circle",
            "circlecontactsegment 1 centerpoint 2 0.3 2.0 radius 0.9",
            "",
        ),
        (
            "circle-node",
            "circlecontactsegment 1 centerpoint 2 0.3 2.0 radius 0.9 node 13",
            "node 13 coords 2 0.3 2.0\n",
        ),
        (
            "poly",
            "polynomialcontactsegment 1 coeffs 3 0.4 -0.1 1.0",
            "",
        ),
        (
            "plane-node",
            "planecontactsegment 1 point 2 0 1.0 normal 2 0.2 1 node 13",
            "node 13 coords 2 5 5\n",
        ),
    ];
    for (name, seg, extra) in cases {
        for cond in [PEN, LM] {
            let nextra = usize::from(!extra.is_empty());
            let text = two_quads("q4", 0, seg, cond, extra, nextra)
                .replace("ndofman 8", &format!("ndofman {}", 8 + nextra));
            let mut disp = vec![(5, [0.05, -0.12, 0.0])];
            if nextra == 1 {
                disp.push((13, [0.01, 0.03, 0.0]));
            }
            // Circles: the node starts outside the disk (centre (0.3, 2), radius 0.9) and moves in.
            if name.starts_with("circle") {
                disp[0].1 = [0.05, 0.12, 0.0];
            }
            check(&Case {
                name,
                text,
                disp,
                lambda: 5.0,
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
    let text = brick_input(
        1,
        1,
        "0.4 0.5 2.5",
        "circlecontactsegment 1 centerpoint 3 0.4 0.5 2.5 radius 1.6 node 9\n\
         SimpleCS 1 material 1 set 1\nIsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n\
         n2spenaltycontact 1 loadTimeFunction 1 penalty 1000 nodeset 2 2 3 segmentset 1 1\n\
         ConstantFunction 1 f(t) 1\nSet 1 allelements\n",
    );
    let disp = vec![
        (2, [0.02, 0.01, 0.1]),
        (3, [-0.01, 0.0, 0.08]),
        (9, [0.0, 0.02, -0.03]),
    ];
    check(&Case {
        name: "sphere",
        text,
        disp,
        lambda: 0.0,
        active: 2,
    });
}

/// Port of the spec's finite-difference check (spec §2.9, fd_check_n2s_tangent.py): edge
/// x1 = (1, 1.02), x2 = (0, 0.98), node xs = (0.7, 0.95), p = 1, deformed normal. hertz's jet
/// tangent equals Wriggers' consistent form K = p NvNvᵀ + (p g/l)(Bv Tvᵀ + Tv Bvᵀ) − (p g²/l²) Bv Bvᵀ
/// and differs from OOFEM's (mixed term with the wrong sign) by the published 0.116.
#[test]
fn n2s_penalty_tangent_matches_the_consistent_closed_form_of_the_spec() {
    use hertz::contact::jet::Jet;
    use hertz::contact::kinematics::gap_line;
    let q0 = [0.7, 0.95, 1.0, 1.02, 0.0, 0.98];
    let q: Vec<Jet> = q0
        .iter()
        .enumerate()
        .map(|(i, &v)| Jet::variable(v, i, 6))
        .collect();
    let g = gap_line(&[q[0], q[1]], &[q[2], q[3]], &[q[4], q[5]], 1.0);
    let p = 1.0;
    // hertz residual r = p g ∇g (internal force) and tangent K = p(∇g∇gᵀ + g∇²g).
    let k_hertz = |i: usize, j: usize| p * (g.g[i] * g.g[j] + g.v * g.h[i][j]);
    // Closed forms of the spec.
    let (xs, x1, x2) = ([q0[0], q0[1]], [q0[2], q0[3]], [q0[4], q0[5]]);
    let t = [x2[0] - x1[0], x2[1] - x1[1]];
    let l = (t[0] * t[0] + t[1] * t[1]).sqrt();
    let e = [t[0] / l, t[1] / l];
    let n = [t[1] / l, -t[0] / l];
    let xi = 2.0 * (e[0] * (xs[0] - x1[0]) + e[1] * (xs[1] - x1[1])) / l - 1.0;
    let (n1, n2) = ((1.0 - xi) / 2.0, (1.0 + xi) / 2.0);
    let gap = (xs[0] - x1[0]) * n[0] + (xs[1] - x1[1]) * n[1];
    assert!((gap - g.v).abs() < 1e-15, "gap {gap} vs {}", g.v);
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

/// Node-to-node contact in 3D (a brick node against a free node above it), penalty and multiplier.
#[test]
fn n2n_tangents_in_3d_are_jacobians_of_residuals() {
    for cond in [
        "n2npenaltycontact 1 loadTimeFunction 1 penalty 1000 masterset 2 slaveset 3",
        "n2nlagrangianmultipliercontact 1 loadTimeFunction 1 masterset 2 slaveset 3",
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
            name: "n2n-3d",
            text,
            disp,
            lambda: 2.0,
            active: 1,
        });
    }
}
