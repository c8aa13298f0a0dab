//! Coulomb friction against analytical answers: the sliding threshold of a pressed block
//! (examples/coulomb_block.in, Code_Aster SSNV503 style), the force a sliding block transmits,
//! and the friction history restored when a step is cut back.

use crate::common;

use hertz::solve::{run_analysis, SolveParams};
use hertz_bench::suite::plate_drawn_on_a_block;
use std::path::Path;

const MU: f64 = 0.3;
const N: f64 = 10.0;

fn example() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/coulomb_block.in"))
        .unwrap()
}

/// How the example's contact is solved.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Method {
    /// Node-to-segment, penalty (the example as written).
    Penalty,
    /// Mortar, penalty.
    Mortar,
    /// Node-to-segment with Lagrange multipliers for the normal and the friction force.
    Multipliers,
    /// Mortar with Lagrange multipliers for the pressure and the friction traction.
    MortarMultipliers,
}

const METHODS: [Method; 4] = [
    Method::Penalty,
    Method::Mortar,
    Method::Multipliers,
    Method::MortarMultipliers,
];

impl Method {
    /// The example (or a variant of it) solved with this method.
    fn form(self, text: &str) -> String {
        match self {
            Method::Penalty => text.to_string(),
            Method::Mortar => as_mortar(text),
            Method::Multipliers => text.replace(
                "n2spenaltycontact 5 loadTimeFunction 1 penalty 1e5 friction 0.3 pt 1e5",
                "n2slagrangianmultipliercontact 5 loadTimeFunction 1 friction 0.3",
            ),
            Method::MortarMultipliers => as_mortar(text).replace(
                "s2spenaltycontact 5 loadTimeFunction 1 penalty 1e5 friction 0.3 pt 1e5",
                "s2slagrangianmultipliercontact 5 loadTimeFunction 1 friction 0.3",
            ),
        }
    }
}

/// The example with mortar contact instead of node-to-segment: the block's bottom edges
/// (segment 2) against the plane, the same penalties (per unit length instead of per node).
fn as_mortar(text: &str) -> String {
    text.replace("ncontactseg 1", "ncontactseg 2")
        .replace("nset 3", "nset 4")
        .replace(
            "planecontactsegment 1 point 2 0 0 normal 2 0 1",
            "planecontactsegment 1 point 2 0 0 normal 2 0 1\n\
             linear2delementedgecontactsegment 2 edgeset 4",
        )
        .replace(
            "n2spenaltycontact 5 loadTimeFunction 1 penalty 1e5 friction 0.3 pt 1e5 nodeset 5 1 2 3 4 5 segmentset 1 1",
            "s2spenaltycontact 5 loadTimeFunction 1 penalty 1e5 friction 0.3 pt 1e5 slavesegment 2 segmentset 1 1",
        )
        + "Set 4 elementboundaries 8 1 1 2 1 3 1 4 1\n"
}

/// The example with the tangential force T = `factor`·μN (nodal forces of the top).
fn pushed_by(factor: f64) -> String {
    let t = factor * MU * N;
    example()
        .replace(
            "components 2 0.37125 0.0 set 2",
            &format!("components 2 {} 0.0 set 2", t / 8.0),
        )
        .replace(
            "components 2 0.7425 0.0 set 3",
            &format!("components 2 {} 0.0 set 3", t / 4.0),
        )
}

struct Outcome {
    /// Per step: the horizontal displacement of the block's bottom-left node.
    slide: Vec<f64>,
    /// Per step: the summed horizontal reaction of the prescribed DOFs.
    reaction_x: Vec<f64>,
    /// Per step: Newton iterations.
    iterations: Vec<usize>,
    /// Per step: the number of contact nodes that stick.
    sticking: Vec<usize>,
}

fn solve(text: &str, params: &SolveParams) -> hertz::error::Result<Outcome> {
    let model = common::model_from_text(text).unwrap();
    let mut out = Outcome {
        slide: vec![],
        reaction_x: vec![],
        iterations: vec![],
        sticking: vec![],
    };
    run_analysis(&model, params, |r| {
        out.slide.push(r.displacement(0, 1).unwrap());
        out.reaction_x.push(
            r.dofs
                .prescribed
                .iter()
                .zip(r.reactions)
                .filter(|((_, d, _), _)| *d == 1)
                .map(|(_, &f)| f)
                .sum(),
        );
        out.iterations.push(r.info.iterations);
        out.sticking.push(
            r.contact
                .iter()
                .filter(|s| s.friction.is_some_and(|f| f.0))
                .count(),
        );
        Ok(())
    })?;
    Ok(out)
}

/// Below μN the block holds (its slide is the tangential penalty's elastic slip, T/pt per unit
/// length of the base, far below a millimetre-scale motion); above it no equilibrium exists and
/// the step fails even after halving.
/// The same with mortar contact (the bottom-left node ends at 2.9e-6 with the penalty; with the
/// hat functions instead of the dual basis its friction, resisting the base's Poisson spread,
/// was spread over its neighbour and the corner slipped in step 1, to −7.6e-5). With multipliers
/// there is no elastic slip and the corner sticks where it started (to 1.5e-13 with mortar).
#[test]
fn block_sticks_below_mu_n_and_slides_above() {
    for method in METHODS {
        let below = solve(&method.form(&pushed_by(0.99)), &common::quiet()).unwrap();
        let elastic_slip = 0.99 * MU * N / (1e5 * 2.0);
        println!(
            "{method:?}: T = 0.99 mu N: slide {:.6e} (elastic slip T/(pt L) = \
             {elastic_slip:.6e}), {:?} iterations",
            below.slide[1], below.iterations
        );
        if method == Method::Multipliers {
            assert!(below.slide[1].abs() < 1e-14, "{}", below.slide[1]);
        } else {
            assert!(below.slide[1].abs() < 20.0 * elastic_slip);
        }
        assert!(
            below.iterations.iter().all(|&i| i <= 6),
            "{:?}",
            below.iterations
        );
        let above = solve(&method.form(&pushed_by(1.01)), &common::quiet());
        let err = above.err().expect("no equilibrium above mu N").to_string();
        assert!(err.contains("step 2"), "{err}");
    }
}

/// Pushed by a prescribed displacement of its top, once every node slides the block transmits
/// exactly μN: Σ μ·p_N,i with Σ p_N,i = N. Also in large deformation with mortar contact (its
/// slip measured on the current segmentation): 4 iterations with the penalty and with
/// multipliers. (The step's predictor is the linear response of the pressed block to a push 20
/// times its stick limit: it tilts the block about its front corner, a geometric error in large
/// deformation that the next iterations undo. Pushed in four steps: 3, 3, then 1 per step.)
#[test]
fn sliding_block_transmits_mu_n() {
    for method in METHODS {
        sliding_block(method, false);
    }
    for method in [Method::Mortar, Method::MortarMultipliers] {
        sliding_block(method, true);
    }
}

fn sliding_block(method: Method, nlgeo: bool) {
    let text = example()
        .replace(
            "NodalLoad 3 loadTimeFunction 2 dofs 2 1 2 components 2 0.37125 0.0 set 2",
            "BoundaryCondition 3 loadTimeFunction 2 dofs 1 1 values 1 0.05 set 2",
        )
        .replace(
            "NodalLoad 4 loadTimeFunction 2 dofs 2 1 2 components 2 0.7425 0.0 set 3",
            "BoundaryCondition 4 loadTimeFunction 2 dofs 1 1 values 1 0.05 set 3",
        );
    let mut text = method.form(&text);
    if nlgeo {
        text = text.replace("crossSect 1 mat 1", "crossSect 1 mat 1 nlgeo 1");
    }
    let out = solve(&text, &common::quiet()).unwrap();
    println!(
        "{method:?} nlgeo {nlgeo}: pushed 0.05: transmitted {:.15} (mu N = {}), {} nodes stick, {:?} iterations",
        -out.reaction_x[1],
        MU * N,
        out.sticking[1],
        out.iterations
    );
    assert_eq!(out.sticking[1], 0, "every node slides");
    assert!(
        (out.reaction_x[1].abs() - MU * N).abs() < 1e-10 * MU * N,
        "{}",
        out.reaction_x[1]
    );
    assert!(
        out.iterations.iter().all(|&i| i <= 6),
        "{:?}",
        out.iterations
    );
}

