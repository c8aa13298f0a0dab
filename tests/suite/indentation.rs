//! Elastoplastic indentation: a rigid cylinder (radius 10, `circlecontactsegment`) pressed into
//! a von Mises block in plane strain, node-to-segment penalty, on the mesh of
//! `examples/hertz_rigid_circle.in` (h = 0.04 under the contact, the half-width about 0.4).

use crate::common;
use hertz::analytic::{contact_modulus, hertz_max_pressure};
use hertz::solve::run_analysis;

const RADIUS: f64 = 10.0;
const YOUNG: f64 = 1000.0;
const NU: f64 = 0.3;

/// The peak pressure p₀ at which a Hertz line contact first yields, over σ_y, and the depth of
/// that point over the half-width a: the largest von Mises stress on the axis x = 0 of the
/// plane-strain Hertz field (McEwen; Johnson, Contact Mechanics §4.2: σ_x = −p₀((1 + 2ζ²)/√(1 +
/// ζ²) − 2ζ), σ_z = −p₀/√(1 + ζ²), σ_y = ν(σ_x + σ_z), no shear on the axis, ζ = z/a), found by
/// golden-section search. ν = 0.3: p₀ = 1.7937 σ_y at z = 0.7043 a (Johnson's 1.79 and 0.70).
fn first_yield_of_a_line_contact(nu: f64) -> (f64, f64) {
    let mises = |z: f64| {
        let s = (1.0 + z * z).sqrt();
        let sx = -((1.0 + 2.0 * z * z) / s - 2.0 * z);
        let sz = -1.0 / s;
        let sy = nu * (sx + sz);
        (0.5 * ((sx - sy).powi(2) + (sy - sz).powi(2) + (sz - sx).powi(2))).sqrt()
    };
    let (mut lo, mut hi) = (0.0, 3.0);
    let phi = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..200 {
        let (a, b) = (hi - phi * (hi - lo), lo + phi * (hi - lo));
        if mises(a) > mises(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    let z = 0.5 * (lo + hi);
    (1.0 / mises(z), z)
}

/// A rigid-cylinder example (`example`: node-to-segment `hertz_rigid_circle.in` or mortar
/// `hertz_mortar.in`) with a `MisesMat` block of yield stress `sig0` (perfectly plastic) on
/// barred quadrilaterals, the cylinder moved down by `depths` (one step each, full Newton).
fn indentation_input(example: &str, sig0: f64, depths: &[f64]) -> String {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples")
            .join(example),
    )
    .unwrap();
    let deepest = depths.iter().copied().fold(0.0, f64::max);
    let t: Vec<String> = (0..=depths.len()).map(|k| k.to_string()).collect();
    let f: Vec<String> = std::iter::once(0.0)
        .chain(depths.iter().copied())
        .map(|d| (d / deepest).to_string())
        .collect();
    let n = depths.len() + 1;
    text.lines()
        .map(|l| {
            if l.starts_with("NonLinearStatic") {
                // StaticStructural: step k at t = k (NonLinearStatic starts at t = 0).
                format!("StaticStructural nsteps {} rtolf 1e-8 maxiter 40", n - 1)
            } else if l.starts_with("IsoLE") {
                format!("MisesMat 1 d 0 E {YOUNG} n {NU} sig0 {sig0} H 0 tAlpha 0")
            } else if l.starts_with("ndofman") {
                l.replace("nltf 1", "nltf 2")
            } else if l.starts_with("BoundaryCondition 3") {
                format!(
                    "BoundaryCondition 3 loadTimeFunction 2 dofs 2 1 2 values 2 0.0 {} set 4",
                    -deepest
                )
            } else if l.starts_with("ConstantFunction") {
                format!(
                    "{l}\nPiecewiseLinFunction 2 t {n} {} f(t) {n} {}",
                    t.join(" "),
                    f.join(" ")
                )
            } else if l.starts_with("Quad1PlaneStrain ") {
                l.replacen("Quad1PlaneStrain", "Quad1PlaneStrainBB", 1)
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// One step of an indentation: Hertz's p₀ of its force, how many elements have yielded, the
/// centre of the one with the largest κ (depth below the surface, distance from the axis), the
/// force F of the whole cylinder, the surface's displacement on the axis, the iterations and
/// substeps.
#[derive(Debug)]
struct Step {
    p0: f64,
    yielded: usize,
    most: (f64, f64),
    force: f64,
    surface: f64,
    iterations: usize,
    substeps: usize,
}

fn indent(example: &str, sig0: f64, depths: &[f64]) -> Vec<Step> {
    let model = common::model_from_text(&indentation_input(example, sig0, depths)).unwrap();
    let e_star = contact_modulus(YOUNG, NU, f64::INFINITY, 0.0);
    let top = (0..model.nodes.len())
        .find(|&n| model.nodes[n].coords[0] == 0.0 && model.nodes[n].coords[1] == 0.0)
        .unwrap();
    let mut steps = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        let force = 2.0 * r.contact.iter().map(|s| s.force).sum::<f64>();
        let (mut yielded, mut most, mut largest) = (0, (0.0, 0.0), 0.0);
        for (e, points) in r.states.iter().enumerate() {
            let kappa = points
                .iter()
                .filter_map(|p| p.plastic.as_ref().map(|s| s.kappa))
                .fold(0.0, f64::max);
            if kappa > 0.0 {
                yielded += 1;
            }
            if kappa > largest {
                largest = kappa;
                let nodes = &model.elements[e].nodes;
                let c = nodes.iter().fold([0.0; 2], |c, &n| {
                    let x = model.nodes[n].coords;
                    [c[0] + x[0], c[1] + x[1]]
                });
                let k = nodes.len() as f64;
                most = (-c[1] / k, c[0] / k);
            }
        }
        steps.push(Step {
            p0: hertz_max_pressure(force, RADIUS, e_star),
            yielded,
            most,
            force,
            surface: r.displacement(top, 2).unwrap(),
            iterations: r.info.iterations,
            substeps: r.info.substeps,
        });
        Ok(())
    })
    .unwrap();
    steps
}

/// The cylinder first yields the block where Johnson's criterion says: with σ_y = 11.7 the
/// predicted p₀ = 1.7937 σ_y = 20.99 is passed halfway through depths 0.020 … 0.040 (p₀ 16.2 …
/// 24.0 by Hertz of the force, 2.3 % a step). No point yields while p₀ < 0.97 of it, some have
/// yielded once p₀ > 1.03 of it, and the most strained point of the first plastic step lies on
/// the axis (within 0.25 a) at a depth of 0.6 to 0.8 a (0.7043 a predicted). Measured: the last
/// elastic step at p₀/σ_y = 1.7455, the first plastic one at 1.7860 (0.4 % below the
/// prediction), its largest κ at depth 0.26 = 0.68 a, 0.05 a off the axis; at most 3 iterations
/// a step (asserted: 5).
#[test]
fn a_rigid_cylinder_first_yields_the_block_at_johnsons_load_and_depth() {
    let (ratio, depth) = first_yield_of_a_line_contact(NU);
    assert!((ratio - 1.7937).abs() < 1e-4 && (depth - 0.7043).abs() < 1e-4);
    let sig0 = 11.7;
    let depths: Vec<f64> = (0..=16).map(|k| 0.020 + 0.00125 * k as f64).collect();
    let steps = indent("hertz_rigid_circle.in", sig0, &depths);
    let p_yield = ratio * sig0;
    for (k, s) in steps.iter().enumerate() {
        if s.p0 < 0.97 * p_yield {
            assert_eq!(s.yielded, 0, "step {}: {s:?}", k + 1);
        }
        if s.p0 > 1.03 * p_yield {
            assert!(s.yielded > 0, "step {}: p0 {}", k + 1, s.p0);
        }
        assert!(
            s.iterations <= 5,
            "step {}: {} iterations",
            k + 1,
            s.iterations
        );
    }
    let first = steps.iter().find(|s| s.yielded > 0).unwrap();
    let e_star = contact_modulus(YOUNG, NU, f64::INFINITY, 0.0);
    // a = 2R p₀/E* for a line contact.
    let a = 2.0 * RADIUS * first.p0 / e_star;
    let (z, x) = first.most;
    assert!(
        z > 0.6 * a && z < 0.8 * a && x < 0.25 * a,
        "{z} {x}, a = {a}"
    );
}

/// examples/indentation.in: the cylinder pressed 0.15 into a perfectly plastic block (σ₀ = 5,
/// H = 0) in ten steps and lifted back in ten. Each step converges without a cut-back in at most
/// 10 iterations (the deepest took 40 and a cut-back before Newton halved the steps that raise
/// the residual where a material yields). At the deepest step the mean pressure F/(2a) lies between
/// 2 σ₀ and the rigid-plastic flat punch's (2 + π) σ₀/√3 = 2.97 σ₀ (an elastic–plastic contact
/// stays below the fully plastic limit; a locking mesh exceeds it). On lifting, the contact
/// opens before the cylinder is back, and the block keeps an imprint: the surface on the axis
/// stays below its start by more than a third of the deepest indentation and by less than the
/// cylinder's position at the last step with contact; the plastic strain stays. Measured: 4 to 9
/// iterations a step loading, 1 or 2 unloading; mean pressure 2.33 σ₀; the contact opens between
/// depths 0.105 and 0.090, the imprint 0.0945 deep; largest κ 0.085 at the deepest step and
/// after (the unloading is elastic).
#[test]
fn an_indentation_leaves_a_residual_imprint() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/indentation.in");
    let model = hertz::input::read_model(&path).unwrap().model;
    let top = (0..model.nodes.len())
        .find(|&n| model.nodes[n].coords[0] == 0.0 && model.nodes[n].coords[1] == 0.0)
        .unwrap();
    let (sig0, delta) = (5.0, 0.15);
    let steps = pressed_and_lifted(&model, 2.0, |x| x[0], (top, 2));
    assert_eq!(steps.len(), 20);
    for (k, s) in steps.iter().enumerate() {
        assert!(s.4 <= 10 && s.5 == 1, "step {}: {s:?}", k + 1);
    }
    let (force, a, kappa, ..) = steps[9];
    let mean = force / (2.0 * a) / sig0;
    let limit = (2.0 + std::f64::consts::PI) / 3f64.sqrt();
    assert!(mean > 2.0 && mean < limit, "mean pressure {mean} sigma0");
    let last_contact = steps.iter().rposition(|s| s.0 > 0.0).unwrap();
    assert!(
        last_contact < 19,
        "the contact opens before the cylinder is back"
    );
    // The cylinder's depth at step k + 1 (down in 10 steps, up in 10).
    let depth = |k: usize| {
        delta
            * if k < 10 {
                (k + 1) as f64
            } else {
                (19 - k) as f64
            }
            / 10.0
    };
    let (_, _, kappa_end, imprint, ..) = steps[19];
    assert!(
        -imprint > delta / 3.0 && -imprint < depth(last_contact),
        "{imprint}"
    );
    assert!(kappa_end >= kappa, "{kappa_end} {kappa}");
}

/// Node-to-segment penalty and mortar multipliers indent the perfectly plastic block alike: the
/// cylinder pressed 0.15 in ten steps and lifted in ten (σ₀ = 5), each step without a cut-back
/// in at most 12 iterations (measured: 4 to 9 node-to-segment, 4 to 10 mortar, the most at the
/// deepest step); the deepest step's force and the residual imprint agree to 1e-3 (measured:
/// 4.5e-5 and 1.3e-4).
#[test]
fn node_to_segment_and_mortar_leave_the_same_imprint() {
    let depths: Vec<f64> = (1..=20)
        .map(|k| 0.015 * if k <= 10 { k } else { 20 - k } as f64)
        .collect();
    let n2s = indent("hertz_rigid_circle.in", 5.0, &depths);
    let mortar = indent("hertz_mortar.in", 5.0, &depths);
    for (name, steps) in [("n2s", &n2s), ("mortar", &mortar)] {
        assert_eq!(steps.len(), 20);
        for (k, s) in steps.iter().enumerate() {
            assert!(
                s.iterations <= 12 && s.substeps == 1,
                "{name} step {}: {s:?}",
                k + 1
            );
        }
    }
    let force = mortar[9].force / n2s[9].force - 1.0;
    let imprint = mortar[19].surface / n2s[19].surface - 1.0;
    assert!(
        force.abs() < 1e-3 && imprint.abs() < 1e-3,
        "{force} {imprint}"
    );
}

/// A rigid sphere (R = 10) pressed 0.05 into a perfectly plastic quarter block of 10³ barred
/// bricks (σ₀ = 10, node-to-face penalty, `hertz bench --rigid-sphere 10 --plastic 10`) and
/// lifted: no cut-back and at most 6 iterations a step; the deepest step's mean pressure
/// F/(πa²) between first yield's (⅔ · 1.61 σ₀ = 1.07 σ₀) and the fully plastic limit (Tabor's
/// 2.8 σ₀, asserted below 3 σ₀); after lift-off the contact is open, the imprint stays and so
/// does the plastic strain. Measured: at most 5 iterations a step, F/(πa²) = 1.26 σ₀ at
/// a = 0.86 (the last closed node's radius; E a/(σ₀ R) = 8.6, the elastic–plastic range of
/// indentation), an imprint 0.038 deep on the axis after lift-off from 0.05.
#[test]
fn a_rigid_sphere_indents_a_plastic_block_in_3d() {
    let sig0 = 10.0;
    let text =
        hertz_bench::verify::RigidSphereBlock::uniform(10, false).pressed_and_lifted(Some(sig0));
    let model = common::model_from_text(&text).unwrap();
    let top = (0..model.nodes.len())
        .find(|&n| model.nodes[n].coords == [0.0, 0.0, 0.0])
        .unwrap();
    let steps = pressed_and_lifted(&model, 4.0, |x| x[0].hypot(x[1]), (top, 3));
    assert_eq!(steps.len(), 20);
    for (k, s) in steps.iter().enumerate() {
        assert!(s.4 <= 6 && s.5 == 1, "step {}: {s:?}", k + 1);
    }
    let (force, a, kappa, ..) = steps[9];
    let mean = force / (std::f64::consts::PI * a * a) / sig0;
    assert!(mean > 1.07 && mean < 3.0, "mean pressure {mean} σ₀");
    let (force_end, _, kappa_end, imprint, ..) = steps[19];
    assert!(
        force_end == 0.0 && imprint < 0.0 && kappa_end == kappa,
        "{:?}",
        steps[19]
    );
}

/// Every step of a pressed-and-lifted indentation: the indenter's force (`parts` times the
/// modelled part's contact forces), the last closed node's distance from the axis (`radius` of
/// its coordinates), the largest κ, the displacement of node `top` along DOF `dof`, the
/// iterations and the substeps.
fn pressed_and_lifted(
    model: &hertz::model::Model,
    parts: f64,
    radius: fn([f64; 3]) -> f64,
    (top, dof): (usize, u8),
) -> Vec<(f64, f64, f64, f64, usize, usize)> {
    let mut steps = Vec::new();
    run_analysis(model, &common::quiet(), |r| {
        let force = parts * r.contact.iter().map(|s| s.force).sum::<f64>();
        let a = r
            .contact
            .iter()
            .filter(|s| s.active)
            .map(|s| radius(model.nodes[s.node].coords))
            .fold(0.0, f64::max);
        let kappa = r
            .states
            .iter()
            .flatten()
            .filter_map(|p| p.plastic.as_ref().map(|s| s.kappa))
            .fold(0.0, f64::max);
        let surface = r.displacement(top, dof).unwrap();
        steps.push((force, a, kappa, surface, r.info.iterations, r.info.substeps));
        Ok(())
    })
    .unwrap();
    steps
}
