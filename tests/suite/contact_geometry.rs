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

/// A 2D plane-strain model from element corner lists (quadrilaterals in counter-clockwise order,
/// triangles too), the master segment the edges `edges` ((element, edge) pairs), the contact
/// node the first node of the last element; `condition` is a node-to-segment record with
/// `NODE` for that node.
fn polygons(
    elements: &[&[[f64; 2]]],
    edges: &[(usize, usize)],
    condition: &str,
) -> (String, usize) {
    let mut nodes = Vec::new();
    let mut records = Vec::new();
    for (e, corners) in elements.iter().enumerate() {
        let first = nodes.len() + 1;
        for c in corners.iter() {
            nodes.push(format!(
                "node {} coords 2 {} {}",
                nodes.len() + 1,
                c[0],
                c[1]
            ));
        }
        let list: Vec<String> = (first..first + corners.len())
            .map(|n| n.to_string())
            .collect();
        let kind = if corners.len() == 3 {
            "TrPlaneStrain"
        } else {
            "Quad1PlaneStrain"
        };
        records.push(format!(
            "{kind} {} nodes {} {}",
            e + 1,
            corners.len(),
            list.join(" ")
        ));
    }
    let slave = nodes.len() - elements.last().unwrap().len() + 1;
    let list: Vec<String> = edges.iter().map(|(e, b)| format!("{e} {b}")).collect();
    let text = format!(
        "x.out\nx\nNonLinearStatic nsteps 1 controlmode 1\ndomain PlaneStrain\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 1 nic 0 nltf 1 nset 2 ncontactseg 1\n{}\n{}\n\
         linear2delementedgecontactsegment 1 edgeset 2\nSimpleCS 1 thick 1 material 1 set 1\n\
         IsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n{}\nConstantFunction 1 f(t) 1\nSet 1 allelements\n\
         Set 2 elementboundaries {} {}\n",
        nodes.len(),
        records.len(),
        nodes.join("\n"),
        records.join("\n"),
        condition.replace("NODE", &slave.to_string()),
        2 * edges.len(),
        list.join(" ")
    );
    (text, slave)
}

