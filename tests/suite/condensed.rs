//! The condensed contact step (Schur complement from the trailing factor block, the contact part
//! dense on its equations, branches searched on the linearized problem) equals a direct
//! factorization of the full tangent in the branches it settled on, for penalty and multipliers,
//! and with friction (multipliers, and a penalty solved in their form with its compliance),
//! some nodes sticking and others slipping.

use hertz::assembly::{Assembler, Contribution, NodalState};
use hertz::contact::{ContactSystem, Search};
use hertz::input::read_model;
use hertz::solve::branches::OnCycle;
use hertz::solve::condensed::CondensedContact;
use hertz::solve::linear::FaerSolver;

fn compare(multipliers: bool, friction: bool) {
    let path = std::env::temp_dir().join(format!(
        "hertz-condensed-{}-{multipliers}-{friction}.in",
        std::process::id()
    ));
    hertz_bench::write_contact_block_input(&path, 8, 0.4, multipliers).unwrap();
    if friction {
        let text = std::fs::read_to_string(&path).unwrap();
        let text = text.replace(" nodeset ", " friction 0.3 nodeset ");
        std::fs::write(&path, text).unwrap();
    }
    let model = read_model(&path).unwrap().model;
    std::fs::remove_file(&path).ok();
    let contact = ContactSystem::new(&model).unwrap();
    let dofs = hertz::assembly::DofMap::new(&model, &contact.extra_dofs()).unwrap();
    let asm = Assembler::new(&model, &dofs).unwrap();
    // Lift the whole block into the rigid circle so that several top nodes penetrate; multipliers
    // of a few of them positive.
    let mut u = vec![0.0; dofs.n_primary()];
    for (n, node) in model.nodes.iter().enumerate() {
        if let Some(c) = dofs.code(n, 2) {
            u[c] = 0.4 + 0.01 * node.coords[0].sin();
        }
        // With friction, a slight shear.
        if let (true, Some(c)) = (friction, dofs.code(n, 1)) {
            u[c] = 1e-6 * (node.coords[0] - 4.0) / 4.0 * (1.0 + node.coords[1] / 8.0);
        }
    }
    for (k, i) in (dofs.n_free - dofs.n_lambda..dofs.n_free).enumerate() {
        u[i] = if friction {
            // Per node (λ_T,x, λ_T,y, λ_n): a pressure of 50 on every node, and a friction
            // force inside the cone (μλ_n = 15) at every other node, beyond it at the rest.
            match (k % 3, (k / 3) % 2) {
                (2, _) => 50.0,
                (0, 0) => 5.0,
                (0, _) => 40.0,
                _ => 0.0,
            }
        } else if k % 3 == 0 {
            50.0
        } else {
            0.0
        };
    }
    // The friction history: the states at u = 0.
    let zero = vec![0.0; u.len()];
    let before = contact
        .evaluate(&NodalState::new(&model, &dofs, &zero), Search::Fresh)
        .unwrap()
        .1;
    let nodes = NodalState::new(&model, &dofs, &u).with_start(Some(&zero));
    let (points, states) = contact
        .evaluate_with_history(&nodes, Search::Fresh, Some(&before))
        .unwrap();
    let n_active = states.iter().filter(|s| s.active).count();
    assert!(n_active >= 3, "{n_active} active contacts");
    if friction {
        let stick: Vec<bool> = states
            .iter()
            .filter_map(|s| s.friction)
            .map(|f| f.0)
            .collect();
        println!("friction states (stick) of the closed nodes: {stick:?}");
        assert!(stick.contains(&true) && stick.contains(&false), "{stick:?}");
    }
    let rhs: Vec<f64> = (0..dofs.n_free)
        .map(|i| ((i * 7 % 13) as f64 - 6.0) * 1e3)
        .collect();

    // Condensed: K_s alone with the contact candidates last.
    let k_s = asm
        .evaluate(&u, true, false, None, &[])
        .unwrap()
        .k_values
        .unwrap();
    let mut cands = contact.candidate_equations(&nodes).unwrap();
    let lambdas = dofs.n_free - dofs.n_lambda..dofs.n_free;
    cands.extend(lambdas.clone());
    let max = hertz::solve::condensed::MAX_CANDIDATES;
    // Shifted as a body held by contact alone or not: the shift is taken back in the contact
    // part, so both are the true step.
    for held in [false, true] {
        let base = Box::new(FaerSolver::default());
        let mut cc = CondensedContact::new(
            base,
            &asm.pattern,
            &k_s,
            &cands,
            lambdas.clone(),
            max,
            held,
            &|e| e.to_string(),
        )
        .unwrap()
        .expect("supernodal with trailing candidates");
        let guess: Vec<bool> = points.iter().map(|p| p.closed).collect();
        let step = cc
            .step(&rhs, &points, &guess, &dofs, OnCycle::FewestMisses, &|eq| {
                format!("equation {eq}")
            })
            .unwrap()
            .expect("all points on candidates");

        // Direct: the full tangent in the settled branches, the residual change of switched points.
        let mut rhs_d = rhs.clone();
        let contribs: Vec<Contribution> = points
            .iter()
            .zip(&step.closed)
            .map(|(p, &c)| {
                if let Some(change) = p.branch_change(c) {
                    for (&code, d) in p.codes.iter().zip(change) {
                        for (e, w) in dofs.entries(code) {
                            if e < dofs.n_free {
                                rhs_d[e] -= w * d;
                            }
                        }
                    }
                }
                let (fe, ke) = p.branch(c);
                Contribution {
                    codes: p.codes.clone(),
                    fe,
                    ke,
                }
            })
            .collect();
        let couplings: Vec<Vec<usize>> = contribs.iter().map(|c| c.codes.clone()).collect();
        // Friction's tangent is unsymmetric: both triangles.
        // (An assembler of its own: the condensed step's keeps K_s's symmetric pattern.)
        let mut asm_d = Assembler::new(&model, &dofs).unwrap();
        asm_d.set_symmetric(!friction);
        asm_d.set_couplings(&couplings);
        let ev = asm_d.evaluate(&u, true, false, None, &contribs).unwrap();
        let mut direct = FaerSolver::default();
        direct
            .factorize(&asm_d.pattern, ev.k_values.as_ref().unwrap(), false, &|e| {
                e.to_string()
            })
            .unwrap();
        direct.solve_in_place(&mut rhs_d).unwrap();

        let scale = rhs_d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = rhs_d
            .iter()
            .zip(&step.du)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            err <= 1e-9 * scale,
            "multipliers {multipliers}, held {held}: max difference {err:e} (scale {scale:e})"
        );
    }
}

