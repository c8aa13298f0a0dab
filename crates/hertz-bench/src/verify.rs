//! Contact verification problems: 3D ones generated for any element kind (hexahedra, tetrahedra,
//! wedges) and any node order (a cube symmetry applied to every element, see
//! [`super::mesh::cube_symmetry`]), so that a test can run each in every orientation.

use super::mesh::{uniform, Block, Input, Kind, Solid};
use super::suite::{analysis, history, n2s, s2s, Law};

/// Young's modulus and Poisson's ratio of the verification bodies.
pub const E: f64 = 1000.0;
pub const NU: f64 = 0.3;

/// The neo-Hookean record with the small-strain moduli E, ν (μ = 2 c1, K = k).
pub fn neo_hookean(number: usize) -> String {
    neo_hookean_with(number, E, NU)
}

/// The neo-Hookean record with the small-strain moduli `e`, `nu`.
pub fn neo_hookean_with(number: usize, e: f64, nu: f64) -> String {
    let mu = e / (2.0 * (1.0 + nu));
    let k = e / (3.0 * (1.0 - 2.0 * nu));
    format!(
        "mooneyrivlincompressiblemat {number} d 0 c1 {} c2 0 k {k}",
        0.5 * mu
    )
}

/// Contact segment 1 on the faces of `master` at height `z`, section 1, and material 1:
/// neo-Hookean for `nlgeo`, else linear elastic with E, ν.
fn contact_faces_and_material(inp: &mut Input, master: &Block, z: f64, nlgeo: bool) {
    let faces = inp.faces_where(master, &|p| (p[2] - z).abs() < 1e-12);
    let seg = inp.boundary_set(&faces);
    inp.segments.push(format!(
        "linear3delementsurfacecontactsegment 1 boundaryset {seg}"
    ));
    inp.sections.push("SimpleCS 1".into());
    inp.materials.push(if nlgeo {
        neo_hookean(1)
    } else {
        format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0")
    });
}

/// Condition 5, on master segment 1: node-to-segment from `nodes`, or mortar from the faces of
/// `slave` whose nodes satisfy `on` (segment 2).
fn contact(
    inp: &mut Input,
    number: usize,
    law: Law,
    mortar: bool,
    slave: &Block,
    nodes: &[usize],
    on: &dyn Fn([f64; 3]) -> bool,
) {
    if !mortar {
        inp.bcs.push(n2s(number, law, nodes, &[1], ""));
        return;
    }
    let faces = inp.faces_where(slave, on);
    let set = inp.boundary_set(&faces);
    inp.segments.push(format!(
        "linear3delementsurfacecontactsegment 2 boundaryset {set}"
    ));
    inp.bcs.push(s2s(number, law));
}

/// Conditions 1–3: rollers on the planes x = 0 and y = 0 and on the nodes `bottom` (held in z);
/// condition 4: the nodes `top` moved down by `delta` times function 1.
/// Conditions 1 and 2: the symmetry planes x = 0 and y = 0 on rollers.
fn rollers(inp: &mut Input) {
    let x0 = inp.nodes_where(&|p| p[0].abs() < 1e-12);
    let y0 = inp.nodes_where(&|p| p[1].abs() < 1e-12);
    let x0 = inp.node_set(&x0);
    let y0 = inp.node_set(&y0);
    for (k, (dof, set)) in [(1, x0), (2, y0)].iter().enumerate() {
        inp.bcs.push(format!(
            "BoundaryCondition {} loadTimeFunction 2 dofs 1 {dof} values 1 0 set {set}",
            k + 1
        ));
    }
}

/// [`rollers`], `bottom` held in z (3) and `top` moved down by `delta` (4).
fn rollers_and_push(inp: &mut Input, bottom: &[usize], top: &[usize], delta: f64) {
    rollers(inp);
    let bottom = inp.node_set(bottom);
    let top = inp.node_set(top);
    inp.bcs.push(format!(
        "BoundaryCondition 3 loadTimeFunction 2 dofs 1 3 values 1 0 set {bottom}"
    ));
    inp.bcs.push(format!(
        "BoundaryCondition 4 loadTimeFunction 1 dofs 1 3 values 1 {} set {top}",
        -delta
    ));
}

/// The 3D contact patch test: two blocks [0, 1]² × [−h, 0] (master, n × n × 2 elements) and
/// [0, 1]² × [0, h] (slave, 2n × 2n × 2: a nested, non-matching mesh) touching at z = 0, rollers
/// on x = 0, y = 0 and the master's bottom, the slave's top moved down by `delta` (in `steps`
/// equal steps). The exact solution is homogeneous uniaxial stress in both blocks: each slave
/// node carries the nominal stress times its tributary area.
#[derive(Debug, Clone, Copy)]
pub struct Patch {
    /// Element kind of the master block, and of the slave block if `slave_kind` is None.
    pub kind: Solid,
    pub slave_kind: Option<Solid>,
    pub sym: usize,
    pub n: usize,
    pub nlgeo: bool,
    pub delta: f64,
    pub steps: usize,
    pub law: Law,
    /// Elements across the slave block, if not 2n (non-nested meshes).
    pub slave_n: Option<usize>,
    /// Mortar (segment-to-segment) contact of the slave's bottom faces, else node-to-segment.
    pub mortar: bool,
}

/// Height of each block of the patch test.
pub const PATCH_H: f64 = 0.5;

impl Patch {
    pub fn input(&self) -> String {
        self.build(false)
    }

    /// [`Patch::input`] with quadratic elements (QTRSpace for `Solid::Tet`, QSpace for
    /// `Solid::Hex`), the mid-side nodes of the slave's bottom among the contact nodes.
    pub fn input_quadratic(&self) -> String {
        self.build(true)
    }

    fn build(&self, quadratic: bool) -> String {
        let mut inp = Input::default();
        let extra = format!("mat 1 crossSect 1 nlgeo {}", u8::from(self.nlgeo));
        let (g, gs) = (
            uniform(0.0, 1.0, self.n),
            uniform(0.0, 1.0, self.slave_n.unwrap_or(2 * self.n)),
        );
        let mut master = inp.solid3d(
            self.kind,
            &g,
            &g,
            &uniform(-PATCH_H, 0.0, 2),
            &extra,
            self.sym,
        );
        let mut slave = inp.solid3d(
            self.slave_kind.unwrap_or(self.kind),
            &gs,
            &gs,
            &uniform(0.0, PATCH_H, 2),
            &extra,
            self.sym,
        );
        if quadratic {
            quadratic_block(&mut inp, &mut master, 0.0, -PATCH_H);
            quadratic_block(&mut inp, &mut slave, PATCH_H, 0.0);
        }
        contact_faces_and_material(&mut inp, &master, 0.0, self.nlgeo);
        rollers_and_push(&mut inp, &master.bottom, &slave.top, self.delta);
        let bottom = slave.bottom.clone();
        contact(&mut inp, 5, self.law, self.mortar, &slave, &bottom, &|p| {
            p[2].abs() < 1e-12
        });
        let steps: Vec<f64> = (1..=self.steps)
            .map(|k| k as f64 / self.steps as f64)
            .collect();
        inp.functions.push(history(&steps));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        // Multipliers converged to round-off: their answer is exact.
        let mut analysis = analysis(self.steps);
        if self.law == Law::Multiplier {
            analysis = analysis.replace("rtolf 1e-8", "rtolf 1e-12");
        }
        inp.render("patch3d", &analysis, "3d")
    }
}

/// Make `block`'s elements quadratic ([`Input::make_quadratic`]), its new mid-side nodes at
/// height `top` or `bottom` added to its top or bottom nodes; returns the new nodes.
fn quadratic_block(inp: &mut Input, block: &mut Block, top: f64, bottom: f64) -> Vec<usize> {
    let mids = inp.make_quadratic(block.elements);
    for &n in &mids {
        let z = inp.nodes[n - 1][2];
        if (z - top).abs() < 1e-12 {
            block.top.push(n);
        } else if (z - bottom).abs() < 1e-12 {
            block.bottom.push(n);
        }
    }
    mids
}

/// The law of [`neo_hookean`].
pub fn neo_hookean_law() -> hertz::material::hyperelastic::MooneyRivlin {
    let mu = E / (2.0 * (1.0 + NU));
    hertz::material::hyperelastic::MooneyRivlin {
        c1: 0.5 * mu,
        c2: 0.0,
        k: E / (3.0 * (1.0 - 2.0 * NU)),
    }
}

/// Homogeneous uniaxial stress along z at axial stretch `stretch`: the lateral stretch (where
/// the lateral nominal stress vanishes, by Newton on a secant) and the axial nominal stress P_zz.
pub fn uniaxial_stress(
    law: &dyn hertz::material::hyperelastic::Energy,
    stretch: f64,
) -> (f64, f64) {
    let p = |lt: f64| {
        let f = [[lt, 0.0, 0.0], [0.0, lt, 0.0], [0.0, 0.0, stretch]];
        hertz::material::hyperelastic::pk1(law, &f)
            .expect("a valid stretch")
            .0
    };
    let (mut a, mut b) = (1.0, 1.0 + 0.5 * (1.0 - stretch));
    let (mut fa, mut fb) = (p(a)[0][0], p(b)[0][0]);
    for _ in 0..100 {
        if fb == fa || (b - a).abs() < 1e-15 {
            break;
        }
        let c = b - fb * (b - a) / (fb - fa);
        (a, fa) = (b, fb);
        b = c;
        fb = p(b)[0][0];
    }
    (b, p(b)[2][2])
}

