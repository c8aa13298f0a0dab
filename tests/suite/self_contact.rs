//! Self-contact: a surface that is both slave and master of one node-to-segment or mortar
//! condition. Symmetry makes the exact check: a ring crushed between two rigid plates until its
//! bore closes, as a whole model whose bore is in self-contact, equals its upper half whose bore
//! meets a rigid plane on the symmetry line, step by step, plate force and contact forces
//! (plane strain, a hollow torus in axisymmetry and a 3D slab of bricks; neo-Hookean, also
//! nearly incompressible; large deformation, multipliers; mortar with a penalty and friction
//! too, in 2D and 3D). A block whose whole boundary is a self-contact surface (sharp corners,
//! opposite faces facing each other through the body) is compressed as without it, and a
//! wedge's sharp convex tip pairs with nothing of its own surface. The merged constraint of a
//! repeated pair has the Jacobian of its residual as tangent.

use crate::common;

use hertz::assembly::NodalState;
use hertz::contact::{ContactSystem, Search};

/// A ring (bore 0.6, outside 1.0; `nt` elements round, `nr` through the wall) crushed by two
/// rigid plates that each travel `crush` over `steps` steps, neo-Hookean (E = 1000, ν = 0.3),
/// `nlgeo 1`, plane strain. 3D (`tz` > 0): `layers` layers of bricks (at least one) each `tz`
/// thick, u_z = 0 on the face z = 0. Nearly incompressible with `kg` = K/G (on barred
/// quadrilaterals). Axisymmetric (`axis`): the ring's section centred at x = `axis` (a hollow
/// torus, `L4Axisymm`); in 3D the tube merely centred there.
#[derive(Clone, Copy, Default)]
struct Ring {
    tz: f64,
    layers: usize,
    nt: usize,
    nr: usize,
    crush: f64,
    steps: usize,
    kg: Option<f64>,
    axis: Option<f64>,
    /// The bore a mortar condition (multipliers; `penalty`: a penalty) rather than
    /// node-to-segment.
    mortar: bool,
    penalty: Option<f64>,
    /// The lower half's nodes moved round by up to this fraction of a spacing (whole model):
    /// the walls' nodes do not match.
    skew: f64,
    /// Coulomb friction on the whole model's bore (a symmetric fold's walls do not slide on
    /// each other: the frictionless half model's answer).
    friction: Option<f64>,
}

impl Ring {
    /// Whole (`full`): the bore a self-contact condition (`slaveset` of its own edges' nodes),
    /// x held at the top and bottom of the outside. Half: the upper half, u_y = 0 on the cut,
    /// the bore against a rigid plane at y = 0. Node labels: layer i (0 the bore), angle j, then
    /// the next z layer; the plates' nodes last.
    fn text(&self, full: bool) -> String {
        ring(full, *self)
    }
}