/// A step cut back restarts from the friction history of the last converged step: run with too
/// few iterations allowed, step 2 (T = 0.99 μN, partial slip) is halved until it converges in S
/// substeps; the same S increments given as steps of their own (iterations to spare) end in the
/// same state. Were the history of a failed attempt's converged substeps kept, the anchors
/// would start ahead of the block and the path-dependent stick state would differ.
/// With node-to-segment and mortar penalty contact (at most 2 iterations: 8 substeps), and with
/// multipliers on the Cattaneo–Mindlin problem (at most 3 iterations: 4 substeps). The block
/// with multipliers is piecewise linear and solved in as many iterations as the stick/slip sets
/// take to settle, the same in the last substep, which holds the last node's onset of slip, as
/// in the whole step: starved, it never converges.
#[test]
fn a_cut_back_step_restarts_from_the_converged_friction_history() {
    for method in [Method::Penalty, Method::Mortar] {
        let text = method.form(&pushed_by(0.99));
        cut_back(
            &format!("{method:?}"),
            &text.replace("maxiter 30", "maxiter 2"),
            &text,
            1e-12,
        );
    }
    let text = cattaneo_mindlin(Method::Multipliers);
    cut_back(
        "Multipliers",
        &text.replace("maxiter 30", "maxiter 3"),
        &text,
        1e-9,
    );
}

/// Run `starved` (step 2 cut back) and `text` with step 2's substeps as steps; compare the
/// first node's horizontal displacement and the contact nodes' (to `tol` relative) and the
/// contact states.
fn cut_back(label: &str, starved: &str, text: &str, tol: f64) {
    let mut substeps = 0;
    let model = common::model_from_text(starved).unwrap();
    let mut slide_cut = f64::NAN;
    let mut states_cut = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        if r.step == 2 {
            substeps = r.info.substeps;
            slide_cut = r.displacement(0, 1).unwrap();
            states_cut = r
                .contact
                .iter()
                .map(|s| (s.force, s.friction, s.x[0]))
                .collect();
        }
        Ok(())
    })
    .unwrap();
    assert!(substeps > 1, "step 2 was cut back ({substeps} substeps)");
    let stepped = text
        .replace("nsteps 2", &format!("nsteps {}", 1 + substeps))
        .replace(
            "PiecewiseLinFunction 2 npoints 2 t 2 1 2 f(t) 2 0 1",
            &format!(
                "PiecewiseLinFunction 2 npoints 2 t 2 1 {} f(t) 2 0 1",
                1 + substeps
            ),
        );
    let model = common::model_from_text(&stepped).unwrap();
    let mut slide = f64::NAN;
    let mut states = Vec::new();
    let mut slips: Vec<f64> = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        slide = r.displacement(0, 1).unwrap();
        states = r
            .contact
            .iter()
            .map(|s| (s.force, s.friction, s.x[0]))
            .collect();
        slips = r
            .contact
            .iter()
            .map(|s| s.x[0] - model.nodes[s.node].coords[0])
            .collect();
        Ok(())
    })
    .unwrap();
    println!("{label}: cut back into {substeps} substeps: slide {slide_cut:.15e}; as steps: {slide:.15e}");
    assert!(
        (slide_cut - slide).abs() <= tol * slide.abs(),
        "{slide_cut} vs {slide}"
    );
    let scale = states.iter().map(|s| s.0).fold(0.0, f64::max);
    let motion = slips.iter().map(|u| u.abs()).fold(0.0, f64::max);
    assert!(motion > 0.0);
    for (a, b) in states_cut.iter().zip(&states) {
        assert!((a.0 - b.0).abs() <= tol.max(1e-9) * scale, "{a:?} vs {b:?}");
        assert!((a.2 - b.2).abs() <= tol * motion, "{a:?} vs {b:?}");
        match (a.1, b.1) {
            (Some(fa), Some(fb)) => {
                assert_eq!(fa.0, fb.0, "stick state");
                assert!(
                    (fa.1 - fb.1).abs() <= tol.max(1e-9) * scale,
                    "{a:?} vs {b:?}"
                );
            }
            (fa, fb) => assert_eq!(fa.is_some(), fb.is_some(), "{a:?} vs {b:?}"),
        }
    }
}

/// examples/cattaneo_mindlin.in solved with `method` (node-to-segment: penalty or multipliers).
fn cattaneo_mindlin(method: Method) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/cattaneo_mindlin.in");
    let text = std::fs::read_to_string(path).unwrap();
    match method {
        Method::Multipliers => text.replace(
            "n2spenaltycontact 4 loadTimeFunction 1 penalty 1e+07 friction 0.3",
            "n2slagrangianmultipliercontact 4 loadTimeFunction 1 friction 0.3",
        ),
        _ => text,
    }
}

/// Cattaneo–Mindlin (examples/cattaneo_mindlin.in): an elastic cylinder pressed on an elastic
/// block of the same material, then sheared by Q < μP. The stick zone's half-width is
/// c = a·√(1 − Q/(μP)) within one element, and the tangential traction follows
/// q(x) = μp0·√(1 − x²/a²) − μp0·(c/a)·√(1 − x²/c²) in the stick zone, μ·p(x) outside, within
/// 4 % of μp0 (away from the cusp at ±c, where it changes over one element).
#[test]
fn cattaneo_mindlin_stick_zone_and_traction() {
    for method in [Method::Penalty, Method::Multipliers] {
        cattaneo_mindlin_check(method);
    }
}

fn cattaneo_mindlin_check(method: Method) {
    const H: f64 = 0.02;
    let model = common::model_from_text(&cattaneo_mindlin(method)).unwrap();
    let mut last = (0.0, 0.0, Vec::new());
    let mut iterations = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        // P and Q: the reactions of the cap's top (vertical, horizontal).
        let sum = |dof: u8| -> f64 {
            r.dofs
                .prescribed
                .iter()
                .zip(r.reactions)
                .filter(|((n, d, _), _)| *d == dof && model.nodes[*n].coords[1] > 5.0)
                .map(|(_, &f)| f)
                .sum()
        };
        last = (-sum(2), sum(1), r.contact.to_vec());
        iterations.push(r.info.iterations);
        Ok(())
    })
    .unwrap();
    let (p, q, states) = last;
    let e_star = 1000.0 / (2.0 * (1.0 - 0.3f64 * 0.3));
    let a = (4.0 * p * 20.0 / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * p / (std::f64::consts::PI * a);
    let c = a * (1.0 - q / (MU * p)).sqrt();
    let closed: Vec<_> = states.iter().filter(|s| s.active).collect();
    let stick: Vec<f64> = closed
        .iter()
        .filter(|s| s.friction.unwrap().0)
        .map(|s| s.x[0])
        .collect();
    let lo = stick.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = stick.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let c_fe = 0.5 * (hi - lo);
    let friction_sum: f64 = closed.iter().map(|s| s.friction.unwrap().1).sum();
    let mut worst = 0.0f64;
    for s in &closed {
        let x = s.x[0];
        if x.abs() > 0.9 * a || (x.abs() - c).abs() < 2.0 * H {
            continue;
        }
        let traction = s.friction.unwrap().1 * s.pressure / s.force;
        let mut exact = MU * p0 * (1.0 - (x / a).powi(2)).max(0.0).sqrt();
        if x.abs() < c {
            exact -= MU * p0 * (c / a) * (1.0 - (x / c).powi(2)).sqrt();
        }
        worst = worst.max((traction - exact).abs() / (MU * p0));
    }
    println!(
        "Cattaneo-Mindlin, {method:?}: P {p:.5}, Q {q:.5} (Q/muP {:.3}), a {a:.4}, c {c:.4}, stick zone [{lo:.4}, {hi:.4}] \
         half-width {c_fe:.4}; traction off by {:.2} % of mu p0; iterations {iterations:?}",
        q / (MU * p),
        100.0 * worst
    );
    assert!((0.3..0.7).contains(&(q / (MU * p))), "Q/μP");
    assert!((c_fe - c).abs() <= H, "stick zone {c_fe} vs {c}");
    assert!(worst < 0.04, "traction {worst}");
    assert!((friction_sum - q).abs() < 1e-6 * q, "{friction_sum} vs {q}");
    assert!(iterations.iter().all(|&i| i <= 6), "{iterations:?}");
}

