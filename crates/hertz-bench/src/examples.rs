//! The verification examples of `examples/`: each input generated from [`super::verify`] with a
//! header stating the problem, its reference solution and what hertz gets. `hertz bench
//! --examples DIR` writes them; a test checks that the committed files are these, and another
//! runs them against their references.

use super::mesh::Solid;
use super::suite::{cylinder_on_block, Law};
use super::verify::{
    neo_hookean_law, uniaxial_stress, ExtrudedCylinder, HertzSphere, Ironing, LargeSliding, Patch,
    ShallowIroning, TwoBeams, WedgeOnBrick, E, NU, PATCH_H,
};
use hertz::error::{Error, Result};
use std::path::{Path, PathBuf};

/// One example file: its name, title, header comment and generated input.
pub struct Example {
    pub file: &'static str,
    pub title: &'static str,
    pub header: String,
    input: String,
}

impl Example {
    /// The input with its output file named after it, the title as its second line and the
    /// header as `#` comments under it.
    pub fn text(&self) -> String {
        let lines = self.input.lines().skip(2);
        let stem = self.file.trim_end_matches(".in");
        let mut s = format!("{stem}.out\n{}\n", self.title);
        for l in self.header.lines() {
            s.push_str(if l.is_empty() { "#" } else { "# " });
            s.push_str(l);
            s.push('\n');
        }
        for l in lines {
            s.push_str(l);
            s.push('\n');
        }
        s
    }
}

/// Compression of the large-deformation patch test.
pub const PATCH_DELTA: f64 = 0.2;
/// Spacing under the contact of the sphere and extruded-cylinder examples.
pub const SPHERE_H: f64 = 0.2;
pub const CYLINDER_H: f64 = 0.2;
/// Force on each beam end of the two-beam example, and the press force of large sliding.
pub const BEAMS_FORCE: f64 = 1.0;
pub const SLIDING_FORCE: f64 = 20.0;

/// The ironing example's mesh and loading.
pub const IRONING: Ironing = Ironing {
    n_die: 40,
    nx: 40,
    ny: 6,
    press_steps: 10,
    slide: 4.0,
    mu: 0.3,
};

/// The shallow ironing example's mesh and loading (the published path: press 1 in ten steps,
/// slide 10; slide steps of 0.1).
pub const SHALLOW_IRONING: ShallowIroning = ShallowIroning {
    nx: 120,
    ny: 20,
    n_arc: 12,
    n_die: 4,
    slide_dt: 0.01,
    end: 2.0,
    mu: 0.3,
};