fn ring(full: bool, r: Ring) -> String {
    let Ring {
        tz,
        layers: brick_layers,
        nt,
        nr,
        crush,
        steps,
        kg,
        axis,
        mortar,
        penalty,
        skew,
        friction,
    } = r;
    let x0 = axis.unwrap_or(0.0);
    let (ri, ro) = (0.6, 1.0);
    let d3 = tz > 0.0;
    let axisymmetric = axis.is_some();
    let jn = if full { nt } else { nt / 2 + 1 };
    let ne = if full { nt } else { nt / 2 };
    let per_layer = (nr + 1) * jn;
    let id =
        |i: usize, j: usize, z: usize| 1 + i * jn + if full { j % nt } else { j } + z * per_layer;
    // Node layers along z, and element layers (one in 2D).
    let layers = if d3 { brick_layers.max(1) + 1 } else { 1 };
    let element_layers = layers.max(2) - 1;
    let nn = per_layer * layers;
    let (p, q) = (nn + 1, nn + 2);
    let mut nodes = String::new();
    for z in 0..layers {
        for i in 0..=nr {
            let r = ri + (ro - ri) * i as f64 / nr as f64;
            for j in 0..jn {
                let step = 2.0 * std::f64::consts::PI / nt as f64;
                let mut th = step * j as f64;
                if full && j > nt / 2 {
                    let s = std::f64::consts::PI * (j - nt / 2) as f64 / (nt / 2) as f64;
                    th += skew * step * s.sin();
                }
                let c = [x0 + r * th.cos(), r * th.sin(), tz * z as f64];
                nodes += &if d3 {
                    format!("node {} coords 3 {} {} {}\n", id(i, j, z), c[0], c[1], c[2])
                } else {
                    format!("node {} coords 2 {} {}\n", id(i, j, z), c[0], c[1])
                };
            }
        }
    }
    let xyz = |x: f64, y: f64| {
        if d3 {
            format!("3 {x} {y} 0")
        } else {
            format!("2 {x} {y}")
        }
    };
    nodes += &format!(
        "node {p} coords {}\nnode {q} coords {}\n",
        xyz(x0, ro),
        xyz(x0, -ro)
    );
    let mut elements = String::new();
    for layer in 0..element_layers {
        for (i, j) in (0..nr).flat_map(|i| (0..ne).map(move |j| (i, j))) {
            let quad = |z| {
                [
                    id(i, j, z),
                    id(i + 1, j, z),
                    id(i + 1, j + 1, z),
                    id(i, j + 1, z),
                ]
            };
            let k = 1 + layer * nr * ne + i * ne + j;
            elements += &if d3 {
                let n: Vec<String> = quad(layer)
                    .iter()
                    .chain(&quad(layer + 1))
                    .map(|n| n.to_string())
                    .collect();
                format!(
                    "LSpace {k} nodes 8 {} crossSect 1 mat 1 nlgeo 1\n",
                    n.join(" ")
                )
            } else {
                let n: Vec<String> = quad(0).iter().map(|n| n.to_string()).collect();
                format!(
                    "{} {k} nodes 4 {} crossSect 1 mat 1 nlgeo 1\n",
                    match (axisymmetric, kg) {
                        (true, _) => "L4Axisymm",
                        (false, Some(_)) => "Quad1PlaneStrainBB",
                        (false, None) => "Quad1PlaneStrain",
                    },
                    n.join(" ")
                )
            };
        }
    }
    let list = |v: &[usize]| format!("{} {}", v.len(), labels(v));
    let all_z = |f: &dyn Fn(usize) -> Vec<usize>| (0..layers).flat_map(f).collect::<Vec<_>>();
    let bore_faces: Vec<usize> = (0..element_layers)
        .flat_map(|l| (1..=ne).map(move |k| l * nr * ne + k))
        .flat_map(|k| [k, if d3 { 6 } else { 4 }])
        .collect();
    let outer = all_z(&|z| (0..jn).map(|j| id(nr, j, z)).collect());
    let bore = all_z(&|z| {
        let js: Vec<usize> = if full {
            (0..jn).collect()
        } else {
            (1..jn - 1).collect()
        };
        js.into_iter().map(|j| id(0, j, z)).collect()
    });
    let d = crush * ro;
    let dofs = |v: f64| {
        if d3 {
            format!("dofs 3 1 2 3 values 3 0 {v} 0")
        } else {
            format!("dofs 2 1 2 values 2 0 {v}")
        }
    };
    let mut records = vec![
        format!("BoundaryCondition 1 loadTimeFunction 2 {} set 2", dofs(-d)),
        "BoundaryCondition 2 loadTimeFunction 1 dofs 1 1 values 1 0 set 4".to_string(),
    ];
    let (plates, self_segments, sets) = if full {
        records.push(format!(
            "BoundaryCondition 3 loadTimeFunction 2 {} set 3",
            dofs(d)
        ));
        let held = all_z(&|z| vec![id(nr, nt / 4, z), id(nr, 3 * nt / 4, z)]);
        (
            "2 2 3",
            "1 1",
            format!("Set 3 nodes 1 {q}\nSet 4 nodes {}\n", list(&held)),
        )
    } else {
        let cut = all_z(&|z| {
            (0..=nr)
                .flat_map(|i| [id(i, 0, z), id(i, jn - 1, z)])
                .collect()
        });
        records
            .push("BoundaryCondition 3 loadTimeFunction 1 dofs 1 2 values 1 0 set 3".to_string());
        let held = all_z(&|z| vec![id(nr, nt / 4, z)]);
        (
            "1 2",
            "1 3",
            format!("Set 3 nodes {}\nSet 4 nodes {}\n", list(&cut), list(&held)),
        )
    };
    records.push(format!(
        "n2slagrangianmultipliercontact 4 loadTimeFunction 1 slaveset 5 segmentset {plates}"
    ));
    // The half model's gap to its plane is half the walls' overlap: twice the penalty.
    let mut law = penalty.map_or(String::new(), |p| {
        format!(" penalty {}", if full { p } else { 2.0 * p })
    });
    if let (Some(mu), true) = (friction, full) {
        law += &format!(" friction {mu}");
    }
    records.push(match (mortar, penalty) {
        (false, None) => format!(
            "n2slagrangianmultipliercontact 5 loadTimeFunction 1{law} slaveset 6 segmentset \
             {self_segments}"
        ),
        (false, Some(_)) => format!(
            "n2spenaltycontact 5 loadTimeFunction 1{law} slaveset 6 segmentset {self_segments}"
        ),
        (true, None) => format!(
            "s2slagrangianmultipliercontact 5 loadTimeFunction 1{law} slavesegment 1 segmentset \
             {self_segments}"
        ),
        (true, Some(_)) => format!(
            "s2spenaltycontact 5 loadTimeFunction 1{law} slavesegment 1 segmentset \
             {self_segments}"
        ),
    });
    let mut sets = format!(
        "Set 1 elementboundaries {}\nSet 2 nodes 1 {p}\n{sets}Set 5 nodes {}\nSet 6 nodes {}\n",
        list(&bore_faces),
        list(&outer),
        list(&bore)
    );
    if d3 {
        records.push("BoundaryCondition 6 loadTimeFunction 1 dofs 1 3 values 1 0 set 7".into());
        sets += &format!(
            "Set 7 nodes {}\n",
            list(&(1..=per_layer).collect::<Vec<_>>())
        );
    }
    let segments = if full {
        format!(
            "planecontactsegment 2 point {} normal {} node {p}\nplanecontactsegment 3 point {} normal {} node {q}\n",
            xyz(x0, ro), xyz(0.0, -1.0), xyz(x0, -ro), xyz(0.0, 1.0)
        )
    } else {
        format!(
            "planecontactsegment 2 point {} normal {} node {p}\nplanecontactsegment 3 point {} normal {}\n",
            xyz(x0, ro), xyz(0.0, -1.0), xyz(x0, 0.0), xyz(0.0, 1.0)
        )
    };
    let (e, nu) = (1000.0, 0.3);
    let g = e / (2.0 * (1.0 + nu));
    let k = kg.map_or(e / (3.0 * (1.0 - 2.0 * nu)), |r| r * g);
    format!(
        "ring.out\nring\nNonLinearStatic nsteps {steps} controlmode 1 rtolf 1e-10 maxiter 30\n\
         domain {}\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc {} nic 0 nltf 2 nset {} ncontactseg 3\n\
         {nodes}{elements}linear{}contactsegment 1 edgeset 1\n{segments}SimpleCS 1 thick 1.0\n\
         mooneyrivlincompressiblemat 1 d 0 c1 {} c2 0 k {k}\n{}\n\
         ConstantFunction 1 f(t) 1.0\nPiecewiseLinFunction 2 npoints 2 t 2 0 {steps} f(t) 2 0 1\n{sets}",
        match (d3, axisymmetric) {
            (true, _) => "3d",
            (false, true) => "2dPlaneStress",
            (false, false) => "PlaneStrain",
        },
        nn + 2,
        nr * ne * element_layers,
        records.len(),
        if d3 { 7 } else { 6 },
        if d3 { "3delementsurface" } else { "2delementedge" },
        g / 2.0,
        records.join("\n"),
    )
}