/// The pressure and shear of the frictional patch test ([`common::sheared_blocks`]).
const PATCH_P: f64 = 10.0;
const PATCH_TAU: f64 = 2.0;

/// The worst deviation of (σ_xx, σ_yy, σ_xy) (Voigt 0, 1, 5) from (0, −p, τ) over every
/// integration point and
/// of the active slots' friction tractions from τ, relative to p, and the iterations.
fn shear_patch_errors(text: &str) -> (f64, f64, usize) {
    let model = common::model_from_text(text).unwrap();
    let (mut stress, mut traction, mut its) = (f64::NAN, f64::NAN, 0);
    run_analysis(&model, &common::quiet(), |r| {
        stress = r
            .states
            .iter()
            .flatten()
            .map(|g| {
                let s = &g.stress;
                s[0].abs()
                    .max((s[1] + PATCH_P).abs())
                    .max((s[5] - PATCH_TAU).abs())
                    / PATCH_P
            })
            .fold(0.0, f64::max);
        traction = r
            .contact
            .iter()
            .filter(|s| s.active)
            .map(|s| {
                let (stick, f) = s.friction.expect("friction at a closed slot");
                assert!(stick, "τ < μp: every slot sticks");
                (f * s.pressure / s.force - PATCH_TAU).abs() / PATCH_P
            })
            .fold(0.0, f64::max);
        its = r.info.iterations;
        Ok(())
    })
    .unwrap();
    (stress, traction, its)
}

/// The frictional contact patch test: two blocks with non-matching meshes pressed by p and
/// sheared by τ < μp stick with the uniform stress (0, −p, τ) at every integration point and the
/// friction traction τ at every slave node, to round-off, with mortar contact (a penalty given
/// or from the mesh, or multipliers); node-to-segment friction on the same meshes misses it by percent (and
/// converges in a few iterations: on 10/7 its first step once went astray, a node anchored at a
/// parameter that does not round-trip exactly taking a round-off slip for a slip at zero
/// pressure).
#[test]
fn mortar_friction_passes_the_shear_patch_test() {
    for (n_low, n_up) in [(5, 3), (3, 5), (10, 7)] {
        for law in [
            "s2spenaltycontact 4 loadTimeFunction 1 penalty 1e6 friction 0.3 slavesegment 1 segmentset 1 2",
            "s2spenaltycontact 4 loadTimeFunction 1 friction 0.3 slavesegment 1 segmentset 1 2",
            "s2slagrangianmultipliercontact 4 loadTimeFunction 1 friction 0.3 slavesegment 1 segmentset 1 2",
        ] {
            let text = common::sheared_blocks(n_low, n_up, PATCH_P, PATCH_TAU, law);
            let (s, t, its) = shear_patch_errors(&text);
            println!("{n_low}/{n_up} mortar {}: stress {s:.1e}, traction {t:.1e}, {its} iterations", &law[..50]);
            // The traction is λ·D_j·t / (λ·D_j): round-off of a penalty's force (ε up to 5e6).
            assert!(s < 1e-10 && t < 1e-9, "{n_low}/{n_up} {law}: {s:e} {t:e}");
            assert!(its <= 3, "{its} iterations");
        }
        let text = common::sheared_blocks(
            n_low,
            n_up,
            PATCH_P,
            PATCH_TAU,
            "n2spenaltycontact 4 loadTimeFunction 1 penalty 1e6 friction 0.3 slaveset 4 segmentset 1 2",
        );
        let model = common::model_from_text(&text).unwrap();
        let (mut stress, mut its) = (f64::NAN, 0);
        run_analysis(&model, &common::quiet(), |r| {
            its = r.info.iterations;
            stress = r
                .states
                .iter()
                .flatten()
                .map(|g| (g.stress[5] - PATCH_TAU).abs() / PATCH_P)
                .fold(0.0, f64::max);
            Ok(())
        })
        .unwrap();
        println!("{n_low}/{n_up} node-to-segment: shear stress {stress:.1e}, {its} iterations");
        assert!(stress > 1e-2, "node-to-segment: {stress:e}");
        assert!(its <= 5, "node-to-segment: {its} iterations");
    }
}

/// A brick block (2 × 2 × 1 hexahedra, E = 1000, ν = 0: no Poisson spread;
/// `verify::pushed_block`) on a rigid plane, pressed down by a prescribed displacement of its
/// top, then pushed along (0.6, 0.8) by 0.05, far beyond the stick limit: every base node
/// slides, its friction force μ times its normal force to round-off (the isotropic Coulomb
/// cone), and the horizontal reaction is μ times the vertical one along the push, to 1e-5 (the
/// couple of the push at the top and the friction at the base tilts the block: the normal
/// forces, and the nodes' slip directions, differ a little). Node-to-face contact, with the
/// penalty law and with multipliers; each also on full tangents by GMRES on the symmetric
/// counterpart (the friction forces rotated into each node's normal and slip directions, the
/// sliding components condensed; as a contact zone too large to condense is solved), to the
/// condensed step's reactions within 1e-9 and its iterations within one.
#[test]
fn brick_pushed_obliquely_transmits_mu_n_along_the_push() {
    let direct = brick_pushed_obliquely(&common::quiet());
    let krylov = brick_pushed_obliquely(&SolveParams {
        condensed_contact: false,
        krylov_min_unknowns: 0,
        ..Default::default()
    });
    for ((a, its_a, _), (b, its_b, krylov)) in direct.iter().zip(&krylov) {
        for k in 0..3 {
            assert!((a[k] - b[k]).abs() <= 1e-9 * a[2].abs(), "{a:?} vs {b:?}");
        }
        assert!(its_a.iter().zip(its_b).all(|(x, y)| x.abs_diff(*y) <= 1));
        assert!(*krylov > 0, "GMRES solved the full tangents");
    }
}

