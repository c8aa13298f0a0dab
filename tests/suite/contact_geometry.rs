//! Contact geometry at vertices and ends, and the geometric-tangent safeguard as used in
//! production:
//! * a node sliding across a vertex of a kinked master at fixed depth sees its force turn
//!   continuously (smoothed normals), in small and large deformation;
//! * a node on a vertex keeps one partner while round-off moves it back and forth (hysteresis);
//! * past the open end of a master the force falls continuously from its full value (node on the
//!   end, its tributary length behind it) to zero (its whole tributary length past the end),
//!   and the node then has no partner;
//! * deep inside a curved rigid master (a pressure above E) the assembled tangent is the exact one
//!   without its geometric part; at any reachable state it is exact.

use crate::common;

use common::{face_input, label_of_slave, strip, PEN};
use hertz::assembly::DofMap;
use hertz::contact::{ContactSystem, Partner, Search, SlotState};
use hertz::model::Model;
use hertz_bench::mesh::Solid;

struct Probe {
    model: Model,
    dofs: DofMap,
    contact: ContactSystem,
}

impl Probe {
    fn new(text: &str) -> Probe {
        let model = common::model_from_text(text).unwrap();
        let contact = ContactSystem::new(&model).unwrap();
        let dofs = DofMap::new(&model, &contact.extra_dofs()).unwrap();
        Probe {
            model,
            dofs,
            contact,
        }
    }

    /// Displacement vector moving the listed nodes (by label) to absolute positions.
    fn at(&self, positions: &[(usize, [f64; 2])]) -> Vec<f64> {
        let mut u = vec![0.0; self.dofs.n_primary()];
        for &(label, p) in positions {
            let n = self
                .model
                .nodes
                .iter()
                .position(|x| x.label == label)
                .unwrap();
            for d in 0..2 {
                u[self.dofs.code(n, d as u8 + 1).unwrap()] = p[d] - self.model.nodes[n].coords[d];
            }
        }
        u
    }

    /// Displacement vector moving the listed nodes (by label) to absolute 3D positions.
    fn at3(&self, positions: &[(usize, [f64; 3])]) -> Vec<f64> {
        let mut u = vec![0.0; self.dofs.n_primary()];
        for &(label, p) in positions {
            let n = self
                .model
                .nodes
                .iter()
                .position(|x| x.label == label)
                .unwrap();
            for d in 0..3 {
                u[self.dofs.code(n, d as u8 + 1).unwrap()] = p[d] - self.model.nodes[n].coords[d];
            }
        }
        u
    }

    /// Force on contact node `slot` (3 components, 3D) and its state.
    fn force3(&self, u: &[f64], slot: usize) -> ([f64; 3], SlotState) {
        let (points, states) = self
            .contact
            .evaluate(
                &hertz::assembly::NodalState::new(&self.model, &self.dofs, u),
                Search::Fresh,
            )
            .unwrap();
        let c = points[slot].contribution();
        let f = if c.fe.is_empty() {
            [0.0; 3]
        } else {
            [c.fe[0], c.fe[1], c.fe[2]]
        };
        (f, states[slot].clone())
    }

    /// Force on the first contact node (2 components) and the states.
    fn force(&self, u: &[f64], search: Search) -> ([f64; 2], Vec<SlotState>) {
        let (points, states) = self
            .contact
            .evaluate(
                &hertz::assembly::NodalState::new(&self.model, &self.dofs, u),
                search,
            )
            .unwrap();
        let c = points[0].contribution();
        let f = if c.fe.is_empty() {
            [0.0, 0.0]
        } else {
            [c.fe[0], c.fe[1]]
        };
        (f, states)
    }
}

/// Height of the wavy top of `strip` (vertices at integer x) at x, on the polygon.
fn top(x: f64) -> f64 {
    let y = |i: f64| 1.0 + 0.03 * (i * 1.7).sin();
    let i = x.floor().clamp(0.0, 2.0);
    let t = x - i;
    (1.0 - t) * y(i) + t * y(i + 1.0)
}