/// Node labels separated by spaces.
fn labels(v: &[usize]) -> String {
    v.iter()
        .map(|n| n.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

/// What a crushed ring does in one step.
#[derive(Debug, Clone, Copy)]
struct Step {
    /// The top plate's force.
    plate: f64,
    iterations: usize,
    /// Of the bore's contact nodes (condition 5) not held in y (the half model's cut): the
    /// smallest gap, how many are active and the sum of the contact forces they report.
    gap: f64,
    active: usize,
    bore_force: f64,
}

/// Every step of the model `text`.
fn crush(text: &str) -> Vec<Step> {
    let model = common::model_from_text(text).unwrap();
    let top = model.nodes.len() - 2;
    let mut out = Vec::new();
    hertz::solve::run_analysis(&model, &common::quiet(), |r| {
        let plate = (r.dofs.prescribed.iter().zip(r.reactions))
            .filter(|((n, d, _), _)| *n == top && *d == 2)
            .map(|(_, f)| f)
            .sum();
        let bore = r.contact.iter().filter(|s| s.condition == 5);
        let held = |n: usize| r.dofs.prescribed.iter().any(|p| p.0 == n && p.1 == 2);
        let gap = bore
            .clone()
            .filter(|s| !held(s.node))
            .map(|s| s.gap)
            .filter(|g| g.is_finite())
            .fold(f64::INFINITY, f64::min);
        // Not the half model's cut nodes (held on its plane by their u_y = 0, their contact
        // force is its round-off).
        out.push(Step {
            plate,
            iterations: r.info.iterations,
            gap,
            active: bore.clone().filter(|s| s.active && !held(s.node)).count(),
            bore_force: bore.filter(|s| !held(s.node)).map(|s| s.force).sum(),
        });
        Ok(())
    })
    .unwrap();
    out
}

/// Every step of the whole `ring` with its bore node-to-segment self-contact, and with it mortar.
fn bore_both_ways(ring: Ring) -> (Vec<Step>, Vec<Step>) {
    let mortar = Ring {
        mortar: true,
        ..ring
    };
    (crush(&ring.text(true)), crush(&mortar.text(true)))
}

/// The plate force of `run` (named `what`) equals the half model's at every step, to 1e-9.
fn same_plate_force(what: &str, run: &[Step], half: &[Step]) {
    plate_forces_agree((what, run), ("half", half), 1e-9);
}

/// The plate force of `run` equals `reference`'s at every step, within `tol` of it.
fn plate_forces_agree((what, run): (&str, &[Step]), (name, reference): (&str, &[Step]), tol: f64) {
    assert_eq!(run.len(), reference.len());
    for (k, (w, h)) in run.iter().zip(reference).enumerate() {
        assert!(
            (w.plate - h.plate).abs() <= tol * h.plate.abs().max(1e-9),
            "step {k}: plate force {} {what}, {} {name}",
            w.plate,
            h.plate
        );
    }
}

/// The whole ring with its bore in self-contact against its half on the symmetry plane: the
/// plate force and the bore's contact forces equal to round-off at every step (the bore closes
/// over the last third), no bore node ever inside the opposite wall, no more Newton iterations
/// than the half model's.
fn check_against_half(ring: Ring) {
    let whole = crush(&ring.text(true));
    let half = crush(&ring.text(false));
    same_plate_force("whole", &whole, &half);
    let size = 1.0;
    for (k, (w, h)) in whole.iter().zip(&half).enumerate() {
        // A penalty's walls overlap by twice the half model's penetration of its plane.
        let overlap = match ring.penalty {
            Some(_) => 2.0 * h.gap.min(0.0),
            None => 0.0,
        };
        assert!(
            w.gap > overlap * (1.0 + 1e-9) - 1e-12 * size,
            "step {k}: a bore node {} inside the other wall (half: {})",
            w.gap,
            h.gap
        );
        assert!(
            w.iterations <= h.iterations.max(5),
            "step {k}: {} iterations (half: {})",
            w.iterations,
            h.iterations
        );
        // Each wall carries what the half model's bore carries on its plane: the contact
        // forces both walls report are twice the half's.
        assert!(
            (w.bore_force - 2.0 * h.bore_force).abs() <= 1e-9 * h.plate.abs().max(1e-9),
            "step {k}: bore contact forces {} whole, {} half",
            w.bore_force,
            h.bore_force
        );
    }
    let last = whole.last().unwrap();
    let closed = half.last().unwrap().active;
    assert!(
        closed > 4,
        "the bore closes: {closed} nodes on the symmetry plane"
    );
    // Each node of the half model's closed bore meets its mirror image in the whole one.
    assert_eq!(last.active, 2 * closed, "active bore nodes, whole model");
}

/// With friction (μ = 0.3) too: a symmetric fold's walls do not slide on each other, so each is
/// the frictionless half model. A repeated pair's friction acts on its mean relative slip
/// (before, a pair with friction was not merged and one of its constraints was dropped: the ring
/// came out 6e-6 off its half model). That slip cancels to round-off (1e-17) on a symmetric fold:
/// taken as a slip, a pair closing with no force yet was pushed along its noise and the walls
/// slid apart (157 iterations at one step); it sticks.
#[test]
fn a_crushed_ring_and_torus_with_their_bore_in_self_contact_equal_their_half_models() {
    let plane = Ring {
        nt: 32,
        nr: 2,
        crush: 0.8,
        steps: 24,
        ..Ring::default()
    };
    // The same section as a hollow torus about an axis 3 away.
    let torus = Ring {
        axis: Some(3.0),
        ..plane
    };
    for ring in [plane, torus] {
        check_against_half(ring);
        check_against_half(Ring {
            friction: Some(0.3),
            ..ring
        });
    }
}

/// Mortar self-contact: the bore one `s2s...` condition whose slave segment is its own master.
/// Each wall is a slave against the other, the rays bisecting the two walls' normals, and the
/// matched pairs of the two walls hold one constraint: the whole ring equals its half model
/// (mortar against the rigid plane) to round-off, in plane strain, with multipliers and a
/// penalty (the half model's twice as stiff: its gap is half the overlap), and with friction
/// (μ = 0.3: the walls of a symmetric fold do not slide on each other, so the frictionless half
/// model's answer; a pair's friction acts on its mean relative slip).
#[test]
fn a_ring_with_its_bore_in_mortar_self_contact_equals_its_half_model() {
    let plane = Ring {
        nt: 32,
        nr: 2,
        crush: 0.8,
        steps: 24,
        mortar: true,
        ..Ring::default()
    };
    check_against_half(plane);
    check_against_half(Ring {
        penalty: Some(1e5),
        ..plane
    });
    check_against_half(Ring {
        friction: Some(0.3),
        ..plane
    });
    // A hollow torus (axisymmetric), whole and half, against node-to-segment's whole torus
    // (which equals its own half model): on matched walls both hold each pair of nodes
    // together, and the plate forces agree to 1e-9 (seen: to the bit). The half model's mortar
    // slave reaches its plane, where the nodes held on it do not constrain anything (it
    // chattered on them: their force is along their held motion, and the dual basis leaves a
    // round-off share on their neighbours). Its bore forces are not compared: in axisymmetry
    // the merged pairs' shares are biorthogonal in the reference configuration only.
    let torus = Ring {
        axis: Some(3.0),
        ..plane
    };
    let n2s = crush(&torus.text(true));
    let mortar = Ring {
        mortar: true,
        ..torus
    };
    for (what, run) in [
        ("whole", crush(&mortar.text(true))),
        ("half", crush(&mortar.text(false))),
    ] {
        for (k, (m, n)) in run.iter().zip(&n2s).enumerate() {
            assert!(
                (m.plate - n.plate).abs() <= 1e-9 * n.plate.abs().max(1e-9)
                    && m.iterations <= n.iterations.max(5),
                "torus {what}, step {k}: mortar {m:?}, node-to-segment {n:?}"
            );
        }
    }
}

/// Mortar self-contact on walls whose nodes do not match (the lower half's nodes moved round by
/// up to 0.3 of a spacing), multipliers, crushed to 80 %: every step converges without a cut,
/// in 2–4 iterations but the last two (at most 15; seen 6 and 13), and the plate
/// force follows node-to-segment self-contact's on the same mesh within 0.5 % (the two
/// discretize the contact differently). Pairs of nodes within half a spacing hold one
/// constraint; with node-to-segment's quarter the step to 97 % failed. With friction (μ = 0.3)
/// every step converges without a cut in at most 8 iterations (seen 2–4 but one 8), the plate
/// force within 1 % of the frictionless one (seen 0.5 %): the pairs merge with their friction
/// on the mean relative slip. Before, a pair with friction dropped one of its constraints and
/// the crush stopped at step 28 of 33 (no convergence after 5 halvings, chattering).
#[test]
fn mortar_self_contact_on_walls_whose_nodes_do_not_match_follows_node_to_segment() {
    let ring = Ring {
        nt: 48,
        nr: 3,
        crush: 0.8,
        steps: 33,
        skew: 0.3,
        ..Ring::default()
    };
    let (n2s, mortar) = bore_both_ways(ring);
    let iterations: Vec<usize> = mortar.iter().map(|s| s.iterations).collect();
    let (early, late) = iterations.split_at(iterations.len() - 2);
    assert!(
        early.iter().all(|&i| i <= 4) && late.iter().all(|&i| i <= 15),
        "{iterations:?}"
    );
    plate_forces_agree(("mortar", &mortar), ("node-to-segment", &n2s), 5e-3);
    let rubbing = crush(
        &Ring {
            mortar: true,
            friction: Some(0.3),
            ..ring
        }
        .text(true),
    );
    let its: Vec<usize> = rubbing.iter().map(|s| s.iterations).collect();
    assert!(its.iter().all(|&i| i <= 8), "with friction: {its:?}");
    plate_forces_agree(("with friction", &rubbing), ("without", &mortar), 1e-2);
}

/// Nearly incompressible rubber (K = 1000 G, barred quadrilaterals) crushed to 80 %: the crease
/// at each side of the bore folds shut, the nodes beside its tip meeting the edge across it.
#[test]
fn a_nearly_incompressible_ring_crushed_shut_equals_its_half_model() {
    check_against_half(Ring {
        nt: 48,
        nr: 3,
        crush: 0.8,
        steps: 40,
        kg: Some(1000.0),
        ..Ring::default()
    });
}

#[test]
fn a_crushed_tube_of_bricks_with_its_bore_in_self_contact_equals_its_half_model() {
    check_against_half(Ring {
        tz: 0.2,
        nt: 24,
        nr: 2,
        crush: 0.8,
        steps: 20,
        ..Ring::default()
    });
}

/// The tube of bricks with its bore a mortar condition against itself: each own face a slave
/// against the faces of the other wall, cut along the rays that bisect the two walls' nodal
/// normals (`mortar::mirror`), the matched pairs of nodes one constraint. The whole tube equals
/// its half model (mortar against the rigid plane) to round-off, with multipliers, a penalty
/// (the half model's twice as stiff) and friction (μ = 0.3: the frictionless half model). The
/// half model's faces take their dual basis on the current face in large deformation as the
/// whole one's do over their overlaps (with the reference face's, the two differed by up to 8e-4
/// in the plate force); cut along the slave's normal, or some of a face's own partners along the
/// rays and some along its normal (a crease's two sides then covered a face twice), they did
/// not meet (the penalty's first closing step inverted elements and was cut in four).
#[test]
fn a_crushed_tube_of_bricks_with_its_bore_in_mortar_self_contact_equals_its_half_model() {
    let tube = Ring {
        tz: 0.2,
        nt: 24,
        nr: 2,
        crush: 0.8,
        steps: 20,
        mortar: true,
        ..Ring::default()
    };
    check_against_half(tube);
    check_against_half(Ring {
        penalty: Some(1e5),
        ..tube
    });
    check_against_half(Ring {
        friction: Some(0.3),
        ..tube
    });
}

/// A tube of three brick layers (24 × 2 × 3, crushed to 80 % in 10 steps), its bore in mortar
/// self-contact, equals its half model at every step: along the tube the bore's crease is a
/// line of tip nodes whose nodal normals all point along the fold. Before, a tip's face met the
/// tip faces of other layers along rays m − n of two such normals (round-off: slivers of far
/// faces, gaps of −0.7), and the last step stopped with inverted elements after five halvings;
/// and the Newton that carries a master corner onto the slave face stalled at round-off near a
/// corner and refused whole pairs by turns (14 iterations at one step of a 48 × 3 × 4 tube).
///
/// The same tube 1 000 from the origin (10⁴ of its elements' size) as well: the mirror rays'
/// round-off grew with the distance, and a crease tip's strips along an edge it shares with
/// the other wall's faces, supports of 1e-23 of a face, closed on their noise (13 iterations
/// and a residual of 1e16 at one step; 8 with the rays mended alone); a slot's support below
/// 1e-9 of its full support is none now.
#[test]
fn a_tube_of_several_brick_layers_closes_its_bore_to_the_crease_tips_in_mortar_self_contact() {
    let tube = Ring {
        tz: 0.1,
        layers: 3,
        nt: 24,
        nr: 2,
        crush: 0.8,
        steps: 10,
        mortar: true,
        ..Ring::default()
    };
    check_against_half(tube);
    // `axis` moves a 3D ring's centre along x (its elements stay bricks).
    check_against_half(Ring {
        axis: Some(1000.0),
        ..tube
    });
}

/// Mortar self-contact in 3D on walls whose nodes do not match (the lower half's nodes moved
/// round by up to 0.3 of a spacing; 32 × 2 bricks round, crushed to 80 %, frictionless): every
/// step converges without a cut in at most 5 iterations (seen 3–5), the plate force follows
/// node-to-segment self-contact's on the same mesh within 0.5 % (seen 0.26 %), and no bore node
/// lies deeper than 5 % of its spacing behind the other wall (seen 4.4 %: a merged pair holds its
/// mean gap, each node to second order in the offset).
#[test]
fn mortar_self_contact_in_3d_on_walls_whose_nodes_do_not_match_follows_node_to_segment() {
    let tube = Ring {
        tz: 0.2,
        nt: 32,
        nr: 2,
        crush: 0.8,
        steps: 24,
        skew: 0.3,
        ..Ring::default()
    };
    let (n2s, mortar) = bore_both_ways(tube);
    let iterations: Vec<usize> = mortar.iter().map(|s| s.iterations).collect();
    assert!(iterations.iter().all(|&i| i <= 5), "{iterations:?}");
    plate_forces_agree(("mortar", &mortar), ("node-to-segment", &n2s), 5e-3);
    let spacing = 2.0 * std::f64::consts::PI * 0.6 / 32.0;
    let deepest = mortar.iter().map(|s| s.gap).fold(f64::INFINITY, f64::min);
    assert!(
        deepest > -0.05 * spacing,
        "a bore node {deepest} behind the other wall"
    );
    assert!(mortar.last().unwrap().active > 40, "the bore closes");
}

/// A flat block (1 × 0.2, 5 × 1 elements), its whole boundary one self-contact surface (a
/// node-to-segment condition, and a mortar one), compressed by 10 % between its bottom (held in y) and top (moved down; x held at one node):
/// top and bottom face each other through the body (a top node lies 0.2 behind the bottom face,
/// facing it, within the search's reach), and beside each corner the neighbouring face is the
/// surface's next. No node may pair: the uniform compression is exact (σ_y = E/(1 − ν²)·ε_y in
/// plane strain with σ_x = 0).
#[test]
fn a_block_whose_boundary_is_one_self_contact_surface_is_compressed_without_contact() {
    let (nx, ny, height) = (5, 1, 0.2);
    let id = |i: usize, j: usize| 1 + j * (nx + 1) + i;
    let mut nodes = String::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let (x, y) = (i as f64 / nx as f64, height * j as f64 / ny as f64);
            nodes += &format!("node {} coords 2 {x} {y}\n", id(i, j));
        }
    }
    let mut elements = String::new();
    let mut boundary = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let k = 1 + j * nx + i;
            elements += &format!(
                "Quad1PlaneStrain {k} nodes 4 {} {} {} {} crossSect 1 mat 1\n",
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j + 1)
            );
            for (side, on) in [(1, j == 0), (2, i == nx - 1), (3, j == ny - 1), (4, i == 0)] {
                if on {
                    boundary.push(format!("{k} {side}"));
                }
            }
        }
    }
    let ring: Vec<usize> = (0..=nx)
        .flat_map(|i| (0..=ny).map(move |j| (i, j)))
        .filter(|&(i, j)| i == 0 || j == 0 || i == nx || j == ny)
        .map(|(i, j)| id(i, j))
        .collect();
    let bottom: Vec<usize> = (0..=nx).map(|i| id(i, 0)).collect();
    let top: Vec<usize> = (0..=nx).map(|i| id(i, ny)).collect();
    let mut text = String::new();
    text += &format!(
        "block.out\nblock\nNonLinearStatic nsteps 1 controlmode 1 rtolf 1e-10\ndomain PlaneStrain\n\
         OutputManager\nndofman {} nelem {} ncrosssect 1 nmat 1 nbc 4 nic 0 nltf 1 nset 5 ncontactseg 1\n\
         {nodes}{elements}linear2delementedgecontactsegment 1 edgeset 1\nSimpleCS 1 thick 1.0\n\
         IsoLE 1 d 0 E 1000 n 0.3 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 2 values 1 0 set 2\n\
         BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 {} set 3\n\
         BoundaryCondition 3 loadTimeFunction 1 dofs 1 1 values 1 0 set 4\n\
         CONDITION\n\
         ConstantFunction 1 f(t) 1.0\n\
         Set 1 elementboundaries {} {}\nSet 2 nodes {} {}\nSet 3 nodes {} {}\nSet 4 nodes 1 {}\n\
         Set 5 nodes {} {}\n",
        (nx + 1) * (ny + 1),
        nx * ny,
        -0.1 * height,
        2 * boundary.len(),
        boundary.join(" "),
        bottom.len(),
        labels(&bottom),
        top.len(),
        labels(&top),
        id(0, 0),
        ring.len(),
        labels(&ring),
    );
    for condition in [
        "n2slagrangianmultipliercontact 4 loadTimeFunction 1 slaveset 5 segmentset 1 1",
        "s2slagrangianmultipliercontact 4 loadTimeFunction 1 slavesegment 1 segmentset 1 1",
    ] {
        let model = common::model_from_text(&text.replace("CONDITION", condition)).unwrap();
        let mut checked = false;
        hertz::solve::run_analysis(&model, &common::quiet(), |r| {
            assert!(
                r.contact.iter().all(|s| !s.active && s.force == 0.0),
                "{condition}: {:?}",
                r.contact
            );
            let force: f64 = (r.dofs.prescribed.iter().zip(r.reactions))
                .filter(|((node, d, _), _)| *d == 2 && model.nodes[*node].coords[1] == height)
                .map(|(_, f)| f)
                .sum();
            let exact = -1000.0 / (1.0 - 0.09) * 0.1;
            assert!(
                (force - exact).abs() < 1e-9 * exact.abs(),
                "{condition}: force {force}, exact {exact}"
            );
            checked = true;
            Ok(())
        })
        .unwrap();
        assert!(checked);
    }
}