/// [`brick_pushed_obliquely_transmits_mu_n_along_the_push`] with `params`, asserted, for the
/// penalty and for multipliers: the reaction, the Newton iterations per step, and the last
/// step's GMRES iterations with every multiplier eliminated (0: another way).
fn brick_pushed_obliquely(params: &SolveParams) -> Vec<([f64; 3], Vec<usize>, usize)> {
    let mut out = Vec::new();
    for law in [
        "n2spenaltycontact 3 loadTimeFunction 1 penalty 1e4 friction 0.3",
        "n2slagrangianmultipliercontact 3 loadTimeFunction 1 friction 0.3",
    ] {
        let text = hertz_bench::verify::pushed_block(2, 1, law);
        let model = common::model_from_text(&text).unwrap();
        let mut reaction = [0.0; 3];
        let mut sliding = 0;
        let mut worst_node = 0.0f64;
        let mut iterations = Vec::new();
        let mut krylov = 0;
        run_analysis(&model, params, |r| {
            reaction = [0.0; 3];
            for ((_, d, _), &f) in r.dofs.prescribed.iter().zip(r.reactions) {
                reaction[usize::from(*d) - 1] += f;
            }
            sliding = r
                .contact
                .iter()
                .filter(|s| s.friction.is_some_and(|f| !f.0))
                .count();
            // A sliding node's friction force is μ times its normal force.
            worst_node = r
                .contact
                .iter()
                .filter_map(|s| s.friction.filter(|f| !f.0).map(|f| (f.1, s.force)))
                .map(|(f, p)| (f - MU * p).abs() / (MU * p))
                .fold(0.0, f64::max);
            iterations.push(r.info.iterations);
            krylov = if r.info.multipliers_eliminated.1 == 0 {
                r.info.solver.krylov_iterations
            } else {
                0
            };
            Ok(())
        })
        .unwrap();
        let n = -reaction[2];
        let t = [reaction[0], reaction[1]];
        let along = 0.6 * t[0] + 0.8 * t[1];
        let across = -0.8 * t[0] + 0.6 * t[1];
        println!(
            "{}: N {n:.12}, T along the push {along:.15} (mu N = {:.15}), across {across:.1e}, \
             {sliding} nodes slide, |f| = mu p to {worst_node:.1e}, iterations {iterations:?}",
            &law[..30],
            MU * n
        );
        assert!(n > 0.0);
        assert_eq!(sliding, 9, "every base node slides");
        assert!(worst_node <= 1e-12, "{worst_node}");
        assert!(
            (along - MU * n).abs() <= 1e-5 * MU * n,
            "{along} vs {}",
            MU * n
        );
        assert!(across.abs() <= 1e-5 * MU * n, "{across}");
        assert!(iterations.iter().all(|&i| i <= 4), "{iterations:?}");
        out.push((reaction, iterations, krylov));
    }
    out
}

/// examples/ironing.in: a stiff half-ring die pressed 1.4 into a soft neo-Hookean slab, then
/// dragged 4 along it (mortar contact with multipliers, μ = 0.3, large deformation). No closed
/// form; checked: every step converges without a cut-back in a few Newton iterations (the slab
/// nodes passing the die's ends made it chatter and fail before the dual basis was adapted to
/// the overlap), the die's reaction balances the slab's, every slipping slave node's friction
/// force is μ times its normal force (to the Newton tolerance, 1e-8 of the die's force), and in
/// sliding the horizontal force exceeds μ times the
/// vertical one (friction plus the slab pushed ahead of the die).
#[test]
fn ironing_converges_and_slides_on_the_coulomb_cone() {
    let model = hertz::input::read_model(Path::new("examples/ironing.in"))
        .unwrap()
        .model;
    let mut iterations = Vec::new();
    let mut slipping = 0;
    let mut ratio = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        iterations.push(r.info.iterations);
        assert_eq!(r.info.substeps, 1, "step {}: cut back", r.step);
        // The die's ends (BCs 2 and 3) against the slab's bottom (BC 1).
        let die = die_reaction_balanced(&model, r, 0.0);
        slipping += slipping_on_the_cone(r, MU, 1e-8 * die[1].abs());
        if r.time > 2.0 + 1e-9 {
            ratio.push(die[0].abs() / die[1].abs());
        }
        Ok(())
    })
    .unwrap();
    let total: usize = iterations.iter().sum();
    println!(
        "ironing: iterations per step {iterations:?} (total {total}), {slipping} slipping node-steps, \
         Fx/Fy in sliding {:.4}..{:.4}",
        ratio.iter().copied().fold(f64::INFINITY, f64::min),
        ratio.iter().copied().fold(0.0, f64::max)
    );
    assert!(iterations.iter().all(|&i| i <= 10), "{iterations:?}");
    assert!(2 * total <= 7 * iterations.len(), "{total} iterations");
    assert!(slipping > 0);
    assert!(ratio.iter().all(|&q| q > MU), "{ratio:?}");
}

/// The number of closed slipping contact nodes of step `r`, each asserted to carry `mu` times
/// its normal force to `tol`.
fn slipping_on_the_cone(r: &hertz::solve::StepResult, mu: f64, tol: f64) -> usize {
    let mut slipping = 0;
    for s in r.contact.iter().filter(|s| s.active) {
        if let Some((false, f)) = s.friction {
            slipping += 1;
            assert!(
                (f - mu * s.force).abs() <= tol,
                "step {}: node {}: friction {f} for normal force {} (relative {:e})",
                r.step,
                s.node,
                s.force,
                (f - mu * s.force) / s.force
            );
        }
    }
    slipping
}

/// The summed reaction of a die driven by BCs other than 1, asserted to balance that of the
/// body held by BC 1 to 1e-7 of the die's vertical reaction (or of `floor` if larger).
fn die_reaction_balanced(
    model: &hertz::model::Model,
    r: &hertz::solve::StepResult,
    floor: f64,
) -> [f64; 2] {
    let (mut die, mut held) = ([0.0; 2], [0.0; 2]);
    for (&(_, d, bc), &f) in r.dofs.prescribed.iter().zip(r.reactions) {
        let k = usize::from(d) - 1;
        if model.dirichlet[bc].number == 1 {
            held[k] += f;
        } else {
            die[k] += f;
        }
    }
    for k in 0..2 {
        assert!(
            (die[k] + held[k]).abs() <= 1e-7 * die[1].abs().max(floor),
            "step {}: die {die:?}, held body {held:?}",
            r.step
        );
    }
    die
}

/// The shallow ironing benchmark (examples/shallow_ironing.in): the published vertical force at
/// the end of the press, 268–332 N, and the ratio Fx/Fy at t = 1.5 (the die slid 5), 0.30–0.53
/// (Yang, Laursen and Meng 2005 and those after them); the die's reaction balances the block's;
/// every step converges without a cut-back, in at most 6 iterations up to t = 1.5 and 7 after.
/// With c_T of the friction multipliers from the die's E alone (ten times the block's) the
/// press cycled between stick and slip at one node and needed 8 and 16 substeps; with the last
/// guess of a branch search that comes back to a guess (see `solve::branches`), step t = 1.94
/// inverted an element at the die's trailing corner and was cut back.
#[test]
#[ignore = "long: runs with `cargo test --release -- --ignored` (CI runs both)"]
fn shallow_ironing_gives_the_published_forces() {
    use hertz_bench::examples::SHALLOW_IRONING;
    shallow_ironing(&SHALLOW_IRONING.input(), 6, 7);
}

/// The shallow ironing benchmark as mortar with a penalty (10⁴ per unit area, ε_T the same):
/// the same published ranges, no cut-back and at most 5 iterations a step. Solved as a penalty
/// (the force −ε·g of the iterate), with stick or slip from the iterate the sliding die's
/// contact nodes swung from one slip direction to the other and the press did not converge
/// (t = 0.4); searched on the linearized problem it took 361 iterations, now 343 in multiplier
/// form (`contact::law::multiplier`).
#[test]
#[ignore = "long: runs with `cargo test --release -- --ignored` (CI runs both)"]
fn shallow_ironing_with_a_penalty_gives_the_published_forces() {
    use hertz_bench::examples::SHALLOW_IRONING;
    let text = SHALLOW_IRONING.input().replace(
        "s2slagrangianmultipliercontact 4 loadTimeFunction 1",
        "s2spenaltycontact 4 loadTimeFunction 1 penalty 1e4",
    );
    assert!(text.contains("s2spenaltycontact 4 loadTimeFunction 1 penalty 1e4"));
    shallow_ironing(&text, 5, 5);
}

/// Runs the shallow ironing input `text` and checks the published forces, no cut-back and at most
/// `press` iterations a step up to t = 1.5 and `slide` after.
fn shallow_ironing(text: &str, press: usize, slide: usize) {
    let (fy, ratio, iterations) = shallow_ironing_run(text);
    assert!((268.0..=332.0).contains(&fy), "Fy(1) = {fy}");
    assert!((0.30..=0.53).contains(&ratio), "Fx/Fy(1.5) = {ratio}");
    assert!(
        iterations
            .iter()
            .all(|&(t, i)| i <= if t <= 1.5 + 1e-9 { press } else { slide }),
        "{iterations:?}"
    );
}