/// A master block whose right side leans out (a trapezoid, 2 wide at its base, its top edge the
/// master from x = 0 to 1) and a small slave triangle above. A node moved into the block past the
/// top edge's open end, beyond its ramp, has no partner: it has crossed the master where nothing
/// measures it, and its state says so (element 1); in the open beside the block it has not.
/// Penalty and multipliers alike.
#[test]
fn a_node_inside_the_master_body_past_its_open_end_is_found_crossed() {
    let block: &[[f64; 2]] = &[[0.0, 0.0], [2.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let slave: &[[f64; 2]] = &[[0.8, 1.2], [0.9, 1.6], [0.7, 1.6]];
    for condition in [PEN, common::LM] {
        let (text, node) = polygons(&[block, slave], &[(1, 3)], condition);
        let p = Probe::new(&text);
        let crossed = |at: [f64; 2]| {
            let (_, states) = p.force(&p.at(&[(node, at)]), Search::Fresh);
            states[0].clone()
        };
        let inside = crossed([1.4, 0.3]);
        let c = inside
            .crossed
            .unwrap_or_else(|| panic!("{condition}: {inside:?}"));
        assert_eq!(p.model.elements[c.element].label, 1, "{condition}");
        // Its depth: the distance to the top edge's line segment, from (1.4, 0.3) to (1, 1).
        let depth = (0.4f64 * 0.4 + 0.7 * 0.7).sqrt();
        assert!(
            (c.depth - depth).abs() < 1e-12,
            "{condition}: {} vs {depth}",
            c.depth
        );
        assert!(
            !inside.active && inside.force == 0.0,
            "{condition}: {inside:?}"
        );
        let message = hertz::contact::crossing_message(&p.model, &[inside]).unwrap();
        assert!(
            message.contains(&format!(
                "node {node} of contact condition 1 lies 8.062e-1 inside element 1"
            )),
            "{message}"
        );
        // Beside the block, past its leaning side: open, not crossed.
        let beside = crossed([1.6, 0.5]);
        assert!(beside.crossed.is_none(), "{condition}: {beside:?}");
        // Pressed into the top edge: held by it, not crossed.
        let held = crossed([0.5, 0.9]);
        assert!(
            held.active && held.crossed.is_none(),
            "{condition}: {held:?}"
        );
    }
}

/// Two master bodies side by side: a plate A (its top edge y = 0, x ∈ [0, 2]) and a wall B to
/// its right whose left face (x = 2, y ∈ [−1, −0.1]) faces A. A node inside A 0.3 below its top
/// and 0.2 from B's face is nearer to B's face, on its open side (gap +0.2), than to the top it
/// crossed (−0.3): the nearest partner would leave it open inside A. It is held by A's top.
#[test]
fn a_node_inside_a_master_body_is_held_by_the_surface_it_crossed_not_the_nearest() {
    let plate: &[[f64; 2]] = &[[0.0, -1.0], [2.0, -1.0], [2.0, 0.0], [0.0, 0.0]];
    let wall: &[[f64; 2]] = &[[2.0, -1.0], [3.0, -1.0], [3.0, -0.1], [2.0, -0.1]];
    let slave: &[[f64; 2]] = &[[1.8, 0.2], [2.2, 0.6], [1.4, 0.6]];
    for condition in [PEN, common::LM] {
        // Plate edge 3 (its top, (2, 0) to (0, 0)), wall edge 4 (its left face).
        let (text, node) = polygons(&[plate, wall, slave], &[(1, 3), (2, 4)], condition);
        let p = Probe::new(&text);
        let (f, states) = p.force(&p.at(&[(node, [1.8, -0.3])]), Search::Fresh);
        let s = &states[0];
        assert_eq!(s.partner, Partner::Edge(0), "{condition}: {s:?}");
        assert!((s.gap + 0.3).abs() < 1e-12, "{condition}: gap {}", s.gap);
        assert!(s.crossed.is_none(), "{condition}: {s:?}");
        if condition == PEN {
            // The penalty pushes it up, out through the top: 1000 × 0.3 (an internal force of
            // the node, so −300 along y).
            assert!(
                s.active && (f[1] + 300.0).abs() < 1e-9 && f[0].abs() < 1e-9,
                "{f:?}"
            );
        }
        // Just above the plate, near the wall: the nearest partner, the top, open.
        let (_, states) = p.force(&p.at(&[(node, [1.9, 0.05])]), Search::Fresh);
        assert_eq!(states[0].partner, Partner::Edge(0));
        assert!(
            !states[0].active && states[0].crossed.is_none(),
            "{:?}",
            states[0]
        );
    }
}

/// The 3D twin of the leaning block: a brick whose +x side leans out (its top face, the master,
/// [0, 1]², its base [0, 2] × [0, 1]) and a slave tetrahedron above. A node moved into the brick
/// past the top face's open edge is crossed (element 1); beside the brick it is not; pressed
/// into the top face it is held.
#[test]
fn a_node_inside_a_master_brick_past_its_open_edge_is_found_crossed() {
    let brick = [
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
        [1.0, 1.0, 1.0],
        [1.0, 0.0, 1.0],
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
    ];
    let tet = [
        [0.5, 0.5, 1.2],
        [0.5, 0.9, 1.6],
        [0.9, 0.5, 1.6],
        [0.5, 0.5, 1.7],
    ];
    let nodes: Vec<String> = brick
        .iter()
        .chain(&tet)
        .enumerate()
        .map(|(k, c)| format!("node {} coords 3 {} {} {}", k + 1, c[0], c[1], c[2]))
        .collect();
    for condition in [PEN, common::LM] {
        let text = format!(
            "x.out\nx\nNonLinearStatic nsteps 1 controlmode 1\ndomain 3d\nOutputManager\n\
             ndofman 12 nelem 2 ncrosssect 1 nmat 1 nbc 1 nic 0 nltf 1 nset 2 ncontactseg 1\n{}\n\
             LSpace 1 nodes 8 1 2 3 4 5 6 7 8\nLTRSpace 2 nodes 4 9 10 11 12\n\
             linear3delementsurfacecontactsegment 1 boundaryset 2\n\
             SimpleCS 1 thick 1 material 1 set 1\nIsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n{}\n\
             ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 elementboundaries 2 1 1\n",
            nodes.join("\n"),
            condition.replace("NODE", "9")
        );
        let p = Probe::new(&text);
        let state = |at: [f64; 3]| p.force3(&p.at3(&[(9, at)]), 0).1;
        let inside = state([1.4, 0.5, 0.3]);
        let c = inside
            .crossed
            .unwrap_or_else(|| panic!("{condition}: {inside:?}"));
        assert_eq!(p.model.elements[c.element].label, 1, "{condition}");
        assert!(
            (c.depth - 0.7).abs() < 1e-12,
            "{condition}: depth {}",
            c.depth
        );
        assert!(!inside.active, "{condition}: {inside:?}");
        let beside = state([1.6, 0.5, 0.5]);
        assert!(beside.crossed.is_none(), "{condition}: {beside:?}");
        let held = state([0.5, 0.5, 0.9]);
        assert!(
            held.active && held.crossed.is_none(),
            "{condition}: {held:?}"
        );
    }
}

/// A slave block pressed down past the end of the master's top edge into its leaning side (the
/// leaning block above, held at its base): no contact force can hold the node there, so the
/// analysis stops with the reason (it used to converge with the node inside, reported open)
/// after the substeps up to the crossing converged.
#[test]
fn an_analysis_stops_where_a_node_crosses_its_master_unheld() {
    let block: &[[f64; 2]] = &[[0.0, 0.0], [2.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let slave: &[[f64; 2]] = &[[1.3, 1.1], [1.7, 1.1], [1.7, 1.5], [1.3, 1.5]];
    for condition in [PEN, common::LM] {
        let (text, _) = polygons(&[block, slave], &[(1, 3)], condition);
        // Base held, the slave block's top moved down by 0.6 (its node 5 from y = 1.1 to 0.5,
        // inside the block from y = 0.7 on).
        let text = text
            .replace("nbc 1 ", "nbc 3 ")
            .replace("nset 2 ", "nset 4 ")
            .replace(
                "ConstantFunction 1",
                "BoundaryCondition 2 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 3\n\
                 BoundaryCondition 3 loadTimeFunction 1 dofs 2 1 2 values 2 0 -0.6 set 4\n\
                 ConstantFunction 1",
            )
            + "Set 3 nodes 2 1 2\nSet 4 nodes 2 7 8\n";
        let model = common::model_from_text(&text).unwrap();
        let err = hertz::solve::run_analysis(&model, &common::quiet(), |_| Ok(())).unwrap_err();
        let msg = err.to_string();
        assert_eq!(err.exit_code(), 3, "{msg}");
        assert!(
            msg.contains("node 5 of contact condition 1 lies")
                && msg.contains("inside element 1 with no contact force")
                && msg.contains("crossed the master surface"),
            "{condition}: {msg}"
        );
    }
}

/// A node may be in two conditions against different masters: a block pushed into the corner
/// of a rigid floor and wall, its corner node a contact node of both (the floor's condition
/// with the bottom nodes, the wall's with the left ones). Each condition carries its whole
/// share: the floor the load's y component, the wall its x component (to the Newton
/// tolerance), penalty and multipliers.
#[test]
fn a_corner_node_against_a_floor_and_a_wall_is_held_by_both() {
    for law in ["n2spenaltycontact", "n2slagrangianmultipliercontact"] {
        let penalty = if law == "n2spenaltycontact" {
            " penalty 1e5"
        } else {
            ""
        };
        let text = format!(
            "c.out\ncorner\nNonLinearStatic nsteps 1 controlmode 1 rtolf 1e-10\n\
             domain PlaneStrain\nOutputManager\n\
             ndofman 9 nelem 4 ncrosssect 1 nmat 1 nbc 3 nic 0 nltf 1 nset 2 ncontactseg 2\n\
             node 1 coords 2 0 0\nnode 2 coords 2 0.5 0\nnode 3 coords 2 1 0\n\
             node 4 coords 2 0 0.5\nnode 5 coords 2 0.5 0.5\nnode 6 coords 2 1 0.5\n\
             node 7 coords 2 0 1\nnode 8 coords 2 0.5 1\nnode 9 coords 2 1 1\n\
             Quad1PlaneStrain 1 nodes 4 1 2 5 4\nQuad1PlaneStrain 2 nodes 4 2 3 6 5\n\
             Quad1PlaneStrain 3 nodes 4 4 5 8 7\nQuad1PlaneStrain 4 nodes 4 5 6 9 8\n\
             planecontactsegment 1 point 2 0 0 normal 2 0 1\n\
             planecontactsegment 2 point 2 0 0 normal 2 1 0\n\
             SimpleCS 1 thick 1 material 1 set 1\nIsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n\
             NodalLoad 1 loadTimeFunction 1 dofs 2 1 2 Components 2 -1 -2 set 2\n\
             {law} 2 loadTimeFunction 1{penalty} nodeset 3 1 2 3 segmentset 1 1\n\
             {law} 3 loadTimeFunction 1{penalty} nodeset 3 1 4 7 segmentset 1 2\n\
             ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 nodes 1 9\n",
        );
        let model = common::model_from_text(&text).unwrap_or_else(|e| panic!("{law}: {e}"));
        let (states, _) = common::solve_model(&model);
        let by = |c: usize| -> f64 {
            states
                .iter()
                .filter(|s| s.condition == c)
                .map(|s| s.force)
                .sum()
        };
        assert!((by(2) - 2.0).abs() < 1e-8, "{law}: floor {}", by(2));
        assert!((by(3) - 1.0).abs() < 1e-8, "{law}: wall {}", by(3));
        let corner: Vec<f64> = states
            .iter()
            .filter(|s| s.node == 0)
            .map(|s| s.force)
            .collect();
        assert_eq!(corner.len(), 2, "{law}");
        assert!(corner.iter().all(|&f| f > 0.0), "{law}: {corner:?}");
    }
}