#[test]
fn condensed_penalty_step_equals_direct_factorization() {
    compare(false, false);
}

#[test]
fn condensed_multiplier_step_equals_direct_factorization() {
    compare(true, false);
}

#[test]
fn condensed_frictional_penalty_step_equals_direct_factorization() {
    compare(false, true);
}

#[test]
fn condensed_frictional_multiplier_step_equals_direct_factorization() {
    compare(true, true);
}

/// The contact conditions the tied blocks are tried with: mortar and node-to-segment
/// multipliers, a mortar penalty.
const TIED_CONDITIONS: [&str; 3] = [
    "s2slagrangianmultipliercontact 3 loadTimeFunction 1 slavesegment 2 segmentset 1 1",
    "n2slagrangianmultipliercontact 3 loadTimeFunction 1 slaveset 5 segmentset 1 1",
    "s2spenaltycontact 3 loadTimeFunction 1 slavesegment 2 segmentset 1 1",
];

/// Two blocks, the lower held at its base, the upper held by contact alone: its top nodes are
/// `SlaveNode`s of one master node that carries the load, held sideways (`sideways` false) or
/// free and pushed sideways as well (true). Plane strain, non-matching meshes (`n` lower
/// elements along the interface), Young's moduli `young` (lower) and `ratio` times it (upper);
/// the upper block `gap` above the lower.
fn tied_blocks(
    young: f64,
    ratio: f64,
    n: usize,
    condition: &str,
    sideways: bool,
    gap: f64,
) -> String {
    let mut nodes: Vec<[f64; 2]> = Vec::new();
    let mut grid = |nx: usize, y0: f64| -> Vec<Vec<usize>> {
        (0..=2)
            .map(|j| {
                (0..=nx)
                    .map(|i| {
                        nodes.push([-1.0 + 2.0 * i as f64 / nx as f64, y0 + 0.25 * j as f64]);
                        nodes.len()
                    })
                    .collect()
            })
            .collect()
    };
    let low = grid(n, -0.5);
    let up = grid(2 * n / 3 + 1, gap);
    let master = nodes.len() + 1;
    let mut elements = Vec::new();
    for (g, mat) in [(&low, 1), (&up, 2)] {
        for j in 0..2 {
            for i in 0..g[0].len() - 1 {
                elements.push(format!(
                    "Quad1PlaneStrain {} nodes 4 {} {} {} {} crossSect {mat} mat {mat}",
                    elements.len() + 1,
                    g[j][i],
                    g[j][i + 1],
                    g[j + 1][i + 1],
                    g[j + 1][i]
                ));
            }
        }
    }
    let top: std::collections::HashSet<usize> = up[2].iter().copied().collect();
    let records: Vec<String> = nodes
        .iter()
        .enumerate()
        .map(|(k, x)| {
            if top.contains(&(k + 1)) {
                format!(
                    "SlaveNode {} coords 2 {} {} masterDofMan 1 {master} doftype 2 2 2",
                    k + 1,
                    x[0],
                    x[1]
                )
            } else {
                format!("node {} coords 2 {} {}", k + 1, x[0], x[1])
            }
        })
        .collect();
    let list = |v: &[usize]| {
        let s: Vec<String> = v.iter().map(|x| x.to_string()).collect();
        format!("{} {}", v.len(), s.join(" "))
    };
    let faces = |first: usize, count: usize, edge: usize| {
        let s: Vec<String> = (first..first + count)
            .map(|e| format!("{e} {edge}"))
            .collect();
        format!("{} {}", 2 * count, s.join(" "))
    };
    let nu = up[0].len() - 1;
    let (load, hold) = if sideways {
        ("0.5 -1", "set 1")
    } else {
        ("0 -1", "set 2")
    };
    format!(
        "m.out\ntied blocks\nNonLinearStatic nsteps 2 controlmode 1 rtolf 1e-8\n\
         domain PlaneStrain\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 2 nmat 2 nbc 4 nic 0 nltf 1 nset 5 ncontactseg 2\n\
         {}\nnode {master} coords 2 0 0.5\n{}\n\
         linear2delementedgecontactsegment 1 edgeset 3\n\
         linear2delementedgecontactsegment 2 edgeset 4\n\
         SimpleCS 1 thick 1\nSimpleCS 2 thick 1\n\
         IsoLE 1 d 0 E {young} n 0.3 tAlpha 0\nIsoLE 2 d 0 E {} n 0.3 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 1\n\
         NodalLoad 2 loadTimeFunction 1 dofs 2 1 2 Components 2 {load} set 2\n\
         {}\n\
         BoundaryCondition 4 loadTimeFunction 1 dofs 1 1 values 1 0 {hold}\n\
         PiecewiseLinFunction 1 npoints 3 t 3 0 1 2 f(t) 3 0 1 2\n\
         Set 1 nodes {}\nSet 2 nodes 1 {master}\nSet 3 elementboundaries {}\n\
         Set 4 elementboundaries {}\nSet 5 nodes {}\n",
        nodes.len() + 1,
        elements.len(),
        records.join("\n"),
        elements.join("\n"),
        young * ratio,
        condition,
        list(&low[0]),
        faces(n + 1, n, 3),
        faces(2 * n + 1, nu, 1),
        list(&up[0]),
    )
}