/// Runs the shallow ironing input `text` to its end without a cut-back: the die's vertical force
/// at t = 1, Fx/Fy at t = 1.5 and the iterations of every step (time, iterations).
fn shallow_ironing_run(text: &str) -> (f64, f64, Vec<(f64, usize)>) {
    let model = common::model_from_text(text).unwrap();
    let mut iterations = Vec::new();
    let at = |t: f64, time: f64| (time - t).abs() < 1e-9;
    let (mut fy_press, mut ratio) = (None, None);
    run_analysis(&model, &common::quiet(), |r| {
        iterations.push((r.time, r.info.iterations));
        assert_eq!(r.info.substeps, 1, "step {}: cut back", r.step);
        // The die's top (BCs 2, 3) against the block's bottom (BC 1).
        let die = die_reaction_balanced(&model, r, 1.0);
        if at(1.0, r.time) {
            fy_press = Some(-die[1]);
        }
        if at(1.5, r.time) {
            ratio = Some(die[0] / -die[1]);
        }
        Ok(())
    })
    .unwrap();
    let (fy, ratio) = (fy_press.unwrap(), ratio.unwrap());
    let total: usize = iterations.iter().map(|(_, i)| i).sum();
    println!(
        "shallow ironing: Fy(1) = {fy:.2} N, Fx/Fy(1.5) = {ratio:.4}, iterations per step \
         {iterations:?} (total {total})"
    );
    assert_eq!(iterations.len(), 110);
    (fy, ratio, iterations)
}

/// The shallow ironing benchmark extruded to 3D ([`ShallowIroning3d`]: bricks, every node held in
/// y, mortar faces), one and two elements through the depth, pressed and slid 0.5: every step
/// converges without a cut-back in at most 5 iterations, and the die's force per unit depth is
/// the 2D plane-strain one to 10⁻⁸ (a y-invariant field on these bricks is the 2D field: the same
/// stiffness, and the mortar integrals are products of the 2D ones). With two layers the slave
/// faces' sides lie along the master's, and the clip of a slave face repeats its vertices on
/// those lines; dropping the cell between the two (a round-off area of either sign) took its
/// derivative out of the tangent, and Newton cycled: 74 iterations and four substeps in the
/// first contact step of the published mesh (120 × 20), 31 and two substeps in step 4 here.
///
/// [`ShallowIroning3d`]: hertz_bench::verify::ShallowIroning3d
#[test]
fn shallow_ironing_extruded_to_3d_irons_as_in_2d() {
    use hertz_bench::mesh::Solid;
    use hertz_bench::verify::{ShallowIroning, ShallowIroning3d};
    let base = ShallowIroning {
        nx: 40,
        ny: 6,
        n_arc: 4,
        n_die: 4,
        slide_dt: 0.01,
        end: 1.05,
        mu: 0.3,
    };
    // The die's force (x, up) at every step: the reactions of its driven nodes (BCs 2 and 3).
    let forces = |text: &str, up: u8| {
        let model = common::model_from_text(text).unwrap();
        let mut out = Vec::new();
        run_analysis(&model, &common::quiet(), |r| {
            assert_eq!(r.info.substeps, 1, "step {}: cut back", r.step);
            assert!(
                r.info.iterations <= 5,
                "step {}: {} iterations",
                r.step,
                r.info.iterations
            );
            let mut f = [0.0; 2];
            for (&(_, d, bc), &v) in r.dofs.prescribed.iter().zip(r.reactions) {
                if [2, 3].contains(&model.dirichlet[bc].number) {
                    if d == 1 {
                        f[0] += v;
                    } else if d == up {
                        f[1] += v;
                    }
                }
            }
            out.push(f);
            Ok(())
        })
        .unwrap();
        out
    };
    let plane = forces(&base.input(), 2);
    assert_eq!(plane.len(), 15);
    let pressed = plane[9][1].abs();
    assert!(pressed > 100.0, "Fy(1) = {pressed}");
    for layers in [1, 2] {
        let solid = forces(
            &ShallowIroning3d {
                base,
                kind: Solid::Hex,
                layers,
                plane_strain: true,
            }
            .input(),
            3,
        );
        for (k, (a, b)) in plane.iter().zip(&solid).enumerate() {
            for i in 0..2 {
                assert!(
                    (a[i] - b[i]).abs() < 1e-8 * pressed,
                    "{layers} layers, step {}: 2D {a:?}, 3D {b:?}",
                    k + 1
                );
            }
        }
    }
    // Free to expand along y (the die held at its top alone), the block is softer than in plane
    // strain: a lower force at the end of the press (0.89 of it), as quickly.
    let free = forces(
        &ShallowIroning3d {
            base,
            kind: Solid::Hex,
            layers: 2,
            plane_strain: false,
        }
        .input(),
        3,
    );
    let ratio = free[9][1].abs() / pressed;
    assert!(ratio > 0.5 && ratio < 0.99, "free / plane strain {ratio}");
}

/// Runs the shallow ironing input `multipliers` as mortar penalty, `penalty` the condition's
/// option ("penalty 1e6 ", or "" for the mesh's), as [`shallow_ironing_run`].
fn shallow_ironing_as_penalty(multipliers: &str, penalty: &str) -> (f64, f64, Vec<(f64, usize)>) {
    let text = multipliers.replace(
        "s2slagrangianmultipliercontact 4 loadTimeFunction 1 ",
        &format!("s2spenaltycontact 4 loadTimeFunction 1 {penalty}"),
    );
    assert!(text.contains(&format!(
        "s2spenaltycontact 4 loadTimeFunction 1 {penalty}slavesegment"
    )));
    shallow_ironing_run(&text)
}

/// Shallow ironing without friction as mortar penalty, the die's arc the slave side: with
/// `penalty 7e7` (10³ E/h with the die's modulus, about 5·10⁻⁶ of penetration against gap errors
/// of 10⁻³–10⁻² from a Newton step along the die's arc) and `penalty 1e6`, at most 6 iterations a
/// step, no cut-back, and the forces of the multipliers to 10⁻³; with the penalty from the mesh
/// (10³ E/h with the softer body's modulus, the block's: 7·10⁶ here) no cut-back, the same forces
/// and at most 20 % more iterations in all than the multipliers (449 against 393; `penalty 1e6`
/// 463, `penalty 7e7` 453). Its worst step is not bounded
/// here: from 3.5·10⁶ to 7·10⁷ the worst of the 110 steps takes 5 to 9 iterations with no trend
/// (the die's edge node closing and opening while the penalty's steps recover from the
/// predictor's gap errors), the totals 450–453. With the geometric tangent part taken from the
/// iterate's force −ε·g instead of the last step's linear force
/// (`SlotLinearization::hold_force`), `penalty 7e7` took 3220 iterations and 55 cut-backs. With
/// `penalty 1e6` a branch search at t = 1.65 cycled between two guesses with equal misses, and
/// the step of the one taken left the iterate where it was, for 14 iterations and two
/// cut-backs, until a stalled cycle took the other (`OnCycle::FewestMissesEarliest`).
#[test]
#[ignore = "long: runs with `cargo test --release -- --ignored` (CI runs both)"]
fn a_stiff_penalty_irons_like_the_multipliers() {
    use hertz_bench::examples::SHALLOW_IRONING;
    let multipliers = SHALLOW_IRONING.input().replace(" friction 0.3", "");
    let (fy_m, fx_fy_m, its_m) = shallow_ironing_run(&multipliers);
    let total_m: usize = its_m.iter().map(|(_, i)| i).sum();
    for penalty in ["penalty 7e7 ", "penalty 1e6 ", ""] {
        let (fy, fx_fy, iterations) = shallow_ironing_as_penalty(&multipliers, penalty);
        if penalty.is_empty() {
            let total: usize = iterations.iter().map(|(_, i)| i).sum();
            assert!(
                total as f64 <= 1.2 * total_m as f64,
                "the mesh's penalty: {total} iterations against the multipliers' {total_m}"
            );
        } else {
            assert!(
                iterations.iter().all(|&(_, i)| i <= 6),
                "{penalty}: {iterations:?}"
            );
        }
        assert!(
            (fy - fy_m).abs() < 1e-3 * fy_m,
            "{penalty}: Fy(1) {fy} against {fy_m}"
        );
        assert!(
            fx_fy.abs() < 0.05 && (fx_fy - fx_fy_m).abs() < 1e-3,
            "{penalty}: Fx/Fy(1.5) {fx_fy} against {fx_fy_m}"
        );
    }
}

