//! The condensed contact solve (Schur complement from the trailing factor block + Woodbury on the
//! active contact DOFs) equals a direct factorization of the full tangent.

use hertz::assembly::Assembler;
use hertz::contact::{ContactSystem, Search};
use hertz::input::read_model;
use hertz::solve::condensed::CondensedContact;
use hertz::solve::linear::LinearSolver;

#[test]
fn condensed_contact_solve_equals_direct_factorization() {
    let path = std::env::temp_dir().join(format!("hertz-condensed-{}.in", std::process::id()));
    hertz::bench::write_contact_block_input(&path, 8, 0.4).unwrap();
    let model = read_model(&path).unwrap().model;
    std::fs::remove_file(&path).ok();
    let contact = ContactSystem::new(&model).unwrap();
    let dofs = hertz::assembly::DofMap::new(&model, &contact.extra_dofs()).unwrap();
    let mut asm = Assembler::new(&model, &dofs).unwrap();
    // Lift the whole block into the rigid circle so that several top nodes penetrate.
    let mut u = vec![0.0; dofs.n_primary()];
    for (n, node) in model.nodes.iter().enumerate() {
        if let Some(c) = dofs.code(n, 2) {
            u[c] = 0.4 + 0.01 * node.coords[0].sin();
        }
    }
    let (contribs, states) = contact.evaluate(&model, &dofs, &u, Search::Fresh).unwrap();
    let n_active = states.iter().filter(|s| s.active).count();
    assert!(n_active >= 3, "{n_active} active contacts");
    let rhs: Vec<f64> = (0..dofs.n_free)
        .map(|i| ((i * 7 % 13) as f64 - 6.0) * 1e3)
        .collect();

    // Direct: the full tangent (elements + contact) factorized.
    let couplings: Vec<Vec<usize>> = contribs.iter().map(|c| c.codes.clone()).collect();
    asm.set_couplings(&couplings);
    let ev = asm.evaluate(&u, true, false, None, &contribs).unwrap();
    let mut direct = LinearSolver::default();
    direct
        .factorize(&asm.pattern, ev.k_values.as_ref().unwrap(), false, &|e| {
            e.to_string()
        })
        .unwrap();
    let mut x_direct = rhs.clone();
    direct.solve_in_place(&mut x_direct).unwrap();

    // Condensed: K_el alone with the contact candidates last.
    let k_el = asm
        .evaluate(&u, true, false, None, &[])
        .unwrap()
        .k_values
        .unwrap();
    let cands = contact.candidate_equations(&dofs);
    let mut cc = CondensedContact::new(&asm.pattern, &k_el, cands, None)
        .expect("supernodal with trailing candidates");
    let mut x_cond = rhs.clone();
    assert!(cc.solve(&mut x_cond, &contribs, &dofs).unwrap());

    let scale = x_direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = x_direct
        .iter()
        .zip(&x_cond)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        err <= 1e-9 * scale,
        "max difference {err:e} (scale {scale:e})"
    );
}