/// Hertz contact of an elastic sphere on an elastic block, quarter model (symmetry planes x = 0
/// and y = 0): the block [0, W]² × [−W, 0] and the cap of the sphere of radius `HERTZ_R`
/// touching it at the origin, cut at height `HERTZ_CAP` and W wide, both graded from spacing `h`
/// within 1.5 of the axis; the cap's flat top moved down by `delta`. Node-to-face from the cap's
/// bottom nodes within r ≤ 1.6 to the block's top faces. Same material (E, ν) in both bodies.
#[derive(Debug, Clone, Copy)]
pub struct HertzSphere {
    pub kind: Solid,
    pub sym: usize,
    pub h: f64,
    pub delta: f64,
    pub nlgeo: bool,
    pub law: Law,
    /// Mortar (segment-to-segment) contact of the cap's bottom faces, else node-to-segment.
    pub mortar: bool,
}

/// The radius around the axis within which [`HertzSphere::input`] takes the slave side.
pub const HERTZ_NEAR: f64 = 1.6;

/// Sphere radius, cap height and width, and block size of [`HertzSphere`].
pub const HERTZ_R: f64 = 10.0;
pub const HERTZ_CAP: f64 = 4.0;
pub const HERTZ_BLOCK: f64 = 6.0;

/// Height above its lowest point of the sphere (cylinder, y = 0) of radius `HERTZ_R` at (x, y).
fn sphere_height(x: f64, y: f64) -> f64 {
    HERTZ_R - (HERTZ_R * HERTZ_R - (x * x + y * y)).sqrt()
}

/// Bend a cap of height `HERTZ_CAP` (nodes `ids`, z from 0 up) onto the sphere:
/// z → z_b + z (H − z_b)/H; `mirrored` (z from −H to 0, its top bent down): z → −z_b + z (H − z_b)/H.
fn bend_onto_sphere(inp: &mut Input, ids: impl IntoIterator<Item = usize>, mirrored: bool) {
    for id in ids {
        let p = &mut inp.nodes[id - 1];
        let zb = sphere_height(p[0], p[1]);
        let base = if mirrored { -zb } else { zb };
        p[2] = base + p[2] * (HERTZ_CAP - zb) / HERTZ_CAP;
    }
}

impl HertzSphere {
    /// The input with the cap's bottom nodes within 1.6 of the axis as the contact's slave side.
    pub fn input(&self) -> String {
        self.input_within(HERTZ_NEAR)
    }

    /// The input with the cap's bottom nodes within `radius` of the axis as the slave side
    /// (`HERTZ_CAP`: all of them, as a user meshing the whole face would).
    pub fn input_within(&self, radius: f64) -> String {
        self.input_of(radius, false)
    }

    /// [`HertzSphere::input_within`], with quadratic elements if `quadratic` (QTRSpace for
    /// `Solid::Tet`, QSpace for `Solid::Hex`): the cap's bottom curved on the sphere, mid-side
    /// nodes included, node-to-face contact of its bottom nodes (mid-sides too) on the block's
    /// 6- or 8-node top faces.
    pub fn input_of(&self, radius: f64, quadratic: bool) -> String {
        use super::mesh::graded;
        let mut inp = Input::default();
        let extra = format!("mat 1 crossSect 1 nlgeo {}", u8::from(self.nlgeo));
        let xs = graded(HERTZ_BLOCK, self.h, 1.5, 1.2);
        let zs: Vec<f64> = graded(HERTZ_BLOCK, self.h, 0.75, 1.2)
            .iter()
            .rev()
            .map(|d| -d)
            .collect();
        let with_mids = |inp: &mut Input, b: &mut Block, top: f64, bottom: f64| {
            if quadratic {
                quadratic_block(inp, b, top, bottom)
            } else {
                Vec::new()
            }
        };
        let mut block = inp.solid3d(self.kind, &xs, &xs, &zs, &extra, self.sym);
        with_mids(&mut inp, &mut block, 0.0, zs[0]);
        let xc = graded(HERTZ_CAP, self.h, 1.5, 1.2);
        let zc = graded(HERTZ_CAP, self.h, 0.75, 1.2);
        let mut cap = inp.solid3d(self.kind, &xc, &xc, &zc, &extra, self.sym);
        let cap_mids = with_mids(&mut inp, &mut cap, HERTZ_CAP, 0.0);
        bend_onto_sphere(&mut inp, (cap.nodes.0..=cap.nodes.1).chain(cap_mids), false);
        contact_faces_and_material(&mut inp, &block, 0.0, self.nlgeo);
        rollers_and_push(&mut inp, &block.bottom, &cap.top, self.delta);
        let near = |p: [f64; 3]| p[0].hypot(p[1]) <= radius;
        let nodes: Vec<usize> = cap
            .bottom
            .iter()
            .copied()
            .filter(|&n| near(inp.nodes[n - 1]))
            .collect();
        contact(&mut inp, 5, self.law, self.mortar, &cap, &nodes, &|p| {
            near(p) && (p[2] - sphere_height(p[0], p[1])).abs() < 1e-9
        });
        inp.functions.push(history(&[1.0]));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("hertz3d", &analysis(1), "3d")
    }
}

/// The seed's two beams, point-symmetric: a lower beam [0, L] × [0, H] clamped at x = 0 and an
/// upper beam [S, S + L] × [H + G, 2H + G] clamped at x = S + L, plane strain, neo-Hookean,
/// large deformation. A force at each free end (spread over its nodes, in `steps` equal steps)
/// bends the beams towards each other: the lower beam's free end rises and the upper beam's
/// falls until each end's corner presses on the other beam. Two node-to-segment conditions with
/// the roles swapped (two-pass): the upper beam's bottom nodes on the lower beam's top edges, and
/// the lower beam's top nodes on the upper beam's bottom edges; each corner is caught by the
/// pass in which it is a contact node. Turning the model by 180° about its centre swaps the
/// beams and the passes: the answer is the same.
#[derive(Debug, Clone, Copy)]
pub struct TwoBeams {
    /// Elements along each beam and through its depth.
    pub nx: usize,
    pub ny: usize,
    /// Elements along the upper beam, if other than `nx` (non-matching meshes).
    pub nx_upper: Option<usize>,
    /// The force on each free end.
    pub force: f64,
    pub steps: usize,
    pub law: Law,
    /// Both passes (else only the first: upper beam's nodes on the lower beam).
    pub two_pass: bool,
}

/// Length, depth, overlap offset and gap of [`TwoBeams`].
pub const BEAM_L: f64 = 10.0;
pub const BEAM_H: f64 = 1.0;
pub const BEAM_S: f64 = 2.0;
pub const BEAM_G: f64 = 0.5;

impl TwoBeams {
    pub fn input(&self) -> String {
        use super::mesh::Kind;
        let mut inp = Input::default();
        let extra = "mat 1 crossSect 1 nlgeo 1";
        let lower = inp.block2d(
            Kind::Q4,
            &uniform(0.0, BEAM_L, self.nx),
            &|_| uniform(0.0, BEAM_H, self.ny),
            extra,
        );
        let upper = inp.block2d(
            Kind::Q4,
            &uniform(BEAM_S, BEAM_S + BEAM_L, self.nx_upper.unwrap_or(self.nx)),
            &|_| uniform(BEAM_H + BEAM_G, 2.0 * BEAM_H + BEAM_G, self.ny),
            extra,
        );
        let lower_edges = inp.boundary_set(&lower.top_edges);
        let upper_edges = inp.boundary_set(&upper.bottom_edges);
        inp.segments.push(format!(
            "linear2delementedgecontactsegment 1 edgeset {lower_edges}"
        ));
        inp.segments.push(format!(
            "linear2delementedgecontactsegment 2 edgeset {upper_edges}"
        ));
        inp.sections.push("SimpleCS 1 thick 1.0".into());
        inp.materials.push(neo_hookean(1));
        let at_x = |x: f64| move |p: [f64; 3]| (p[0] - x).abs() < 1e-12;
        let upper_clamp = inp.nodes_where(&at_x(BEAM_S + BEAM_L));
        let (lower_end, upper_end): (Vec<usize>, Vec<usize>) = (
            inp.nodes_where(&at_x(BEAM_L))
                .into_iter()
                .filter(|&n| inp.nodes[n - 1][1] < BEAM_H + 1e-9)
                .collect(),
            inp.nodes_where(&at_x(BEAM_S))
                .into_iter()
                .filter(|&n| inp.nodes[n - 1][1] > BEAM_H + 1e-9)
                .collect(),
        );
        let clamps = [lower.left.clone(), upper_clamp].concat();
        let clamps = inp.node_set(&clamps);
        inp.bcs.push(format!(
            "BoundaryCondition 1 loadTimeFunction 2 dofs 2 1 2 values 2 0 0 set {clamps}"
        ));
        for (k, (nodes, sign)) in [(lower_end, 1.0), (upper_end, -1.0)].iter().enumerate() {
            let set = inp.node_set(nodes);
            inp.bcs.push(format!(
                "NodalLoad {} loadTimeFunction 1 dofs 2 1 2 components 2 0 {} set {set}",
                k + 2,
                sign * self.force / nodes.len() as f64
            ));
        }
        let k = inp.bcs.len();
        inp.bcs.push(n2s(k + 1, self.law, &upper.bottom, &[1], ""));
        if self.two_pass {
            inp.bcs.push(n2s(k + 2, self.law, &lower.top, &[2], ""));
        }
        let steps: Vec<f64> = (1..=self.steps)
            .map(|k| k as f64 / self.steps as f64)
            .collect();
        inp.functions.push(history(&steps));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("two_beams", &analysis(self.steps), "PlaneStrain")
    }
}