/// Shallow ironing with friction as mortar penalty with the penalty from the mesh (10³ E/h) and
/// with `penalty 1e5`: no cut-back, at most 6 iterations a step up to t = 1.5 and 8 after (the
/// multipliers take 7 as the die nears the block's end), Fy(1) of the multipliers to 10⁻³ and
/// Fx/Fy(1.5) to 2·10⁻³ (the mesh's penalty's own error: 1.4·10⁻⁵ and 7·10⁻⁴; `penalty 1e5`,
/// sixty times softer, to 10⁻² and 2·10⁻²: 4.4·10⁻³ and 7·10⁻⁴).
/// Solved as a penalty, the friction force μ·ε·(−g) carried ε times each iterate's gap error
/// (10⁻³ after a step along the die's arc, against a penetration of 10⁻⁶) and the stick/slip
/// decision ε_T times its slip error: the mesh's penalty stopped at t = 0.3 and `penalty 1e5`
/// needed 152 cut-backs. With its forces as unknowns (the penalty's compliance in the
/// multipliers' rows) the solution is the penalty's and the iteration the multipliers'.
#[test]
#[ignore = "long: runs with `cargo test --release -- --ignored` (CI runs both)"]
fn a_stiff_penalty_with_friction_irons_like_the_multipliers() {
    use hertz_bench::examples::SHALLOW_IRONING;
    let multipliers = SHALLOW_IRONING.input();
    let (fy_m, fx_fy_m, _) = shallow_ironing_run(&multipliers);
    for (penalty, tol) in [("", 1e-3), ("penalty 1e5 ", 1e-2)] {
        let (fy, fx_fy, iterations) = shallow_ironing_as_penalty(&multipliers, penalty);
        assert!(
            iterations
                .iter()
                .all(|&(t, i)| i <= if t <= 1.5 + 1e-9 { 6 } else { 8 }),
            "{penalty}: {iterations:?}"
        );
        assert!(
            (fy - fy_m).abs() < tol * fy_m,
            "{penalty}: Fy(1) {fy} against {fy_m}"
        );
        assert!(
            (fx_fy - fx_fy_m).abs() < 2.0 * tol,
            "{penalty}: Fx/Fy(1.5) {fx_fy} against {fx_fy_m}"
        );
    }
}

/// examples/large_sliding.in (a block held by contact alone, pressed by a force onto a bump and
/// dragged over it) as node-to-segment penalty with friction (`penalty 1e3`, μ = 0.3): every
/// step converges without a cut-back. The first step's predictor left every node open; from
/// there the guess with no point closed had no Newton step (the body held by nothing: a
/// singular tangent) and, solved anyway, predicted itself and inverted an element. The
/// condensed step now takes that guess with the body held by the solver's springs instead.
#[test]
fn a_body_held_by_frictional_contact_alone_is_dragged_without_cut_back() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/large_sliding.in");
    let text = std::fs::read_to_string(path).unwrap().replace(
        "n2slagrangianmultipliercontact 4 loadTimeFunction 1 nodeset",
        "n2spenaltycontact 4 loadTimeFunction 1 penalty 1e3 friction 0.3 nodeset",
    );
    assert!(text.contains("penalty 1e3 friction 0.3"));
    let model = common::model_from_text(&text).unwrap();
    let mut iterations = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        assert_eq!(r.info.substeps, 1, "step {}: cut back", r.step);
        iterations.push(r.info.iterations);
        Ok(())
    })
    .unwrap();
    println!("large sliding with penalty friction: iterations {iterations:?}");
    assert_eq!(iterations.len(), 25);
    assert!(iterations.iter().all(|&i| i <= 6), "{iterations:?}");
}

/// A column of contact nodes along x: its x, and the normal and friction forces summed over it.
type Column = (f64, f64, f64);

/// Per step, the columns of contact nodes (z = 0 and 1 in 3D) and whether every node slides.
fn column_forces(text: &str) -> Vec<(Vec<Column>, bool)> {
    let model = common::model_from_text(text).unwrap();
    let mut out = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        let cols = columns(&model, r.contact)
            .into_iter()
            .map(|c| c.0)
            .collect();
        let slides = r.contact.iter().all(|s| s.friction.is_some_and(|f| !f.0));
        out.push((cols, slides));
        Ok(())
    })
    .unwrap();
    out
}

/// The contact nodes in columns along x (within 1e-9), sorted by x: each column's x, its normal
/// and friction forces summed, and whether any of its nodes slides.
fn columns(
    model: &hertz::model::Model,
    contact: &[hertz::contact::SlotState],
) -> Vec<(Column, bool)> {
    let mut cols: Vec<(Column, bool)> = Vec::new();
    for s in contact {
        let x = model.nodes[s.node].coords[0];
        let (stick, f) = s.friction.unwrap_or((true, 0.0));
        match cols.iter_mut().find(|c| (c.0 .0 - x).abs() < 1e-9) {
            Some(c) => {
                c.0 .1 += s.force;
                c.0 .2 += f;
                c.1 |= !stick;
            }
            None => cols.push(((x, s.force, f), !stick)),
        }
    }
    cols.sort_by(|a, b| a.0 .0.total_cmp(&b.0 .0));
    cols
}

/// Friction multipliers on nodes with a prescribed displacement component (issue 30, class 2): a
/// plate held at u_z = 0 everywhere, drawn along a fixed block, is the plane-strain problem.
/// Node-to-face and mortar, multipliers and a penalty solved in their form: the 3D columns'
/// normal and friction forces equal the 2D nodes', and the friction is μ times the normal force
/// on every sliding node. Before, the friction component along z (whose column and, at the start
/// of a slide, whose row were empty) made the Newton system singular: "a body is held by
/// contact alone and no contact holds it", after 5 halvings.
#[test]
fn friction_multipliers_on_nodes_held_along_an_axis_give_the_plane_strain_answer() {
    // Node-to-face penalties act per node: a 3D column of two nodes has half the 2D node's each.
    for (keyword, params, params_3d, mortar) in [
        (
            "n2slagrangianmultipliercontact",
            "friction 0.3",
            "friction 0.3",
            false,
        ),
        (
            "n2spenaltycontact",
            "penalty 1e5 friction 0.3 pt 1e5",
            "penalty 5e4 friction 0.3 pt 5e4",
            false,
        ),
        (
            "s2slagrangianmultipliercontact",
            "friction 0.3",
            "friction 0.3",
            true,
        ),
        (
            "s2spenaltycontact",
            "penalty 1e5 friction 0.3 pt 1e5",
            "penalty 1e5 friction 0.3 pt 1e5",
            true,
        ),
    ] {
        let plane = column_forces(&plate_drawn_on_a_block(2, keyword, params, mortar));
        let solid = column_forces(&plate_drawn_on_a_block(3, keyword, params_3d, mortar));
        assert_eq!(plane.len(), 2);
        for (step, ((p, p_slides), (s, s_slides))) in plane.iter().zip(&solid).enumerate() {
            assert!(
                *p_slides && *s_slides,
                "{keyword} step {}: all nodes slide",
                step + 1
            );
            assert_eq!(p.len(), s.len());
            let total: f64 = p.iter().map(|c| c.1).sum();
            assert!(total > 1.0, "{keyword}: pressed ({total})");
            for (a, b) in p.iter().zip(s) {
                assert!(
                    (a.1 - b.1).abs() < 1e-8 * total && (a.2 - b.2).abs() < 1e-8 * total,
                    "{keyword} step {} x = {}: 2D {:?}, 3D {:?}",
                    step + 1,
                    a.0,
                    a,
                    b
                );
                assert!((b.2 - MU * b.1).abs() < 1e-9 * total, "{keyword}: μN {b:?}");
            }
        }
    }
}

