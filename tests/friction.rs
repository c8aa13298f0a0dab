//! Coulomb friction against analytical answers: the sliding threshold of a pressed block
//! (examples/coulomb_block.in, Code_Aster SSNV503 style), the force a sliding block transmits,
//! and the friction history restored when a step is cut back.

mod common;

use hertz::solve::{run_analysis, SolveParams};
use std::path::Path;

const MU: f64 = 0.3;
const N: f64 = 10.0;

fn example() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/coulomb_block.in"))
        .unwrap()
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

fn quiet() -> SolveParams {
    SolveParams {
        log_steps: false,
        ..Default::default()
    }
}

/// Below μN the block holds (its slide is the tangential penalty's elastic slip, T/pt per unit
/// length of the base, far below a millimetre-scale motion); above it no equilibrium exists and
/// the step fails even after halving.
#[test]
fn block_sticks_below_mu_n_and_slides_above() {
    let below = solve(&pushed_by(0.99), &quiet()).unwrap();
    let elastic_slip = 0.99 * MU * N / (1e5 * 2.0);
    println!(
        "T = 0.99 mu N: slide {:.3e} (elastic slip T/(pt L) = {elastic_slip:.3e}), {:?} iterations",
        below.slide[1], below.iterations
    );
    assert!(below.slide[1] > 0.0 && below.slide[1] < 20.0 * elastic_slip);
    assert!(
        below.iterations.iter().all(|&i| i <= 6),
        "{:?}",
        below.iterations
    );
    let above = solve(&pushed_by(1.01), &quiet());
    let err = above.err().expect("no equilibrium above mu N").to_string();
    assert!(err.contains("step 2"), "{err}");
}

/// Pushed by a prescribed displacement of its top, once every node slides the block transmits
/// exactly μN: Σ μ·p_N,i with Σ p_N,i = N.
#[test]
fn sliding_block_transmits_mu_n() {
    let text = example()
        .replace(
            "NodalLoad 3 loadTimeFunction 2 dofs 2 1 2 components 2 0.37125 0.0 set 2",
            "BoundaryCondition 3 loadTimeFunction 2 dofs 1 1 values 1 0.05 set 2",
        )
        .replace(
            "NodalLoad 4 loadTimeFunction 2 dofs 2 1 2 components 2 0.7425 0.0 set 3",
            "BoundaryCondition 4 loadTimeFunction 2 dofs 1 1 values 1 0.05 set 3",
        );
    let out = solve(&text, &quiet()).unwrap();
    println!(
        "pushed 0.05: transmitted {:.15} (mu N = {}), {} nodes stick, {:?} iterations",
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
#[test]
fn a_cut_back_step_restarts_from_the_converged_friction_history() {
    let starved = pushed_by(0.99).replace("maxiter 30", "maxiter 2");
    let mut substeps = 0;
    let model = common::model_from_text(&starved).unwrap();
    let mut slide_cut = f64::NAN;
    let mut states_cut = Vec::new();
    run_analysis(&model, &quiet(), |r| {
        if r.step == 2 {
            substeps = r.info.substeps;
            slide_cut = r.displacement(0, 1).unwrap();
            states_cut = r.contact.iter().map(|s| (s.force, s.friction)).collect();
        }
        Ok(())
    })
    .unwrap();
    assert!(substeps > 1, "step 2 was cut back ({substeps} substeps)");
    let stepped = pushed_by(0.99)
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
    run_analysis(&model, &quiet(), |r| {
        slide = r.displacement(0, 1).unwrap();
        states = r.contact.iter().map(|s| (s.force, s.friction)).collect();
        Ok(())
    })
    .unwrap();
    println!("cut back into {substeps} substeps: slide {slide_cut:.15e}; as steps: {slide:.15e}");
    assert!(
        (slide_cut - slide).abs() <= 1e-12 * slide.abs(),
        "{slide_cut} vs {slide}"
    );
    for (a, b) in states_cut.iter().zip(&states) {
        assert!(
            (a.0 - b.0).abs() <= 1e-9 * a.0.abs().max(1.0),
            "{a:?} vs {b:?}"
        );
        let (fa, fb) = (a.1.unwrap(), b.1.unwrap());
        assert_eq!(fa.0, fb.0, "stick state");
        assert!(
            (fa.1 - fb.1).abs() <= 1e-9 * fb.1.max(1.0),
            "{a:?} vs {b:?}"
        );
    }
}