/// The elastic cylinder on a block of [`super::suite::cylinder_on_block`] (plane strain, half
/// model, spacing h under the contact) extruded to a unit depth along y in 3D, with every node
/// held in y (plane strain): node-to-face from the cap's bottom nodes to the block's top faces.
/// The force per unit depth is the 2D node-to-segment force.
#[derive(Debug, Clone, Copy)]
pub struct ExtrudedCylinder {
    pub sym: usize,
    pub h: f64,
    /// Elements through the depth.
    pub ny: usize,
    pub law: Law,
}

impl ExtrudedCylinder {
    pub fn input(&self) -> String {
        use super::mesh::graded;
        use super::suite::{CYL_CAP, CYL_DELTA, CYL_DEPTH, CYL_R, CYL_W};
        let (h, r) = (self.h, CYL_R);
        let mut inp = Input::default();
        let extra = "mat 1 crossSect 1";
        let xs = graded(CYL_W, h, 1.0, 1.2);
        let zs: Vec<f64> = graded(CYL_DEPTH, h, 0.5, 1.2)
            .iter()
            .rev()
            .map(|d| -d)
            .collect();
        let depth = uniform(0.0, 1.0, self.ny);
        let block = inp.solid3d(Solid::Hex, &xs, &depth, &zs, extra, self.sym);
        let xc = graded(CYL_CAP, h, 1.0, 1.2);
        let hcs = graded(CYL_CAP, h, 0.5, 1.2);
        let cap = inp.solid3d(Solid::Hex, &xc, &depth, &hcs, extra, self.sym);
        for id in cap.nodes.0..=cap.nodes.1 {
            let p = &mut inp.nodes[id - 1];
            let zb = r - (r * r - p[0] * p[0]).sqrt();
            p[2] = zb + p[2] * (CYL_CAP - zb) / CYL_CAP;
        }
        let faces = inp.faces_where(&block, &|p| p[2].abs() < 1e-12);
        let seg = inp.boundary_set(&faces);
        inp.segments.push(format!(
            "linear3delementsurfacecontactsegment 1 boundaryset {seg}"
        ));
        inp.sections.push("SimpleCS 1".into());
        inp.materials
            .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
        let all: Vec<usize> = (1..=inp.nodes.len()).collect();
        let x0 = inp.nodes_where(&|p| p[0].abs() < 1e-12);
        let (all, x0) = (inp.node_set(&all), inp.node_set(&x0));
        let bottom = inp.node_set(&block.bottom);
        let top = inp.node_set(&cap.top);
        for (k, (dof, set, value)) in [
            (2, all, 0.0),
            (1, x0, 0.0),
            (3, bottom, 0.0),
            (3, top, -CYL_DELTA),
        ]
        .iter()
        .enumerate()
        {
            let f = if *value == 0.0 { 2 } else { 1 };
            inp.bcs.push(format!(
                "BoundaryCondition {} loadTimeFunction {f} dofs 1 {dof} values 1 {value} set {set}",
                k + 1
            ));
        }
        let contact: Vec<usize> = cap
            .bottom
            .iter()
            .copied()
            .filter(|&n| inp.nodes[n - 1][0] <= 1.2)
            .collect();
        inp.bcs.push(n2s(5, self.law, &contact, &[1], ""));
        inp.functions.push(history(&[1.0]));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("cylinder3d", &analysis(1), "3d")
    }
}

/// The seed's wedge pressed onto a brick: one LSpace [0, 1]³ held at its bottom (rollers, one
/// corner pinned) and one LWedge above it, its triangle (0.2, 0.2), (0.8, 0.3), (0.4, 0.8) resting
/// on the brick's top at z = 1 and its top triangle at z = 1.5 moved down by `delta` (and held
/// sideways). Node-to-face from the wedge's three bottom nodes to the brick's top face.
#[derive(Debug, Clone, Copy)]
pub struct WedgeOnBrick {
    /// Cube symmetry of the brick's node order.
    pub sym: usize,
    pub delta: f64,
    pub nlgeo: bool,
    pub steps: usize,
    pub law: Law,
}

impl WedgeOnBrick {
    pub fn input(&self) -> String {
        let mut inp = Input::default();
        let extra = format!("mat 1 crossSect 1 nlgeo {}", u8::from(self.nlgeo));
        let brick = inp.solid3d(
            Solid::Hex,
            &[0.0, 1.0],
            &[0.0, 1.0],
            &[0.0, 1.0],
            &extra,
            self.sym,
        );
        let tri = [[0.2, 0.2], [0.8, 0.3], [0.4, 0.8]];
        let bottom: Vec<usize> = tri.iter().map(|p| inp.node(p[0], p[1], 1.0)).collect();
        let top: Vec<usize> = tri.iter().map(|p| inp.node(p[0], p[1], 1.5)).collect();
        let ids: Vec<String> = bottom.iter().chain(&top).map(|n| n.to_string()).collect();
        inp.elements.push(format!(
            "LWedge {} nodes 6 {} {extra}",
            inp.elements.len() + 1,
            ids.join(" ")
        ));
        let mut cells = bottom.clone();
        cells.extend(&top);
        inp.cells.push((hertz::fem::shape::Shape::Wedge6, cells));
        contact_faces_and_material(&mut inp, &brick, 1.0, self.nlgeo);
        let base = inp.node_set(&brick.bottom);
        let pin = inp.nodes_where(&|p| p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0);
        let pin = inp.node_set(&pin);
        let corner_y = inp.nodes_where(&|p| p[0] == 1.0 && p[1] == 0.0 && p[2] == 0.0);
        let corner_y = inp.node_set(&corner_y);
        let top = inp.node_set(&top);
        inp.bcs.push(format!(
            "BoundaryCondition 1 loadTimeFunction 2 dofs 1 3 values 1 0 set {base}"
        ));
        inp.bcs.push(format!(
            "BoundaryCondition 2 loadTimeFunction 2 dofs 2 1 2 values 2 0 0 set {pin}"
        ));
        inp.bcs.push(format!(
            "BoundaryCondition 3 loadTimeFunction 2 dofs 1 2 values 1 0 set {corner_y}"
        ));
        inp.bcs.push(format!(
            "BoundaryCondition 4 loadTimeFunction 1 dofs 3 1 2 3 values 3 0 0 {} set {top}",
            -self.delta
        ));
        inp.bcs.push(n2s(5, self.law, &bottom, &[1], ""));
        let steps: Vec<f64> = (1..=self.steps)
            .map(|k| k as f64 / self.steps as f64)
            .collect();
        inp.functions.push(history(&steps));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("wedge_on_brick", &analysis(self.steps), "3d")
    }
}

/// Large sliding in 2D: a block 1 wide and 0.5 high pressed by a force F onto a circular bump
/// (the top of a block of width 8, radius `SLIDE_R`, highest at x = 4) and dragged by its top from
/// the summit to x = 4 + `travel` in `steps` steps, over many master vertices, tilting with the
/// surface; plane strain, neo-Hookean, large deformation; the block's bottom nodes on the bump's
/// edges. Frictionless: the drag force is F times the slope of the surface under the contact.
#[derive(Debug, Clone, Copy)]
pub struct LargeSliding {
    /// Elements along the bump.
    pub nx: usize,
    pub travel: f64,
    pub force: f64,
    pub steps: usize,
    pub law: Law,
}

/// Radius of the bump of [`LargeSliding`].
pub const SLIDE_R: f64 = 10.0;

/// Height of the bump of [`LargeSliding`] at x (its summit at x = 4 is at 0).
pub fn bump(x: f64) -> f64 {
    (SLIDE_R * SLIDE_R - (x - 4.0).powi(2)).sqrt() - SLIDE_R
}

impl LargeSliding {
    pub fn input(&self) -> String {
        use super::mesh::Kind;
        let mut inp = Input::default();
        let extra = "mat 1 crossSect 1 nlgeo 1";
        let xs = uniform(0.0, 8.0, self.nx);
        let master = inp.block2d(Kind::Q4, &xs, &|i| uniform(-2.0, bump(xs[i]), 4), extra);
        let slave = inp.block2d(
            Kind::Q4,
            &uniform(3.5, 4.5, 8),
            &|_| uniform(1e-3, 0.501, 2),
            extra,
        );
        let edges = inp.boundary_set(&master.top_edges);
        inp.segments.push(format!(
            "linear2delementedgecontactsegment 1 edgeset {edges}"
        ));
        inp.sections.push("SimpleCS 1 thick 1.0".into());
        inp.materials.push(neo_hookean(1));
        let bottom = inp.node_set(&master.bottom);
        let top = inp.node_set(&slave.top);
        inp.bcs.push(format!(
            "BoundaryCondition 1 loadTimeFunction 2 dofs 2 1 2 values 2 0 0 set {bottom}"
        ));
        inp.bcs.push(format!(
            "BoundaryCondition 2 loadTimeFunction 1 dofs 1 1 values 1 {} set {top}",
            self.travel
        ));
        inp.bcs.push(format!(
            "NodalLoad 3 loadTimeFunction 2 dofs 2 1 2 components 2 0 {} set {top}",
            -self.force / slave.top.len() as f64
        ));
        inp.bcs.push(n2s(4, self.law, &slave.bottom, &[1], ""));
        let steps: Vec<f64> = (1..=self.steps)
            .map(|k| k as f64 / self.steps as f64)
            .collect();
        inp.functions.push(history(&steps));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("large_sliding", &analysis(self.steps), "PlaneStrain")
    }
}

