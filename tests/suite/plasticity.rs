//! Materials with a state: von Mises plasticity of bars (`MisesMat`), whose plastic strain and
//! hardening variable are committed with each converged step and restored on a cut-back.

use crate::common;

use hertz::solve::{run_analysis, SolveParams};

/// Young's modulus, hardening modulus and the three bars' yield stresses.
const E: f64 = 100.0;
const H: f64 = 10.0;
const SIG0: [f64; 3] = [1.0, 2.0, 3.0];

/// Three bars of unit length and area side by side between node 1 (held) and node 2, each of
/// its own MisesMat (yield stresses 1, 2, 3), node 2 pulled by the force history `forces`
/// (one step each) with `maxiter` Newton iterations per step.
fn three_bars(forces: &[f64], maxiter: usize) -> String {
    let t: Vec<String> = (0..=forces.len()).map(|i| i.to_string()).collect();
    let f: Vec<String> = std::iter::once(0.0)
        .chain(forces.iter().copied())
        .map(|v| v.to_string())
        .collect();
    let mut s = format!(
        "bars.out\nthree bars yielding one after the other\n\
         StaticStructural nsteps {} rtolf 1e-12 maxiter {maxiter} manrmsteps 1\n\
         domain 1dTruss\nOutputManager\n\
         ndofman 2 nelem 3 ncrosssect 1 nmat 3 nbc 2 nic 0 nltf 1 nset 2\n\
         node 1 coords 1 0\nnode 2 coords 1 1\n",
        forces.len()
    );
    for e in 1..=3 {
        s += &format!("Truss1d {e} nodes 2 1 2 crossSect 1 mat {e}\n");
    }
    s += "SimpleCS 1 area 1\n";
    for (m, sig0) in SIG0.iter().enumerate() {
        s += &format!(
            "MisesMat {} d 0 E {E} n 0.3 sig0 {sig0} H {H} tAlpha 0\n",
            m + 1
        );
    }
    s += "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 1\n";
    s += "NodalLoad 2 loadTimeFunction 1 dofs 1 1 components 1 1 set 2\n";
    s += &format!(
        "PiecewiseLinFunction 1 npoints {} t {} {} f(t) {} {}\n",
        t.len(),
        t.len(),
        t.join(" "),
        f.len(),
        f.join(" ")
    );
    s += "Set 1 nodes 1 1\nSet 2 nodes 1 2\n";
    s
}

/// Displacement of node 2 and substeps, per step.
fn solve(text: &str) -> Vec<(f64, usize)> {
    let model = common::model_from_text(text).unwrap();
    let mut out = Vec::new();
    run_analysis(&model, &SolveParams::default(), |r| {
        out.push((r.displacement(1, 1).unwrap(), r.info.substeps));
        Ok(())
    })
    .unwrap();
    out
}

/// The exact response: the force of the three bars at a monotonically reached strain ε.
fn force_at(eps: f64) -> f64 {
    SIG0.iter()
        .map(|&s0| {
            let ey = s0 / E;
            if eps <= ey {
                E * eps
            } else {
                s0 + E * H / (E + H) * (eps - ey)
            }
        })
        .sum()
}

/// Loaded to 8 (every bar yields: ε = 0.28/3 exactly), unloaded to 0 (elastically, E·3 = 300:
/// a residual strain 0.28/3 − 8/300), reloaded to 8 (elastically back to the same strain).
#[test]
fn bars_yield_harden_and_keep_their_plastic_strain_after_unloading() {
    let steps = solve(&three_bars(&[2.0, 5.0, 8.0, 0.0, 8.0], 25));
    let peak = 0.28 / 3.0;
    assert!((force_at(peak) - 8.0).abs() < 1e-12);
    let expected = [2.0 / 300.0, 0.0, peak, peak - 8.0 / 300.0, peak];
    // Step 2 (F = 5): bar 1 has yielded, bars 2 and 3 not: 1 + 100/11 (ε − 0.01) + 200 ε = 5
    // (E·H/(E + H) = 100/11).
    let eps5 = (5.0 - 1.0 + 100.0 / 11.0 * 0.01) / (100.0 / 11.0 + 200.0);
    assert!((force_at(eps5) - 5.0).abs() < 1e-12);
    let expected = [expected[0], eps5, expected[2], expected[3], expected[4]];
    for (k, ((u, _), want)) in steps.iter().zip(expected).enumerate() {
        assert!(
            (u - want).abs() < 1e-12,
            "step {}: u {u}, exact {want}",
            k + 1
        );
    }
}

/// Loaded to 8, then to −12 in one step: the bars unload and yield in compression. With two
/// Newton iterations per step, that step is cut back, and so are its halves: substeps that
/// converge before a failing one (the bars yielding back) commit their plastic strains, which
/// the retry must roll back to the step's start, or the bars would start the retry yielded
/// backwards, yield forwards again and harden more. The answer equals the run without
/// cut-backs.
#[test]
fn a_cut_back_restores_the_committed_plastic_state() {
    let reference = solve(&three_bars(&[8.0, -12.0], 25));
    assert!(reference.iter().all(|&(_, n)| n == 1), "{reference:?}");
    let cut = solve(&three_bars(&[8.0, -12.0], 2));
    assert!(
        cut[1].1 >= 8,
        "the reversal is cut back three times: {cut:?}"
    );
    for (k, (a, b)) in cut.iter().zip(&reference).enumerate() {
        assert!(
            (a.0 - b.0).abs() < 1e-12,
            "step {}: {} with cut-backs, {} without",
            k + 1,
            a.0,
            b.0
        );
    }
    assert!((reference[0].0 - 0.28 / 3.0).abs() < 1e-12);
}