/// Every example, in the order of docs/verification.md's table.
pub fn all() -> Vec<Example> {
    let stretch = 1.0 - PATCH_DELTA / (2.0 * PATCH_H);
    let law = neo_hookean_law();
    let (lateral, nominal) = uniaxial_stress(&law, stretch);
    let p = -nominal;
    let sigma = p / (lateral * lateral);
    let (c1, k) = (law.c1, law.k);
    // The Hertz sphere of examples/hertz_sphere.in (node-to-face) and hertz_sphere_mortar.in.
    let sphere = HertzSphere {
        kind: Solid::Hex,
        sym: 0,
        h: SPHERE_H,
        delta: 0.15,
        nlgeo: false,
        law: Law::Multiplier,
        mortar: false,
    };
    vec![
        Example {
            file: "patch3d.in",
            title: "3D contact patch test, non-matching meshes, large deformation",
            header: format!(
                "Two neo-Hookean blocks [0,1]^2 x [-{h},0] (master, 2x2x2 bricks) and [0,1]^2 x [0,{h}]
(slave, 4x4x2 bricks: a nested, non-matching mesh) touching at z = 0; rollers on x = 0, y = 0
and the master's bottom; the slave's top moved down by {PATCH_DELTA} (20 % compression) in 4 steps.
Node-to-face contact with multipliers, the slave's bottom nodes on the master's top faces.
Exact solution: homogeneous uniaxial stress, axial stretch {stretch}; for mooneyrivlincompressiblemat
c1 = {c1:.6}, c2 = 0, k = {k:.6} the nominal pressure is P = {p:.10} at the lateral stretch
{lateral:.10} where the lateral nominal stress vanishes: each contact node carries P times its
reference tributary area, and its (true) contact pressure is P / {lateral:.6}^2 = {sigma:.10}.
hertz: every node's pressure equals {sigma:.10} to 1e-12, 2-3 Newton iterations per step
(tests/suite/examples.rs; all six face numbers, tets and wedges in tests/suite/contact3d.rs).
Run:  cargo run --release -- run examples/patch3d.in",
                h = PATCH_H
            ),
            input: Patch {
                kind: Solid::Hex,
                slave_kind: None,
                sym: 0,
                n: 2,
                nlgeo: true,
                delta: PATCH_DELTA,
                steps: 4,
                law: Law::Multiplier,
                slave_n: None,
                mortar: false,
            }
            .input(),
        },
        Example {
            file: "hertz_sphere.in",
            title: "Hertz: elastic sphere on an elastic block (3D, quarter model)",
            header: format!(
                "The cap (height 4, width 4) of an elastic sphere of radius R = 10 on an elastic block 6 x 6 x 6,
quarter model (symmetry planes x = 0 and y = 0), both E = {E}, nu = {NU}; bricks graded from
spacing {SPHERE_H} within r < 1.5 of the axis; the cap's flat top moved down by 0.15.
Node-to-face contact with multipliers: the cap's bottom nodes within r <= 1.6 on the block's top.
Analytical solution (Hertz, force F of the full sphere = 4 x the quarter's contact force):
  1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,  a = (3 F R/(4 E*))^(1/3),  p0 = 3 F/(2 pi a^2)
p0 is the pressure of the node on the axis, a the radius of the ellipse fitted to the active nodes.
hertz: p0 +0.05 %, a -0.87 % of Hertz for the computed F (bounds 3 % and 5 %, in every
orientation of the bricks: tests/suite/contact3d.rs).
Run:  cargo run --release -- run examples/hertz_sphere.in"
            ),
            input: sphere.input(),
        },
        Example {
            file: "hertz_sphere_mortar.in",
            title: "Hertz: elastic sphere on an elastic block with mortar contact (3D, quarter model)",
            header: format!(
                "examples/hertz_sphere.in with mortar (segment-to-segment) contact: the cap's bottom faces
within r <= 1.6 against the block's top faces, weighted gaps over their clipped overlaps and dual
(biorthogonal) multipliers; both E = {E}, nu = {NU}, bricks graded from spacing {SPHERE_H}.
Analytical solution (Hertz, force F of the full sphere = 4 x the quarter's contact force):
  1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,  a = (3 F R/(4 E*))^(1/3),  p0 = 3 F/(2 pi a^2)
p0 is the pressure of the node on the axis, a the radius of the ellipse fitted to the active nodes.
hertz: p0 +0.87 %, a -0.83 % of Hertz for the computed F, no pressure above p0 by more than
0.9 %, 1 iteration (tests/suite/mortar.rs: also wedges and tetrahedra, and the penalty from the mesh).
Run:  cargo run --release -- run examples/hertz_sphere_mortar.in"
            ),
            input: HertzSphere {
                mortar: true,
                ..sphere
            }
            .input(),
        },
        Example {
            file: "two_beams.in",
            title: "The seed's two beams in large-deformation two-pass contact",
            header: format!(
                "A lower beam [0,10] x [0,1] clamped at x = 0 and an upper beam [2,12] x [1.5,2.5] clamped at
x = 12, plane strain, neo-Hookean (E = {E}, nu = {NU}), large deformation, 40 x 4 elements each.
A force {BEAMS_FORCE} on each free end (spread over its nodes, 10 steps) bends them towards each other
until each end's corner presses on the other beam. Two node-to-segment conditions with the
roles swapped (two-pass), multipliers.
References: global equilibrium (the clamp reactions balance the applied forces to 1e-8),
point symmetry about the model's centre (the two beams' answers agree to 1e-8), and the
clamp force converging as h^2 with the mesh:
  elements 20 x 2: -0.599854,  40 x 4: -0.626077,  80 x 8: -0.632189
hertz: 2-4 Newton iterations per step (tests/suite/contact3d.rs).
Run:  cargo run --release -- run examples/two_beams.in"
            ),
            input: TwoBeams {
                nx: 40,
                ny: 4,
                nx_upper: None,
                force: BEAMS_FORCE,
                steps: 10,
                law: Law::Multiplier,
                two_pass: true,
            }
            .input(),
        },
        Example {
            file: "wedge_on_brick.in",
            title: "The seed's wedge pressed onto a brick (3D)",
            header: "One LSpace brick [0,1]^3 on rollers at its bottom (one corner pinned) and one LWedge
above it, its triangle (0.2,0.2), (0.8,0.3), (0.4,0.8) resting on the brick's top (z = 1) and
its top triangle at z = 1.5 moved down by 0.01 (held sideways). Node-to-face contact with
multipliers, the wedge's three bottom nodes on the brick's top face.
References: the reactions balance to 1e-8; the contact force equals the force on the wedge's
top (small strain: both along z); the brick's node order (each of its face numbers on top)
changes nothing to 1e-10; the penalty gives the same force within its error (1e-3).
Run:  cargo run --release -- run examples/wedge_on_brick.in"
                .to_string(),
            input: WedgeOnBrick {
                sym: 0,
                delta: 0.01,
                nlgeo: false,
                steps: 1,
                law: Law::Multiplier,
            }
            .input(),
        },
        Example {
            file: "cylinder2d.in",
            title: "Elastic cylinder on an elastic block, plane strain (the section of cylinder3d.in)",
            header: format!(
                "The cap (height 4, half-width 4) of an elastic cylinder of radius 20 on an elastic block
6 wide and 6 deep, half model (x >= 0), plane strain, both E = {E}, nu = {NU}, spacing
{CYLINDER_H} under the contact; the cap's top moved down by 0.022. Node-to-segment contact
with multipliers. The reference for cylinder3d.in (and Hertz: see hertz_cylinder.in).
Run:  cargo run --release -- run examples/cylinder2d.in"
            ),
            input: cylinder_on_block(CYLINDER_H, Law::Multiplier, false),
        },
        Example {
            file: "cylinder3d.in",
            title: "Elastic cylinder on an elastic block extruded in 3D, plane-strain constraints",
            header: format!(
                "cylinder2d.in's section extruded to a unit depth along y (2 bricks through the depth), every
node held in y: plane strain in 3D. Node-to-face contact with multipliers, the cap's bottom
nodes within x <= 1.2 on the block's top faces.
Reference: the force per unit depth equals the 2D node-to-segment force of cylinder2d.in.
hertz: equal to 1e-9 with multipliers, 1e-4 with a penalty, with the bricks numbered so
that each of their six face numbers is on the contact surfaces (tests/suite/contact3d.rs, at
spacing 0.1; this file uses {CYLINDER_H}).
Run:  cargo run --release -- run examples/cylinder3d.in"
            ),
            input: ExtrudedCylinder {
                sym: 0,
                h: CYLINDER_H,
                ny: 2,
                law: Law::Multiplier,
            }
            .input(),
        },
        Example {
            file: "large_sliding.in",
            title: "Large sliding in 2D: a block dragged over a curved master",
            header: format!(
                "A block 1 wide and 0.5 high (8 x 2 elements) pressed by a force {SLIDING_FORCE} onto a circular bump
of radius 10 (the top of a block 8 wide, 32 elements, highest at x = 4) and dragged by its
top from the summit by 2.5 in 25 steps, over ten master vertices, tilting by 15 degrees;
plane strain, neo-Hookean, large deformation, node-to-segment with multipliers.
Reference: frictionless contact, so the drag force is the press force times the slope of the
bump under the contact's centre; hertz: within 0.1 % at every step, Newton quadratic,
at most 3 iterations per step (tests/suite/contact3d.rs).
Run:  cargo run --release -- run examples/large_sliding.in"
            ),
            input: LargeSliding {
                nx: 32,
                travel: 2.5,
                force: SLIDING_FORCE,
                steps: 25,
                law: Law::Multiplier,
            }
            .input(),
        },
        Example {
            file: "ironing.in",
            title: "Ironing in 2D: a stiff die pressed into a soft slab and dragged along it, with friction",
            header: format!(
                "The plane-strain section of Puso and Laursen's ironing problem (2004): a half-ring die (radii 2.8
and 3.0, E = 1000) above a slab 9 x 3 (E = 1), both neo-Hookean (nu = 0.3), large deformation;
the die's lowest point 0.03 above the slab at x = -2.7; its two ends pressed down by 1.4 over
t in [0, 1] (10 steps), then moved along x by {slide} over t in [1, 5] (40 steps); the slab's
bottom held. Mortar contact with multipliers, the slab's top the slave side, mu = {mu}.
{n} x 1 die elements, {nx} x {ny} slab elements.
No closed form. Checks (tests/suite/friction.rs): the die's reaction balances the slab's, every
slipping slave node carries mu times its normal force, in sliding Fx/Fy > mu (friction plus
the slab pushed ahead of the die); every step converges without a cut-back.
hertz: Fy = 1.837 at t = 1 (slab meshes 20 x 3: 2.481, 60 x 8: 1.661); Fx/Fy 0.313-0.373 in
sliding (frictionless: 0.008 at t = 3); 2-4 Newton iterations per step, 10 at the onset of
sliding, 150 in all. The dual basis adapted to the overlap is what lets it run: with the
whole slave edge's basis, slab nodes near the die's ends took a false penetration and the
press failed at step 6. Force histories: hertz plot ironing.steps.csv --chart load --time
Run:  cargo run --release -- run examples/ironing.in",
                slide = IRONING.slide,
                mu = IRONING.mu,
                n = IRONING.n_die,
                nx = IRONING.nx,
                ny = IRONING.ny
            ),
            input: IRONING.input(),
        },
        Example {
            file: "o_ring.in",
            title: "An O-ring squeezed 25 % between rigid plates (axisymmetric, large deformation)",
            header: "An O-ring of cross-section radius 1 about r = 3 (axisymmetric: x = r, y = z, per radian),
half model z >= 0 (u_z = 0 on z = 0), nearly incompressible neo-Hookean rubber
(mooneyrivlincompressiblemat c1 = 0.5, c2 = 0, k = 1000: G = 1, K = 1000 G) on 8 x 4 Q4Axisymm
elements in large deformation, squeezed 25 % of its section by a rigid plate (planecontactsegment
moving with node 154, down 0.25 in 10 steps), the arc's nodes node-to-segment with the mesh's
penalty.
hertz: 3-5 iterations a step (8 in the last), no cut-back; det F within 8e-4 of 1 at every
point; the plate's force per radian 0.147, 0.330, ..., 2.96 (tests/suite/axisymmetry.rs).
Run:  cargo run --release -- run examples/o_ring.in
      cargo run --release -- plot examples/o_ring.out -c load   (force against the plate's travel)"
                .to_string(),
            input: super::verify::o_ring(4, 10),
        },
        Example {
            file: "shallow_ironing.in",
            title: "Shallow ironing (Yang, Laursen and Meng): published force range, with friction",
            header: format!(
                "The 2D shallow ironing benchmark (Yang, Laursen and Meng 2005; Fischer and Wriggers 2006;
Poulios and Renard 2015; Kratos' validation case), plane strain, mm and N/mm^2: a block
12 x 4 (E = 689.6), bottom held, and a die (E = 6896) whose lower face is an arc of radius
0.75 (chord 1.2, lowest point 0.2 above the block) under a rectangle; both neo-Hookean
(nu = 0.32, simopistermat with k = Lame's lambda: W = G/2 (I1 - 3) - G ln J + lambda/2 (ln J)^2).
The die's top pressed down by 1 over t in [0, 1] (10 steps), then moved along x by 10 (t - 1)
({slides} steps). Mortar contact with multipliers, the die's arc the slave side, mu = {mu}.
{nx} x {ny} block elements, {na} x {nd} die elements.
Published: vertical force at t = 1 in 268-332 N, Fx/Fy at t = 1.5 in 0.30-0.53.
hertz: Fy = 316.2 N at t = 1 (frictionless 309.6), Fx/Fy = 0.325 at t = 1.5 (block 80 x 14:
317.4 and 0.327; 60 x 10 with slide steps of 0.05: 318.6 and 0.324); 1-5 Newton iterations
per step up to t = 1.87, then 3-7 as the die nears the block's end, no cut-back. Checked in
tests/suite/friction.rs. Force histories: hertz plot shallow_ironing.steps.csv --chart load --time
Run:  cargo run --release -- run examples/shallow_ironing.in",
                slides = ((SHALLOW_IRONING.end - 1.0) / SHALLOW_IRONING.slide_dt).round(),
                mu = SHALLOW_IRONING.mu,
                nx = SHALLOW_IRONING.nx,
                ny = SHALLOW_IRONING.ny,
                na = SHALLOW_IRONING.n_arc,
                nd = SHALLOW_IRONING.n_die
            ),
            input: SHALLOW_IRONING.input(),
        },
    ]
}

/// Write every example into `dir`; the paths written.
pub fn write_all(dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| Error::Output(format!("cannot create {}: {e}", dir.display())))?;
    let mut out = Vec::new();
    for ex in all() {
        let path = dir.join(ex.file);
        hertz::output::write_atomic(&path, ex.text().as_bytes())?;
        out.push(path);
    }
    Ok(out)
}