/// A body that contact alone holds is no mechanism where its load is along the contact's
/// normal: its step solves whatever the bodies' moduli and their ratio (the dense system's
/// multiplier rows are scaled by areas, its displacement rows by stiffnesses: with E = 10⁶ a
/// vanishing pivot read as a mechanism before, the scale-free test does not), and the contact
/// carries the load exactly. Its twin pushed sideways on frictionless contact is a mechanism,
/// and is reported as one, at a DOF 1 (sideways).
#[test]
fn a_body_held_by_contact_alone_is_a_mechanism_only_where_its_load_drives_one() {
    for young in [1.0, 1e6, 1e12] {
        for ratio in [1.0, 1e4] {
            for n in [4, 16] {
                for condition in TIED_CONDITIONS {
                    let case = format!("E {young} ratio {ratio} n {n}: {condition}");
                    let text = tied_blocks(young, ratio, n, condition, false, 0.0);
                    carries_the_load(&text, &crate::common::quiet(), &case);
                    let text = tied_blocks(young, ratio, n, condition, true, 0.0);
                    let model = crate::common::model_from_text(&text).unwrap();
                    let err =
                        hertz::solve::run_analysis(&model, &crate::common::quiet(), |_| Ok(()))
                            .unwrap_err()
                            .to_string();
                    assert!(
                        err.contains(
                            "the tangent with the contact's stiffness is singular at node"
                        ) && err.contains("DOF 1: a mechanism"),
                        "{case}: {err}"
                    );
                }
            }
        }
    }
}

/// A body held by contact alone that starts apart from its support (a gap of 0.01 under the
/// upper block): its first guess closes no point and its tangent is singular. The condensed
/// step holds it by its shift; full tangents now hold its contact nodes by springs and stretch
/// that step until a point closes, where before they stopped on a false mechanism ("singular at
/// node 34 DOF 2"; on the Gmsh hemispheres of BENCHMARKS.md the step went nowhere, no point ever
/// closed in 40 iterations). Both paths: the contact force carries the load, in a few iterations
/// a step.
#[test]
fn a_body_held_by_contact_alone_across_a_gap_is_solved_with_full_tangents_too() {
    for condition in TIED_CONDITIONS {
        for condensed_contact in [true, false] {
            let case = format!("{condition}, condensed {condensed_contact}");
            let text = tied_blocks(1e3, 10.0, 8, condition, false, 0.01);
            let params = hertz::solve::SolveParams {
                condensed_contact,
                max_cutbacks: 0,
                ..crate::common::quiet()
            };
            carries_the_load(&text, &params, &case);
        }
    }
}

/// Solve the tied blocks `text` with `params`: both steps converge in at most 6 iterations and
/// the contact force carries the load of 1 (`case` names the run).
fn carries_the_load(text: &str, params: &hertz::solve::SolveParams, case: &str) {
    let model = crate::common::model_from_text(text).unwrap();
    let mut last = (0.0, 0);
    hertz::solve::run_analysis(&model, params, |r| {
        assert!(
            r.info.iterations <= 6,
            "{case}: {} iterations",
            r.info.iterations
        );
        last = (r.contact.iter().map(|s| s.force).sum(), r.step);
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{case}: {e}"));
    assert_eq!(last.1, 2, "{case}");
    assert!(
        (last.0 - 1.0).abs() < 1e-7,
        "{case}: contact force {}",
        last.0
    );
}