/// The merged constraint of a repeated pair (the two walls of a ring's bore pressed onto each
/// other, node onto mirror node, offsets of 1 % of a spacing along and across the walls) has the
/// Jacobian of its residual as tangent, over the displacements and the multipliers, in 2D and 3D
/// node-to-segment and mortar (in 3D along the mirror rays, whose nodal normals move with the
/// faces around them), frictionless and with friction (sliding, the slips from the anchors of a
/// state with a smaller shift).
#[test]
fn a_repeated_self_contact_pair_has_the_jacobian_of_its_residual_as_tangent() {
    for (tz, mortar, friction) in [
        (0.0, false, None),
        (0.2, false, None),
        (0.0, true, None),
        (0.0, false, Some(0.3)),
        (0.2, false, Some(0.3)),
        (0.0, true, Some(0.3)),
        (0.2, true, None),
        (0.2, true, Some(0.3)),
    ] {
        // In 3D the slab's faces z = 0 free (u_z held at the plate's node instead), so that the
        // upper wall can be shifted off the lower one in z as well: mortar's segments of two
        // walls whose edges coincide have a kink there (a master's edge projects inside or
        // outside the slave's as either tilts), which differences cannot take.
        let text = Ring {
            tz,
            nt: 16,
            nr: 1,
            crush: 0.5,
            steps: 1,
            mortar,
            friction,
            ..Ring::default()
        }
        .text(true)
        .replace("dofs 1 3 values 1 0 set 7", "dofs 1 3 values 1 0 set 2");
        let model = common::model_from_text(&text).unwrap();
        let mut contact = ContactSystem::new(&model).unwrap();
        let dofs = hertz::solve::number_dofs(&model).unwrap();
        contact.set_pressure_limit(f64::INFINITY);
        let mut u = vec![0.0; dofs.n_primary()];
        // Flatten the bore onto y = 0 where |x| < 0.4, the upper wall a hair below its mirror
        // image and shifted along it.
        for (n, node) in model.nodes.iter().enumerate() {
            let [x, y, _] = node.coords;
            if x.abs() < 0.4 && (x * x + y * y).sqrt() < 0.61 {
                let shift = if y > 0.0 {
                    [0.0015, -y - 0.0008, 0.003]
                } else {
                    [0.0, -y, 0.0]
                };
                for (k, v) in shift.iter().enumerate() {
                    if let Some(c) = dofs.code(n, k as u8 + 1) {
                        u[c] = *v;
                    }
                }
            }
        }
        for v in &mut u[dofs.n_free - dofs.n_lambda..dofs.n_free] {
            *v = 50.0;
        }
        // With friction, the slips from the anchors of a state with the upper wall's shift
        // along it a fifth smaller.
        let history = friction.map(|_| {
            let mut before = u.clone();
            for (n, node) in model.nodes.iter().enumerate() {
                let [x, y, _] = node.coords;
                if x.abs() < 0.4 && y > 0.0 && (x * x + y * y).sqrt() < 0.61 {
                    if let Some(c) = dofs.code(n, 1) {
                        before[c] -= 0.0003;
                    }
                }
            }
            let nodes = NodalState::new(&model, &dofs, &before);
            contact.evaluate(&nodes, Search::Fresh).unwrap().1
        });
        let (points, states) = contact
            .evaluate_with_history(
                &NodalState::new(&model, &dofs, &u),
                Search::Fresh,
                history.as_deref(),
            )
            .unwrap();
        let merged = states.iter().filter(|s| s.repeated).count();
        assert!(
            merged >= 2,
            "tz {tz} mortar {mortar}: {merged} merged pairs"
        );
        let rubbing = (states.iter())
            .filter(|s| s.repeated && s.active && s.friction.is_some())
            .count();
        assert!(
            friction.is_none() || rubbing >= 2,
            "tz {tz}: {rubbing} merged pairs' nodes with friction"
        );
        let at = |u: &[f64]| {
            let p = contact
                .evaluate_with_history(
                    &NodalState::new(&model, &dofs, u),
                    Search::Frozen(&states),
                    history.as_deref(),
                )
                .unwrap()
                .0;
            p.iter().map(|p| p.contribution().fe).collect::<Vec<_>>()
        };
        let h = 1e-7;
        let mut worst = 0.0f64;
        let mut checked = 0;
        for (k, p) in points.iter().enumerate() {
            let c = p.contribution();
            // With friction the merged pairs alone: a lone node on the held face z = 0 projects
            // onto the edge of its master face, where its friction along z moves nothing free
            // and is held at zero (`law::multiplier`), a switch any perturbation crosses.
            if c.fe.is_empty() || !states[k].active || (friction.is_some() && !states[k].repeated) {
                continue;
            }
            checked += 1;
            let m = c.codes.len();
            let scale = c.ke.iter().fold(1e-12f64, |a, v| a.max(v.abs()));
            for j in 0..m {
                if c.codes[j] >= dofs.n_free {
                    continue;
                }
                let mut up = u.clone();
                let mut um = u.clone();
                up[c.codes[j]] += h;
                um[c.codes[j]] -= h;
                let (fp, fm) = (at(&up), at(&um));
                for i in 0..m {
                    let fd = (fp[k][i] - fm[k][i]) / (2.0 * h);
                    worst = worst.max((fd - c.ke[i * m + j]).abs() / scale);
                }
            }
        }
        assert!(
            checked >= 2,
            "tz {tz} mortar {mortar}: {checked} active points"
        );
        assert!(
            worst < 1e-6,
            "tz {tz} mortar {mortar}: tangent off by {worst:e}"
        );
        println!("tz {tz} mortar {mortar}: {checked} active points, tangent within {worst:.1e}");
    }
}