/// Ironing in 2D (the plane-strain section of Puso and Laursen's 3D ironing, 2004): a stiff
/// half-ring die (radii 2.8 and 3.0, E = 1000) above a soft slab 9 × 3 (E = 1), both
/// neo-Hookean (ν = 0.3), the die's lowest point 0.03 above the slab at x = −2.7, its two ends
/// pressed down by 1.4 over t ∈ [0, 1] and then moved along x by `slide` over t ∈ [1, 5];
/// mortar contact with multipliers, the slab's top the slave side, Coulomb friction `mu`.
#[derive(Debug, Clone, Copy)]
pub struct Ironing {
    /// Elements along the die's half circle and along the slab, and through the slab.
    pub n_die: usize,
    pub nx: usize,
    pub ny: usize,
    /// Steps of the press (of length 1/`press_steps`, the slide's too).
    pub press_steps: usize,
    pub slide: f64,
    pub mu: f64,
}

/// The die's press depth, inner and outer radii, and centre of [`Ironing`].
const IRONING_DEPTH: f64 = 1.4;
const IRONING_RADII: (f64, f64) = (2.8, 3.0);
const IRONING_CENTRE: [f64; 2] = [-2.7, 3.03];

impl Ironing {
    pub fn input(&self) -> String {
        use super::mesh::Kind;
        use hertz::fem::shape::Shape;
        let mut inp = Input::default();
        let (ri, ro) = IRONING_RADII;
        let [xc, yc] = IRONING_CENTRE;
        // The die: one element through its thickness, lower half circle from θ = π to 2π.
        let ring: Vec<[usize; 2]> = (0..=self.n_die)
            .map(|i| {
                let th = std::f64::consts::PI * (1.0 + i as f64 / self.n_die as f64);
                let (c, s) = (th.cos(), th.sin());
                [
                    inp.node(xc + ri * c, yc + ri * s, 0.0),
                    inp.node(xc + ro * c, yc + ro * s, 0.0),
                ]
            })
            .collect();
        let mut die_edges = Vec::new();
        for i in 0..self.n_die {
            // Counter-clockwise, edge 1 (nodes 1–2) on the outer circle.
            let n = [ring[i][1], ring[i + 1][1], ring[i + 1][0], ring[i][0]];
            let e = inp.elements.len() + 1;
            inp.elements.push(format!(
                "Quad1PlaneStrain {e} nodes 4 {} {} {} {} mat 1 crossSect 1 nlgeo 1",
                n[0], n[1], n[2], n[3]
            ));
            inp.cells.push((Shape::Quad4, n.to_vec()));
            die_edges.push((e, 1));
        }
        let ends = [ring[0], ring[self.n_die]].concat();
        let xs = uniform(-4.5, 4.5, self.nx);
        let slab = inp.block2d(
            Kind::Q4,
            &xs,
            &|_| uniform(-3.0, 0.0, self.ny),
            "mat 2 crossSect 1 nlgeo 1",
        );
        PressAndSlide {
            dim: 2,
            law: Law::Multiplier,
            master: &die_edges,
            slave: &slab.top_edges,
            materials: [
                neo_hookean_with(1, 1000.0, 0.3),
                neo_hookean_with(2, 1.0, 0.3),
            ],
            held: &slab.bottom,
            driven: &ends,
            depth: IRONING_DEPTH,
            slide: self.slide,
            slide_end: 5.0,
            mu: self.mu,
        }
        .write(&mut inp);
        let n = 5 * self.press_steps;
        let analysis = format!(
            "StaticStructural nsteps {n} deltat {} rtolf 1e-8 maxiter 25",
            1.0 / self.press_steps as f64
        );
        inp.render("ironing", &analysis, "PlaneStrain")
    }
}

/// The shallow ironing benchmark in 2D (Yang, Laursen and Meng 2005; also Fischer and Wriggers
/// 2006, Poulios and Renard 2015, Kratos' `shallow_ironing` validation), plane strain, lengths
/// in mm and moduli in N/mm² (forces in N per mm of thickness): a block 12 × 4 (E = 689.6) with
/// its bottom held, and a die (E = 6896) whose lower face is a circular arc of radius 0.75
/// (chord 1.2 from x = 0.2 to 1.4, its lowest point at x = 0.8, 0.2 above the block), its flat
/// top 1.2 above that lowest point; both neo-Hookean (ν = 0.32, Simo–Pister's
/// compressible form with G and Lamé's λ: W = G/2 (I₁ − 3) − G ln J + λ/2 (ln J)², Kratos'
/// `HyperElastic3DLaw`). The die's top is moved down by 1 over t ∈ [0, 1] in ten steps, then
/// along x by 10 (t − 1); mortar contact with multipliers, the die's arc the slave side.
#[derive(Debug, Clone, Copy)]
pub struct ShallowIroning {
    /// Block elements along x and through y; die elements along the arc and through the die.
    pub nx: usize,
    pub ny: usize,
    pub n_arc: usize,
    pub n_die: usize,
    /// Time step of the slide (the press is ten steps of 0.1), and the last time.
    pub slide_dt: f64,
    pub end: f64,
    pub mu: f64,
}

impl ShallowIroning {
    /// The die's arc: radius, the x of its centre and lowest point, and half its chord; the
    /// die's height from that lowest point to its top.
    pub const RADIUS: f64 = 0.75;
    pub const CENTRE_X: f64 = 0.8;
    pub const HALF_CHORD: f64 = 0.6;
    pub const DIE_HEIGHT: f64 = 1.2;
    /// The block's length and height, the die's initial gap, press depth and slide per unit t.
    pub const LENGTH: f64 = 12.0;
    pub const HEIGHT: f64 = 4.0;
    pub const GAP: f64 = 0.2;
    pub const DEPTH: f64 = 1.0;
    pub const SPEED: f64 = 10.0;

    /// The times of the steps: the press in ten steps, then the slide in steps of `slide_dt`.
    pub fn times(&self) -> Vec<f64> {
        let mut t: Vec<f64> = (1..=10).map(|k| k as f64 / 10.0).collect();
        let n = ((self.end - 1.0) / self.slide_dt).round() as usize;
        // Rounded to 1e-9 so that the file reads 1.14, not 1.1400000000000001.
        t.extend((1..=n).map(|k| ((1.0 + k as f64 * self.slide_dt) * 1e9).round() / 1e9));
        t
    }

    pub fn input(&self) -> String {
        use super::mesh::Kind;
        let mut inp = Input::default();
        let (columns, top) = self.die_columns();
        let xs: Vec<f64> = columns.iter().map(|c| c.0).collect();
        let die = inp.block2d(
            Kind::Q4,
            &xs,
            &|i| uniform(columns[i].1, top, self.n_die),
            "mat 1 crossSect 1 nlgeo 1",
        );
        let block = inp.block2d(
            Kind::Q4,
            &uniform(0.0, Self::LENGTH, self.nx),
            &|_| uniform(0.0, Self::HEIGHT, self.ny),
            "mat 2 crossSect 1 nlgeo 1",
        );
        self.press_and_slide(
            2,
            Law::Multiplier,
            &block.top_edges,
            &die.bottom_edges,
            &block.bottom,
            &die.top,
        )
        .write(&mut inp);
        inp.render("shallow_ironing", &self.analysis(), "PlaneStrain")
    }

    /// The die's columns at equal angles along its arc, each (x, the arc's height there), and
    /// the height of the die's top.
    fn die_columns(&self) -> (Vec<(f64, f64)>, f64) {
        let r = Self::RADIUS;
        let bottom = Self::HEIGHT + Self::GAP;
        let half_angle = (Self::HALF_CHORD / r).asin();
        let columns = uniform(-half_angle, half_angle, self.n_arc)
            .iter()
            .map(|a| (Self::CENTRE_X + r * a.sin(), bottom + r - r * a.cos()))
            .collect();
        (columns, bottom + Self::DIE_HEIGHT)
    }

    /// The die's `driven` top pressed into the block (its `held` bottom) and slid along it: the
    /// slide x = SPEED (t − 1) from t = 1 to the end (at least 2); the contact law `law`.
    fn press_and_slide<'a>(
        &self,
        dim: usize,
        law: Law,
        master: &'a [(usize, usize)],
        slave: &'a [(usize, usize)],
        held: &'a [usize],
        driven: &'a [usize],
    ) -> PressAndSlide<'a> {
        let end = self.end.max(2.0);
        PressAndSlide {
            dim,
            law,
            master,
            slave,
            materials: [
                simo_pister_with(1, 6896.0, 0.32),
                simo_pister_with(2, 689.6, 0.32),
            ],
            held,
            driven,
            depth: Self::DEPTH,
            slide: Self::SPEED * (end - 1.0),
            slide_end: end,
            mu: self.mu,
        }
    }

    /// The analysis record: the steps of [`Self::times`].
    fn analysis(&self) -> String {
        let times: Vec<String> = self.times().iter().map(|t| format!("{t}")).collect();
        format!(
            "StaticStructural nsteps {} prescribedTimes {} {} rtolf 1e-8 maxiter 25",
            times.len(),
            times.len(),
            times.join(" ")
        )
    }
}