#[test]
fn force_turns_continuously_as_a_node_slides_across_a_vertex() {
    for nlgeo in [0u8, 1] {
        let text = strip("q4", nlgeo, 3, (1.0, 1.1), None, PEN);
        let probe = Probe::new(&text);
        let s = label_of_slave(&text);
        let n = 401;
        let samples: Vec<([f64; 2], SlotState)> = (0..n)
            .map(|k| {
                let x = 0.9 + 0.2 * k as f64 / (n - 1) as f64;
                let u = probe.at(&[(s, [x, top(x) - 0.01])]);
                let (f, st) = probe.force(&u, Search::Fresh);
                (f, st[0].clone())
            })
            .collect();
        // The vertex is a kink of 0.06 rad: the force direction sweeps through it, without a jump.
        let jumps: Vec<f64> = samples
            .windows(2)
            .map(|w| ((w[1].0[0] - w[0].0[0]).powi(2) + (w[1].0[1] - w[0].0[1]).powi(2)).sqrt())
            .collect();
        let fmag = (samples[0].0[0].powi(2) + samples[0].0[1].powi(2)).sqrt();
        let worst = jumps.iter().fold(0.0f64, |m, v| m.max(*v));
        assert!(fmag > 1.0, "nlgeo {nlgeo}: force {fmag}");
        assert!(
            worst < 0.02 * fmag,
            "nlgeo {nlgeo}: largest change between neighbouring samples {worst} (force {fmag})"
        );
        // A node under the vertex, along its normal (the average of the two edges' normals),
        // is pushed along that normal.
        let normal = |x0: f64, x1: f64| {
            let (dx, dy) = (x1 - x0, top(x1) - top(x0));
            let l = (dx * dx + dy * dy).sqrt();
            [-dy / l, dx / l]
        };
        let (nl, nr) = (normal(0.0, 1.0), normal(1.0, 2.0));
        let avg = [nl[0] + nr[0], nl[1] + nr[1]];
        let l = avg[0].hypot(avg[1]);
        let under = [1.0 - 0.01 * avg[0] / l, top(1.0) - 0.01 * avg[1] / l];
        let (fv, _) = probe.force(&probe.at(&[(s, under)]), Search::Fresh);
        let fvn = (fv[0] * fv[0] + fv[1] * fv[1]).sqrt();
        let cross = (fv[0] * avg[1] - fv[1] * avg[0]) / (fvn * (avg[0].hypot(avg[1])));
        assert!(
            cross.abs() < 1e-9,
            "nlgeo {nlgeo}: force {fv:?} not along {avg:?}"
        );
        // Both edges are used.
        let partners: std::collections::BTreeSet<String> = samples
            .iter()
            .map(|(_, s)| format!("{:?}", s.partner))
            .collect();
        assert_eq!(partners.len(), 2, "{partners:?}");
    }
}

#[test]
fn a_node_on_a_vertex_keeps_its_partner_while_round_off_moves_it() {
    let text = strip("q4", 0, 3, (1.0, 1.1), None, PEN);
    let probe = Probe::new(&text);
    let s = label_of_slave(&text);
    let y = top(1.0) - 0.01;
    let (f0, st0) = probe.force(&probe.at(&[(s, [1.0, y])]), Search::Fresh);
    let first = st0[0].partner;
    assert!(matches!(first, Partner::Edge(_)));
    let mut prev = st0;
    for k in 0..20 {
        let dx = if k % 2 == 0 { 1e-12 } else { -1e-12 };
        let (f, st) = probe.force(&probe.at(&[(s, [1.0 + dx, y])]), Search::Hint(&prev));
        assert_eq!(
            st[0].partner, first,
            "the partner alternated at iteration {k}"
        );
        assert!((f[0] - f0[0]).abs() + (f[1] - f0[1]).abs() < 1e-6 * f0[1].abs());
        prev = st;
    }
}

#[test]
fn force_falls_continuously_to_zero_past_the_open_end_of_the_master() {
    // Two contact nodes 0.6 apart on the slave's bottom; the right one (s + 1) has its tributary
    // length 0.3 behind it. The master (two elements) ends at x = 2.
    let text = strip("q4", 0, 2, (1.4, 1.0), None, PEN);
    let s = label_of_slave(&text);
    let text = text.replace(
        &format!("nodeset 1 {s}"),
        &format!("nodeset 2 {} {s}", s + 1),
    );
    let probe = Probe::new(&text);
    let p = 1000.0;
    let depth = 0.01;
    // The end edge's line, continued past the end.
    let end_line = |x: f64| top(1.0) + (top(2.0) - top(1.0)) * (x - 1.0);
    let n = 301;
    let mut forces = Vec::new();
    for k in 0..n {
        let d = -0.2 + 0.6 * k as f64 / (n - 1) as f64;
        let x = 2.0 + d;
        let u = probe.at(&[
            (s + 1, [x, end_line(x) - depth]),
            (s, [x - 0.6, end_line(x - 0.6) - depth]),
        ]);
        let (points, states) = probe
            .contact
            .evaluate(
                &hertz::assembly::NodalState::new(&probe.model, &probe.dofs, &u),
                Search::Fresh,
            )
            .unwrap();
        let _ = points;
        forces.push((d, states[0].force, states[0].partner));
    }
    let full = p * depth / (1.0 + (top(2.0) - top(1.0)).powi(2)).sqrt();
    for &(d, f, partner) in &forces {
        if d <= 0.0 {
            assert!(
                (f - full).abs() < 1e-3 * full,
                "d = {d}: force {f}, full {full}"
            );
        } else if d >= 0.3 {
            assert_eq!(f, 0.0, "d = {d}");
            assert_eq!(partner, Partner::None, "d = {d}: no partner past the ramp");
        } else {
            assert!(f > 0.0 && f < full * (1.0 + 1e-9), "d = {d}: {f}");
        }
    }
    // Monotone and without jumps.
    for w in forces.windows(2) {
        assert!(w[1].1 <= w[0].1 + 1e-9 * full, "{w:?}");
        assert!((w[1].1 - w[0].1).abs() < 0.02 * full, "jump {w:?}");
    }
}