/// A wedge of half-angle 15° (triangles), its slanted faces one self-contact surface, clamped at
/// its base and bent by its tip (large deformation). Beside the tip the next face faces a node
/// at 150° from behind (the node lies behind its plane): a sharp convex fold, where no node may
/// pair with its own neighbourhood or with the far face behind it. The tip's reaction equals
/// the run without the condition to the Newton tolerance, and no node is ever in contact.
#[test]
fn a_node_on_a_sharp_convex_fold_pairs_with_nothing_of_its_own_surface() {
    let (length, n) = (1.0, 8);
    let half = (15.0f64).to_radians().tan() * length;
    let id = |i: usize, k: usize| if i == n { 3 * n + 1 } else { 1 + 3 * i + k };
    let mut nodes = String::new();
    for i in 0..n {
        let x = length * i as f64 / n as f64;
        let w = half * (1.0 - i as f64 / n as f64);
        for (k, y) in [-w, 0.0, w].into_iter().enumerate() {
            nodes += &format!("node {} coords 2 {x} {y}\n", id(i, k));
        }
    }
    nodes += &format!("node {} coords 2 {length} 0\n", id(n, 0));
    let mut tri = Vec::new();
    for i in 0..n - 1 {
        for k in 0..2 {
            tri.push([id(i, k), id(i + 1, k), id(i + 1, k + 1)]);
            tri.push([id(i, k), id(i + 1, k + 1), id(i, k + 1)]);
        }
    }
    tri.push([id(n - 1, 0), id(n, 0), id(n - 1, 1)]);
    tri.push([id(n - 1, 1), id(n, 0), id(n - 1, 2)]);
    let elements: String = (tri.iter().enumerate())
        .map(|(e, t)| {
            format!(
                "TrPlaneStrain {} nodes 3 {} {} {} crossSect 1 mat 1 nlgeo 1\n",
                e + 1,
                t[0],
                t[1],
                t[2]
            )
        })
        .collect();
    // The slanted faces: the bottom edges (first side of the lower triangles) and the top ones.
    let mut edges = Vec::new();
    for (e, t) in tri.iter().enumerate() {
        for (side, (a, b)) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
            .into_iter()
            .enumerate()
        {
            let on = |m: usize, k: usize| (m == id(n, 0)) || (m - 1) % 3 == k && m != id(0, k);
            let bottom = (on(a, 0) || a == id(0, 0)) && (on(b, 0) || b == id(0, 0));
            let top = (on(a, 2) || a == id(0, 2)) && (on(b, 2) || b == id(0, 2));
            if (bottom || top) && a != b {
                edges.push(format!("{} {}", e + 1, side + 1));
            }
        }
    }
    let surface: Vec<usize> = (1..n)
        .flat_map(|i| [id(i, 0), id(i, 2)])
        .chain([id(n, 0)])
        .collect();
    let base = [id(0, 0), id(0, 1), id(0, 2)];
    // The surface as a node-to-segment condition (true) or a mortar one, or none.
    let input = |contact: Option<bool>| {
        format!(
            "wedge.out\nwedge\nNonLinearStatic nsteps 4 controlmode 1 rtolf 1e-10\n\
             domain PlaneStrain\nOutputManager\n\
             ndofman {} nelem {} ncrosssect 1 nmat 1 nbc {} nic 0 nltf 2 nset 3 ncontactseg 1\n\
             {nodes}{elements}linear2delementedgecontactsegment 1 edgeset 1\nSimpleCS 1 thick 1\n\
             mooneyrivlincompressiblemat 1 d 0 c1 192.3 c2 0 k 833.3\n\
             BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 2\n\
             BoundaryCondition 2 loadTimeFunction 2 dofs 1 2 values 1 -0.4 set 3\n{}\
             ConstantFunction 1 f(t) 1.0\nPiecewiseLinFunction 2 npoints 2 t 2 0 4 f(t) 2 0 1\n\
             Set 1 elementboundaries {} {}\nSet 2 nodes 3 {}\nSet 3 nodes 1 {}\n",
            3 * n + 1,
            tri.len(),
            if contact.is_some() { 3 } else { 2 },
            match contact {
                Some(true) => format!(
                    "n2slagrangianmultipliercontact 3 loadTimeFunction 1 nodeset {} {} \
                     segmentset 1 1\n",
                    surface.len(),
                    labels(&surface)
                ),
                Some(false) => "s2slagrangianmultipliercontact 3 loadTimeFunction 1 \
                                slavesegment 1 segmentset 1 1\n"
                    .to_string(),
                None => String::new(),
            },
            2 * edges.len(),
            edges.join(" "),
            labels(&base),
            id(n, 0)
        )
    };
    let run = |contact: Option<bool>| {
        let model = common::model_from_text(&input(contact)).unwrap();
        let tip = model
            .nodes
            .iter()
            .position(|x| x.label == id(n, 0))
            .unwrap();
        let mut forces = Vec::new();
        hertz::solve::run_analysis(&model, &common::quiet(), |r| {
            assert!(r.contact.iter().all(|s| !s.active), "{:?}", r.contact);
            forces.extend(
                (r.dofs.prescribed.iter().zip(r.reactions))
                    .filter(|((m, d, _), _)| *m == tip && *d == 2)
                    .map(|(_, f)| *f),
            );
            Ok(())
        })
        .unwrap();
        forces
    };
    let without = run(None);
    assert!(edges.len() == 2 * n, "{} slanted edges", edges.len());
    for n2s in [true, false] {
        let with = run(Some(n2s));
        assert_eq!(with.len(), 4);
        for (a, b) in with.iter().zip(&without) {
            assert!(
                (a - b).abs() <= 1e-8 * b.abs().max(1e-12),
                "node-to-segment {n2s}: tip force {a} with, {b} without"
            );
        }
    }
    assert!(
        without.last().unwrap().abs() > 1.0,
        "the tip is bent: {without:?}"
    );
}