/// [`ShallowIroning`] extruded to a unit depth along y in 3D (z up): `kind` elements over
/// `layers` cells through the depth, held in y at every node (plane strain) when `plane_strain`,
/// else at the die's top alone; mortar face contact, the die's arc the slave side, with
/// multipliers ([`Self::input`]) or a penalty ([`Self::input_with`]). On bricks in plane strain
/// its force per unit depth is the 2D one.
#[derive(Debug, Clone, Copy)]
pub struct ShallowIroning3d {
    pub base: ShallowIroning,
    pub kind: Solid,
    pub layers: usize,
    pub plane_strain: bool,
}

impl ShallowIroning3d {
    /// The input with multipliers.
    pub fn input(&self) -> String {
        self.input_with(Law::Multiplier)
    }

    /// The input with the contact law `law` (a penalty per unit area, friction's ε_T the same).
    pub fn input_with(&self, law: Law) -> String {
        let b = &self.base;
        let mut inp = Input::default();
        let (columns, top) = b.die_columns();
        let xs: Vec<f64> = columns.iter().map(|c| c.0).collect();
        let depth = uniform(0.0, 1.0, self.layers);
        let extra = |m: usize| format!("mat {m} crossSect 1 nlgeo 1");
        // The die on a unit grid in z, then each column mapped from the arc up to the top.
        let die = inp.solid3d(
            self.kind,
            &xs,
            &depth,
            &uniform(0.0, 1.0, b.n_die),
            &extra(1),
            0,
        );
        let arc_at = |x: f64| {
            columns
                .iter()
                .find(|c| c.0 == x)
                .expect("die nodes on its columns")
                .1
        };
        for id in die.nodes.0..=die.nodes.1 {
            let p = &mut inp.nodes[id - 1];
            let zb = arc_at(p[0]);
            p[2] = zb + p[2] * (top - zb);
        }
        let block = inp.solid3d(
            self.kind,
            &uniform(0.0, ShallowIroning::LENGTH, b.nx),
            &depth,
            &uniform(0.0, ShallowIroning::HEIGHT, b.ny),
            &extra(2),
            0,
        );
        let h = ShallowIroning::HEIGHT;
        let master = inp.faces_where(&block, &|p| (p[2] - h).abs() < 1e-12);
        let slave = inp.faces_where(&die, &|p| p[2] == arc_at(p[0]));
        b.press_and_slide(3, law, &master, &slave, &block.bottom, &die.top)
            .write(&mut inp);
        // Held in y: every node (plane strain), or else the die's driven top (which the die
        // would otherwise be free to leave along y before it touches).
        let across: Vec<usize> = if self.plane_strain {
            (1..=inp.nodes.len()).collect()
        } else {
            die.top.clone()
        };
        let across = inp.node_set(&across);
        let k = inp.bcs.len() + 1;
        inp.bcs.push(format!(
            "BoundaryCondition {k} loadTimeFunction 1 dofs 1 2 values 1 0 set {across}"
        ));
        inp.render("shallow_ironing3d", &b.analysis(), "3d")
    }
}

/// A die pressed into a body and slid along it, as [`Ironing`] and [`ShallowIroning`] write it:
/// edge (2D) or face (3D) segments 1 (`master`) and 2 (`slave`), materials 1 and 2, the body's
/// `held` nodes fixed (BC 1), the die's `driven` nodes moved down by `depth` over t ∈ [0, 1]
/// (BC 2) and along x by `slide` over t ∈ [1, `slide_end`] (BC 3), the mortar condition of
/// `law` with friction `mu` (BC 4), and the three time functions.
struct PressAndSlide<'a> {
    /// 2: edge segments, the press along y; 3: face segments, the press along z.
    dim: usize,
    law: Law,
    master: &'a [(usize, usize)],
    slave: &'a [(usize, usize)],
    materials: [String; 2],
    held: &'a [usize],
    driven: &'a [usize],
    depth: f64,
    slide: f64,
    slide_end: f64,
    mu: f64,
}

impl PressAndSlide<'_> {
    fn write(self, inp: &mut Input) {
        let master = inp.boundary_set(self.master);
        let slave = inp.boundary_set(self.slave);
        let (segment, set, up, held_dofs) = match self.dim {
            2 => (
                "linear2delementedgecontactsegment",
                "edgeset",
                2,
                "2 1 2 values 2 0 0",
            ),
            _ => (
                "linear3delementsurfacecontactsegment",
                "boundaryset",
                3,
                "3 1 2 3 values 3 0 0 0",
            ),
        };
        inp.segments.push(format!("{segment} 1 {set} {master}"));
        inp.segments.push(format!("{segment} 2 {set} {slave}"));
        inp.sections.push("SimpleCS 1 thick 1.0".into());
        inp.materials.extend(self.materials);
        let held = inp.node_set(self.held);
        let driven = inp.node_set(self.driven);
        inp.bcs.push(format!(
            "BoundaryCondition 1 loadTimeFunction 1 dofs {held_dofs} set {held}"
        ));
        inp.bcs.push(format!(
            "BoundaryCondition 2 loadTimeFunction 2 dofs 1 {up} values 1 -{} set {driven}",
            self.depth
        ));
        inp.bcs.push(format!(
            "BoundaryCondition 3 loadTimeFunction 3 dofs 1 1 values 1 {} set {driven}",
            self.slide
        ));
        inp.bcs
            .push(format!("{} friction {}", s2s(4, self.law), self.mu));
        let end = self.slide_end;
        inp.functions.push("ConstantFunction 1 f(t) 1.0".into());
        inp.functions.push(format!(
            "PiecewiseLinFunction 2 npoints 3 t 3 0 1 {end} f(t) 3 0 1 1"
        ));
        inp.functions.push(format!(
            "PiecewiseLinFunction 3 npoints 3 t 3 0 1 {end} f(t) 3 0 0 1"
        ));
    }
}

/// The Simo–Pister record with the small-strain moduli `e`, `nu` (g = G, k = Lamé's λ: the
/// compressible neo-Hookean W = G/2 (I₁ − 3) − G ln J + λ/2 (ln J)²).
pub fn simo_pister_with(number: usize, e: f64, nu: f64) -> String {
    let g = e / (2.0 * (1.0 + nu));
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    format!("simopistermat {number} d 0 g {g} k {lambda}")
}

/// Two equal spherical caps of [`HertzSphere`] (radius `HERTZ_R`) pressed together pole to pole,
/// quarter model: the upper cap as in [`HertzSphere`], the lower its mirror image in z = 0 with
/// its flat bottom held; the upper cap's top moved down by 2δ. By symmetry the interface stays
/// flat and the answer is that of one cap pressed by δ onto a rigid plane, which `rigid_plane`
/// builds instead (the plane z = 0, fixed). Slave: the upper cap's bottom within `HERTZ_NEAR`
/// of the axis; master: the lower cap's top faces, or the plane.
#[derive(Debug, Clone, Copy)]
pub struct TwoCaps {
    pub kind: Solid,
    pub h: f64,
    pub delta: f64,
    pub nlgeo: bool,
    pub law: Law,
    pub mortar: bool,
    pub rigid_plane: bool,
}

impl TwoCaps {
    pub fn input(&self) -> String {
        use super::mesh::graded;
        let mut inp = Input::default();
        let extra = format!("mat 1 crossSect 1 nlgeo {}", u8::from(self.nlgeo));
        let xc = graded(HERTZ_CAP, self.h, 1.5, 1.2);
        let zc = graded(HERTZ_CAP, self.h, 0.75, 1.2);
        let sphere = |p: &[f64; 3]| sphere_height(p[0], p[1]);
        let lower = (!self.rigid_plane).then(|| {
            let zl: Vec<f64> = zc.iter().rev().map(|d| -d).collect();
            let lower = inp.solid3d(self.kind, &xc, &xc, &zl, &extra, 0);
            bend_onto_sphere(&mut inp, lower.nodes.0..=lower.nodes.1, true);
            lower
        });
        let cap = inp.solid3d(self.kind, &xc, &xc, &zc, &extra, 0);
        bend_onto_sphere(&mut inp, cap.nodes.0..=cap.nodes.1, false);
        let near = |p: [f64; 3]| p[0].hypot(p[1]) <= HERTZ_NEAR;
        match &lower {
            Some(lower) => {
                let faces = inp.faces_where(lower, &|p| (p[2] + sphere(&p)).abs() < 1e-9);
                let seg = inp.boundary_set(&faces);
                inp.segments.push(format!(
                    "linear3delementsurfacecontactsegment 1 boundaryset {seg}"
                ));
            }
            None => inp
                .segments
                .push("planecontactsegment 1 point 3 0 0 0 normal 3 0 0 1".into()),
        }
        inp.sections.push("SimpleCS 1".into());
        inp.materials.push(if self.nlgeo {
            neo_hookean(1)
        } else {
            format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0")
        });
        let number = match &lower {
            Some(lower) => {
                rollers_and_push(&mut inp, &lower.bottom, &cap.top, 2.0 * self.delta);
                5
            }
            None => {
                rollers(&mut inp);
                let top = inp.node_set(&cap.top);
                inp.bcs.push(format!(
                    "BoundaryCondition 3 loadTimeFunction 1 dofs 1 3 values 1 {} set {top}",
                    -self.delta
                ));
                4
            }
        };
        let nodes: Vec<usize> = cap
            .bottom
            .iter()
            .copied()
            .filter(|&n| near(inp.nodes[n - 1]))
            .collect();
        contact(
            &mut inp,
            number,
            self.law,
            self.mortar,
            &cap,
            &nodes,
            &|p| near(p) && (p[2] - sphere(&p)).abs() < 1e-9,
        );
        inp.functions.push(history(&[1.0]));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("two_caps", &analysis(1), "3d")
    }
}

