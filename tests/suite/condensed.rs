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
    let mut asm = Assembler::new(&model, &dofs).unwrap();
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
    let mut cc = CondensedContact::new(&asm.pattern, &k_s, &cands, lambdas, max, None, &|e| {
        e.to_string()
    })
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
    asm.set_symmetric(!friction);
    asm.set_couplings(&couplings);
    let ev = asm.evaluate(&u, true, false, None, &contribs).unwrap();
    let mut direct = FaerSolver::default();
    direct
        .factorize(&asm.pattern, ev.k_values.as_ref().unwrap(), false, &|e| {
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
        "multipliers {multipliers}: max difference {err:e} (scale {scale:e})"
    );
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