/// examples/crushed_tube.in (48 × 3 elements, each plate moved 0.8 over 33 steps) is the whole
/// ring of this file's generator: its top plate's force equals the half model's at every step
/// (to 1e-9; the bore closes over the last third).
#[test]
fn the_crushed_tube_example_equals_its_half_model() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/crushed_tube.in");
    let example = crush(&std::fs::read_to_string(path).unwrap());
    let half = crush(
        &Ring {
            nt: 48,
            nr: 3,
            crush: 0.8,
            steps: 33,
            ..Ring::default()
        }
        .text(false),
    );
    same_plate_force("example", &example, &half);
    assert!(half.last().unwrap().active > 4, "the bore closes");
}

/// The 3D block of the same kind: a slab 1 × 0.2 × 0.2 of 5 × 1 × 1 bricks whose whole
/// boundary is one mortar self-contact surface, compressed by 10 % in y (bottom held in y, the
/// top moved; x and z free but for the rigid motions). Top and bottom face each other through the
/// body and the end faces meet the side faces at right angles: no face may meet any, so the
/// uniaxial compression is exact, F = E·ε·A, and no node is ever in contact.
#[test]
fn a_slab_whose_boundary_is_one_mortar_self_contact_surface_is_compressed_without_contact() {
    use hertz::fem::shape::Shape;
    let (nx, side) = (5, 0.2);
    let id = |i: usize, j: usize, k: usize| 1 + k * 2 * (nx + 1) + j * (nx + 1) + i;
    let at =
        |i: usize, j: usize, k: usize| [i as f64 / nx as f64, side * j as f64, side * k as f64];
    let mut nodes = String::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..=nx {
                let [x, y, z] = at(i, j, k);
                nodes += &format!("node {} coords 3 {x} {y} {z}\n", id(i, j, k));
            }
        }
    }
    let mut elements = String::new();
    let mut boundary = Vec::new();
    for i in 0..nx {
        // The node order of hertz's own brick (its corners as `Shape::Hexa8` numbers them).
        let corners = [
            (i, 0, 1),
            (i, 1, 1),
            (i + 1, 1, 1),
            (i + 1, 0, 1),
            (i, 0, 0),
            (i, 1, 0),
            (i + 1, 1, 0),
            (i + 1, 0, 0),
        ];
        let list: Vec<String> = corners
            .iter()
            .map(|&(a, b, c)| id(a, b, c).to_string())
            .collect();
        elements += &format!(
            "LSpace {} nodes 8 {} crossSect 1 mat 1\n",
            i + 1,
            list.join(" ")
        );
        for (b, face) in Shape::Hexa8.boundaries().iter().enumerate() {
            let x: Vec<[f64; 3]> = face
                .iter()
                .map(|&a| {
                    let (p, q, r) = corners[a];
                    at(p, q, r)
                })
                .collect();
            let on = (0..3).any(|d| {
                let hi = if d == 0 { 1.0 } else { side };
                x.iter().all(|p| p[d].abs() < 1e-12) || x.iter().all(|p| (p[d] - hi).abs() < 1e-12)
            });
            if on {
                boundary.push(format!("{} {}", i + 1, b + 1));
            }
        }
    }
    let layer = |j: usize| -> Vec<usize> {
        (0..2)
            .flat_map(|k| (0..=nx).map(move |i| id(i, j, k)))
            .collect()
    };
    let text = format!(
        "slab.out\nslab\nNonLinearStatic nsteps 1 controlmode 1 rtolf 1e-10\ndomain 3d\n\
         OutputManager\nndofman {} nelem {nx} ncrosssect 1 nmat 1 nbc 5 nic 0 nltf 1 nset 5 ncontactseg 1\n\
         {nodes}{elements}linear3delementsurfacecontactsegment 1 boundaryset 1\nSimpleCS 1\n\
         IsoLE 1 d 0 E 1000 n 0.3 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 2 values 1 0 set 2\n\
         BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 {} set 3\n\
         BoundaryCondition 3 loadTimeFunction 1 dofs 2 1 3 values 2 0 0 set 4\n\
         BoundaryCondition 4 loadTimeFunction 1 dofs 1 3 values 1 0 set 5\n\
         s2slagrangianmultipliercontact 5 loadTimeFunction 1 slavesegment 1 segmentset 1 1\n\
         ConstantFunction 1 f(t) 1.0\n\
         Set 1 elementboundaries {} {}\nSet 2 nodes {} {}\nSet 3 nodes {} {}\nSet 4 nodes 1 {}\n\
         Set 5 nodes 1 {}\n",
        4 * (nx + 1),
        -0.1 * side,
        2 * boundary.len(),
        boundary.join(" "),
        layer(0).len(),
        labels(&layer(0)),
        layer(1).len(),
        labels(&layer(1)),
        id(0, 0, 0),
        id(nx, 0, 0),
    );
    assert_eq!(boundary.len(), 4 * nx + 2, "the slab's boundary faces");
    let model = common::model_from_text(&text).unwrap();
    let mut checked = false;
    hertz::solve::run_analysis(&model, &common::quiet(), |r| {
        assert!(
            r.contact.iter().all(|s| !s.active && s.force == 0.0),
            "{:?}",
            r.contact.iter().filter(|s| s.active).collect::<Vec<_>>()
        );
        let force: f64 = (r.dofs.prescribed.iter().zip(r.reactions))
            .filter(|((node, d, _), _)| *d == 2 && model.nodes[*node].coords[1] == side)
            .map(|(_, f)| f)
            .sum();
        let exact = -1000.0 * 0.1 * side;
        assert!(
            (force - exact).abs() < 1e-9 * exact.abs(),
            "force {force}, exact {exact}"
        );
        checked = true;
        Ok(())
    })
    .unwrap();
    assert!(checked);
}