/// [`TwoCaps`] in plane strain: two equal cylinders (radius `HERTZ_R`, caps `HERTZ_CAP` wide and
/// high, half model about x = 0, 4-node quadrilaterals) pressed together, the upper one's top
/// moved down by δ plus the lower one's share of the approach, its bottom held. Slave: the upper
/// cap's bottom within `HERTZ_NEAR` of the axis.
#[derive(Debug, Clone, Copy)]
pub struct TwoCylinders {
    pub h: f64,
    pub delta: f64,
    pub law: Law,
    pub mortar: bool,
    pub lower: Lower,
}

/// The lower body of [`TwoCylinders`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lower {
    /// The mirror image of the upper cylinder, its modulus this many times the upper one's: it
    /// takes δ/s of the approach (geometry alike, so its displacements are the upper one's over s).
    Elastic(f64),
    /// The fixed rigid line y = 0: the equal bodies' flat interface.
    RigidPlane,
    /// The fixed rigid circle of radius `HERTZ_R` below y = 0: an infinitely stiff lower body.
    RigidCircle,
}

impl TwoCylinders {
    pub fn input(&self) -> String {
        use super::mesh::{graded, Kind};
        let mut inp = Input::default();
        let xc = graded(HERTZ_CAP, self.h, 1.5, 1.2);
        let hc = graded(HERTZ_CAP, self.h, 0.75, 1.2);
        let bottom = |x: f64| sphere_height(x, 0.0);
        let lower = matches!(self.lower, Lower::Elastic(_)).then(|| {
            inp.block2d(
                Kind::Q4,
                &xc,
                &|i| {
                    let yb = bottom(xc[i]);
                    hc.iter()
                        .rev()
                        .map(|t| -yb - t * (HERTZ_CAP - yb) / HERTZ_CAP)
                        .collect()
                },
                "mat 2 crossSect 1",
            )
        });
        let cap = inp.block2d(
            Kind::Q4,
            &xc,
            &|i| {
                let yb = bottom(xc[i]);
                hc.iter()
                    .map(|t| yb + t * (HERTZ_CAP - yb) / HERTZ_CAP)
                    .collect()
            },
            "mat 1 crossSect 1",
        );
        match &lower {
            Some(lower) => {
                let set = inp.boundary_set(&lower.top_edges);
                inp.segments
                    .push(format!("linear2delementedgecontactsegment 1 edgeset {set}"));
            }
            None if self.lower == Lower::RigidPlane => inp
                .segments
                .push("planecontactsegment 1 point 2 0 0 normal 2 0 1".into()),
            None => inp.segments.push(format!(
                "circlecontactsegment 1 centerpoint 2 0 {} radius {HERTZ_R}",
                -HERTZ_R
            )),
        }
        inp.sections.push("SimpleCS 1 thick 1.0".into());
        let stiff = match self.lower {
            Lower::Elastic(s) => s,
            _ => f64::INFINITY,
        };
        inp.materials
            .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
        if lower.is_some() {
            inp.materials
                .push(format!("IsoLE 2 d 0 E {} n {NU} tAlpha 0", E * stiff));
        }
        let x0 = inp.nodes_where(&|p| p[0].abs() < 1e-12);
        let x0 = inp.node_set(&x0);
        inp.bcs.push(format!(
            "BoundaryCondition 1 loadTimeFunction 2 dofs 1 1 values 1 0 set {x0}"
        ));
        let top = inp.node_set(&cap.top);
        let push = (1.0 + 1.0 / stiff) * self.delta;
        inp.bcs.push(format!(
            "BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 {} set {top}",
            -push
        ));
        if let Some(lower) = &lower {
            let held = inp.node_set(&lower.bottom);
            inp.bcs.push(format!(
                "BoundaryCondition 3 loadTimeFunction 2 dofs 1 2 values 1 0 set {held}"
            ));
        }
        let number = inp.bcs.len() + 1;
        let near: Vec<usize> = cap
            .bottom
            .iter()
            .zip(&xc)
            .filter(|(_, &x)| x <= HERTZ_NEAR)
            .map(|(&n, _)| n)
            .collect();
        if self.mortar {
            let edges: Vec<(usize, usize)> = cap
                .bottom_edges
                .iter()
                .zip(xc.windows(2))
                .filter(|(_, x)| x[1] <= HERTZ_NEAR + 1e-12)
                .map(|(&e, _)| e)
                .collect();
            let set = inp.boundary_set(&edges);
            inp.segments
                .push(format!("linear2delementedgecontactsegment 2 edgeset {set}"));
            inp.bcs.push(s2s(number, self.law));
        } else {
            inp.bcs.push(n2s(number, self.law, &near, &[1], ""));
        }
        inp.functions.push(history(&[1.0]));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("two_cylinders", &analysis(1), "PlaneStrain")
    }
}

/// The rings' inner surface (`nodes`, at r = `RING_A`) pushed out radially by `RING_PUSH`: one
/// condition per node (its own direction).
fn push_out_radially(inp: &mut Input, nodes: &[usize]) {
    for &n in nodes {
        let p = inp.nodes[n - 1];
        let set = inp.node_set(&[n]);
        let k = inp.bcs.len() + 1;
        inp.bcs.push(format!(
            "BoundaryCondition {k} loadTimeFunction 1 dofs 2 1 2 values 2 {} {} set {set}",
            RING_PUSH * p[0] / RING_A,
            RING_PUSH * p[1] / RING_A
        ));
    }
}

/// [`ConcentricRings`] in 3D: each ring `RING_DEPTH` deep in `layers` cells, every node held
/// in z (plane strain), in 10-node tetrahedra (QTRSpace, the Kuhn split) or 20-node bricks
/// (QSpace) whose faces on the arcs are curved (mid-side nodes on the circles); `inner` and
/// `outer` cells around the quarter, `radial` through each thickness. Mortar contact of the outer
/// ring's inner faces (slave, segment 2) on the inner ring's outer faces (segment 1). The
/// answer is the rings' Lamé cylinder ([`ConcentricRings::pressure`]).
#[derive(Debug, Clone, Copy)]
pub struct ConcentricCylinders {
    pub kind: Solid,
    pub inner: usize,
    pub outer: usize,
    pub radial: usize,
    pub layers: usize,
    pub law: Law,
}

/// The depth of [`ConcentricCylinders`].
pub const RING_DEPTH: f64 = 0.2;

impl ConcentricCylinders {
    pub fn input(&self) -> String {
        use std::f64::consts::FRAC_PI_2;
        let mut inp = Input::default();
        // One ring as a block over (r, θ, z), made quadratic, its contact faces at r = `at`,
        // then bent onto the circles (mid-side nodes at mid θ land on the arcs).
        let ring = |inp: &mut Input, r0: f64, r1: f64, nt: usize, at: f64| {
            let block = inp.solid3d(
                self.kind,
                &uniform(r0, r1, self.radial),
                &uniform(0.0, FRAC_PI_2, nt),
                &uniform(0.0, RING_DEPTH, self.layers),
                "mat 1 crossSect 1",
                0,
            );
            let mids = inp.make_quadratic(block.elements);
            let faces = inp.faces_where(&block, &|p| (p[0] - at).abs() < 1e-12);
            for n in (block.nodes.0..=block.nodes.1).chain(mids) {
                let [r, t, z] = inp.nodes[n - 1];
                inp.nodes[n - 1] = [r * t.cos(), r * t.sin(), z];
            }
            faces
        };
        let master = ring(&mut inp, RING_A, RING_B, self.inner, RING_B);
        let slave = ring(&mut inp, RING_B, RING_C, self.outer, RING_B);
        for (k, faces) in [master, slave].iter().enumerate() {
            let set = inp.boundary_set(faces);
            inp.segments.push(format!(
                "linear3delementsurfacecontactsegment {} boundaryset {set}",
                k + 1
            ));
        }
        inp.sections.push("SimpleCS 1".into());
        inp.materials
            .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
        let all: Vec<usize> = (1..=inp.nodes.len()).collect();
        let x0 = inp.nodes_where(&|p| p[0].abs() < 1e-12);
        let y0 = inp.nodes_where(&|p| p[1].abs() < 1e-12);
        for (k, (dof, nodes)) in [(1, x0), (2, y0), (3, all)].into_iter().enumerate() {
            let set = inp.node_set(&nodes);
            inp.bcs.push(format!(
                "BoundaryCondition {} loadTimeFunction 2 dofs 1 {dof} values 1 0 set {set}",
                k + 1
            ));
        }
        let inside = inp.nodes_where(&|p| (p[0].hypot(p[1]) - RING_A).abs() < 1e-9);
        push_out_radially(&mut inp, &inside);
        let k = inp.bcs.len() + 1;
        inp.bcs.push(s2s(k, self.law));
        inp.functions.push(history(&[1.0]));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("cylinders", &analysis(1), "3d")
    }
}