#[test]
fn geometric_tangent_is_dropped_only_beyond_a_pressure_of_e() {
    // A node pressed into a rigid circle (radius 0.9) by `depth`, E = 100, penalty 1000 × 10.
    let seg = "circlecontactsegment 1 centerpoint 2 0.3 0.2 radius 0.9";
    let law = "n2spenaltycontact 1 loadTimeFunction 1 penalty 1e4 nodeset 1 NODE segmentset 1 1";
    let text = strip("q4", 0, 1, (0.3, 1.05), Some(seg), law);
    let s = label_of_slave(&text);
    let probe = Probe::new(&text);
    let mut exact = ContactSystem::new(&probe.model).unwrap();
    exact.set_pressure_limit(f64::INFINITY);
    // The isolated node stands for an area of a tenth of the model size (0.24 here): pressure E
    // is a force of 24, i.e. a penetration of 2.4e-3.
    for (depth, dropped) in [(1e-3, false), (0.05, true)] {
        let u = probe.at(&[(s, [0.3, 0.2 + 0.9 - depth])]);
        let prod = probe
            .contact
            .evaluate(
                &hertz::assembly::NodalState::new(&probe.model, &probe.dofs, &u),
                Search::Fresh,
            )
            .unwrap()
            .0[0]
            .clone();
        let full = exact
            .evaluate(
                &hertz::assembly::NodalState::new(&probe.model, &probe.dofs, &u),
                Search::Fresh,
            )
            .unwrap()
            .0[0]
            .clone();
        let (kp, kx, fe) = (
            prod.contribution().ke,
            full.contribution().ke,
            prod.contribution().fe,
        );
        let m = prod.codes.len();
        let g = prod.gap;
        let mut diff = 0.0f64;
        let mut material = 0.0f64;
        for i in 0..m {
            for j in 0..m {
                diff = diff.max((kp[i * m + j] - kx[i * m + j]).abs());
                // Material part p·v⊗∇g = fe_i ∇g_j / g.
                material = material.max((kp[i * m + j] - fe[i] * prod.gap_grad[j] / g).abs());
            }
        }
        let scale = kx.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if dropped {
            assert!(diff > 1e-3 * scale, "depth {depth}: geometric part present");
            assert!(
                material < 1e-9 * scale,
                "depth {depth}: production tangent is the material part"
            );
        } else {
            assert!(
                diff < 1e-12 * scale,
                "depth {depth}: production tangent exact ({diff:e})"
            );
        }
    }
}

/// A node sliding at a fixed depth under the wavy faces of `common::face_input` (hexahedra,
/// tetrahedra, wedges; small and large deformation), straight over the corner where faces meet
/// and obliquely across face edges: its force changes by less than 2 % of itself between
/// neighbouring samples (no jump where the partner changes), and it meets several faces.
#[test]
fn force_is_continuous_as_a_node_slides_over_face_edges_and_corners() {
    let pen = "n2spenaltycontact 1 loadTimeFunction 1 penalty 1000";
    let wavy = |x: f64, y: f64| 1.0 + 0.05 * (1.3 * x + 0.7 * y).sin();
    for (kind, sym) in [
        (Solid::Hex, 0),
        (Solid::Hex, 45),
        (Solid::Tet, 0),
        (Solid::Wedge, 13),
    ] {
        for nlgeo in [0u8, 1] {
            let (text, label) = face_input(kind, sym, nlgeo, [0.3, 0.4, 1.1], pen);
            let probe = Probe::new(&text);
            for (from, to) in [([0.3, 0.3], [1.7, 1.7]), ([0.3, 0.4], [1.7, 1.6])] {
                let n = 701;
                let samples: Vec<([f64; 3], SlotState)> = (0..n)
                    .map(|k| {
                        let t = k as f64 / (n - 1) as f64;
                        let x = from[0] + t * (to[0] - from[0]);
                        let y = from[1] + t * (to[1] - from[1]);
                        let u = probe.at3(&[(label, [x, y, wavy(x, y) - 0.05])]);
                        probe.force3(&u, 4)
                    })
                    .collect();
                let norm = |f: &[f64; 3]| (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
                let smallest = samples
                    .iter()
                    .map(|s| norm(&s.0))
                    .fold(f64::INFINITY, f64::min);
                let worst = samples
                    .windows(2)
                    .map(|w| {
                        norm(&[
                            w[1].0[0] - w[0].0[0],
                            w[1].0[1] - w[0].0[1],
                            w[1].0[2] - w[0].0[2],
                        ])
                    })
                    .fold(0.0f64, f64::max);
                let name = format!("{kind:?} sym {sym} nlgeo {nlgeo} from {from:?}");
                assert!(smallest > 20.0, "{name}: force {smallest}");
                assert!(
                    worst < 0.02 * smallest,
                    "{name}: jump {worst} (force {smallest})"
                );
                let partners: std::collections::BTreeSet<String> = samples
                    .iter()
                    .map(|(_, s)| format!("{:?}", s.partner))
                    .collect();
                assert!(partners.len() >= 2, "{name}: {partners:?}");
                assert!(!partners.contains("None"), "{name}: {partners:?}");
            }
        }
    }
}