/// [`plate_drawn_on_a_block`] with the contact one node-to-segment self-contact condition: the
/// plate's bottom and the block's top one surface, each node a slave against it. Every plate
/// node meets a block node and the reverse: the pairs merge, their friction acting on the mean
/// relative slip. Drawn along the block, every pair slides, so the plate's top carries
/// R_x = μ·R_y exactly (its contact forces are all normal force and μ times it), in 2D and 3D.
/// A merged friction force with the block's side taken with the plate's sign cancels on the
/// plate: R_x came out near zero.
#[test]
fn a_self_contact_surface_of_two_blocks_drawn_along_each_other_slides_with_mu_n() {
    for (dim, mortar) in [(2, false), (3, false), (2, true)] {
        let two =
            plate_drawn_on_a_block(dim, "n2slagrangianmultipliercontact", "friction 0.3", false);
        // The nodes on y = 0 (the plate's bottom and the block's top) and y = 1 (the plate's top).
        let at = |y: f64| -> Vec<usize> {
            (two.lines())
                .filter_map(|l| {
                    let w: Vec<&str> = l.split_whitespace().collect();
                    (w.first() == Some(&"node") && w[5].parse::<f64>() == Ok(y))
                        .then(|| w[1].parse::<usize>().unwrap())
                })
                .collect()
        };
        let (face, set) = if dim == 3 {
            ("linear3delementsurfacecontactsegment", "boundaryset")
        } else {
            ("linear2delementedgecontactsegment", "edgeset")
        };
        let condition = (two.lines())
            .find(|l| l.starts_with("n2slagrangianmultipliercontact"))
            .unwrap()
            .to_string();
        let surface = at(0.0);
        let one = if mortar {
            // One segment of both sets of edges, the slave among its masters.
            let items = |k: usize| -> Vec<String> {
                let line = (two.lines())
                    .find(|l| l.starts_with(&format!("Set {k} elementboundaries")))
                    .unwrap();
                line.split_whitespace().skip(4).map(String::from).collect()
            };
            let both = [items(4), items(5)].concat();
            two.replace("nset 5", "nset 6")
                .replace(
                    &format!("{face} 1 {set} 4\n"),
                    &format!("{face} 1 {set} 6\n"),
                )
                .replace(
                    &condition,
                    "s2slagrangianmultipliercontact 4 loadTimeFunction 1 friction 0.3 \
                     slavesegment 1 segmentset 1 1",
                )
                + &format!(
                    "Set 6 elementboundaries {} {}\n",
                    both.len(),
                    both.join(" ")
                )
        } else {
            let own = format!(
                "n2slagrangianmultipliercontact 4 loadTimeFunction 1 friction 0.3 nodeset {} {} \
                 segmentset 2 1 2",
                surface.len(),
                surface
                    .iter()
                    .map(|n| n.to_string())
                    .collect::<Vec<_>>()
                    .join(" ")
            );
            two.replace("ncontactseg 1", "ncontactseg 2")
                .replace(
                    &format!("{face} 1 {set} 4\n"),
                    &format!("{face} 1 {set} 4\n{face} 2 {set} 5\n"),
                )
                .replace(&condition, &own)
        };
        let model = common::model_from_text(&one).unwrap();
        let top: Vec<usize> = at(1.0).iter().map(|&l| l - 1).collect();
        let mut steps = 0;
        run_analysis(&model, &common::quiet(), |r| {
            steps += 1;
            // Node-to-segment marks a pair's second node, mortar both.
            let merged = r.contact.iter().filter(|s| s.repeated).count();
            assert!(
                2 * merged >= surface.len(),
                "{dim}D mortar {mortar}: {merged} nodes in merged pairs"
            );
            assert!(
                r.contact.iter().all(|s| s.friction.is_some_and(|f| !f.0)),
                "{dim}D mortar {mortar} step {}: every node slides",
                r.step
            );
            let mut force = [0.0; 2];
            for (&(n, d, _), &f) in r.dofs.prescribed.iter().zip(r.reactions) {
                if top.contains(&n) && (d as usize) <= 2 {
                    force[d as usize - 1] += f;
                }
            }
            assert!(force[1].abs() > 1.0, "{dim}D: pressed ({force:?})");
            assert!(
                (force[0].abs() - MU * force[1].abs()).abs() < 1e-9 * force[1].abs(),
                "{dim}D mortar {mortar} step {}: top reactions {force:?}",
                r.step
            );
            Ok(())
        })
        .unwrap();
        assert_eq!(steps, 2);
    }
}