/// Two concentric elastic rings in plane strain, quarter model, 8-node quadrilaterals
/// (`QPlaneStrain`) with curved edges (mid-side nodes on the arcs): the inner ring a ≤ r ≤ b,
/// the outer one b ≤ r ≤ c, touching at r = b with non-matching meshes (`inner` and `outer`
/// elements around the quarter, two through each thickness). The inner surface r = a is pushed
/// out radially by `push`, the outer r = c is free, rollers on x = 0 and y = 0. Contact: the
/// outer ring's inner edges (slave) on the inner ring's outer edges, node-to-segment or mortar.
/// By continuity the answer is one Lamé cylinder a ≤ r ≤ c ([`ConcentricRings::pressure`]).
#[derive(Debug, Clone, Copy)]
pub struct ConcentricRings {
    pub inner: usize,
    pub outer: usize,
    pub law: Law,
    pub mortar: bool,
}

/// Radii a, b, c of [`ConcentricRings`] and the inner surface's radial displacement (2 % of a:
/// a hundred times the 2.2e-4 by which the coarsest mesh's quadratic arcs stray from the circle
/// r = b, which at 0.1 % of a made the pressure 150 % off there).
pub const RING_A: f64 = 1.0;
pub const RING_B: f64 = 1.5;
pub const RING_C: f64 = 2.0;
pub const RING_PUSH: f64 = 0.02;

impl ConcentricRings {
    /// The exact contact pressure at r = b (plane strain, E and ν of the verification bodies):
    /// u = A r + B/r with u(a) = push and σ_r(c) = 0, p = −σ_r(b).
    pub fn pressure() -> f64 {
        let mu = E / (2.0 * (1.0 + NU));
        let lambda = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
        let k = (lambda + mu) * RING_C * RING_C / mu;
        let a = RING_PUSH / (RING_A + k / RING_A);
        let b = k * a;
        2.0 * mu * b / (RING_B * RING_B) - 2.0 * (lambda + mu) * a
    }

    pub fn input(&self) -> String {
        use std::f64::consts::FRAC_PI_2;
        let mut inp = Input::default();
        // One ring: node ids on a (2·nr + 1) × (2·nt + 1) polar grid, elements, and its inner
        // and outer arc edges (element, edge).
        type Ring = (Vec<Vec<usize>>, Vec<(usize, usize)>, Vec<(usize, usize)>);
        let ring = |inp: &mut Input, r0: f64, r1: f64, nt: usize, mat: usize| -> Ring {
            let nr = 2;
            let mut id = vec![vec![0usize; 2 * nt + 1]; 2 * nr + 1];
            for (i, row) in id.iter_mut().enumerate() {
                let r = r0 + (r1 - r0) * i as f64 / (2 * nr) as f64;
                for (j, v) in row.iter_mut().enumerate() {
                    if i % 2 == 1 && j % 2 == 1 {
                        continue;
                    }
                    let t = FRAC_PI_2 * j as f64 / (2 * nt) as f64;
                    *v = inp.node(r * t.cos(), r * t.sin(), 0.0);
                }
            }
            let (mut inner, mut outer) = (Vec::new(), Vec::new());
            for i in 0..nr {
                for j in 0..nt {
                    let (i0, j0) = (2 * i, 2 * j);
                    let n = [
                        id[i0][j0],
                        id[i0 + 2][j0],
                        id[i0 + 2][j0 + 2],
                        id[i0][j0 + 2],
                        id[i0 + 1][j0],
                        id[i0 + 2][j0 + 1],
                        id[i0 + 1][j0 + 2],
                        id[i0][j0 + 1],
                    ];
                    let list: Vec<String> = n.iter().map(|v| v.to_string()).collect();
                    inp.elements.push(format!(
                        "QPlaneStrain {} nodes 8 {} mat {mat} crossSect 1",
                        inp.elements.len() + 1,
                        list.join(" ")
                    ));
                    let e = inp.elements.len();
                    if i == 0 {
                        inner.push((e, 4));
                    }
                    if i + 1 == nr {
                        outer.push((e, 2));
                    }
                }
            }
            (id, inner, outer)
        };
        let (inner_ids, _, inner_outer) = ring(&mut inp, RING_A, RING_B, self.inner, 1);
        let (outer_ids, outer_inner, _) = ring(&mut inp, RING_B, RING_C, self.outer, 1);
        let master = inp.boundary_set(&inner_outer);
        let slave = inp.boundary_set(&outer_inner);
        inp.segments.push(format!(
            "linear2delementedgecontactsegment 1 edgeset {master}"
        ));
        inp.segments.push(format!(
            "linear2delementedgecontactsegment 2 edgeset {slave}"
        ));
        inp.sections.push("SimpleCS 1 thick 1.0".into());
        inp.materials
            .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
        let x0 = inp.nodes_where(&|p| p[0].abs() < 1e-12);
        let y0 = inp.nodes_where(&|p| p[1].abs() < 1e-12);
        let (x0, y0) = (inp.node_set(&x0), inp.node_set(&y0));
        inp.bcs.push(format!(
            "BoundaryCondition 1 loadTimeFunction 2 dofs 1 1 values 1 0 set {x0}"
        ));
        inp.bcs.push(format!(
            "BoundaryCondition 2 loadTimeFunction 2 dofs 1 2 values 1 0 set {y0}"
        ));
        push_out_radially(&mut inp, &inner_ids[0]);
        let k = inp.bcs.len() + 1;
        if self.mortar {
            inp.bcs.push(s2s(k, self.law));
        } else {
            inp.bcs.push(n2s(k, self.law, &outer_ids[0], &[1], ""));
        }
        inp.functions.push(history(&[1.0]));
        inp.functions.push("ConstantFunction 2 f(t) 1.0".into());
        inp.render("rings", &analysis(1), "PlaneStrain")
    }
}

/// A block of 2 × 2 × 1 (E = 1000, ν = 0: no Poisson spread) in `n` × `n` × `layers` bricks on
/// a rigid plane, its top pressed down by 0.01 and then (a second step) pushed by 0.05 along
/// (0.6, 0.8), every one of its (n + 1)² bottom nodes a slave node of the contact record `law`
/// (numbered 3, before its `nodeset`); with `friction 0.3`, far beyond the stick limit: every
/// base node slides.
pub fn pushed_block(n: usize, layers: usize, law: &str) -> String {
    let mut inp = Input::default();
    let g = uniform(0.0, 2.0, n);
    let block = inp.block3d(&g, &g, &uniform(0.0, 1.0, layers), "mat 1 crossSect 1");
    inp.sections.push("SimpleCS 1".into());
    inp.materials.push("IsoLE 1 d 0 E 1000 n 0 tAlpha 0".into());
    inp.segments
        .push("planecontactsegment 1 point 3 0 0 0 normal 3 0 0 1".into());
    let top = inp.node_set(&block.top);
    let bottom: Vec<String> = block.bottom.iter().map(|n| n.to_string()).collect();
    inp.bcs.push(format!(
        "BoundaryCondition 1 loadTimeFunction 1 dofs 1 3 values 1 -0.01 set {top}"
    ));
    inp.bcs.push(format!(
        "BoundaryCondition 2 loadTimeFunction 2 dofs 2 1 2 values 2 0.03 0.04 set {top}"
    ));
    inp.bcs.push(format!(
        "{law} nodeset {} {} segmentset 1 1",
        bottom.len(),
        bottom.join(" ")
    ));
    inp.functions.push("ConstantFunction 1 f(t) 1.0".into());
    inp.functions
        .push("PiecewiseLinFunction 2 npoints 2 t 2 1 2 f(t) 2 0 1".into());
    inp.render(
        "pushed_block",
        "StaticStructural nsteps 2 rtolf 1e-10 maxiter 30",
        "3d",
    )
}

/// A rigid sphere of `radius` (`circlecontactsegment 1`, centred at (0, 0, radius), moved down
/// by `depth` through its own node) pressed into a quarter block of `kind` elements on `xs` × `xs`
/// × `zs` (E, NU; rollers on x = 0 and y = 0 below the sphere, the bottom held) by contact record
/// `law` (numbered 4).
pub struct RigidSphereBlock<'a> {
    pub kind: Solid,
    pub xs: Vec<f64>,
    pub zs: Vec<f64>,
    pub radius: f64,
    pub depth: f64,
    pub law: &'a str,
}

impl RigidSphereBlock<'_> {
    /// The scale issue's case: n × n × n bricks of 0.1 pressed 0.05 by a sphere of R = 10, every
    /// one of the (n + 1)² top nodes a node-to-segment slave node (`input`), as a user taking the
    /// whole face as the contact surface would (n = 30: 89 000 unknowns, 961 slave nodes), with
    /// multipliers or a penalty of 1e5.
    pub fn uniform(n: usize, multipliers: bool) -> RigidSphereBlock<'static> {
        let xs: Vec<f64> = (0..=n).map(|i| i as f64 * 0.1).collect();
        let zs: Vec<f64> = xs.iter().map(|x| x - n as f64 * 0.1).collect();
        RigidSphereBlock {
            kind: Solid::Hex,
            xs,
            zs,
            radius: 10.0,
            depth: 0.05,
            law: if multipliers {
                "n2slagrangianmultipliercontact 4 loadTimeFunction 1"
            } else {
                "n2spenaltycontact 4 loadTimeFunction 1 penalty 1e5"
            },
        }
    }

    /// [`Self::input`] pressed in ten steps and lifted in ten, on barred bricks (`LSpaceBB`), of
    /// a perfectly plastic `MisesMat` with yield stress `sig0`, or with `None` its elastic twin.
    pub fn pressed_and_lifted(&self, sig0: Option<f64>) -> String {
        let text = self.input();
        let lines = text.lines().map(|l| match l.split_whitespace().next() {
            Some("StaticStructural") => {
                "StaticStructural nsteps 20 deltat 1 rtolf 1e-8 maxiter 25".to_string()
            }
            Some("ndofman") => l.replace("nltf 1", "nltf 2"),
            Some("IsoLE") => match sig0 {
                Some(s) => format!("MisesMat 1 d 0 E {E} n {NU} sig0 {s} H 0 tAlpha 0"),
                None => l.to_string(),
            },
            Some("LSpace") => l.replacen("LSpace", "LSpaceBB", 1),
            Some("BoundaryCondition") if l.starts_with("BoundaryCondition 5 ") => {
                l.replace("loadTimeFunction 1", "loadTimeFunction 2")
            }
            Some("ConstantFunction") => {
                format!("{l}\nPiecewiseLinFunction 2 t 3 0 10 20 f(t) 3 0 1 0")
            }
            _ => l.to_string(),
        });
        lines.collect::<Vec<_>>().join("\n") + "\n"
    }

    /// Every top node a slave node (`slaveset`).
    pub fn input(&self) -> String {
        self.input_with("rigid_sphere_block", |inp, _| {
            let top = inp.nodes_where(&|p| p[2].abs() < 1e-12);
            (None, format!("slaveset {}", inp.node_set(&top)))
        })
    }

    /// The same problem in axisymmetry: the block's section x = 0 (r along `xs`, z along `zs`)
    /// as a body of revolution on `L4Axisymm` (a cylinder of the block's half-width, the same
    /// spacing under the sphere), every top node a slave node, u_r held on the axis.
    pub fn axisymmetric_section(&self) -> String {
        let r = self.radius;
        let mut inp = Input::default();
        let zs = self.zs.clone();
        let block = inp.block2d(Kind::Q4, &self.xs, &|_| zs.clone(), "mat 1 crossSect 1");
        for e in &mut inp.elements {
            *e = e.replacen("Quad1PlaneStrain", "L4Axisymm", 1);
        }
        let reference = inp.node(0.0, r, 0.0);
        inp.sections.push("SimpleCS 1".into());
        inp.materials
            .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
        inp.segments.push(format!(
            "circlecontactsegment 1 centerpoint 2 0 {r} radius {r} node {reference}"
        ));
        let axis = inp.nodes_where(&|p| p[0].abs() < 1e-12 && p[1] < r - 1.0);
        let axis = inp.node_set(&axis);
        let bottom = inp.node_set(&block.bottom);
        let top = inp.node_set(&block.top);
        let tool = inp.node_set(&[reference]);
        for (k, (dof, set)) in [(1, axis), (2, bottom)].iter().enumerate() {
            inp.bcs.push(format!(
                "BoundaryCondition {} loadTimeFunction 1 dofs 1 {dof} values 1 0 set {set}",
                k + 1
            ));
        }
        inp.bcs.push(format!(
            "BoundaryCondition 3 loadTimeFunction 1 dofs 2 1 2 values 2 0 {} set {tool}",
            -self.depth
        ));
        // The contact record is the fourth, as in 3D.
        inp.bcs
            .push(format!("{} slaveset {top} segmentset 1 1", self.law));
        inp.functions.push("ConstantFunction 1 f(t) 1.0".into());
        inp.render(
            "rigid_sphere_section",
            "StaticStructural nsteps 1 deltat 1 rtolf 1e-8 maxiter 25",
            "2dPlaneStress",
        )
    }

    /// The input titled `title`, whose slave side `slave` sets up on the block: it returns a
    /// segment record to add after the sphere's (or None) and the contact record's slave part.
    pub fn input_with(
        &self,
        title: &str,
        slave: impl FnOnce(&mut Input, &Block) -> (Option<String>, String),
    ) -> String {
        let r = self.radius;
        let mut inp = Input::default();
        let block = inp.solid3d(
            self.kind,
            &self.xs,
            &self.xs,
            &self.zs,
            "mat 1 crossSect 1",
            0,
        );
        let reference = inp.node(0.0, 0.0, r);
        inp.sections.push("SimpleCS 1".into());
        inp.materials
            .push(format!("IsoLE 1 d 0 E {E} n {NU} tAlpha 0"));
        let (segment, slave) = slave(&mut inp, &block);
        inp.segments.push(format!(
            "circlecontactsegment 1 centerpoint 3 0 0 {r} radius {r} node {reference}"
        ));
        inp.segments.extend(segment);
        let x0 = inp.nodes_where(&|p| p[0].abs() < 1e-12 && p[2] < r - 1.0);
        let y0 = inp.nodes_where(&|p| p[1].abs() < 1e-12 && p[2] < r - 1.0);
        let x0 = inp.node_set(&x0);
        let y0 = inp.node_set(&y0);
        let bottom = inp.node_set(&block.bottom);
        let tool = inp.node_set(&[reference]);
        for (k, (dof, set)) in [(1, x0), (2, y0), (3, bottom)].iter().enumerate() {
            inp.bcs.push(format!(
                "BoundaryCondition {} loadTimeFunction 1 dofs 1 {dof} values 1 0 set {set}",
                k + 1
            ));
        }
        inp.bcs.push(format!("{} {slave} segmentset 1 1", self.law));
        inp.bcs.push(format!(
            "BoundaryCondition 5 loadTimeFunction 1 dofs 3 1 2 3 values 3 0 0 {} set {tool}",
            -self.depth
        ));
        inp.functions.push("ConstantFunction 1 f(t) 1.0".into());
        inp.render(
            title,
            "StaticStructural nsteps 1 deltat 1 rtolf 1e-8 maxiter 25",
            "3d",
        )
    }
}

/// An O-ring (cross-section radius 1 about r = 3; half model z ≥ 0, u_z = 0 on z = 0) of
/// nearly incompressible neo-Hookean rubber (G = 1, K = 1000 G) on `Q4Axisymm` in large
/// deformation, squeezed 25 % by a rigid plate (`planecontactsegment`, moved down 0.25 in
/// `steps` steps), its arc's nodes node-to-segment with the mesh's penalty. The section is the
/// square [−1, 1] × [0, 1] of 2n × n elements mapped onto the half disk.
pub fn o_ring(n: usize, steps: usize) -> String {
    let (mu, mv) = (4 * n, 2 * n);
    let id = |i: usize, j: usize| i * (mv + 1) + j + 1;
    let on = |i: usize, j: usize| !(i % 2 == 1 && j % 2 == 1);
    let (mut nodes, mut arc, mut plane) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..=mu {
        for j in (0..=mv).filter(|&j| on(i, j)) {
            let (u, v) = (-1.0 + 2.0 * i as f64 / mu as f64, j as f64 / mv as f64);
            let (x, y) = (
                u * (1.0 - v * v / 2.0).sqrt(),
                v * (1.0 - u * u / 2.0).sqrt(),
            );
            nodes.push(format!("node {} coords 2 {} {}", id(i, j), 3.0 + x, y));
            if i == 0 || i == mu || j == mv {
                arc.push(id(i, j));
            }
            if j == 0 {
                plane.push(id(i, j));
            }
        }
    }
    let mut elements = Vec::new();
    for i in 0..2 * n {
        for j in 0..n {
            let c = |a: usize, b: usize| id(2 * i + a, 2 * j + b);
            elements.push(format!(
                "Q4Axisymm {} nodes 8 {} {} {} {} {} {} {} {} nlgeo 1",
                elements.len() + 1,
                c(0, 0),
                c(2, 0),
                c(2, 2),
                c(0, 2),
                c(1, 0),
                c(2, 1),
                c(1, 2),
                c(0, 1)
            ));
        }
    }
    let plate = id(mu, mv) + 1;
    let list = |v: &[usize]| {
        let s: Vec<String> = v.iter().map(|x| x.to_string()).collect();
        format!("{} {}", v.len(), s.join(" "))
    };
    format!(
        "oring.out\nO-ring\nStaticStructural nsteps {steps} rtolf 1e-8 maxiter 30\n\
         domain 2dPlaneStress\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 3 nic 0 nltf 2 nset 3 ncontactseg 1\n{}\n\
         node {plate} coords 2 3 1.5\n{}\n\
         planecontactsegment 1 point 2 3 1 normal 2 0 -1 node {plate}\n\
         SimpleCS 1 material 1 set 1\nMooneyRivlinCompressibleMat 1 d 0 c1 0.5 c2 0 k 1000\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 2 values 1 0 set 2\n\
         BoundaryCondition 2 loadTimeFunction 2 dofs 2 1 2 values 2 0 -0.25 set 3\n\
         n2spenaltycontact 3 loadTimeFunction 1 nodeset {} segmentset 1 1\n\
         ConstantFunction 1 f(t) 1\nPiecewiseLinFunction 2 t 2 0 {steps} f(t) 2 0 1\n\
         Set 1 elementranges {{(1 {})}}\nSet 2 nodes {}\nSet 3 nodes 1 {plate}\n",
        nodes.len() + 1,
        elements.len(),
        nodes.join("\n"),
        elements.join("\n"),
        list(&arc),
        elements.len(),
        list(&plane),
    )
}