/// Per column of contact nodes (by x): normal force, friction force, and whether any slides;
/// the iterations of the one step.
fn ssnv128(dim: usize, n: usize, law: &str) -> (Vec<(f64, f64, f64, bool)>, usize) {
    let text = hertz_bench::suite::plate_pushed_on_a_rigid_plane(dim, n, law);
    let model = common::model_from_text(&text).unwrap();
    let params = SolveParams {
        max_cutbacks: 0,
        ..Default::default()
    };
    let (mut cols, mut its) = (Vec::new(), 0);
    run_analysis(&model, &params, |r| {
        its = r.info.iterations;
        cols = columns(&model, r.contact)
            .into_iter()
            .map(|((x, n, f), slides)| (x, n, f, slides))
            .collect();
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{law}, {dim}D, {n} × {n}: {e}"));
    (cols, its)
}

/// Code_Aster's SSNV128 (issue 50, item 6): a plate pushed along a rigid plane with μ = 1, held
/// at u_x = 0 on its far side, in 3D one layer with u_z = 0. The corner node on the back face is
/// held along x and z, and its mortar friction force moves nothing free but its neighbours'
/// round-off shares (1e-22 against 5e-6): the multiplier was undetermined (1.9e25 after one
/// iteration), and the mortar penalty with friction failed the step even in 32 substeps (every
/// mesh, 4 × 4 to 16 × 16). Now a force that moves free unknowns by less than 1e-9 of its share
/// is held at zero as one that moves none. Checks: one step without cut-back in ≤ 8 iterations
/// (penalty from the mesh, given, multipliers); the 3D columns equal the plane-strain nodes for
/// multipliers to 1e-8 (but the corner, held by the support in 2D and half by contact in 3D);
/// the penalty within its own error of them; the sliding columns carry μ times their normal force.
#[test]
fn a_plate_pushed_along_a_rigid_plane_ssnv128_converges_with_every_law() {
    for n in [4, 8] {
        let (plane, _) = ssnv128(2, n, "s2slagrangianmultipliercontact");
        let total: f64 = plane.iter().map(|c| c.1).sum();
        for law in [
            "s2slagrangianmultipliercontact",
            "s2spenaltycontact",
            "s2spenaltycontact penalty 1e16",
            "n2slagrangianmultipliercontact",
            "n2spenaltycontact",
        ] {
            let (solid, its) = ssnv128(3, n, law);
            assert!(its <= 8, "{law}, {n} × {n}: {its} iterations");
            let tol = if law.contains("multiplier") {
                1e-8
            } else {
                2e-3
            };
            assert_eq!(plane.len(), solid.len());
            for (a, b) in plane.iter().zip(&solid).take(n) {
                assert!(
                    (a.1 - b.1).abs() < tol * total && (a.2 - b.2).abs() < tol * total,
                    "{law}, {n} × {n}, x = {}: 2D {a:?}, 3D {b:?}",
                    a.0
                );
                if b.3 {
                    assert!((b.2 - b.1).abs() < 1e-9 * total, "{law}: μN {b:?}");
                }
            }
            let slides = solid.iter().filter(|c| c.3).count();
            assert!(
                slides > 1 && slides < n,
                "{law}, {n} × {n}: {slides} columns slide"
            );
        }
    }
}

/// 3D mortar multipliers with friction solved on full tangents (`max_condensed` 0, as a contact
/// zone too large to condense is): the brick patch pressed together sticks in one iteration with
/// the exact pressure at every slave node, in 8-node and 20-node bricks. The slave nodes on the
/// symmetry planes have a friction traction component along the plane's normal that acts only
/// on held unknowns: its row of the tangent was zero, and the first step went to a residual of
/// 1.8e20 and never converged (the condensed step solved it).
#[test]
fn mortar_friction_multipliers_on_full_tangents_converge() {
    use hertz_bench::mesh::Solid;
    use hertz_bench::suite::Law;
    use hertz_bench::verify::{Patch, E, PATCH_H};
    for quadratic in [false, true] {
        let patch = Patch {
            kind: Solid::Hex,
            slave_kind: None,
            sym: 0,
            n: 2,
            nlgeo: false,
            delta: 0.01,
            steps: 1,
            law: Law::Multiplier,
            slave_n: None,
            mortar: true,
        };
        let text = if quadratic {
            patch.input_quadratic()
        } else {
            patch.input()
        }
        .replace("slavesegment", "friction 0.3 slavesegment");
        let model = common::model_from_text(&text).unwrap();
        let params = SolveParams {
            max_condensed: Some(0),
            max_cutbacks: 0,
            ..Default::default()
        };
        let exact = E * 0.01 / (2.0 * PATCH_H);
        let (mut its, mut worst, mut slipping) = (0, f64::NAN, usize::MAX);
        run_analysis(&model, &params, |r| {
            its = r.info.iterations;
            worst = r
                .contact
                .iter()
                .map(|s| (s.pressure / exact - 1.0).abs())
                .fold(0.0, f64::max);
            slipping = r
                .contact
                .iter()
                .filter(|s| s.friction.is_some_and(|f| !f.0))
                .count();
            Ok(())
        })
        .unwrap_or_else(|e| panic!("quadratic {quadratic}: {e}"));
        assert!(
            its == 1 && worst < 1e-10 && slipping == 0,
            "quadratic {quadratic}: {its} iterations, pressure {worst:e}, {slipping} slipping"
        );
    }
}

/// A block 4 × 1 of 32 × 5 plane-strain Q4 (E = 1000, ν = 0.3), its bottom held, and above it a
/// die 3 wide, 16 × 1 Q4 ten times stiffer, whose bottom is a flat facet 1 wide touching the
/// block and two facets rising 1 in 10 from its ends; the die's top moved down by 0.1 in one
/// step. Node-to-segment contact with friction μ, the block's top nodes the slaves; `law` the
/// condition record's head.
fn faceted_die(law: &str, mu: f64) -> String {
    let (nx, ny, nd) = (32usize, 5usize, 16usize);
    let mut nodes: Vec<[f64; 2]> = Vec::new();
    let mut cells: Vec<[usize; 5]> = Vec::new();
    let block: Vec<Vec<usize>> = (0..=ny)
        .map(|j| {
            (0..=nx)
                .map(|i| {
                    nodes.push([-2.0 + 4.0 * i as f64 / nx as f64, j as f64 / ny as f64]);
                    nodes.len()
                })
                .collect()
        })
        .collect();
    for j in 0..ny {
        for i in 0..nx {
            cells.push([
                block[j][i],
                block[j][i + 1],
                block[j + 1][i + 1],
                block[j + 1][i],
                1,
            ]);
        }
    }
    let bottom = |x: f64| 1.0 + 0.1 * (x.abs() - 0.5).max(0.0);
    let (mut low, mut high) = (Vec::new(), Vec::new());
    for k in 0..=nd {
        let x = -1.5 + 3.0 * k as f64 / nd as f64;
        nodes.push([x, bottom(x)]);
        low.push(nodes.len());
        nodes.push([x, 1.4]);
        high.push(nodes.len());
    }
    for k in 0..nd {
        cells.push([low[k], low[k + 1], high[k + 1], high[k], 2]);
    }
    let labels = |v: &[usize]| {
        v.iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut text = format!(
        "die.out\nfaceted die\nStaticStructural nsteps 1 rtolf 1e-9 maxiter 30\ndomain PlaneStrain\n\
         OutputManager\nndofman {} nelem {} ncrosssect 1 nmat 2 nbc 3 nic 0 nltf 1 nset 3 \
         ncontactseg 1\n",
        nodes.len(),
        cells.len()
    );
    for (k, x) in nodes.iter().enumerate() {
        text += &format!("node {} coords 2 {} {}\n", k + 1, x[0], x[1]);
    }
    for (e, c) in cells.iter().enumerate() {
        text += &format!(
            "Quad1PlaneStrain {} nodes 4 {} {} {} {} mat {} crossSect 1\n",
            e + 1,
            c[0],
            c[1],
            c[2],
            c[3],
            c[4]
        );
    }
    let die_edges: Vec<String> = (0..nd).map(|k| format!("{} 1", nx * ny + k + 1)).collect();
    text += &format!(
        "linear2delementedgecontactsegment 1 edgeset 1\nSimpleCS 1 thick 1.0\n\
         IsoLE 1 d 0 E 1000 n 0.3 tAlpha 0\nIsoLE 2 d 0 E 10000 n 0.3 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 2\n\
         BoundaryCondition 2 loadTimeFunction 1 dofs 2 1 2 values 2 0 -0.1 set 3\n\
         {law} friction {mu} nodeset {} {} segmentset 1 1\nConstantFunction 1 f(t) 1.0\n\
         Set 1 elementboundaries {} {}\nSet 2 nodes {} {}\nSet 3 nodes {} {}\n",
        nx + 1,
        labels(&block[ny]),
        2 * nd,
        die_edges.join(" "),
        nx + 1,
        labels(&block[0]),
        high.len(),
        labels(&high),
    );
    text
}

/// A faceted die pressed onto a block in one step (the flat facet touching at the start, nodes
/// under the rising facets closing within the step; issue 50 item 8): semismooth Newton
/// cycled there between two stick/slip states of closed nodes (a residual up and down for 30
/// iterations) and the step was cut into 2 (41 iterations with multipliers at μ = 0.2). From
/// such a cycle on, its steps are backtracked: 8 iterations with multipliers and with a
/// penalty, no cut-back. Checked: the die's reaction balances the block's (1e-7), and every slipping node
/// carries μ times its normal force (1e-8 of the die's force).
#[test]
fn a_faceted_die_pressed_in_one_step_converges_without_cut_back() {
    for law in [
        "n2slagrangianmultipliercontact 3 loadTimeFunction 1",
        "n2spenaltycontact 3 loadTimeFunction 1 penalty 1e6 pt 1e6",
    ] {
        let mu = 0.2;
        let model = common::model_from_text(&faceted_die(law, mu)).unwrap();
        let mut slipping = 0;
        run_analysis(&model, &common::quiet(), |r| {
            println!(
                "{law}: {} iterations, {} substeps",
                r.info.iterations, r.info.substeps
            );
            assert_eq!(r.info.substeps, 1, "{law}: cut back");
            assert!(
                r.info.iterations <= 12,
                "{law}: {} iterations",
                r.info.iterations
            );
            let die = die_reaction_balanced(&model, r, 0.0);
            slipping += slipping_on_the_cone(r, mu, 1e-8 * die[1].abs());
            Ok(())
        })
        .unwrap();
        assert!(slipping > 0, "{law}: no node slips");
    }
}
